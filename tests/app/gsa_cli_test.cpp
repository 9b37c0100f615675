// `terrastudio gsa` and `terrastudio bands` on the real executable: the indices' limit cases,
// reproducibility by seed, the same table as a script's "sensitivity-global" analysis, and exit
// code 2 naming the flag, the value and the range for bad input.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../core/test_temp_dir.h"
#include "cli_process.h"
#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;

using terra::test::CliRun;
using terra::test::readText;
using terra::test::run;

struct Csv {
    std::vector<std::string> columns;
    std::vector<std::vector<double>> rows;
    double at(std::size_t row, const std::string& column) const {
        for (std::size_t i = 0; i < columns.size(); ++i) {
            if (columns[i] == column) return rows.at(row).at(i);
        }
        ADD_FAILURE() << "no column " << column;
        return NAN;
    }
};

Csv parseCsv(const std::string& text) {
    Csv csv;
    std::stringstream lines(text);
    std::string line;
    bool header = true;
    while (std::getline(lines, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::stringstream cells(line);
        std::vector<double> row;
        for (std::string cell; std::getline(cells, cell, ',');) {
            if (header)
                csv.columns.push_back(cell);
            else
                row.push_back(std::stod(cell));
        }
        if (!header) csv.rows.push_back(row);
        header = false;
    }
    return csv;
}

// φ and γ over ranges at s = 0.3, β = 0: F_x does not depend on γ there (bulldozing acts
// sideways; core/analysis test UnitWeightDoesNotMoveFxAtZeroSlipAngle checks it on the model).
const std::string kStudyWithoutSeed =
    "gsa --soil sandy-loam --wheel A --param phi_deg=20:35 --param gamma_kN_m3=10:20 "
    "--slip 0.3 --load 58.86 --outputs Fx_N,sinkage_m --samples 512 --resamples 200";
const std::string kStudy = kStudyWithoutSeed + " --seed 1";

TEST(GsaCli, ParameterWithoutEffectHasZeroIndicesWithinTheirInterval) {
    const CliRun r = run(kStudy);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Csv csv = parseCsv(r.out);
    ASSERT_EQ(csv.rows.size(), 1u) << r.out;
    EXPECT_EQ(csv.at(0, "slip"), 0.3);
    // γ does not move F_x: S_T exactly 0 (Jansen's estimator of identical runs), S_1 within its
    // confidence interval of 0.
    EXPECT_EQ(csv.at(0, "Fx_N_ST_gamma_kN_m3"), 0.0);
    EXPECT_LE(std::abs(csv.at(0, "Fx_N_S1_gamma_kN_m3")), csv.at(0, "Fx_N_S1_gamma_kN_m3_conf"));
    // φ then carries it all.
    EXPECT_NEAR(csv.at(0, "Fx_N_S1_phi_deg"), 1.0, csv.at(0, "Fx_N_S1_phi_deg_conf") + 0.02);
    EXPECT_EQ(csv.at(0, "Fx_N_samples"), 512.0);
}

TEST(GsaCli, SumsOfFirstOrderAndTotalIndicesBracketOne) {
    const CliRun r =
        run("gsa --param phi_deg=20:35 --param c_kPa=0:5 --param K_m=0.005:0.04 --param n=0.5:1.1 "
            "--slip 0.1,0.3,0.6 --outputs Fx_N --samples 256 --resamples 200");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Csv csv = parseCsv(r.out);
    ASSERT_EQ(csv.rows.size(), 3u);
    for (std::size_t row = 0; row < 3; ++row) {
        double s1 = 0, st = 0, c1 = 0, ct = 0;
        for (const char* p : {"phi_deg", "c_kPa", "K_m", "n"}) {
            const std::string k = p;
            s1 += csv.at(row, "Fx_N_S1_" + k);
            c1 += csv.at(row, "Fx_N_S1_" + k + "_conf");
            st += csv.at(row, "Fx_N_ST_" + k);
            ct += csv.at(row, "Fx_N_ST_" + k + "_conf");
        }
        EXPECT_LE(s1, 1.0 + c1) << row;
        EXPECT_GE(st, 1.0 - ct) << row;
    }
}

TEST(GsaCli, SameSeedSameBytesOtherSeedOtherNumbers) {
    const CliRun a = run(kStudy), b = run(kStudy + " --threads 1");
    ASSERT_EQ(a.exit_code, 0) << a.err;
    ASSERT_EQ(b.exit_code, 0) << b.err;
    EXPECT_EQ(a.out, b.out);
    const CliRun c = run(kStudyWithoutSeed + " --seed 2");
    ASSERT_EQ(c.exit_code, 0) << c.err;
    EXPECT_NE(a.out, c.out);
}

TEST(GsaCli, JsonHasTheIndicesPerOutputParameterAndSlip) {
    const CliRun r = run(kStudy + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["parameters"], (std::vector<std::string>{"phi_deg", "gamma_kN_m3"}));
    EXPECT_EQ(j["method"], "sobol");
    EXPECT_EQ(j["ST"]["Fx_N"][1][0], 0.0);
    EXPECT_EQ(j["S1"]["sinkage_m"].size(), 2u);
    EXPECT_EQ(j["evaluations"], 512 * 4);
    const Csv csv = parseCsv(run(kStudy).out);
    EXPECT_EQ(j["S1"]["Fx_N"][0][0].get<double>(), csv.at(0, "Fx_N_S1_phi_deg"));
}

TEST(GsaCli, MorrisScreeningGivesNoEffectToTheUnusedParameter) {
    const CliRun r =
        run("gsa --method morris --param phi_deg=20:35 --param gamma_kN_m3=10:20 --slip 0.3 "
            "--samples 20");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Csv csv = parseCsv(r.out);
    EXPECT_EQ(csv.at(0, "Fx_N_mu_star_gamma_kN_m3"), 0.0);
    EXPECT_GT(csv.at(0, "Fx_N_mu_star_phi_deg"), 1.0);
    EXPECT_EQ(csv.at(0, "Fx_N_trajectories"), 20.0);
}

class GsaScript : public ::testing::Test {
protected:
    fs::path writeScript(const nlohmann::json& analysis) {
        const nlohmann::json script = {{"soil", "sandy-loam"},
                                       {"wheel", "A"},
                                       {"export", {{"width", 400}, {"height", 300}}},
                                       {"analyses", {analysis}}};
        const fs::path path = dir_ / "script.json";
        std::ofstream(path) << script.dump(2);
        return path;
    }
    terra::testing::TempDir temp_;  // a fresh directory per test, removed afterwards
    const std::filesystem::path dir_ = temp_.path();
};

TEST_F(GsaScript, ScriptAndCommandLineGiveTheSameTable) {
    const nlohmann::json analysis = {
        {"name", "gsa"},
        {"type", "sensitivity-global"},
        {"parameters",
         {{{"key", "phi_deg"}, {"range", {20, 35}}},
          {{"key", "gamma_kN_m3"}, {"range", {10, 20}}}}},
        {"slips", {0.3}},
        {"load_N", 58.86},
        {"outputs", {"Fx_N", "sinkage_m"}},
        {"samples", 512},
        {"resamples", 200},
        {"seed", 1},
        {"expect",
         {{{"column", "Fx_N_ST_gamma_kN_m3"}, {"at", {{"slip", 0.3}}}, {"min", 0}, {"max", 0}}}}};
    const CliRun r =
        run("run " + writeScript(analysis).string() + " --out " + (dir_ / "out").string());
    ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
    const CliRun cli = run(kStudy);
    ASSERT_EQ(cli.exit_code, 0) << cli.err;
    EXPECT_EQ(readText(dir_ / "out" / "gsa.csv"), cli.out);
    EXPECT_TRUE(fs::exists(dir_ / "out" / "gsa-indices.png"));
    EXPECT_TRUE(fs::exists(dir_ / "out" / "gsa-indices.json"));
}

TEST_F(GsaScript, UnknownKeysAndBadRangesExitTwoNamingThem) {
    const nlohmann::json analysis = {{"name", "gsa"},
                                     {"type", "sensitivity-global"},
                                     {"parameters", {{{"key", "phi_deg"}, {"range", {20, 95}}}}},
                                     {"sampels", 64}};
    const CliRun r =
        run("run " + writeScript(analysis).string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("analyses[0].parameters[0].range[1]: 95 is outside the allowed range"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("analyses[0].sampels"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("did you mean \"samples\""), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "gsa.csv"));
}

TEST_F(GsaScript, BandsScriptMatchesTheBandsCommand) {
    const nlohmann::json analysis = {
        {"name", "bands"},
        {"type", "uncertainty-bands"},
        {"parameters",
         {{{"key", "phi_deg"}, {"range", {26, 32}}},
          {{"key", "c_kPa"}, {"normal", {1.7, 0.3}}, {"bounds", {0.5, 3}}}}},
        {"slips", {0.1, 0.3, 0.6}},
        {"samples", 128}};
    const CliRun r =
        run("run " + writeScript(analysis).string() + " --out " + (dir_ / "out").string());
    ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
    const CliRun cli =
        run("bands --param phi_deg=26:32 --normal c_kPa=1.7,0.3,0.5:3 --slip 0.1,0.3,0.6 "
            "--samples 128");
    ASSERT_EQ(cli.exit_code, 0) << cli.err;
    EXPECT_EQ(readText(dir_ / "out" / "bands.csv"), cli.out);
    const Csv csv = parseCsv(cli.out);
    ASSERT_EQ(csv.rows.size(), 3u);
    for (std::size_t row = 0; row < 3; ++row) {
        for (const char* o : {"Fx_N", "Fs_N"}) {
            const std::string k = o;
            EXPECT_LE(csv.at(row, k + "_p5"), csv.at(row, k + "_p50"));
            EXPECT_LE(csv.at(row, k + "_p50"), csv.at(row, k + "_p95"));
            EXPECT_LE(csv.at(row, k + "_p5"), csv.at(row, k + "_nominal"));
            EXPECT_GE(csv.at(row, k + "_p95"), csv.at(row, k + "_nominal"));
        }
    }
}

TEST(GsaCli, ProgressGoesToStderrUpToTheEnd) {
    const CliRun r = run(kStudy + " --progress");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("progress: 100 %"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, run(kStudy).out);
}

// Ctrl-C: the indices of the base samples evaluated so far are written, marked, exit 130.
TEST_F(GsaScript, InterruptedStudyWritesTheSamplesSoFar) {
    using namespace std::chrono_literals;
    const fs::path csv = dir_ / "gsa.csv";
    terra::test::CliProcess p(
        {"gsa", "--slip", "0.3", "--samples", "262144", "--resamples", "10", "--out", csv.string()},
        dir_ / "gsa");
    ASSERT_TRUE(p.waitUntilCatching(SIGINT, 60s)) << p.err();
    std::this_thread::sleep_for(300ms);
    p.signal(SIGINT);
    const int status = p.wait();
    ASSERT_TRUE(WIFEXITED(status)) << p.err();
    EXPECT_EQ(WEXITSTATUS(status), 130) << p.err();
    const std::string text = readText(csv);
    EXPECT_NE(text.find("# cancelled by SIGINT"), std::string::npos) << text;
    const Csv table = parseCsv(text);
    ASSERT_EQ(table.rows.size(), 1u) << text;
    EXPECT_LT(table.at(0, "Fx_N_samples"), 262144.0);
    EXPECT_NE(p.err().find("cancelled: indices from the"), std::string::npos) << p.err();
}

struct BadFlag {
    std::string arguments;
    std::string message;
};

class GsaBadFlags : public ::testing::TestWithParam<BadFlag> {};

TEST_P(GsaBadFlags, ExitTwoNamingFlagValueAndRange) {
    const CliRun r = run(GetParam().arguments);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(GetParam().message), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
}

// The flags are the analysis's settings object read by its own reader (issue 26): the messages
// are the reader's, named by the flag (a parameter by its flag and text).
INSTANTIATE_TEST_SUITE_P(
    Flags, GsaBadFlags,
    ::testing::Values(
        BadFlag{"gsa --param phi_deg=20:95",
                "--param 'phi_deg=20:95': 95 is outside the allowed range [0, 60) deg"},
        BadFlag{"gsa --param phi=20:35",
                "--param 'phi=20:35': \"phi\" is not a soil field (did you mean \"phi_deg\"?)"},
        BadFlag{"gsa --param phi_deg=35:20", "low 35 must be below high 20"},
        BadFlag{"gsa --param phi_deg=20", "expected a range LOW:HIGH"},
        BadFlag{"gsa --normal phi_deg=29,-2", "--normal 'phi_deg=29,-2': sd -2 must be above 0"},
        BadFlag{"gsa --outputs Fx_N,sinkage",
                "--outputs[1]: \"sinkage\" is not an output (did you mean \"sinkage_m\"?)"},
        BadFlag{"gsa --samples 1", "--samples: 1 is outside the allowed range [2, 16777216]"},
        BadFlag{"gsa --slip 0.3,1.5", "--slip[1]: 1.5 is outside the allowed range [-1, 1]"},
        BadFlag{"gsa --slip-angle 95",
                "--slip-angle[0]: 95 is outside the allowed range (-90, 90) deg"},
        BadFlag{"gsa --load -3", "--load: -3 is outside the allowed range [0.01, 1e+05] N"},
        BadFlag{"gsa --method sobel",
                "--method: \"sobel\" is not one of sobol, morris (did you mean \"sobol\"?)"},
        BadFlag{"gsa --method morris --normal phi_deg=29,2",
                "--normal 'phi_deg=29,2': Morris screening needs ranges, not distributions"},
        BadFlag{"gsa --param phi_deg=20:30 --normal phi_deg=29,2",
                "--normal 'phi_deg=29,2': \"phi_deg\" is varied twice"},
        BadFlag{"gsa --levels 3", "--levels: 3 must be even"},
        BadFlag{"gsa --confidence 1", "--confidence: 1 is outside the allowed range (0, 1)"},
        BadFlag{"gsa --max-failed-fraction 2",
                "--max-failed-fraction: 2 is outside the allowed range [0, 1]"},
        BadFlag{"gsa --depth 20", "--depth: 20 is outside the allowed range (0, 10] m"},
        BadFlag{"gsa --passes 0", "--passes: 0 is outside the allowed range [1, 100]"},
        BadFlag{"bands --samples 1", "--samples: 1 is outside the allowed range [2, 16777216]"},
        BadFlag{"bands --percentiles 5,150",
                "--percentiles[1]: 150 is outside the allowed range [0, 100] %"}));

}  // namespace
