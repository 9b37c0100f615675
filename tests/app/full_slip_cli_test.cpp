// Slip s = ±1 through the real executable: the wheel spinning in place (s = 1) and the locked
// wheel (s = −1) are valid operating points for `wheel`, sweeps, batches, identification data and
// `stresses`; their forces continue those at s = ±0.999999 (docs/model.md, "Full slip").
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;
using terra::test::CliRun;
using terra::test::run;

nlohmann::json wheelAt(const std::string& slip, const std::string& more = "") {
    const CliRun r = run("wheel --slip " + slip + " --slip-angle 10 --load 58.86 --json " + more);
    EXPECT_EQ(r.exit_code, 0) << slip << ": " << r.err;
    return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json::object();
}

TEST(FullSlipCli, WheelAtPlusMinusOneContinuesTheForcesJustInside) {
    for (const char* model : {"full", "quadratic"}) {
        for (const auto& [at, near] : {std::pair{"1", "0.999999"}, {"-1", "-0.999999"}}) {
            const auto a = wheelAt(at, std::string("--model ") + model);
            const auto b = wheelAt(near, std::string("--model ") + model);
            ASSERT_FALSE(a.empty() || b.empty());
            const double scale =
                std::abs(a["Fz_N"].get<double>()) + std::abs(a["Fx_N"].get<double>());
            for (const char* key : {"Fx_N", "Fy_N", "Fz_N", "My_Nm", "entry_angle_deg"}) {
                EXPECT_NEAR(a[key].get<double>(), b[key].get<double>(), 1e-5 * scale)
                    << model << " s = " << at << " " << key;
            }
        }
    }
    // Spinning in place: κ = 0, no lateral shear whatever β (Eq. 2.14: j_l = r κ tan β (θ_f − θ)).
    EXPECT_EQ(wheelAt("1")["Fy_N"].get<double>(), 0.0);
    // Locked and dragged: the soil resists the travel and pushes against the lateral slip.
    const auto locked = wheelAt("-1");
    EXPECT_LT(locked["Fx_N"].get<double>(), 0.0);
    EXPECT_LT(locked["Fy_N"].get<double>(), 0.0);
    EXPECT_LT(locked["My_Nm"].get<double>(), 0.0);
}

TEST(FullSlipCli, BeyondOneIsStillRefused) {
    for (const char* slip : {"1.000001", "-1.000001"}) {
        const CliRun r = run(std::string("wheel --load 58.86 --slip ") + slip);
        EXPECT_EQ(r.exit_code, 2);
        EXPECT_NE(
            r.err.find(std::string("slip: ") + slip + " is outside the allowed range [-1, 1]"),
            std::string::npos)
            << r.err;
    }
}

TEST(FullSlipCli, SweepReachesOneInclusive) {
    const CliRun r = run("sweep --slips 0.9:1:11 --slip-angles 10 --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto rows = nlohmann::json::parse(r.out)["rows"];
    ASSERT_EQ(rows.size(), 11u);
    EXPECT_EQ(rows.back()["slip"], 1.0);
    // The same point by the single-point command (its own solve).
    EXPECT_NEAR(rows.back()["Fx_N"].get<double>(), wheelAt("1")["Fx_N"].get<double>(), 1e-8);
    const CliRun braking = run("sweep --slips -1:-0.9:11 --slip-angles 10");
    ASSERT_EQ(braking.exit_code, 0) << braking.err;
    EXPECT_NE(braking.out.find("\n10,-1,"), std::string::npos) << braking.out.substr(0, 300);
}

TEST(FullSlipCli, BatchIdentificationAndStressesAcceptFullSlip) {
    const fs::path dir =
        fs::temp_directory_path() / ("terra_full_slip_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path points = dir / "points.csv";
    std::ofstream(points) << "slip,slip_angle_deg,load_N\n1,10,58.86\n-1,10,58.86\n";
    CliRun r = run("wheel --input " + points.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::istringstream lines(r.out);
    std::vector<std::string> rows;
    for (std::string line; std::getline(lines, line);) rows.push_back(line);
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[1].rfind("1,10,58.86,ok,", 0), 0u) << rows[1];
    EXPECT_EQ(rows[2].rfind("-1,10,58.86,ok,", 0), 0u) << rows[2];

    // Identification data with s = 1 (a stuck robot's spinning wheel): synthesised and fitted.
    const fs::path data = dir / "data.csv";
    r = run("synth --slips 0:1:21 --out " + data.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run("identify --data " + data.string() + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["samples"], 21);

    for (const char* slip : {"1", "-1"}) {
        r = run(std::string("stresses --slip ") + slip + " --json");
        ASSERT_EQ(r.exit_code, 0) << slip << ": " << r.err;
        const auto j = nlohmann::json::parse(r.out);
        EXPECT_TRUE(std::isfinite(j["errors"]["tau_rmse_kPa"].get<double>()));
    }
    fs::remove_all(dir);
}

}  // namespace
