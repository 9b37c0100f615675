// .terra files read strictly: what the studio writes reads back the same; what is wrong is
// named, panels' settings included.
#include "core/project/project.h"

#include <gtest/gtest.h>

#include "core/io/atomic_file.h"
#include "core/io/json.h"
#include "core/project/panels.h"
#include "tests/core/test_support.h"
#include "tests/core/test_temp_dir.h"

namespace terra::project {
namespace {

using nlohmann::json;

using terra::testing::kLocations;

using terra::testing::contains;

Project sandyLoam() {
    Project p;
    p.soil = io::resolveSoil(kLocations, "sandy-loam").value();
    p.wheel = io::resolveWheel(kLocations, "A").value();
    return p;
}

TEST(ProjectFile, WhatIsWrittenReadsBackTheSame) {
    Project p = sandyLoam();
    p.conditions.load_n = 73.5;
    p.conditions.quadratic = true;
    p.data_sets = {"a.csv"};
    StressPanelSettings stresses;
    stresses.analysis.slip = 0.25;
    p.panels["stresses"] = toJson(stresses);
    p.panels["rover"] = toJson(RoverPanelSettings{"straight", json::object()});
    const Result<Project> back = projectFromJson(toJson(p), "p.terra", &kLocations);
    ASSERT_TRUE(back.ok()) << back.message();
    EXPECT_TRUE(back.value() == p);
    EXPECT_EQ(back->conditions.load_n, 73.5);
    EXPECT_EQ(inputsOf(*back).conditions.load_n, 73.5);
}

TEST(ProjectFile, ProblemsAreNamedPanelsIncluded) {
    json j = toJson(sandyLoam());
    j["conditions"]["slip_count"] = 1e308;
    j["soil"]["phi_deg"] = "29";
    j["scenarioz"] = json::array();
    j["panels"]["stresses"] = {{"slip", 2}};
    j["panels"]["sensitivity"] = {{"plot", "Fz"}};
    j["panels"]["rover"] = {{"edited", {{"straight", {{"duration_s", 5}}}}}};
    j["panels"]["charts"] = json::object();
    const Result<Project> p = projectFromJson(j, "p.terra", &kLocations);
    ASSERT_FALSE(p.ok());
    const std::string m = p.message();
    for (const char* part :
         {"p.terra: conditions.slip_count: 1e+308 is outside the allowed range",
          "p.terra: soil.phi_deg: expected a number", "scenarioz: unknown key",
          "did you mean \"scenarios\"?", "panels.stresses.slip: 2 is outside",
          "panels.sensitivity.plot: \"Fz\" is not one of Fx, Fs, tornado",
          "panels.rover.edited.straight: ", "terrain: missing", "panels.charts: unknown key"}) {
        EXPECT_TRUE(contains(m, part)) << part << "\n" << m;
    }
}

TEST(ProjectFile, NotAProjectAndNewerVersions) {
    EXPECT_FALSE(projectFromJson(json::object(), "x", nullptr).ok());
    json j = toJson(Project{});
    j["version"] = 2;
    const Result<Project> p = projectFromJson(j, "x", nullptr);
    ASSERT_FALSE(p.ok());
    EXPECT_TRUE(contains(p.message(), "version: 2 is outside the allowed range [1, 1]"))
        << p.message();
}

// The measured test (core/io/experiment.h) is an optional key of version 1: a project with one
// reads back with it, a project without one is written without the key (the file of the studios
// before it, which reject unknown keys), and a file of those studios reads as "no test".
TEST(ProjectFile, TheExperimentIsAnOptionalReferenceOfVersionOne) {
    Project p = sandyLoam();
    EXPECT_FALSE(toJson(p).contains("experiment"));
    p.experiment = "../experiments/ding2011-smooth-hit-lss1-80N.json";
    const json written = toJson(p);
    EXPECT_EQ(written["version"], 1);
    EXPECT_EQ(written["experiment"], "../experiments/ding2011-smooth-hit-lss1-80N.json");
    const Result<Project> back = projectFromJson(written, "p.terra", &kLocations);
    ASSERT_TRUE(back.ok()) << back.message();
    EXPECT_EQ(back->experiment, p.experiment);
    EXPECT_TRUE(back.value() == p);

    // A version-1 file written before the key existed: every key but "experiment".
    json old = toJson(sandyLoam());
    ASSERT_FALSE(old.contains("experiment"));
    const Result<Project> read = projectFromJson(old, "old.terra", &kLocations);
    ASSERT_TRUE(read.ok()) << read.message();
    EXPECT_TRUE(read->experiment.empty());

    // Only the reference is read: a test file that does not exist does not stop the project.
    old["experiment"] = "no/such/test.csv";
    EXPECT_TRUE(projectFromJson(old, "p.terra", &kLocations).ok());
    old["experiment"] = 3;
    const Result<Project> bad = projectFromJson(old, "p.terra", &kLocations);
    ASSERT_FALSE(bad.ok());
    EXPECT_TRUE(contains(bad.message(), "p.terra: experiment: expected a string")) << bad.message();
}

TEST(ProjectFile, DuplicatedKeysInTheFileAreErrors) {
    const Result<json> parsed = io::parseJson(
        "{\"format\": \"terrastudio-project\", \"conditions\": {\"load_N\": 1, "
        "\"load_N\": 2}}",
        "p.terra");
    ASSERT_FALSE(parsed.ok());
    EXPECT_TRUE(contains(parsed.message(), "duplicated key \"load_N\" in conditions"));
}

// Issue 27: the .terra file stored absolute paths, so a project folder could not be moved.
TEST(ProjectFile, PathsInsideTheProjectFolderAreWrittenRelative) {
    Project p = sandyLoam();
    p.data_sets = {"/home/ana/field/data/run1.csv", "/opt/terra/share/drive.csv"};
    p.experiment = "/home/ana/field/tests/ding.csv";
    p.panels["identification"] = json{{"csv", "/home/ana/field/data/run1.csv"}, {"stream_csv", ""}};
    p.scenarios = {"/home/ana/field/runs/a.json"};
    p.panels["rover"] = json{{"scenario", "/home/ana/field/runs/a.json"},
                             {"edited",
                              {{"/home/ana/field/runs/a.json", json{{"duration_s", 2}}},
                               {"straight", json{{"duration_s", 3}}}}}};
    const Project written = withRelativePaths(p, "/home/ana/field");
    EXPECT_EQ(written.scenarios[0], "runs/a.json");
    EXPECT_EQ(written.panels["rover"]["scenario"], "runs/a.json");
    EXPECT_EQ(written.panels["rover"]["edited"]["runs/a.json"]["duration_s"], 2);
    EXPECT_EQ(written.panels["rover"]["edited"]["straight"]["duration_s"], 3);  // a preset's name
    Project preset = p;
    preset.panels["rover"]["scenario"] = "straight";
    EXPECT_EQ(withAbsolutePaths(withRelativePaths(preset, "/home/ana/field"), "/mnt/usb/field")
                  .panels["rover"]["scenario"],
              "straight");
    EXPECT_EQ(written.data_sets[0], "data/run1.csv");
    EXPECT_EQ(written.data_sets[1], "/opt/terra/share/drive.csv");  // outside: kept
    EXPECT_EQ(written.experiment, "tests/ding.csv");
    EXPECT_EQ(written.panels["identification"]["csv"], "data/run1.csv");
    EXPECT_EQ(written.panels["identification"]["stream_csv"], "");
    // Read from the folder's new place, relative names follow it; absolute ones stay.
    const Project moved = withAbsolutePaths(written, "/mnt/usb/field");
    EXPECT_EQ(moved.data_sets[0], "/mnt/usb/field/data/run1.csv");
    EXPECT_EQ(moved.data_sets[1], "/opt/terra/share/drive.csv");
    EXPECT_EQ(moved.experiment, "/mnt/usb/field/tests/ding.csv");
    EXPECT_EQ(moved.panels["identification"]["csv"], "/mnt/usb/field/data/run1.csv");
    EXPECT_EQ(moved.scenarios[0], "/mnt/usb/field/runs/a.json");
    EXPECT_EQ(moved.panels["rover"]["scenario"], "/mnt/usb/field/runs/a.json");
    EXPECT_EQ(moved.panels["rover"]["edited"]["/mnt/usb/field/runs/a.json"]["duration_s"], 2);
    // A scenario file's suffix in any case is a file; a preset's name never is.
    EXPECT_TRUE(isScenarioFileName("/home/ana/field/Run.JSON"));
    EXPECT_TRUE(isScenarioFileName("runs/a.json"));
    EXPECT_FALSE(isScenarioFileName("straight"));
    EXPECT_FALSE(isScenarioFileName("json"));
    Project upper = p;
    upper.panels["rover"] = json{{"scenario", "/home/ana/field/runs/B.Json"}};
    EXPECT_EQ(withRelativePaths(upper, "/home/ana/field").panels["rover"]["scenario"],
              "runs/B.Json");
    // A sibling folder with the same prefix is not inside.
    EXPECT_EQ(withRelativePaths(p, "/home/ana/fie").data_sets[0], "/home/ana/field/data/run1.csv");
}

// Issue 27: a robot file dropped onto the window is kept in the scenario's edit; inside the
// project's folder it is written relative and follows a moved folder, like the scenario files.
TEST(ProjectFile, ADroppedRobotFileInTheProjectFolderIsWrittenRelative) {
    Project p = sandyLoam();
    p.panels["rover"] =
        json{{"scenario", "straight"},
             {"edited",
              {{"straight", json{{"duration_s", 3}, {"robot", "/home/ana/field/robots/r2.json"}}},
               {"counter-steer", json{{"robot", "/opt/robots/big.JSON"}}},
               {"pulse-steering", json{{"robot", "default"}}},
               {"soil-border", json{{"robot", json{{"wheelbase_m", 0.6}}}}}}}};
    const Project written = withRelativePaths(p, "/home/ana/field");
    const json& edited = written.panels["rover"]["edited"];
    EXPECT_EQ(edited["straight"]["robot"], "robots/r2.json");
    EXPECT_EQ(edited["straight"]["duration_s"], 3);
    EXPECT_EQ(edited["counter-steer"]["robot"], "/opt/robots/big.JSON");  // outside: kept
    EXPECT_EQ(edited["pulse-steering"]["robot"], "default");              // a preset's name
    EXPECT_EQ(edited["soil-border"]["robot"]["wheelbase_m"], 0.6);        // an object
    const Project reopened = withAbsolutePaths(written, "/mnt/usb/field");
    const json& moved = reopened.panels["rover"]["edited"];
    EXPECT_EQ(moved["straight"]["robot"], "/mnt/usb/field/robots/r2.json");
    EXPECT_EQ(moved["counter-steer"]["robot"], "/opt/robots/big.JSON");
    EXPECT_EQ(moved["pulse-steering"]["robot"], "default");
}

// The file itself: a project whose rover edit names its robot relative to the project's folder
// opens (the edit is checked as a scenario with the robot read from that folder, not from the
// working directory), and the robot resolves in the folder the project was moved to.
TEST(ProjectFile, AProjectWithARelativeRobotOpensFromItsMovedFolder) {
    const testing::TempDir dir;
    const std::filesystem::path folder = dir.path() / "moved-project";
    std::filesystem::create_directories(folder / "robots");
    std::filesystem::copy_file(std::filesystem::path(TERRA_RESOURCE_DIR) / "robots/default.json",
                               folder / "robots/r2.json");
    json straight =
        io::readJsonFile(std::filesystem::path(TERRA_RESOURCE_DIR) / "scenarios/straight.json")
            .value();
    straight["robot"] = "robots/r2.json";
    Project p = sandyLoam();
    p.panels["rover"] = json{{"scenario", "straight"}, {"edited", {{"straight", straight}}}};
    ASSERT_FALSE(io::writeFileAtomically(folder / "p.terra", toJson(p).dump(2)));
    const Result<Project> opened = loadProject(folder / "p.terra", &kLocations);
    ASSERT_TRUE(opened.ok()) << opened.message();
    const Project absolute = withAbsolutePaths(*opened, folder);
    EXPECT_EQ(absolute.panels["rover"]["edited"]["straight"]["robot"],
              (folder / "robots/r2.json").generic_string());
    // Without its robot file the project is refused, the robot named.
    std::filesystem::remove(folder / "robots/r2.json");
    const Result<Project> missing = loadProject(folder / "p.terra", &kLocations);
    ASSERT_FALSE(missing.ok());
    EXPECT_TRUE(contains(missing.message(), "r2.json")) << missing.message();
}

}  // namespace
}  // namespace terra::project
