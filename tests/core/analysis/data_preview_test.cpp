// The identification's preview of a CSV (core/analysis/data_preview.h) on small files written
// here: the rows as typed with their line numbers, the columns read and ignored, the rows read and
// each bad row by line, and the full model's channels and source of θ_f.
#include "core/analysis/data_preview.h"

#include <gtest/gtest.h>

#include <fstream>

#include "tests/core/test_support.h"
#include "tests/core/test_temp_dir.h"

namespace terra::analysis {
namespace {

using terra::testing::contains;
using terra::testing::TempDir;
namespace id = identification;

std::filesystem::path writePreviewCsv(const TempDir& dir, const char* name,
                                      const std::string& text) {
    const std::filesystem::path path = dir.path() / name;
    std::ofstream(path) << text;
    return path;
}

TEST(DataPreview, KeepsTheFirstRowsAsTypedAndListsEveryBadRowByLine) {
    TempDir dir;
    // Line 1 the header; line 3 blank (counted, not shown); line 7 has "abc" for θ_f; probe_id is
    // not a data column.
    const auto path = writePreviewCsv(dir, "drive.csv",
                                      "slip,entry_angle_deg,Fx_N,Fz_N,My_Nm,probe_id\n"
                                      "0.1, 20 ,5.5,80,1.2,7\n"
                                      "\n"
                                      "0.2,21,9.5,80,1.6,7\n"
                                      "0.3,22,12,80,1.9,7\n"
                                      "0.4,23,14,80,2.1,7\n"
                                      "0.45,abc,15,80,2.2,7\n"
                                      "0.5,24,16,80,2.3,7\n"
                                      "0.6,25,17,80,2.4,7\n");
    const DataPreview p = previewDataFile(path, id::ColumnNeeds::kFullModel);
    ASSERT_TRUE(p.readable);
    EXPECT_EQ(p.header, (std::vector<std::string>{"slip", "entry_angle_deg", "Fx_N", "Fz_N",
                                                  "My_Nm", "probe_id"}));
    EXPECT_EQ(p.known_columns,
              (std::vector<std::string>{"slip", "entry_angle_deg", "Fx_N", "Fz_N", "My_Nm"}));
    EXPECT_EQ(p.ignored_columns, std::vector<std::string>{"probe_id"});
    ASSERT_EQ(p.rows.size(), 5U);
    EXPECT_EQ(p.rows[0].line, 2);
    EXPECT_EQ(p.rows[0].cells, (std::vector<std::string>{"0.1", "20", "5.5", "80", "1.2", "7"}));
    EXPECT_EQ(p.rows[1].line, 4);  // after the blank line 3
    EXPECT_EQ(p.rows[4].line, 7);
    EXPECT_EQ(p.rows[4].cells[1], "abc");
    // Seven data rows, one bad: six read, the bad one at line 7.
    EXPECT_TRUE(p.read_error.empty()) << p.read_error;
    EXPECT_EQ(p.samples, 6U);
    ASSERT_EQ(p.bad_rows.size(), 1U);
    EXPECT_TRUE(p.bad_rows[0].where.ends_with(":7")) << p.bad_rows[0].where;
    // θ_f measured: F_x, F_z and M_y are compared, not the sinkage (no such column).
    ASSERT_TRUE(p.setup.has_value()) << p.setup_error;
    EXPECT_EQ(p.setup->source, id::DataSource::kEntryAngle);
    EXPECT_EQ(p.setup->channels, (std::array<bool, id::kChannelCount>{true, true, true, false}));

    // The decoupled fit reads the same rows; it has no model setup to preview.
    const DataPreview decoupled = previewDataFile(path, id::ColumnNeeds::kDecoupled, 2);
    EXPECT_EQ(decoupled.samples, 6U);
    EXPECT_EQ(decoupled.rows.size(), 2U);
    EXPECT_FALSE(decoupled.setup.has_value());
    EXPECT_TRUE(decoupled.setup_error.empty());
}

TEST(DataPreview, DataWithoutAnEntryAngleAreFittedFromTheLoadOrNotAtAllByTheDecoupledFit) {
    TempDir dir;
    const auto path = writePreviewCsv(dir, "loads.csv",
                                      "slip,W_N,Fx_N,My_Nm,sinkage_m\n"
                                      "0.1,80,5.5,1.2,0.010\n"
                                      "0.3,80,12,1.9,0.013\n"
                                      "0.5,80,16,2.3,0.016\n");
    const DataPreview full = previewDataFile(path, id::ColumnNeeds::kFullModel);
    EXPECT_EQ(full.samples, 3U);
    EXPECT_TRUE(full.bad_rows.empty());
    EXPECT_TRUE(full.ignored_columns.empty());
    ASSERT_TRUE(full.setup.has_value()) << full.setup_error;
    EXPECT_EQ(full.setup->source, id::DataSource::kLoad);
    // No F_z column and θ_f solved from W: F_x, M_y and the sinkage.
    EXPECT_EQ(full.setup->channels, (std::array<bool, id::kChannelCount>{true, false, true, true}));

    const DataPreview decoupled = previewDataFile(path, id::ColumnNeeds::kDecoupled);
    EXPECT_TRUE(decoupled.readable);
    EXPECT_EQ(decoupled.rows.size(), 3U);  // the rows as typed are shown all the same
    EXPECT_TRUE(contains(decoupled.read_error, "entry_angle")) << decoupled.read_error;
    EXPECT_EQ(decoupled.samples, 0U);
}

TEST(DataPreview, AMissingFileIsNotReadableAndDataWithNeitherAngleNorLoadCannotBeFitted) {
    TempDir dir;
    EXPECT_FALSE(previewDataFile(dir.path() / "missing.csv", id::ColumnNeeds::kFullModel).readable);
    EXPECT_FALSE(previewDataFile(dir.path(), id::ColumnNeeds::kFullModel).readable);
    // Neither θ_f nor a load: the file reads, but the full model cannot be set up, and says why.
    const DataPreview no_load = previewDataFile(
        writePreviewCsv(dir, "no_load.csv", "slip,Fx_N\n0.1,5\n"), id::ColumnNeeds::kFullModel);
    EXPECT_TRUE(no_load.readable);
    EXPECT_TRUE(no_load.read_error.empty()) << no_load.read_error;
    EXPECT_EQ(no_load.samples, 1U);
    EXPECT_FALSE(no_load.setup.has_value());
    EXPECT_TRUE(contains(no_load.setup_error, "load")) << no_load.setup_error;
}

}  // namespace
}  // namespace terra::analysis
