// Exported plots: PNG, SVG and PDF exist, have the asked size and are not blank; CSV beside them.
#include "widgets/plots/plot_export.h"

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QAbstractButton>
#include <QApplication>
#include <QFile>
#include <QFileInfo>
#include <QImage>
#include <QLineEdit>
#include <QMessageBox>
#include <QPointer>
#include <QRegularExpression>
#include <QSvgRenderer>
#include <QTemporaryDir>
#include <QTimer>
#include <functional>
#include <memory>

#include "core/analysis/forces.h"
#include "core/project/project.h"
#include "widgets/plots/export_dialog.h"
#include "widgets/plots/sweep_plot.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

// Pixels of the curves (saturated colours), not the white background or grey axes.
int colouredPixels(const QImage& image) {
    int coloured = 0;
    for (int y = 0; y < image.height(); y += 2) {
        for (int x = 0; x < image.width(); x += 2) {
            if (QColor(image.pixel(x, y)).saturation() > 100) ++coloured;
        }
    }
    return coloured;
}

class PlotExport : public ::testing::Test {
protected:
    void SetUp() override {
        analysis::Inputs in = project::inputsOf(ProjectDocument::defaultProject(test::resources()));
        in.conditions.slip_angles_deg = {5, 20};
        in.conditions.slip_count = 40;
        table_ = analysis::computeForceSweep(in).table;
        plotSweep(plot_, table_, sweepQuantities()[0], "test");
    }
    QCustomPlot plot_;
    Table table_;
    QTemporaryDir dir_;
};

TEST_F(PlotExport, PngHasTheAskedSizeAndIsNotBlank) {
    const QString path = dir_.filePath("fx.png");
    QString error;
    ASSERT_TRUE(exportPlot(plot_, path, {640, 480, 150, 1.0}, &error)) << error.toStdString();
    const QImage image(path);
    ASSERT_FALSE(image.isNull());
    EXPECT_EQ(image.width(), 640);
    EXPECT_EQ(image.height(), 480);
    EXPECT_NEAR(image.dotsPerMeterX() * 0.0254, 150.0, 1.0);
    EXPECT_GT(colouredPixels(image), 200);
    EXPECT_FALSE(QFile::exists(path + ".part.png"));
}

TEST_F(PlotExport, SvgHasTheAskedSizeAndRendersCurves) {
    const QString path = dir_.filePath("fx.svg");
    QString error;
    ASSERT_TRUE(exportPlot(plot_, path, {800, 500, 96, 1.0}, &error)) << error.toStdString();
    QSvgRenderer renderer(path);
    ASSERT_TRUE(renderer.isValid());
    EXPECT_EQ(renderer.viewBox(), QRect(0, 0, 800, 500));
    QImage image(800, 500, QImage::Format_ARGB32);
    image.fill(Qt::white);
    QPainter painter(&image);
    renderer.render(&painter);
    painter.end();
    EXPECT_GT(colouredPixels(image), 200);
}

TEST_F(PlotExport, PdfHasTheAskedPageSize) {
    const QString path = dir_.filePath("fx.pdf");
    QString error;
    ASSERT_TRUE(exportPlot(plot_, path, {600, 400, 96, 1.0}, &error)) << error.toStdString();
    QFile file(path);
    ASSERT_TRUE(file.open(QIODevice::ReadOnly));
    const QByteArray bytes = file.readAll();
    EXPECT_TRUE(bytes.startsWith("%PDF"));
    EXPECT_GT(bytes.size(), 3000);  // curves and text, not an empty page
    // The page is width × height points (QCustomPlot::savePdf).
    const QRegularExpression media(R"(/MediaBox\s*\[\s*0\s+0\s+([\d.]+)\s+([\d.]+)\s*\])");
    const auto match = media.match(QString::fromLatin1(bytes));
    ASSERT_TRUE(match.hasMatch());
    EXPECT_NEAR(match.captured(1).toDouble(), 600.0, 1.0);
    EXPECT_NEAR(match.captured(2).toDouble(), 400.0, 1.0);
}

TEST_F(PlotExport, CsvHoldsThePlottedTableAndBadRequestsFailCleanly) {
    const QString path = dir_.filePath("fx.csv");
    QString error;
    ASSERT_TRUE(exportTable(table_, path, &error)) << error.toStdString();
    QFile file(path);
    ASSERT_TRUE(file.open(QIODevice::ReadOnly));
    EXPECT_EQ(file.readAll().count('\n'), static_cast<qsizetype>(table_.rows.size() + 1));

    EXPECT_FALSE(exportPlot(plot_, dir_.filePath("fx.bmp"), {}, &error));
    EXPECT_TRUE(error.contains("bmp"));
    EXPECT_FALSE(exportPlot(plot_, dir_.filePath("missing/dir/fx.png"), {}, &error));
    EXPECT_FALSE(exportPlot(plot_, dir_.filePath("fx2.png"), {5, 5, 96, 1.0}, &error));
    EXPECT_FALSE(QFile::exists(dir_.filePath("fx2.png")));
}

}  // namespace
}  // namespace terra::ui

namespace terra::ui {
namespace {

/// Every `interval_ms`, hands the modal widget on top to `act` (once per distinct widget) until
/// `act` returns true; for dialogs that open one after another (a dialog, then its question).
void driveModals(std::function<bool(QWidget*)> act) {
    auto* timer = new QTimer;
    timer->setInterval(20);
    auto last = std::make_shared<QPointer<QWidget>>();
    QObject::connect(timer, &QTimer::timeout, [timer, act, last] {
        QWidget* modal = QApplication::activeModalWidget();
        if (!modal || modal == last->data()) return;
        *last = modal;
        if (act(modal)) {
            timer->stop();
            timer->deleteLater();
        }
    });
    timer->start();
}

// Issue 27, item 5: an export into a folder that does not exist offers to create it ("cannot
// write" was all it said); declined, the dialog comes back with its path; accepted, the folder is
// made and the plot and its CSV written there.
TEST_F(PlotExport, AMissingFolderIsOfferedToBeCreated) {
    QTemporaryDir dir;
    const QString path = dir.filePath("figures/2026/forces.png");
    QStringList seen;
    int questions = 0;
    driveModals([&](QWidget* modal) {
        if (auto* dialog = qobject_cast<ExportDialog*>(modal)) {
            seen << "dialog";
            dialog->findChild<QLineEdit*>("export.path")->setText(path);
            QMetaObject::invokeMethod(dialog, &QDialog::accept, Qt::QueuedConnection);
            return false;
        }
        if (auto* box = qobject_cast<QMessageBox*>(modal)) {
            seen << "question";
            EXPECT_TRUE(box->text().contains("does not exist")) << box->text().toStdString();
            // The first time No (back to the dialog), the second time Yes.
            QAbstractButton* button =
                box->button(++questions == 1 ? QMessageBox::No : QMessageBox::Yes);
            QMetaObject::invokeMethod(button, &QAbstractButton::click, Qt::QueuedConnection);
            return questions == 2;
        }
        return false;
    });
    QStringList written;
    ASSERT_TRUE(ExportDialog::exportWithDialog(nullptr, plot_, table_, "forces.png", &written));
    EXPECT_EQ(seen, (QStringList{"dialog", "question", "dialog", "question"}));
    EXPECT_EQ(written, (QStringList{path, dir.filePath("figures/2026/forces.csv")}));
    EXPECT_TRUE(QImage(path).width() > 0);
    EXPECT_TRUE(QFileInfo::exists(dir.filePath("figures/2026/forces.csv")));
}

}  // namespace
}  // namespace terra::ui
