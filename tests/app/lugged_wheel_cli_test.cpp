// A lugged wheel file through the real executable (docs/model.md, "Lugs"): grousers without a
// lug-effect coefficient give the smooth wheel's numbers exactly; with λ_s the drawbar pull at the
// load rises; on a (nearly) frictionless soil the torque is that of a smooth wheel of radius
// r_s = r + λ_s h_g, a limit case computed by a second `wheel` run; an out-of-range λ_s is an
// input error naming the field; `sweep`, `validate` (forward and --calibrate) and `identify` take
// the file.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../core/test_temp_dir.h"
#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using terra::test::CliRun;
using terra::test::contains;
using terra::test::kDing;
using terra::test::run;

class LuggedWheelCli : public ::testing::Test {
protected:
    // The Ding wheel (r = 0.15735 m, b = 0.165 m) with 24 grousers of `height`, and λ_s when > 0.
    std::string wheel(const std::string& name, double radius, double height, double lambda) {
        json w{{"name", name}, {"r_m", radius}, {"b_m", 0.165}};
        if (height > 0.0) {
            w["grouser_height_m"] = height;
            w["grouser_count"] = 24;
            w["grouser_thickness_m"] = 0.002;
        }
        if (lambda > 0.0) w["lug_effect_coefficient"] = lambda;
        const fs::path path = dir_ / (name + ".json");
        std::ofstream(path) << w.dump(2);
        return path.string();
    }
    json wheelJson(const std::string& args) {
        const CliRun r = run("wheel " + args + " --json");
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return r.exit_code == 0 ? json::parse(r.out) : json::object();
    }
    terra::testing::TempDir temp_;
    const fs::path dir_ = temp_.path();
};

TEST_F(LuggedWheelCli, GrousersWithoutTheCoefficientAreTheSmoothWheelExactly) {
    const std::string grousers = wheel("grousers", 0.15735, 0.010, 0.0);
    const std::string smooth = wheel("smooth", 0.15735, 0.0, 0.0);
    for (const char* point :
         {"--load 80 --slip 0.3", "--entry-angle 25 --slip -0.4 --slip-angle 5"}) {
        const json a = wheelJson("--soil hit-lss1 --wheel " + grousers + " " + point);
        const json b = wheelJson("--soil hit-lss1 --wheel " + smooth + " " + point);
        for (const char* key : {"Fx_N", "Fy_N", "Fz_N", "Mx_Nm", "My_Nm", "Mz_Nm", "Fb_N", "Fs_N",
                                "entry_angle_deg", "sinkage_m"})
            EXPECT_EQ(a[key].get<double>(), b[key].get<double>()) << key << " at " << point;
    }
    const CliRun sa = run("sweep --soil hit-lss1 --wheel " + grousers + " --slips 0:0.6:4");
    const CliRun sb = run("sweep --soil hit-lss1 --wheel " + smooth + " --slips 0:0.6:4");
    ASSERT_EQ(sa.exit_code, 0) << sa.err;
    EXPECT_EQ(sa.out, sb.out);
}

TEST_F(LuggedWheelCli, LugsRaiseTheDrawbarPullAtTheLoad) {
    const std::string smooth = wheel("smooth", 0.15735, 0.0, 0.0);
    const std::string lugged = wheel("lugged", 0.15735, 0.010, 0.5);
    for (double slip : {0.1, 0.3, 0.6}) {
        const std::string point = " --load 80 --slip " + std::to_string(slip);
        const json s = wheelJson("--soil hit-lss1 --wheel " + smooth + point);
        const json l = wheelJson("--soil hit-lss1 --wheel " + lugged + point);
        EXPECT_NEAR(l["Fz_N"].get<double>(), 80.0, 1e-6);
        EXPECT_GT(l["Fx_N"].get<double>(), s["Fx_N"].get<double>() + 0.5) << "s = " << slip;
    }
}

