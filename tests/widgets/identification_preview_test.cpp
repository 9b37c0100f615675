// The identification panel's preview of a CSV before Fit, on real widgets (offscreen): the first
// rows as the file has them, the columns found and ignored, the rows read and each bad row by
// line, and the channels the fit will compare. The preview is read on a worker (AnalysisRunner):
// the tests wait for it to be shown.
#include <gtest/gtest.h>

#include <QSignalSpy>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QTest>
#include <fstream>
#include <string>

#include "core/contact/contact_parameters.h"
#include "core/identification/synthetic.h"
#include "core/io/parameters_json.h"
#include "widgets/panels/identification_panel.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

std::string writeFile(const QTemporaryDir& dir, const char* name, const std::string& text) {
    const std::string path = dir.filePath(name).toStdString();
    std::ofstream(path) << text;
    return path;
}

// Waits until the preview being read on the worker is on screen (true), or times out.
bool waitForPreview(IdentificationPanel& panel, int timeout_ms = 10000) {
    if (!panel.dataPreviewReading()) return true;
    QSignalSpy shown(&panel, &IdentificationPanel::dataPreviewShown);
    return shown.wait(timeout_ms);
}

TEST(IdentificationPreview, ShowsRowsColumnsBadRowsByLineAndTheFittedChannels) {
    QTemporaryDir dir;
    // Header = line 1; line 6 has "abc" for θ_f; probe_id is not a data column.
    const std::string path = writeFile(dir, "drive.csv",
                                       "slip,entry_angle_deg,Fx_N,Fz_N,My_Nm,probe_id\n"
                                       "0.1,20,5.5,80,1.2,7\n"
                                       "0.2,21,9.5,80,1.6,7\n"
                                       "0.3,22,12,80,1.9,7\n"
                                       "0.4,23,14,80,2.1,7\n"
                                       "0.45,abc,15,80,2.2,7\n"
                                       "0.5,24,16,80,2.3,7\n"
                                       "0.6,25,17,80,2.4,7\n");
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    EXPECT_TRUE(panel.dataPreview().isEmpty());  // synthetic data: nothing to preview
    panel.setDataFile(QString::fromStdString(path));
    ASSERT_TRUE(waitForPreview(panel));
    const QString preview = panel.dataPreview();
    EXPECT_TRUE(
        preview.contains("Columns: slip, entry_angle_deg, Fx_N, Fz_N, My_Nm (ignored: "
                         "probe_id)"))
        << preview.toStdString();
    EXPECT_TRUE(preview.contains("Rows: 6 read, 1 bad")) << preview.toStdString();
    EXPECT_TRUE(preview.contains("line 6: ")) << preview.toStdString();
    EXPECT_TRUE(preview.contains("Fit refuses the file")) << preview.toStdString();
    EXPECT_TRUE(preview.contains("Fits: F_x, F_z, M_y (entry angle measured)"))
        << preview.toStdString();
    // The first five data rows as typed, the bad one included.
    EXPECT_EQ(panel.dataPreviewHeader(0), "slip");
    EXPECT_EQ(panel.dataPreviewHeader(5), "probe_id");
    EXPECT_EQ(panel.dataPreviewCell(0, 0), "0.1");
    EXPECT_EQ(panel.dataPreviewCell(0, 2), "5.5");
    EXPECT_EQ(panel.dataPreviewCell(4, 1), "abc");
    EXPECT_TRUE(panel.dataPreviewCell(5, 0).isEmpty());  // only five rows

    // The decoupled fit reads the same file the same way; its channels are always the three.
    panel.applySettings({{"refine", false}});
    ASSERT_TRUE(waitForPreview(panel));
    EXPECT_TRUE(panel.dataPreview().contains("Fits: F_x, F_z, M_y (decoupled fit"))
        << panel.dataPreview().toStdString();

    // Back to synthetic data: no preview.
    panel.setDataFile({});
    EXPECT_TRUE(panel.dataPreview().isEmpty());
}

