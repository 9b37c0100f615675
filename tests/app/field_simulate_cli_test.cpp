// `terrastudio simulate` on a field (docs/field.md, "Field scenarios"): the maps beside the time
// series, the summary's new keys, and bad rasters refused with exit 2, each named.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;

fs::path tempDir(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("terra_fieldsim_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

using terra::test::readText;

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

// A 4 × 3 grid of 1 m cells from (x0, 0), every value `v` (one cell `odd` when given).
std::string grid(double x0, const std::string& v, const std::string& odd = {}) {
    std::string s = "ncols 4\nnrows 3\nxllcorner " + std::to_string(x0) +
                    "\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n";
    for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 4; ++col)
            s += (row == 1 && col == 2 && !odd.empty() ? odd : v) + (col < 3 ? " " : "\n");
    }
    return s;
}

// A scenario on a small field in `dir` whose rasters the test writes.
void writeScenario(const fs::path& dir) {
    write(dir / "scenario.json", R"({
  "name": "small field", "robot": "default", "duration_s": 1, "time_step_s": 0.001,
  "model": "quadratic", "initial": {"x_m": 1.5, "y_m": 1.5},
  "terrain": {"height": "height.asc", "soils": "soils.asc",
              "legend": {"1": "sandy-loam", "2": "clayey-soil"}},
  "wheels": {"all": {"omega_rad_s": 0.4, "steer_deg": 0}}
})");
}

TEST(FieldSimulateCli, WritesTheMapsAndTheSummarysFieldKeys) {
    const fs::path out = tempDir("maps");
    const auto r = terra::test::run("simulate --scenario field-slope-wet --duration 4 --out " +
                                    out.string() + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["status"], "completed");
    EXPECT_GT(j["real_time_factor"].get<double>(), 0.0);
    EXPECT_GT(j["energy_per_m_J"].get<double>(), 0.0);
    // Four wheels on 0.1 m cells: at least the cells the four centre lines crossed.
    const double distance = j["distance_m"].get<double>();
    EXPECT_GE(j["cells_touched"].get<long>(), 4 * static_cast<long>(distance / 0.1));
    EXPECT_GT(j["max_rut_depth_m"].get<double>(), 0.0);
    for (const char* name : {"rut_depth_m.asc", "passes.asc", "compaction_risk.asc", "slip.asc",
                             "energy_per_m_J.asc"}) {
        const std::string text = readText(out / name);
        // The field's extent (60 m × 40 m from the origin) on the memory's 0.1 m cells.
        EXPECT_EQ(text.rfind("ncols 600\nnrows 400\nxllcorner 0\nyllcorner 0\ncellsize 0.1\n", 0),
                  0u)
            << name << ": " << text.substr(0, 80);
    }
    // Beside each grid its GeoTIFF (little-endian TIFF) and PNG picture, and the run lists them.
    const auto listed =
        terra::test::run("simulate --scenario field-slope-wet --duration 1 --out " + out.string());
    ASSERT_EQ(listed.exit_code, 0) << listed.err;
    for (const char* stem :
         {"rut_depth_m", "passes", "compaction_risk", "slip", "energy_per_m_J"}) {
        const std::string stem_path = (out / stem).string();
        EXPECT_EQ(readText(out / (std::string(stem) + ".tif")).substr(0, 4),
                  std::string("II*\0", 4))
            << stem;
        EXPECT_EQ(readText(out / (std::string(stem) + ".png")).substr(0, 8), "\x89PNG\r\n\x1a\n")
            << stem;
        for (const char* ext : {".asc", ".tif", ".png"})
            EXPECT_NE(listed.out.find(stem_path + ext), std::string::npos) << listed.out;
    }
    // A patch scenario in the same folder afterwards leaves no maps of the field run behind.
    const auto again =
        terra::test::run("simulate --scenario straight --duration 1 --out " + out.string());
    ASSERT_EQ(again.exit_code, 0) << again.err;
    for (const char* name : {"passes.asc", "energy_per_m_J.asc", "passes.tif", "slip.png"})
        EXPECT_FALSE(fs::exists(out / name)) << name;
    fs::remove_all(out);
}

