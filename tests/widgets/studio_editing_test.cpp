// Issue 12, the property editors and the document as a person uses them: an edited preset soil is
// named as such everywhere (editor, plot title, export, .terra file); typed values out of range
// stay whole on screen with the range named; letters are refused with a word; a red field moves
// nothing; a drag and a later typed value are two undo steps with the right labels; the slip-angle
// list is checked while typing; the plots' right-click menu copies the data.
#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QAction>
#include <QApplication>
#include <QClipboard>
#include <QComboBox>
#include <QFile>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QSlider>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>
#include <nlohmann/json.hpp>

#include "core/common/units.h"
#include "widgets/editors/property_editors.h"
#include "widgets/editors/validated_spin_box.h"
#include "widgets/panels/forces_panel.h"
#include "widgets/plots/figures.h"
#include "widgets/plots/plot_export.h"
#include "widgets/plots/plot_menu.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

QString messageOf(QWidget& editor) {
    auto* label = editor.findChild<QLabel*>("message");
    return label ? label->text() : QString("<no message label>");
}

TEST(EditedSoil, IsNamedAsEditedInTheEditorPlotExportAndFile) {
    ProjectDocument document;
    test::resetToDefault(document);
    ASSERT_EQ(document.project().soil.name, "sandy loam");
    ASSERT_EQ(document.project().soil_preset, "sandy-loam");
    SoilEditor editor(&document, test::resources());
    ForcesPanel panel(&document);
    panel.resize(900, 600);
    panel.show();
    ASSERT_TRUE(test::waitForResult(panel));

    ASSERT_TRUE(document.setSoilValue("phi_deg", 35.0));
    EXPECT_EQ(document.project().soil.name, "sandy loam (edited)");
    EXPECT_EQ(document.project().soil_preset, "");  // no longer the preset
    auto* combo = editor.findChild<QComboBox*>();
    ASSERT_NE(combo, nullptr);
    EXPECT_EQ(combo->currentText(), "sandy loam (edited)");
    EXPECT_EQ(editor.findChild<QLineEdit*>("soil.name")->text(), "sandy loam (edited)");

    ASSERT_TRUE(test::waitForResult(panel));
    EXPECT_TRUE(plotTitle(*panel.currentPlot()).startsWith("sandy loam (edited)"))
        << plotTitle(*panel.currentPlot()).toStdString();
    QTemporaryDir dir;
    QString error;
    ASSERT_TRUE(exportPlot(*panel.currentPlot(), dir.filePath("fx.svg"), {}, &error))
        << error.toStdString();
    QFile svg(dir.filePath("fx.svg"));
    ASSERT_TRUE(svg.open(QIODevice::ReadOnly));
    EXPECT_TRUE(QString::fromUtf8(svg.readAll()).contains("sandy loam (edited)"));

    ASSERT_TRUE(document.save(dir.filePath("p.terra"), &error));
    QFile file(dir.filePath("p.terra"));
    ASSERT_TRUE(file.open(QIODevice::ReadOnly));
    const auto json = nlohmann::json::parse(file.readAll().toStdString());
    EXPECT_EQ(json["soil"]["name"], "sandy loam (edited)");
    EXPECT_EQ(json["soil_preset"], "");

    // A second edit keeps one suffix; undoing both is the preset again, by name too.
    ASSERT_TRUE(document.setSoilValue("c_kPa", 2.0));
    EXPECT_EQ(document.project().soil.name, "sandy loam (edited)");
    document.undoStack()->undo();
    document.undoStack()->undo();
    EXPECT_EQ(document.project().soil.name, "sandy loam");
    EXPECT_EQ(document.project().soil_preset, "sandy-loam");
    EXPECT_EQ(combo->currentText(), "sandy loam");  // the preset's name; its id is the data
    EXPECT_EQ(combo->currentData().toString(), "sandy-loam");

    // A name the user types is what the soil is called.
    auto* name = editor.findChild<QLineEdit*>("soil.name");
    name->setText("field 7, wet");
    emit name->editingFinished();
    EXPECT_EQ(document.project().soil.name, "field 7, wet");
    EXPECT_EQ(combo->currentText(), "field 7, wet");
}