TEST(IdentificationPreview, DataWithoutAnEntryAngleFitTheirChannelsFromTheLoad) {
    QTemporaryDir dir;
    const std::string path = writeFile(dir, "loads.csv",
                                       "slip,W_N,Fx_N,My_Nm,sinkage_m\n"
                                       "0.1,80,5.5,1.2,0.010\n"
                                       "0.3,80,12,1.9,0.013\n"
                                       "0.5,80,16,2.3,0.016\n");
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.applySettings({{"refine", true}});
    panel.setDataFile(QString::fromStdString(path));
    ASSERT_TRUE(waitForPreview(panel));
    QString preview = panel.dataPreview();
    EXPECT_TRUE(preview.contains("Rows: 3 read")) << preview.toStdString();
    EXPECT_FALSE(preview.contains("bad")) << preview.toStdString();
    EXPECT_TRUE(preview.contains("Fits: F_x, M_y, h (entry angle solved from the load)"))
        << preview.toStdString();
    // The decoupled fit needs θ_f and F_z: the preview says so before Fit is pressed.
    panel.applySettings({{"refine", false}});
    ASSERT_TRUE(waitForPreview(panel));
    preview = panel.dataPreview();
    EXPECT_TRUE(preview.contains("Cannot be fitted: ")) << preview.toStdString();
    EXPECT_TRUE(preview.contains("entry_angle")) << preview.toStdString();
    // A path that is not a file is said to be one.
    panel.setDataFile(dir.filePath("missing.csv"));
    ASSERT_TRUE(waitForPreview(panel));
    EXPECT_TRUE(panel.dataPreview().startsWith("No such file"))
        << panel.dataPreview().toStdString();
}

TEST(IdentificationPreview, IsInFrontUntilAFitIsShownThenTheParametersAre) {
    identification::SyntheticSpec spec;
    for (int i = 0; i < 30; ++i) spec.slips.push_back(0.03 * i);
    auto soil = io::resolveSoil(test::resources(), "sandy-loam");
    auto wheel = io::resolveWheel(test::resources(), "A");
    ASSERT_TRUE(soil && wheel);
    const auto data =
        identification::synthesize(contact::makeContactParameters(*soil, *wheel), spec).data;
    QTemporaryDir dir;
    const std::string path = writeFile(dir, "good.csv", identification::toCsv(data));
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    auto* side = panel.findChild<QTabWidget*>("identification.side_tabs");
    ASSERT_NE(side, nullptr);
    EXPECT_FALSE(side->isTabVisible(1));
    panel.setDataFile(QString::fromStdString(path));
    EXPECT_TRUE(side->isTabVisible(1));
    EXPECT_EQ(side->currentIndex(), 1);
    ASSERT_TRUE(waitForPreview(panel));
    EXPECT_TRUE(panel.dataPreview().contains("Rows: 30 read")) << panel.dataPreview().toStdString();
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    EXPECT_EQ(side->currentIndex(), 0);           // the parameters of the fit
    EXPECT_FALSE(panel.dataPreview().isEmpty());  // the preview stays one click away
}

TEST(IdentificationPreview, IsReadOffTheGuiThreadAndTheNewestFileWins) {
    QTemporaryDir dir;
    const std::string first = writeFile(dir, "first.csv",
                                        "slip,entry_angle_deg,Fx_N,Fz_N,My_Nm\n"
                                        "0.1,20,5.5,80,1.2\n"
                                        "0.2,21,9.5,80,1.6\n");
    const std::string second = writeFile(dir, "second.csv",
                                         "slip,entry_angle_deg,Fx_N,Fz_N,My_Nm\n"
                                         "0.1,20,5.5,80,1.2\n"
                                         "0.2,21,9.5,80,1.6\n"
                                         "0.3,22,12,80,1.9\n"
                                         "0.4,23,14,80,2.1\n");
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    QSignalSpy shown(&panel, &IdentificationPanel::dataPreviewShown);
    panel.setDataFile(QString::fromStdString(first));
    // setDataFile returned without reading the file: the worker reads it, the GUI thread shows
    // it once the event loop hands the result over.
    EXPECT_TRUE(panel.dataPreviewReading());
    EXPECT_FALSE(panel.dataPreview().contains("Rows:")) << panel.dataPreview().toStdString();
    EXPECT_EQ(shown.count(), 0);
    // Another file before the first is shown: only the newest is ever shown.
    panel.setDataFile(QString::fromStdString(second));
    ASSERT_TRUE(waitForPreview(panel));
    QTest::qWait(50);  // a stale preview would arrive by now
    EXPECT_EQ(shown.count(), 1);
    EXPECT_TRUE(panel.dataPreview().contains("Rows: 4 read")) << panel.dataPreview().toStdString();
    EXPECT_EQ(panel.dataPreviewCell(3, 0), "0.4");
    // Back to synthetic data while a preview is being read: it is dropped, nothing is shown.
    panel.setDataFile(QString::fromStdString(first));
    panel.setDataFile({});
    QTest::qWait(50);
    EXPECT_FALSE(panel.dataPreviewReading());
    EXPECT_EQ(shown.count(), 1);
    EXPECT_TRUE(panel.dataPreview().isEmpty());
}

}  // namespace
}  // namespace terra::ui