// A mission scenario from the command line: the summary's mission keys and the path columns; a
// bad mission is exit 2 naming the key and its range, and writes nothing.
TEST(FieldSimulateCli, MissionsRunAndBadOnesAreNamed) {
    const fs::path out = tempDir("mission");
    const auto r = terra::test::run(
        "simulate --scenario mission-controlled-traffic --duration 3 "
        "--out " +
        out.string() + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["mission_completed"], false);  // 3 s of a 37 m path
    EXPECT_TRUE(j["mission_time_s"].is_null());
    EXPECT_NEAR(j["path_length_m"].get<double>(), 32.0 + 1.5 * M_PI, 1e-3);
    EXPECT_GT(j["path_progress_m"].get<double>(), 1.0);
    EXPECT_LT(j["path_error_max_m"].get<double>(), 0.02);
    EXPECT_NE(readText(out / "timeseries.csv").find("path_s_m,path_error_m,curvature_1_m"),
              std::string::npos);
    EXPECT_TRUE(fs::exists(out / "slip.asc"));
    fs::remove_all(out);

    struct Case {
        const char* mission;
        const char* expected;
    };
    const Case cases[] = {
        {R"({"lanes": {"start": [0, 0], "heading_deg": 0, "length_m": 5, "spacing_m": 2,
             "count": 2, "turn_radius_m": 1.5}, "speed_m_s": 0.5})",
         "mission.lanes.turn_radius_m: 1.5 m is more than half the spacing (2 m): the turn would "
         "overshoot the next lane; allowed range [0.05, 1] m"},
        {R"({"waypoints": [[0, 0], [1, 0]], "speed_m_s": 20})",
         "mission.speed_m_s: 20 is outside the allowed range (0, 10] m/s"},
        {R"({"waypoints": [[0, 0], [1, 0]], "speed_m_s": 0.5, "lookahead_m": -1})",
         "mission.lookahead_m"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.mission);
        const fs::path dir = tempDir("badmission");
        write(dir / "scenario.json", std::string(R"({"name": "m", "duration_s": 1,
            "time_step_s": 0.001, "terrain": "sandy-loam", "mission": )") +
                                         c.mission + "}");
        const auto bad =
            terra::test::run("simulate --scenario " + (dir / "scenario.json").string() + " --out " +
                             (dir / "out").string());
        EXPECT_EQ(bad.exit_code, 2) << bad.err;
        EXPECT_NE(bad.err.find(c.expected), std::string::npos) << bad.err;
        EXPECT_FALSE(fs::exists(dir / "out" / "summary.json"));
        fs::remove_all(dir);
    }
}

TEST(FieldSimulateCli, BadRastersAreRefusedByName) {
    struct Case {
        const char* what;
        std::string height, soils, prj_height, prj_soils;
        const char* expected;
    };
    const std::string flat = grid(0, "0"), classes = grid(0, "1", "2");
    const Case cases[] = {
        {"no height in a cell", grid(0, "0", "-9999"), classes, "", "", "has no height"},
        {"a class not in the legend", flat, grid(0, "1", "7"), "", "",
         "class 7 (1 cell) has no entry in the legend"},
        {"sizes that do not match", flat, grid(1, "1"), "", "",
         "the maps must cover the same ground"},
        {"another coordinate system", flat, classes, "PROJCS[\"ETRS89 / UTM 32N\"]",
         "PROJCS[\"WGS 84 / UTM 33N\"]", "coordinate system (.prj) differs"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        const fs::path dir = tempDir("bad");
        writeScenario(dir);
        write(dir / "height.asc", c.height);
        write(dir / "soils.asc", c.soils);
        if (!c.prj_height.empty()) write(dir / "height.prj", c.prj_height);
        if (!c.prj_soils.empty()) write(dir / "soils.prj", c.prj_soils);
        const auto r = terra::test::run("simulate --scenario " + (dir / "scenario.json").string() +
                                        " --out " + (dir / "out").string());
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("terrain"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir / "out" / "summary.json"));
        fs::remove_all(dir);
    }
    // The good small field runs.
    const fs::path dir = tempDir("good");
    writeScenario(dir);
    write(dir / "height.asc", flat);
    write(dir / "soils.asc", classes);
    const auto r = terra::test::run("simulate --scenario " + (dir / "scenario.json").string() +
                                    " --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "out" / "passes.asc"));
    fs::remove_all(dir);
}

}  // namespace
