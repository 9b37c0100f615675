// Strict flags and bounded messages through the real executable (issue 28, findings 7, 8 and 9):
// empty values, hexadecimal, subnormal and negative-unsigned numbers, repeated keys, a zero count
// that used to mean "the default", --values without --parameter, an entry-angle noise beyond 90°
// and an unknown subcommand are exit-2 errors naming the flag; at most ~20 problems are printed
// per input, each line a few hundred characters at most (docs/cli.md, "Exit codes").
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../core/test_temp_dir.h"
#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;
using terra::test::CliRun;
using terra::test::run;

class StrictFlags : public ::testing::Test {
protected:
    // Runs `command`, expects exit 2 and `piece` in stderr, and nothing on stdout.
    void expectRejected(const std::string& command, const std::string& piece) {
        const CliRun r = run(command);
        EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.err << r.out;
        EXPECT_NE(r.err.find(piece), std::string::npos)
            << command << "\nmissing: " << piece << "\nin: " << r.err;
        EXPECT_EQ(r.out, "") << command;
    }
    fs::path write(const std::string& name, const std::string& text) {
        const fs::path path = dir_ / name;
        std::ofstream(path) << text;
        return path;
    }
    terra::testing::TempDir temp_;  // a fresh directory per test, removed afterwards
    const fs::path dir_ = temp_.path();
};

TEST_F(StrictFlags, EmptyValuesAreErrorsNamingTheFlag) {
    expectRejected("wheel --slip '' --load 58", "--slip: empty value");
    expectRejected("sweep --slips ''", "--slips: empty value");
    expectRejected("sweep --out ''", "--out: empty value");
    expectRejected("wheel --soil '' --load 58", "--soil: empty value");
}

TEST_F(StrictFlags, HexSubnormalAndOverflowingNumbersAreRefused) {
    expectRejected("wheel --slip 0x0.8p0 --load 58", "--slip: '0x0.8p0' is not a decimal number");
    expectRejected("wheel --slip 1e-320 --load 58",
                   "--slip: '1e-320' is subnormal (magnitude below 2.2e-308)");
    expectRejected("wheel --slip 1e999 --load 58", "--slip: '1e999' overflows a double");
    expectRejected("wheel --slip nan --load 58", "--slip: 'nan' is not a finite number");
    expectRejected("sweep --slips 0.1,1e-320", "--slips: '1e-320' is subnormal");
    expectRejected("wheel --set c_kPa=1e-320 --load 58", "--set c_kPa: expected KEY=NUMBER");
    expectRejected("gsa --samples 0x10", "--samples: '0x10' is not a whole number in decimal");
    expectRejected("gsa --samples 1e3", "--samples: '1e3' is not a whole number in decimal");
    // A leading zero is decimal, not octal: "010" is ten (CLI11 alone read 8; too few for the
    // range [2, …] would not show it, so the count is checked through the error of a bad one).
    expectRejected("gsa --samples 01", "--samples: 1 is outside the allowed range [2, 16777216]");
}

TEST_F(StrictFlags, ZeroCountsAndNegativeSeedsAreRangeErrors) {
    expectRejected("gsa --samples 0", "--samples: 0 is outside the allowed range [2, 16777216]");
    expectRejected("bands --samples 0", "--samples: 0 is outside the allowed range [2, 16777216]");
    expectRejected("gsa --seed -1", "--seed: '-1' is negative");
    expectRejected("synth --seed -1", "--seed: '-1' is negative");
}

TEST_F(StrictFlags, ARepeatedKeyIsAnError) {
    expectRejected("wheel --set phi_deg=30 --set phi_deg=25 --load 58",
                   "--set phi_deg: given twice ('phi_deg=30' and 'phi_deg=25')");
    expectRejected("synth --noise fx=1 --noise fx=2", "--noise fx: given twice");
    expectRejected("synth --noise fx=1,fx=2", "--noise fx: given twice");
    const std::string ding =
        std::string(TERRA_RESOURCE_DIR) + "/experiments/ding2011-smooth-hit-lss1-80N.csv";
    expectRejected("validate --experiments " + ding + " --calibrate --noise Fx_N=1,Fx_N=2",
                   "--noise Fx_N: given twice");
    const fs::path data = dir_ / "data.csv";
    ASSERT_EQ(run("synth --slips 0:0.9:10 --out " + data.string()).exit_code, 0);
    expectRejected(
        "identify --data " + data.string() + " --prior phi_deg=30+-5 --prior phi_deg=25+-5",
        "--prior phi_deg: given twice");
    expectRejected("identify --data " + data.string() + " --fix a0=0.2 --fix a0=0.3",
                   "--fix a0: given twice");
}

TEST_F(StrictFlags, ValuesWithoutTheirParameterAndAHugeAngleNoiseAreRefused) {
    expectRejected("sensitivity --values 1,2", "--values requires --parameter");
    expectRejected("synth --noise theta=1000",
                   "--noise theta: 1000 is outside the allowed range [0, 90] deg");
}