TEST(ValidatedField, OutOfRangeTextStaysWholeAndNamesTheRange) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    editor.show();
    ValidatedSpinBox* phi = editor.spinBox("phi_deg");
    ValidatedSpinBox* kc = editor.spinBox("kc");
    const int height = phi->height(), below = kc->y();
    phi->setFocus();
    phi->selectAll();
    QTest::keyClicks(phi, "75");
    EXPECT_EQ(phi->findChild<QLineEdit*>()->text(), "75");  // it used to show "7"
    EXPECT_FALSE(phi->textIsValid());
    EXPECT_TRUE(messageOf(editor).contains("75")) << messageOf(editor).toStdString();
    EXPECT_TRUE(messageOf(editor).contains("[0, 60)")) << messageOf(editor).toStdString();
    QApplication::processEvents();
    EXPECT_EQ(phi->height(), height);  // a flagged field moves nothing (it shifted rows by 3 px)
    EXPECT_EQ(kc->y(), below);
    QTest::keyClick(phi, Qt::Key_Return);
    EXPECT_TRUE(phi->textIsValid());
    EXPECT_EQ(document.undoStack()->count(), 0);
    EXPECT_TRUE(messageOf(editor).isEmpty());

    ValidatedSpinBox* c = editor.spinBox("c_kPa");
    c->selectAll();
    QTest::keyClicks(c, "-5");
    EXPECT_EQ(c->findChild<QLineEdit*>()->text(), "-5");  // it used to show "-"
    EXPECT_TRUE(messageOf(editor).contains("-5")) << messageOf(editor).toStdString();
    QTest::keyClick(c, Qt::Key_Return);

    // Letters are refused, with a word: the field keeps its number, the message says why.
    phi->selectAll();
    QTest::keyClicks(phi, "abc");
    EXPECT_EQ(phi->value(), 29.0);
    EXPECT_TRUE(messageOf(editor).contains("takes a number")) << messageOf(editor).toStdString();
    EXPECT_TRUE(messageOf(editor).contains("[0, 60)")) << messageOf(editor).toStdString();
    EXPECT_EQ(document.undoStack()->count(), 0);
}

TEST(UndoSteps, ADragAndALaterTypedValueAreTwoStepsWithTheirOwnLabels) {
    ProjectDocument document;
    test::resetToDefault(document);
    SoilEditor editor(&document, test::resources());
    editor.show();
    QSlider* slider = editor.slider("phi_deg");
    ValidatedSpinBox* phi = editor.spinBox("phi_deg");
    slider->setSliderDown(true);
    for (int p : {400, 600, 853}) slider->setValue(p);
    slider->setSliderDown(false);
    emit slider->sliderReleased();
    ASSERT_EQ(document.undoStack()->count(), 1);
    const double dragged = phi->value();
    EXPECT_EQ(document.undoStack()->text(0), QString("Set φ = %1 deg").arg(dragged));

    phi->setFocus();
    phi->selectAll();
    QTest::keyClicks(phi, "19.2");
    QTest::keyClick(phi, Qt::Key_Return);
    ASSERT_EQ(document.undoStack()->count(), 2);  // not merged into the drag
    EXPECT_EQ(document.undoStack()->text(1), "Set φ = 19.2 deg");
    document.undoStack()->undo();
    EXPECT_DOUBLE_EQ(phi->value(), dragged);
    document.undoStack()->undo();
    EXPECT_DOUBLE_EQ(phi->value(), 29.0);
}

TEST(SlipAngles, ListIsCheckedWhileTypingAndNamesTheBadValue) {
    ProjectDocument document;
    test::resetToDefault(document);
    ConditionsEditor editor(&document);
    editor.show();
    QLineEdit* angles = editor.slipAnglesEdit();
    const auto before = document.project().conditions.slip_angles_deg;
    angles->selectAll();
    QTest::keyClicks(angles, "0, 5, 5x");  // no Enter yet
    EXPECT_TRUE(messageOf(editor).contains("\"5x\" is not a number"))
        << messageOf(editor).toStdString();
    angles->selectAll();
    QTest::keyClicks(angles, "0, 120");
    EXPECT_TRUE(messageOf(editor).contains("120")) << messageOf(editor).toStdString();
    QTest::keyClick(angles, Qt::Key_Return);
    EXPECT_EQ(document.project().conditions.slip_angles_deg, before);  // never applied
    angles->selectAll();
    QTest::keyClicks(angles, "0, 10");
    EXPECT_TRUE(messageOf(editor).isEmpty());
    QTest::keyClick(angles, Qt::Key_Return);
    EXPECT_EQ(document.project().conditions.slip_angles_deg, (std::vector<double>{0.0, 10.0}));
}

TEST(PlotMenu, CopiesTheDataAndResetsTheView) {
    ProjectDocument document;
    test::resetToDefault(document);
    ForcesPanel panel(&document);
    panel.resize(900, 600);
    panel.show();
    ASSERT_TRUE(test::waitForResult(panel));
    bool exported = false;
    QMenu* menu =
        makePlotMenu(*panel.currentPlot(),
                     {[&] { return panel.currentTable(); }, [&] { exported = true; }}, &panel);
    QStringList names;
    for (QAction* action : menu->actions()) names << action->objectName();
    for (const char* name : {"plot.export", "plot.copy_image", "plot.copy_data", "plot.reset_view"})
        EXPECT_TRUE(names.contains(name)) << name;
    menu->findChild<QAction*>("plot.copy_data")->trigger();
    const QString csv = QApplication::clipboard()->text();
    EXPECT_TRUE(csv.startsWith("slip")) << csv.left(80).toStdString();
    EXPECT_EQ(csv.count('\n'), static_cast<int>(panel.currentTable().rows.size()) + 1);
    menu->findChild<QAction*>("plot.export")->trigger();
    EXPECT_TRUE(exported);
    QCustomPlot* plot = panel.currentPlot();
    plot->xAxis->setRange(100.0, 200.0);
    menu->findChild<QAction*>("plot.reset_view")->trigger();
    EXPECT_LE(plot->xAxis->range().upper, 1.0 + 1e-9);  // slip ∈ [0, 1] again
}

}  // namespace
}  // namespace terra::ui
