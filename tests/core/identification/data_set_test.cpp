#include "core/identification/data_set.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/core/test_support.h"

namespace terra::identification {
namespace {

using terra::testing::kDeg;

TEST(DataSet, ReadsNamedColumnsInAnyOrderAndIgnoresExtras) {
    const std::string text =
        "My_Nm,note,slip,Fz_N,entry_angle_deg,Fx_N,W_N\n"
        "0.55,a,0.3,58.86,16.8,-1.8,58.86\n"
        "0.60,b,0.4,58.86,17.0,-0.5,\n";
    const auto read = parseDataSet(text, "d.csv", BadRows::kStop);
    ASSERT_TRUE(read.ok()) << read.message();
    const auto& samples = read->data.samples;
    ASSERT_EQ(samples.size(), 2u);
    EXPECT_EQ(samples[0].slip, 0.3);
    EXPECT_NEAR(samples[0].entry_angle_rad, 16.8 * kDeg, 1e-15);
    EXPECT_EQ(samples[0].fx_n, -1.8);
    EXPECT_EQ(samples[0].fz_n, 58.86);
    EXPECT_EQ(samples[0].my_nm, 0.55);
    EXPECT_EQ(samples[0].load_n, 58.86);
    EXPECT_FALSE(samples[1].load_n.has_value());  // empty optional cell
    EXPECT_FALSE(samples[0].fy_n.has_value());
}

TEST(DataSet, AcceptsRadians) {
    const auto read = parseDataSet("slip,entry_angle_rad,Fx_N,Fz_N,My_Nm\n0.1,0.3,1,2,3\n", "r.csv",
                                   BadRows::kStop);
    ASSERT_TRUE(read.ok()) << read.message();
    EXPECT_EQ(read->data.samples[0].entry_angle_rad, 0.3);
}

TEST(DataSet, BadRowsAreReportedByLineAndCanBeSkipped) {
    const std::string text =
        "slip,entry_angle_deg,Fx_N,Fz_N,My_Nm\n"  // 1
        "0.1,20,1,2,3\n"                          // 2 good
        "abc,20,1,2,3\n"                          // 3 non-numeric
        "0.2,nan,1,2,3\n"                         // 4 NaN
        "1.2,20,1,2,3\n"                          // 5 slip outside [−1, 1]
        "0.3,95,1,2,3\n"                          // 6 θ_f outside (0, 90)
        "0.4,20,1\n"                              // 7 short row
        "0.5,25,1,2,3\n";                         // 8 good
    const auto stop = parseDataSet(text, "d.csv", BadRows::kStop);
    ASSERT_FALSE(stop.ok());
    ASSERT_EQ(stop.issues().size(), 5u) << stop.message();
    std::string all = stop.message();
    for (const char* line : {"d.csv:3", "d.csv:4", "d.csv:5", "d.csv:6", "d.csv:7"}) {
        EXPECT_NE(all.find(line), std::string::npos) << line << "\n" << all;
    }
    EXPECT_NE(all.find("slip"), std::string::npos);
    EXPECT_NE(all.find("entry_angle_deg"), std::string::npos);

    const auto skip = parseDataSet(text, "d.csv", BadRows::kSkip);
    ASSERT_TRUE(skip.ok());
    EXPECT_EQ(skip->data.samples.size(), 2u);
    EXPECT_EQ(skip->skipped.size(), 5u);
    EXPECT_EQ(skip->data.samples[1].slip, 0.5);
}

TEST(DataSet, MissingColumnsAreNamed) {
    const auto read = parseDataSet("slip,Fx_N\n0.1,2\n", "m.csv", BadRows::kSkip);
    ASSERT_FALSE(read.ok());
    const std::string message = read.message();
    for (const char* column : {"Fz_N", "My_Nm", "entry_angle_deg"}) {
        EXPECT_NE(message.find(column), std::string::npos) << column;
    }
}

TEST(DataSet, CsvRoundTrip) {
    DataSet data;
    data.samples.push_back({0.25, 0.3, -1.5, 58.86, 0.5, 0.1, -2.0, 58.86, 0.0, 0.012, 0.031});
    data.samples.push_back({0.5, 0.31, 0.5, 58.9, 0.6, std::nullopt, std::nullopt, 80.0, 0.01,
                            std::nullopt, std::nullopt});
    const auto read = parseDataSet(toCsv(data), "rt.csv", BadRows::kStop);
    ASSERT_TRUE(read.ok()) << read.message();
    ASSERT_EQ(read->data.samples.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        const Sample& a = data.samples[i];
        const Sample& b = read->data.samples[i];
        EXPECT_EQ(a.slip, b.slip);
        EXPECT_NEAR(a.entry_angle_rad, b.entry_angle_rad, 1e-15);  // via degrees
        EXPECT_EQ(a.fx_n, b.fx_n);
        EXPECT_EQ(a.load_n, b.load_n);
        EXPECT_EQ(a.fy_n, b.fy_n);
        EXPECT_EQ(a.time_s, b.time_s);
        EXPECT_EQ(a.sinkage_m, b.sinkage_m);
        EXPECT_EQ(a.slip_std, b.slip_std);  // 0.031, and none on the second row
    }
    EXPECT_NEAR(*read->data.samples[0].slip_angle_rad, 0.1, 1e-15);
}

// Every column read has a range; the issue's cases: slip_angle_deg = 1e308 used to become +inf
// rad, entry_angle_deg = 1e-320 passed (0, 90) as 0 rad.
TEST(DataSet, EveryColumnHasARange) {
    const std::string header =
        "slip,entry_angle_deg,Fx_N,Fz_N,My_Nm,slip_angle_deg,Fy_N,W_N,time_s,slip_std\n";
    struct Case {
        const char* row;
        const char* message;
    };
    for (const Case& c : {
             Case{"0.1,20,1,2,3,1e308,0,50,0,0.01",
                  "slip_angle_deg = 1e+308 is outside the allowed range (-90, 90) deg"},
             Case{"0.1,1e-320,1,2,3,0,0,50,0,0.01",
                  "entry_angle_deg = '1e-320' is subnormal (magnitude below 2.2e-308), too small "
                  "to compute with; allowed range (0, 90) deg"},
             Case{"0.1,20,2e7,2,3,0,0,50,0,0.01",
                  "Fx_N = 2e+07 is outside the allowed range [-1e+07, 1e+07] N"},
             Case{"0.1,20,1,1e999,3,0,0,50,0,0.01",
                  "Fz_N = '1e999' overflows a double; allowed range [-1e+07, 1e+07] N"},
             Case{"0.1,20,1,2,-2e7,0,0,50,0,0.01",
                  "My_Nm = -2e+07 is outside the allowed range [-1e+07, 1e+07] N·m"},
             Case{"0.1,20,1,2,3,0,inf,50,0,0.01",
                  "Fy_N = 'inf' is not a finite number; allowed range [-1e+07, 1e+07] N"},
             Case{"0.1,20,1,2,3,0,0,0,0,0.01", "W_N = 0 is outside the allowed range (0, 1e+07] N"},
             Case{"0.1,20,1,2,3,0,0,50,2e12,0.01",
                  "time_s = 2e+12 is outside the allowed range [-1e+12, 1e+12] s"},
             Case{"0.1,20,1,2,3,0,0,50,0,-0.01",
                  "slip_std = -0.01 is outside the allowed range [0, 2]"},
         }) {
        const auto read = parseDataSet(header + c.row + "\n", "d.csv", BadRows::kStop);
        ASSERT_FALSE(read.ok()) << c.row;
        ASSERT_EQ(read.issues().size(), 1u) << read.message();
        EXPECT_EQ(read.issues()[0].where, "d.csv:2") << c.row;
        EXPECT_EQ(read.issues()[0].message, c.message) << c.row;
    }
}

TEST(DataSet, DuplicatedColumnsAndBothEntryAngleUnitsAreErrors) {
    const auto twice = parseDataSet("slip,entry_angle_deg,Fx_N,Fz_N,My_Nm,Fx_N\n0.1,20,1,2,3,4\n",
                                    "d.csv", BadRows::kSkip);
    ASSERT_FALSE(twice.ok());
    EXPECT_EQ(twice.message(),
              "d.csv:1: column 'Fx_N' appears twice (columns 3 and 6); each column may be given "
              "once");
    const auto both =
        parseDataSet("slip,entry_angle_deg,entry_angle_rad,Fx_N,Fz_N,My_Nm\n0.1,20,0.3,1,2,3\n",
                     "d.csv", BadRows::kSkip);
    ASSERT_FALSE(both.ok());
    EXPECT_NE(both.message().find("'entry_angle_deg' and 'entry_angle_rad' both given"),
              std::string::npos)
        << both.message();
}

}  // namespace
}  // namespace terra::identification