// Issue 28, finding 9: an unknown subcommand is named, with the nearest one.
TEST_F(StrictFlags, AnUnknownSubcommandIsNamed) {
    expectRejected("whee --load 5",
                   "error: 'whee' is not a subcommand; did you mean wheel? (subcommands: wheel, ");
    expectRejected("--load 5", "error: '--load' comes before any subcommand");
}

// Issue 28, finding 7: 100,000 unknown soil keys gave 12.3 MB on stderr, 20,000 bad batch rows
// 1.25 MB; at most 20 problems are listed, then their count.
TEST_F(StrictFlags, AMisspeltOptionIsNamedWithTheNearestOne) {
    CliRun r = run("wheel --slp 0.3");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("'--slp' is not an option of wheel; did you mean --slip?"),
              std::string::npos)
        << r.err;
    r = run("compaction --pases=2");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("'--pases' is not an option of compaction; did you mean --passes?"),
              std::string::npos)
        << r.err;
    // Nothing near: named, with where to look.
    r = run("traction --colour red");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("'--colour' is not an option of traction\n"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("terrastudio traction --help"), std::string::npos) << r.err;
}

TEST_F(StrictFlags, TheSameQuantityHasTheSameFlagInEveryListCommand) {
    // Where a list makes sense, the singular and the plural name the same option.
    const CliRun plural = run("sweep --slips 0.1,0.3 --slip-angles 5 --json");
    const CliRun singular = run("sweep --slip 0.1,0.3 --slip-angle 5 --json");
    ASSERT_EQ(plural.exit_code, 0) << plural.err;
    EXPECT_EQ(singular.exit_code, 0) << singular.err;
    EXPECT_EQ(singular.out, plural.out);
    const CliRun gsa = run("gsa --slips 0.2,0.4 --slip-angles 0 --samples 16 --json");
    const CliRun gsa_singular = run("gsa --slip 0.2,0.4 --slip-angle 0 --samples 16 --json");
    ASSERT_EQ(gsa.exit_code, 0) << gsa.err;
    EXPECT_EQ(gsa.out, gsa_singular.out);
    const CliRun sens = run("sensitivity --slip 0.2,0.4 --slip-angles 5 --json");
    EXPECT_EQ(sens.exit_code, 0) << sens.err;
    // Giving both names of one option is a repeated option, not two.
    EXPECT_NE(run("sweep --slip 0.1 --slips 0.2").exit_code, 0);
}

TEST_F(StrictFlags, AThousandProblemsPrintAScreenful) {
    std::ostringstream soil;
    soil << "{\"name\": \"s\", \"n\": 0.7, \"c_kPa\": 1, \"phi_deg\": 29, \"kc\": 5.3, "
            "\"kphi\": 1515, \"K_m\": 0.025, \"gamma_kN_m3\": 15.2";
    for (int i = 0; i < 100000; ++i) soil << ", \"k" << i << "\": 1";
    soil << "}";
    const fs::path soil_file = write("soil.json", soil.str());
    CliRun r = run("wheel --soil " + soil_file.string() + " --load 58");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_LT(r.err.size(), 20000u);
    EXPECT_NE(r.err.find("… and 99980 more (100000 problems in all)"), std::string::npos)
        << r.err.substr(0, 2000);

    std::string rows = "slip,load_N\n";
    for (int i = 0; i < 20000; ++i) rows += "2,58\n";
    const fs::path points = write("points.csv", rows);
    r = run("wheel --input " + points.string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_LT(r.err.size(), 20000u);
    EXPECT_NE(r.err.find("… and 19980 more (20000 problems in all)"), std::string::npos)
        << r.err.substr(0, 2000);
    EXPECT_NE(r.err.find("20000 bad row(s); nothing written"), std::string::npos);
    // Skipped, they are counted the same way.
    r = run("wheel --input " + points.string() + " --skip-bad-rows");
    EXPECT_EQ(r.exit_code, 0) << r.err.substr(0, 2000);
    EXPECT_LT(r.err.size(), 20000u);
}

TEST_F(StrictFlags, ALongPathKeepsItsEndAndTheMessageWithinAFewHundredCharacters) {
    fs::path deep = dir_;
    for (int i = 0; i < 5; ++i) deep /= std::string(200, static_cast<char>('a' + i));
    fs::create_directories(deep);
    std::ofstream(deep / "points.csv") << "slip,load_N\n0.1,58\n1.5,58\n";
    const CliRun r = run("wheel --input " + (deep / "points.csv").string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    std::istringstream lines(r.err);
    for (std::string line; std::getline(lines, line);) EXPECT_LT(line.size(), 600u) << line;
    EXPECT_NE(r.err.find("eeee/points.csv:3: slip = 1.5 is outside the allowed range [-1, 1]"),
              std::string::npos)
        << r.err;
}

}  // namespace
