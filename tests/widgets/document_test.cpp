// The project document: one undo command per setter, none when unchanged, refusal of invalid
// values, save → load round trip.
#include <gtest/gtest.h>

#include <QFile>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QUndoStack>

#include "core/common/units.h"
#include "widgets/document/project_document.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

TEST(ProjectDocument, EditIsOneUndoableCommandAndUnchangedValuePushesNothing) {
    ProjectDocument document;
    test::resetToDefault(document);
    const double phi_before = document.project().soil.friction_angle_rad;
    QSignalSpy changed(&document, &ProjectDocument::soilChanged);
    const int revision = document.revision();

    ASSERT_TRUE(document.setSoilValue("phi_deg", 35.0));
    EXPECT_NEAR(document.project().soil.friction_angle_rad, units::degToRad(35.0), 1e-12);
    EXPECT_EQ(document.undoStack()->count(), 1);
    EXPECT_EQ(changed.count(), 1);
    EXPECT_GT(document.revision(), revision);
    EXPECT_TRUE(document.isModified());

    ASSERT_TRUE(document.setSoilValue("phi_deg", 35.0));  // unchanged: nothing pushed
    EXPECT_EQ(document.undoStack()->count(), 1);
    EXPECT_EQ(changed.count(), 1);

    document.undoStack()->undo();
    EXPECT_DOUBLE_EQ(document.project().soil.friction_angle_rad, phi_before);
    EXPECT_FALSE(document.isModified());
    document.undoStack()->redo();
    EXPECT_NEAR(document.project().soil.friction_angle_rad, units::degToRad(35.0), 1e-12);
}

TEST(ProjectDocument, RepeatedEditsOfOneFieldMergeButDifferentFieldsDoNot) {
    ProjectDocument document;
    test::resetToDefault(document);
    const double c_before = document.project().soil.cohesion_pa;
    for (double c : {2.0, 2.5, 3.0}) ASSERT_TRUE(document.setSoilValue("c_kPa", c));
    EXPECT_EQ(document.undoStack()->count(), 1);  // a slider drag is one undo step
    ASSERT_TRUE(document.setLoad(80.0));
    EXPECT_EQ(document.undoStack()->count(), 2);
    document.undoStack()->undo();
    EXPECT_DOUBLE_EQ(document.project().conditions.load_n, 58.86);
    document.undoStack()->undo();
    EXPECT_DOUBLE_EQ(document.project().soil.cohesion_pa, c_before);
}

TEST(ProjectDocument, InvalidValuesNeverReachTheModel) {
    ProjectDocument document;
    test::resetToDefault(document);
    const Project before = document.project();
    EXPECT_FALSE(document.setSoilValue("phi_deg", 75.0));  // range [0, 60)
    EXPECT_FALSE(document.setSoilValue("phi_deg", 60.0));  // open upper end
    EXPECT_FALSE(document.setSoilValue("K_m", 0.0));       // (0, 0.5]
    EXPECT_FALSE(document.setSoilValue("n", std::nan("")));
    EXPECT_FALSE(document.setSoilValue("no_such_field", 1.0));
    EXPECT_FALSE(document.setWheelValue("r_m", -0.1));
    EXPECT_FALSE(document.setLoad(0.0));
    EXPECT_FALSE(document.setSlipAngles({}));
    EXPECT_TRUE(document.project() == before);
    EXPECT_EQ(document.undoStack()->count(), 0);
}

