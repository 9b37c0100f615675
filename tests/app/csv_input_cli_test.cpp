// Bad CSV input through the real executable: every column read has a range; overflow,
// non-finite, subnormal and out-of-range cells, duplicated columns and huge cells in the
// identification data (`identify --data`, `identify --stream`) and in the `wheel --input` batch
// are exit-2 errors naming the file, the line, the column, the value (quoted short) and the
// allowed range.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;
using terra::test::CliRun;
using terra::test::run;

class CsvInput : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("terra_csv_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string write(const std::string& name, const std::string& text) {
        const fs::path path = dir_ / name;
        std::ofstream(path) << text;
        return path.string();
    }
    fs::path dir_;
};

const std::string kDataHeader = "slip,entry_angle_deg,Fx_N,Fz_N,My_Nm,slip_angle_deg,W_N,time_s\n";
const std::string kGoodRow = "0.2,17,-1,58.86,0.5,0,58.86,0\n";

struct BadCell {
    std::string row;      // replaces the good row at line 3
    std::string message;  // expected after "FILE:3: "
};

// The identify --data and --stream cases: one bad cell each, between two good rows.
std::vector<BadCell> dataSetCases() {
    return {
        {"0.2,17,-1,58.86,0.5,1e308,58.86,0",
         "slip_angle_deg = 1e+308 is outside the allowed range (-90, 90) deg"},
        {"0.2,1e-320,-1,58.86,0.5,0,58.86,0",
         "entry_angle_deg = '1e-320' is subnormal (magnitude below 2.2e-308), too small to "
         "compute with; allowed range (0, 90) deg"},
        {"0.2,1e-307,-1,58.86,0.5,0,58.86,0",
         "entry_angle_deg = 1e-307 deg underflows when converted to SI units "
         "(1.74532925199433e-309); allowed range (0, 90) deg"},
        {"0.2,17,1e999,58.86,0.5,0,58.86,0",
         "Fx_N = '1e999' overflows a double; allowed range [-1e+07, 1e+07] N"},
        {"0.2,17,-1,nan,0.5,0,58.86,0",
         "Fz_N = 'nan' is not a finite number; allowed range [-1e+07, 1e+07] N"},
        {"0.2,17,-1,58.86,x,0,58.86,0",
         "My_Nm = 'x' is not a number; allowed range [-1e+07, 1e+07] N·m"},
        {"1.5,17,-1,58.86,0.5,0,58.86,0", "slip = 1.5 is outside the allowed range [-1, 1]"},
        {"0.2,17,-1,58.86,0.5,0,-5,0", "W_N = -5 is outside the allowed range (0, 1e+07] N"},
        {"0.2,17,-1,58.86,0.5,0,58.86,1e300",
         "time_s = 1e+300 is outside the allowed range [-1e+12, 1e+12] s"},
    };
}

TEST_F(CsvInput, IdentifyRejectsEveryBadCellWithFileLineColumnValueAndRange) {
    for (const char* mode : {"--data", "--stream"}) {
        for (const BadCell& c : dataSetCases()) {
            const std::string file = write(
                "data.csv", kDataHeader + kGoodRow + c.row + "\n" + kGoodRow + kGoodRow + kGoodRow);
            const CliRun r = run(std::string("identify ") + mode + " " + file);
            EXPECT_EQ(r.exit_code, 2) << mode << " " << c.row << "\n" << r.err;
            EXPECT_NE(r.err.find("error: " + file + ":3: " + c.message), std::string::npos)
                << mode << " " << c.row << "\n"
                << r.err;
            EXPECT_TRUE(r.out.empty()) << r.out;
        }
    }
}

TEST_F(CsvInput, AHugeCellIsQuotedShort) {
    const std::string huge(200000, '9');
    const std::string file =
        write("data.csv", kDataHeader + kGoodRow + "0.2," + huge + ",-1,58.86,0.5,0,58.86,0\n");
    const CliRun r = run("identify --data " + file);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(file + ":3: entry_angle_deg = '" + std::string(80, '9') +
                         "\u2026' (200000 characters) overflows a double"),
              std::string::npos)
        << r.err.substr(0, 500);
    EXPECT_LT(r.err.size(), 1000u);  // not the 200 kB cell
}

TEST_F(CsvInput, DuplicatedColumnsAreErrors) {
    const std::string data = write("data.csv",
                                   "slip,entry_angle_deg,Fx_N,Fz_N,My_Nm,slip\n"
                                   "0.2,17,-1,58.86,0.5,0.3\n");
    CliRun r = run("identify --data " + data);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(data + ":1: column 'slip' appears twice (columns 1 and 6)"),
              std::string::npos)
        << r.err;
    r = run("identify --stream " + data);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("appears twice"), std::string::npos) << r.err;

    const std::string points = write("points.csv", "slip,load_N,load_N\n0.2,58.86,30\n");
    r = run("wheel --input " + points);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(points + ":1: column 'load_N' appears twice (columns 2 and 3)"),
              std::string::npos)
        << r.err;
}

