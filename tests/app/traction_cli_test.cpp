// `terrastudio traction` through the real executable (docs/traction.md): the JSON of the issue's
// interface, s* on its own curve, bad flags named (exit 2), a cap no slip meets (exit 1).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.h"

namespace {

using nlohmann::json;
using terra::test::CliRun;
using terra::test::contains;
using terra::test::run;

TEST(TractionCli, TheJsonHasTheInterfacesKeysAndSStarIsTheCurvesBest) {
    const CliRun r =
        run("traction --soil sandy-loam --wheel A --load 58.86 --objective drawbar "
            "--slip-max 0.6 --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json out = json::parse(r.out);
    for (const char* key : {"optimal_slip", "objective", "Fx_N", "My_Nm", "efficiency", "curve"})
        EXPECT_TRUE(out.contains(key)) << key;
    EXPECT_EQ(out["objective"], "drawbar");
    double best = -1e300;
    for (const json& p : out["curve"]) {
        for (const char* key : {"slip", "Fx_N", "My_Nm", "efficiency", "sinkage_m"})
            EXPECT_TRUE(p.contains(key)) << key;
        best = std::max(best, p["Fx_N"].get<double>());
    }
    // Drawbar pull grows with slip here: s* is the search's bound, no curve point is better.
    EXPECT_GE(out["Fx_N"].get<double>(), best);
    EXPECT_NEAR(out["optimal_slip"].get<double>(), 0.6, 1e-6);
    EXPECT_TRUE(contains(r.err, "upper bound")) << r.err;
}

TEST(TractionCli, BadFlagsAreNamedAndAnImpossibleCapFails) {
    CliRun r = run("traction --objective power");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "--objective")) << r.err;
    r = run("traction --slip-min 0.8 --slip-max 0.2");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "--slip-max")) << r.err;
    r = run("traction --quantile 1.5");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "--quantile")) << r.err;
    r = run("traction --posterior /no/such/file.json");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "--posterior")) << r.err;
    r = run("traction --max-sinkage 0.0001");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "sinkage")) << r.err;
    // A cap that only slips without pull meet: s* is reported, and a note says it does not pull.
    r = run("traction --soil sandy-loam --wheel A --max-sinkage 0.004 --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json weak = json::parse(r.out);
    EXPECT_LE(weak["Fx_N"].get<double>(), 0.0);
    EXPECT_TRUE(contains(weak["notes"].dump(), "does not pull")) << r.out;
    // A load the soil cannot carry: the reason says how much it carries.
    r = run("traction --soil sandy-loam --wheel A --load 5000");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(contains(r.err, "no slip has an equilibrium at this load")) << r.err;
    EXPECT_TRUE(contains(r.err, "the soil carries only")) << r.err;
    // With --json the failure is still a JSON document (docs/cli.md: "status" always), exit 1.
    r = run("traction --max-sinkage 0.0001 --json");
    EXPECT_EQ(r.exit_code, 1);
    const json failed = json::parse(r.out);
    EXPECT_EQ(failed["status"], "failed");
    EXPECT_TRUE(contains(failed["message"].get<std::string>(), "sinkage")) << r.out;
}

// The flags are the settings object read by the analysis's reader: its wording, named by the
// flag, exit 2.
TEST(TractionCli, AFlagOutOfRangeGetsTheReadersWordsNamedByTheFlag) {
    CliRun r = run("traction --points 3");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "--points: 3 is outside the allowed range [5, 10000]")) << r.err;
    r = run("traction --samples 5");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "--samples: 5 is outside the allowed range [10, 1e+05]")) << r.err;
    r = run("traction --objective effciency");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "--objective: ")) << r.err;
    EXPECT_TRUE(contains(r.err, "did you mean \"efficiency\"")) << r.err;
}

}  // namespace