TEST(ProjectDocument, SaveThenLoadGivesTheSameProject) {
    QTemporaryDir dir;
    ProjectDocument document;
    test::resetToDefault(document);
    ASSERT_TRUE(document.setSoilValue("c_kPa", 2.25));
    ASSERT_TRUE(document.setWheelValue("b_m", 0.15));
    ASSERT_TRUE(document.setLoad(73.5));
    ASSERT_TRUE(document.setSlipAngles({0.0, 12.5}));
    ASSERT_TRUE(document.setQuadraticModel(true));
    ASSERT_TRUE(document.addDataSet("/data/run1.csv"));
    document.setPanelSettings("stresses", {{"slip", 0.4}});
    const QString path = dir.filePath("session.terra");
    QString error;
    ASSERT_TRUE(document.save(path, &error)) << error.toStdString();
    EXPECT_FALSE(document.isModified());
    EXPECT_EQ(document.filePath(), path);

    const auto loaded = ProjectDocument::load(path);
    ASSERT_TRUE(loaded.ok()) << loaded.message();
    EXPECT_TRUE(*loaded == document.project());
    EXPECT_DOUBLE_EQ(loaded->soil.cohesion_pa, 2250.0);
    EXPECT_DOUBLE_EQ(loaded->wheel.width_m, 0.15);
    EXPECT_EQ(loaded->conditions.slip_angles_deg, (std::vector<double>{0.0, 12.5}));
    EXPECT_TRUE(loaded->conditions.quadratic);
    EXPECT_EQ(loaded->panels["stresses"]["slip"].get<double>(), 0.4);

    // The file is readable JSON with unit-suffixed keys.
    QFile file(path);
    ASSERT_TRUE(file.open(QIODevice::ReadOnly));
    const QByteArray text = file.readAll();
    EXPECT_TRUE(text.contains("\"c_kPa\": 2.25"));
    EXPECT_TRUE(text.contains("\"load_N\": 73.5"));
}

TEST(ProjectDocument, FailedSaveKeepsTheDocumentModifiedAndBadFilesAreReported) {
    QTemporaryDir dir;
    ProjectDocument document;
    test::resetToDefault(document);
    ASSERT_TRUE(document.setLoad(70.0));
    QString error;
    EXPECT_FALSE(document.save(dir.filePath("missing/dir/x.terra"), &error));
    EXPECT_FALSE(error.isEmpty());
    EXPECT_TRUE(document.isModified());

    const QString bad = dir.filePath("bad.terra");
    QFile file(bad);
    ASSERT_TRUE(file.open(QIODevice::WriteOnly));
    file.write(
        R"({"format": "terrastudio-project", "conditions": {"load_N": -5, "model": "magic"}})");
    file.close();
    const auto loaded = ProjectDocument::load(bad);
    ASSERT_FALSE(loaded.ok());
    EXPECT_NE(loaded.message().find("load_N"), std::string::npos) << loaded.message();
    EXPECT_NE(loaded.message().find("magic"), std::string::npos) << loaded.message();
}

// An edited scenario lives in the panel settings: changing them must make a close ask and the
// autosave run, and a save must clear it.
TEST(ProjectDocument, PanelSettingsChangeMarksTheProjectModifiedUntilSaved) {
    QTemporaryDir dir;
    ProjectDocument document;
    test::resetToDefault(document);
    ASSERT_FALSE(document.isModified());
    QSignalSpy modified(&document, &ProjectDocument::modifiedChanged);
    const nlohmann::json edited = {{"scenario", "straight"},
                                   {"edited", {{"straight", {{"duration_s", 5.0}}}}}};
    document.setPanelSettings("rover", edited);
    EXPECT_TRUE(document.isModified());
    ASSERT_EQ(modified.count(), 1);
    EXPECT_TRUE(modified.at(0).at(0).toBool());
    document.setPanelSettings("rover", edited);  // unchanged: nothing new
    EXPECT_EQ(modified.count(), 1);

    QString error;
    ASSERT_TRUE(document.save(dir.filePath("p.terra"), &error)) << error.toStdString();
    EXPECT_FALSE(document.isModified());
    ASSERT_EQ(modified.count(), 2);
    EXPECT_FALSE(modified.at(1).at(0).toBool());
    const auto loaded = ProjectDocument::load(dir.filePath("p.terra"));
    ASSERT_TRUE(loaded.ok()) << loaded.message();
    EXPECT_EQ(loaded->panels["rover"], edited);

    // Set back to what was saved: no change left, no "*" (issue 27).
    document.setPanelSettings("rover", {{"scenario", "pulse-steering"}});
    EXPECT_TRUE(document.isModified());
    document.setPanelSettings("rover", edited);
    EXPECT_FALSE(document.isModified());
    ASSERT_EQ(modified.count(), 4);
    EXPECT_FALSE(modified.at(3).at(0).toBool());
}

}  // namespace
}  // namespace terra::ui
