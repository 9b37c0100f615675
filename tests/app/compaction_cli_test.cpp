// `terrastudio compaction` through the real executable (docs/compaction.md): the JSON of the
// issue's interface; pass 1 is `terrastudio wheel` at the same point exactly; the risk column
// follows the bands from the printed σ_z and σ_pc; bad profiles and flags are exit-2 errors that
// name the layer and the field; a load without equilibrium is exit 1.
#include <gtest/gtest.h>

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
using terra::test::run;

json compaction(const std::string& flags) {
    const CliRun r = run("compaction " + flags + " --json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return json::parse(r.out);
}

TEST(CompactionCli, TheJsonHasTheInterfacesKeys) {
    const json out = compaction(
        "--soil sandy-loam --wheel B --load 800 --slip 0.2 --profile clay-wet --passes 2 "
        "--depths 0.1:0.5:5");
    ASSERT_EQ(out["profile"].size(), 5u);
    for (const json& row : out["profile"]) {
        for (const char* key : {"depth_m", "sigma_z_kPa", "p_kPa", "sigma_pc_kPa", "risk"})
            EXPECT_TRUE(row.contains(key)) << key;
    }
    EXPECT_TRUE(out.contains("red_to_depth_m"));
    ASSERT_EQ(out["passes"].size(), 2u);
    for (const json& pass : out["passes"]) {
        for (const char* key :
             {"pass", "sinkage_m", "rut_depth_m", "Fx_N", "My_Nm", "bulk_density_Mg_m3"})
            EXPECT_TRUE(pass.contains(key)) << key;
        EXPECT_EQ(pass["bulk_density_Mg_m3"].size(), 3u);  // one per layer
    }
    // Terranimo's bands, from the printed numbers.
    for (const json& row : out["profile"]) {
        const double ratio = row["sigma_z_kPa"].get<double>() / row["sigma_pc_kPa"].get<double>();
        const std::string expected = ratio > 1.1 ? "red" : ratio > 0.5 ? "yellow" : "green";
        EXPECT_EQ(row["risk"], expected) << row.dump();
    }
    // The red zone ends between the deepest red depth and the next one.
    const double red = out["red_to_depth_m"];
    EXPECT_EQ(out["profile"][0]["risk"], "red");
    EXPECT_GT(red, 0.1);
    EXPECT_LT(red, 0.2);
    // The second wheel in the first's rut sinks further, by less than the first did.
    const json& p1 = out["passes"][0];
    const json& p2 = out["passes"][1];
    EXPECT_GT(p2["sinkage_m"].get<double>(), p1["sinkage_m"].get<double>());
    EXPECT_LT(p2["sinkage_increment_m"].get<double>(), p1["sinkage_increment_m"].get<double>());
    EXPECT_LT(p1["rut_depth_m"].get<double>(), p1["sinkage_m"].get<double>());  // rebound
}

TEST(CompactionCli, PassOneIsTheWheelCommandExactly) {
    const json out = compaction("--soil sandy-loam --wheel A --load 70 --slip 0.3 --slip-angle 5");
    const CliRun w =
        run("wheel --soil sandy-loam --wheel A --load 70 --slip 0.3 --slip-angle 5 --json");
    ASSERT_EQ(w.exit_code, 0) << w.err;
    const json wheel = json::parse(w.out);
    const json& point = wheel.is_array() ? wheel[0] : wheel;
    const json& pass = out["passes"][0];
    EXPECT_EQ(pass["Fx_N"].get<double>(), point["Fx_N"].get<double>());
    EXPECT_EQ(pass["My_Nm"].get<double>(), point["My_Nm"].get<double>());
    EXPECT_EQ(pass["sinkage_m"].get<double>(), point["sinkage_m"].get<double>());
    // No profile: no σ_pc, no risk, no red zone.
    EXPECT_FALSE(out["profile"][0].contains("risk"));
    EXPECT_FALSE(out.contains("red_to_depth_m"));
}

TEST(CompactionCli, BadProfilesAndFlagsNameTheLayerAndField) {
    terra::testing::TempDir dir;
    auto profile = [&](const json& layers) {
        const fs::path path = dir.path() / "p.json";
        std::ofstream(path) << json{{"name", "bad"}, {"layers", layers}}.dump();
        return run("compaction --profile " + path.string());
    };
    const json good{{"top_m", 0},
                    {"bottom_m", 0.3},
                    {"clay_kg_kg", 0.2},
                    {"matric_suction_hPa", 100},
                    {"bulk_density_Mg_m3", 1.4}};
    json overlap = json::array({good, good});
    overlap[1]["top_m"] = 0.25;
    overlap[1]["bottom_m"] = 0.6;
    CliRun r = profile(overlap);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "layers[1].top_m")) << r.err;
    EXPECT_TRUE(contains(r.err, "overlaps")) << r.err;
    json percent = json::array({good});
    percent[0]["clay_kg_kg"] = 20;
    r = profile(percent);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "layers[0].clay_kg_kg")) << r.err;
    EXPECT_TRUE(contains(r.err, "20 % is 0.2")) << r.err;
    json suction = json::array({good});
    suction[0]["matric_suction_hPa"] = -50;
    r = profile(suction);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "layers[0].matric_suction_hPa")) << r.err;

    r = run("compaction --passes 0");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "--passes: 0 is outside the allowed range [1, 1000]")) << r.err;
    r = run("compaction --depths 0.3,0.2");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "--depths: depths must increase (0.2 after 0.3)")) << r.err;
    r = run("compaction --concentration 2");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "--concentration: 2 is outside the allowed range [2.5, 12]"))
        << r.err;
    r = run("compaction --profile no-such-profile");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "profile")) << r.err;
    EXPECT_TRUE(contains(r.err, "loam-moist")) << r.err;  // the presets are listed
}

TEST(CompactionCli, ALoadWithoutEquilibriumFails) {
    const CliRun r = run("compaction --load 5000");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "no equilibrium")) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
}

}  // namespace