TEST_F(CsvInput, WheelBatchRejectsEveryBadCellWithFileLineColumnValueAndRange) {
    const std::string header =
        "slip,slip_angle_deg,entry_angle_deg,load_N,exit_angle_deg,rut_ratio,"
        "max_stress_angle_deg\n";
    const std::vector<BadCell> cases{
        {"1.5,0,20,,,,", "slip = 1.5 is outside the allowed range [-1, 1]"},
        {"0.2,1e308,20,,,,", "slip_angle_deg = 1e+308 is outside the allowed range (-90, 90) deg"},
        {"0.2,0,1e-320,,,,",
         "entry_angle_deg = '1e-320' is subnormal (magnitude below 2.2e-308), too small to "
         "compute with; allowed range (0, 90] deg"},
        {"0.2,0,,1e999,,,", "load_N = '1e999' overflows a double; allowed range [0.01, 1e+05] N"},
        {"0.2,0,,58.86,5,,", "exit_angle_deg = 5 is outside the allowed range [-90, 0] deg"},
        {"0.2,0,,58.86,,-inf,", "rut_ratio = '-inf' is not a finite number; allowed range [0, 1]"},
        {"0.2,0,,58.86,,,abc",
         "max_stress_angle_deg = 'abc' is not a number; allowed range [-90, 90] deg"},
    };
    for (const BadCell& c : cases) {
        const std::string points =
            write("points.csv", header + "0.2,0,20,,,,\n" + c.row + "\n0.3,0,,58.86,,,\n");
        const CliRun r =
            run("wheel --input " + points + " --output " + (dir_ / "out.csv").string());
        EXPECT_EQ(r.exit_code, 2) << c.row << "\n" << r.err;
        EXPECT_NE(r.err.find(points + ":3: " + c.message), std::string::npos) << c.row << "\n"
                                                                              << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "out.csv")) << c.row;
    }
}

// Issue 28, finding 5: LF, CR LF and CR-only line endings are all lines (a CR-only file was
// one header line: zero rows computed, exit 0); the rows' line numbers count the same way.
TEST_F(CsvInput, EveryLineEndingIsALineEnd) {
    const std::string expected =
        run("wheel --input " + write("lf.csv", "slip,load_N\n0.1,58\n0.3,58\n") + " --output " +
            (dir_ / "lf-out.csv").string())
            .err;
    for (const auto& [name, eol] : {std::pair{"crlf", "\r\n"}, {"cr", "\r"}, {"mixed", "\n"}}) {
        const std::string text = std::string("slip,load_N") + eol + "0.1,58" + eol + "0.3,58" +
                                 (std::string(name) == "mixed" ? "\r" : eol);
        const std::string points = write(std::string(name) + ".csv", text);
        const fs::path out = dir_ / (std::string(name) + "-out.csv");
        const CliRun r = run("wheel --input " + points + " --output " + out.string());
        EXPECT_EQ(r.exit_code, 0) << name << ": " << r.err;
        EXPECT_NE(r.err.find("wrote " + out.string() + ": 2 rows"), std::string::npos)
            << name << ": " << r.err;
    }
    EXPECT_NE(expected.find(": 2 rows"), std::string::npos) << expected;
    // A bad cell on the third line of a CR-only file is named at line 3.
    const std::string bad = write("bad.csv", "slip,load_N\r0.1,58\r1.5,58\r");
    const CliRun r = run("wheel --input " + bad);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(bad + ":3: slip = 1.5 is outside"), std::string::npos) << r.err;
    // The identification data set too.
    const std::string data = write("data.csv",
                                   "slip,entry_angle_deg,Fx_N,Fz_N,My_Nm\r0.2,17,-1,58.86,0.5\r"
                                   "0.3,18,1,58.86,0.6\r");
    // (Two samples are six values for seven parameters: the prior makes them enough.)
    const CliRun d = run("identify --data " + data + " --prior sandy-loam --json");
    EXPECT_NE(d.exit_code, 2) << d.err;
    EXPECT_NE(d.out.find("\"samples\": 2"), std::string::npos) << d.out << d.err;
}

// A misspelt batch column would leave every row at the flag's default (slip 0): an error when
// the column it most likely means is missing, a warning for any other unknown column, a note
// when there is no slip column at all.
TEST_F(CsvInput, MisspeltBatchColumnsAreNamedWithTheNearestOne) {
    for (const std::string column : {"slp", "Slip", "slip_"}) {
        const std::string points = write("points.csv", column + ",load_N\n0.3,58\n");
        const CliRun r = run("wheel --input " + points);
        EXPECT_EQ(r.exit_code, 2) << column << ": " << r.err;
        EXPECT_NE(r.err.find(points + ":1: unknown column '" + column +
                             "'; did you mean slip? (the file has no slip column"),
                  std::string::npos)
            << r.err;
        EXPECT_EQ(r.out, "") << column;
    }
    // An unknown column next to the one it resembles is data of the user's: a warning, copied.
    const std::string both = write("both.csv", "slip,Slip,load_N,run_id\n0.3,x,58,7\n");
    CliRun r = run("wheel --input " + both);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find(both + ":1: warning: column 'Slip' is not read (columns read: slip, "),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find(both + ":1: warning: column 'run_id' is not read"), std::string::npos)
        << r.err;
    EXPECT_NE(r.out.find("0.3,x,58,7,ok,"), std::string::npos) << r.out;
    // No slip column: said, with the slip every row takes.
    const std::string none = write("none.csv", "load_N\n58\n");
    r = run("wheel --input " + none + " --slip 0.2");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find(none + ": note: no column slip: every row at s = 0.2 (--slip)"),
              std::string::npos)
        << r.err;
}

// Issue 28, finding 9: an unbalanced quote is named as one, with its line and column.
TEST_F(CsvInput, AnUnbalancedQuoteIsNamed) {
    const std::string points = write("q.csv", "slip,load_N,label\n0.2,58,\"open\n0.3,58,ok\n");
    CliRun r = run("wheel --input " + points);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(points + ":2: unbalanced double quote: the quoted cell in column 3 is "
                                  "not closed on its line"),
              std::string::npos)
        << r.err;
    const std::string header = write("h.csv", "slip,\"load_N\n0.2,58\n");
    r = run("identify --data " + header);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(header + ":1: header: unbalanced double quote"), std::string::npos)
        << r.err;
}

}  // namespace
