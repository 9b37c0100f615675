// `terrastudio field` through the real executable (docs/field.md): the summary of the shipped
// fields against what their generator drew, the slope map, and bad fields named (exit 2).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../core/test_temp_dir.h"
#include "cli_runner.h"

namespace {

using nlohmann::json;
using terra::test::CliRun;
using terra::test::run;

const std::string kFields = std::string(TERRA_RESOURCE_DIR) + "/fields/";

// The controlled-traffic field's lanes are 0.6 m of every 3 m: a share of 0.2 exactly, 240 m² of
// its 40 m × 30 m.
TEST(FieldCli, ControlledTrafficLanesCoverAFifth) {
    const CliRun r = run("field " + kFields + "controlled-traffic/field.json --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json out = json::parse(r.out);
    EXPECT_EQ(out["extent_m"], json({0.0, 0.0, 40.0, 30.0}));
    EXPECT_TRUE(out["height_m"].is_null());
    ASSERT_EQ(out["classes"].size(), 2u);
    EXPECT_EQ(out["classes"][1]["label"], "traffic lane");
    EXPECT_NEAR(out["classes"][1]["share"].get<double>(), 0.6 / 3.0, 1e-12);
    EXPECT_NEAR(out["classes"][1]["area_m2"].get<double>(), 0.2 * 40 * 30, 1e-9);
}

// The sloped field rises 8 % along x and 3 % across: away from its hollow the slope is
// atan √(0.08² + 0.03²) = 4.889°, and the hollow's flanks are steeper.
TEST(FieldCli, SlopeMapOfTheSlopedField) {
    terra::testing::TempDir dir;
    const std::string map = (dir.path() / "slope.asc").string();
    const CliRun r = run("field " + kFields + "sloped-wet/field.json --slope-map " + map);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("wet hollow"), std::string::npos) << r.out;
    std::ifstream in(map);
    std::string key;
    double value = 0.0;
    int cols = 0;
    for (int i = 0; i < 6; ++i) {
        in >> key >> value;
        if (key == "ncols") cols = static_cast<int>(value);
    }
    EXPECT_EQ(cols, 120);
    const double plane_deg = std::atan(std::hypot(0.08, 0.03)) * 180.0 / M_PI;
    double first = 0.0, largest = 0.0;
    in >> first;  // the north-west corner: far from the hollow
    largest = first;
    while (in >> value) largest = std::max(largest, value);
    EXPECT_NEAR(first, plane_deg, 1e-3);
    EXPECT_GT(largest, plane_deg + 1.0);
}

// The traversability table: one row per cell and heading with the interface's columns; the JSON
// counts agree with the table's statuses; a bad --headings is named with its range.
TEST(FieldCli, TraversabilityTableAndSummaryAgree) {
    terra::testing::TempDir dir;
    const std::string csv = (dir.path() / "t.csv").string();
    const CliRun r =
        run("field " + kFields + "sloped-wet/field.json --robot wheel-b --headings 4 " +
            "--cell 2 --traversability " + csv + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json out = json::parse(r.out)["traversability"];
    EXPECT_EQ(out["cells"], 30 * 20);
    std::ifstream in(csv);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "x_m,y_m,heading_deg,grade_deg,slip,status");
    int rows = 0, stalled_uphill = 0;
    while (std::getline(in, line)) {
        ++rows;
        // x_m, y_m, heading_deg, grade_deg, slip, status: heading 0 and status 1 (stall).
        std::vector<std::string> cells;
        std::stringstream row(line);
        for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
        ASSERT_EQ(cells.size(), 6u) << line;
        if (cells[2] == "0" && cells[5] == "1") ++stalled_uphill;
    }
    EXPECT_EQ(rows, 30 * 20 * 4);
    EXPECT_EQ(out["headings"][0]["stalled"].get<int>(), stalled_uphill);
    const CliRun bad =
        run("field " + kFields + "sloped-wet/field.json --traversability " + csv + " --headings 0");
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("--headings: 0 is outside the allowed range [1, 360]"),
              std::string::npos)
        << bad.err;
}

TEST(FieldCli, BadFieldsAreNamed) {
    terra::testing::TempDir dir;
    std::ofstream(dir.path() / "c.asc") << "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\n"
                                           "cellsize 1\n1 9\n";
    std::ofstream(dir.path() / "f.json")
        << R"({"soil": "sandy-loam", "soil_classes": "c.asc", "legend": {"1": "sandy-loam"}})";
    const CliRun r = run("field " + (dir.path() / "f.json").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("class 9 (1 cell) has no entry in the legend"), std::string::npos)
        << r.err;
    std::ofstream(dir.path() / "g.json") << R"({"soil": "sandy-loam"})";
    const CliRun flat = run("field " + (dir.path() / "g.json").string() + " --slope-map " +
                            (dir.path() / "x.asc").string());
    EXPECT_EQ(flat.exit_code, 2);
    EXPECT_NE(flat.err.find("has no height map"), std::string::npos) << flat.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "x.asc"));
}

}  // namespace