// With φ → 0 (1e-6°, the range excludes 0) the shear no longer depends on σ: at one entry angle
// and slip, the lugged wheel's torque is the smooth wheel's of radius r_s = 0.15735 + 0.5 · 0.01.
TEST_F(LuggedWheelCli, FrictionlessTorqueIsTheSmoothWheelOfTheShearingRadius) {
    const std::string lugged = wheel("lugged", 0.15735, 0.010, 0.5);
    const std::string equivalent = wheel("equivalent", 0.16235, 0.0, 0.0);
    const std::string soil = "--soil hit-lss1 --set phi_deg=1e-6 --set c_kPa=2";
    for (const char* point : {"--entry-angle 20 --slip 0.3", "--entry-angle 15 --slip 0.05"}) {
        const json l = wheelJson(soil + " --wheel " + lugged + " " + point);
        const json e = wheelJson(soil + " --wheel " + equivalent + " " + point);
        const double my = e["My_Nm"].get<double>();
        EXPECT_NEAR(l["My_Nm"].get<double>(), my, 1e-5 * std::abs(my)) << point;
        // The normal stress is the rim's: F_z differs from the r_s wheel's.
        EXPECT_GT(std::abs(l["Fz_N"].get<double>() - e["Fz_N"].get<double>()), 1.0) << point;
    }
}

TEST_F(LuggedWheelCli, CoefficientOutOfRangeNamesTheFieldAndTheRange) {
    const std::string bad = wheel("bad", 0.15735, 0.010, 1.5);
    const CliRun r = run("wheel --soil hit-lss1 --wheel " + bad + " --load 80 --slip 0.2");
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_TRUE(contains(r.err, "lug_effect_coefficient")) << r.err;
    EXPECT_TRUE(contains(r.err, "1.5")) << r.err;
    EXPECT_TRUE(contains(r.err, "[0, 1]")) << r.err;
}

TEST_F(LuggedWheelCli, ValidateAndCalibrateTakeTheLuggedWheel) {
    const std::string lugged = wheel("lugged", 0.15735, 0.010, 0.5);
    const CliRun r =
        run("validate --experiments " + kDing + " --soil hit-lss1 --wheel " + lugged + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json j = json::parse(r.out);
    ASSERT_EQ(j["points"].size(), 6u);
    // The validation predicts with the forward model of `wheel --load`, lugs included.
    const json at = wheelJson("--soil hit-lss1 --wheel " + lugged + " --load 80 --slip 0.3");
    EXPECT_NEAR(j["points"][3]["Fx_N"]["predicted"].get<double>(), at["Fx_N"].get<double>(), 1e-9);
    const CliRun human =
        run("validate --experiments " + kDing + " --soil hit-lss1 --wheel " + lugged);
    EXPECT_TRUE(contains(human.out, "note: lug model")) << human.out;

    const CliRun c = run("validate --experiments " + kDing + " --soil hit-lss1 --wheel " + lugged +
                         " --calibrate --noise Fx_N=1,sinkage_m=0.001 --json");
    ASSERT_EQ(c.exit_code, 0) << c.err << c.out;
    const json k = json::parse(c.out);
    ASSERT_TRUE(k.contains("calibration")) << c.out;
    EXPECT_LT(k["calibration"]["metrics"]["Fx_N"]["rmse"].get<double>(),
              k["metrics"]["Fx_N"]["rmse"].get<double>());
}

// `synth` with a lugged wheel A, then `identify` with the same wheel: the full-model
// identification gives back the soil (sandy loam, j_max 0.02 m); the decoupled fit, which has no
// shearing radius, says that it treats the wheel as smooth.
TEST_F(LuggedWheelCli, IdentifyWithTheLuggedWheelRecoversTheSoil) {
    json w{{"name", "A lugged"},       {"r_m", 0.092},        {"b_m", 0.107},
           {"grouser_height_m", 0.01}, {"grouser_count", 18}, {"lug_effect_coefficient", 0.5}};
    const std::string wheel_file = (dir_ / "wheel-a-lugged.json").string();
    std::ofstream(wheel_file) << w.dump();
    const std::string data = (dir_ / "lugged.csv").string();
    const CliRun s = run("synth --soil sandy-loam --wheel " + wheel_file +
                         " --load 40,58.86,80 --slips 0:0.75:16 --out " + data);
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const CliRun r =
        run("identify --data " + data + " --wheel " + wheel_file + " --jmax 0.02 --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json p = json::parse(r.out);
    EXPECT_NEAR(p["phi_deg"].get<double>(), 29.0, 1e-3) << r.out;
    EXPECT_NEAR(p["n0"].get<double>(), 0.7, 1e-4) << r.out;
    EXPECT_NEAR(p["K_m"].get<double>(), 0.025, 1e-5) << r.out;
    const CliRun decoupled =
        run("identify --data " + data + " --wheel " + wheel_file + " --no-refine");
    EXPECT_EQ(decoupled.exit_code, 0) << decoupled.err;
    EXPECT_TRUE(contains(decoupled.err, "treats the lugged wheel as smooth")) << decoupled.err;
}

}  // namespace
