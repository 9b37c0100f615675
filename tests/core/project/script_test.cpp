// Run scripts read whole and strictly: every shipped script reads, every problem of a broken one
// is listed with its path, expectations check what they say.
#include "core/project/script.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/analysis/stresses.h"
#include "tests/core/test_support.h"

namespace terra::project {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using terra::testing::kLocations;

Result<Script> read(const json& script) {
    return scriptFromJson(script, "s.json", kLocations, TERRA_RESOURCE_DIR "/scripts");
}

using terra::testing::contains;

TEST(Script, ShippedScriptsRead) {
    int count = 0;
    for (const auto& entry : fs::directory_iterator(TERRA_RESOURCE_DIR "/scripts")) {
        const Result<Script> s = loadScript(entry.path(), kLocations);
        EXPECT_TRUE(s.ok()) << entry.path() << ": " << s.message();
        ++count;
    }
    EXPECT_GE(count, 7);
}

TEST(Script, AnalysesGetTheSharedInputsTheirOwnOverridesAndTheirSettings) {
    const json script = {{"soil", "sandy-loam"},
                         {"set", {{"phi_deg", 31}}},
                         {"conditions", {{"load_N", 40}, {"slip_angles_deg", {5}}}},
                         {"analyses",
                          {{{"type", "stresses"}, {"slip", 0.1}},
                           {{"name", "clay"},
                            {"type", "forces"},
                            {"soil", "clayey-soil"},
                            {"conditions", {{"model", "quadratic"}}},
                            {"plots", {"Fz_N", "Fx_N"}}}}}};
    const Result<Script> s = read(script);
    ASSERT_TRUE(s.ok()) << s.message();
    ASSERT_EQ(s->analyses.size(), 2u);
    const ScriptAnalysis& a = s->analyses[0];
    EXPECT_EQ(a.name, "stresses");  // the type when no name is given
    EXPECT_EQ(a.inputs.soil.name, "sandy loam");
    EXPECT_DOUBLE_EQ(a.inputs.soil.friction_angle_rad, 31.0 * M_PI / 180.0);
    EXPECT_EQ(a.inputs.conditions.load_n, 40.0);
    EXPECT_EQ(std::any_cast<const analysis::StressSettings&>(a.settings).slip, 0.1);
    EXPECT_EQ(a.figures.size(), 1u);
    const ScriptAnalysis& b = s->analyses[1];
    EXPECT_EQ(b.inputs.soil.name, "clayey soil");
    EXPECT_DOUBLE_EQ(b.inputs.soil.friction_angle_rad, 31.0 * M_PI / 180.0);  // the script's set
    EXPECT_TRUE(b.inputs.conditions.quadratic);
    EXPECT_EQ(b.inputs.conditions.load_n, 40.0);  // merged over the script's conditions
    ASSERT_EQ(b.figures.size(), 2u);
    EXPECT_EQ(b.figures[0].key, "Fz_N");
    EXPECT_EQ(b.figures[0].file_suffix, "-Fz_N");
}

TEST(Script, EveryProblemWithItsPath) {
    const json script = {{"title", 7},
                         {"soil", "moon-dust"},
                         {"set", {{"phii_deg", 20}}},
                         {"export", {{"width", 10}, {"formats", {"png", "gif"}}}},
                         {"analyses",
                          {{{"type", "forces"}, {"expect", {{{"column", "Fx_N"}, {"value", 3}}}}},
                           {{"type", "rover"}, {"soil", "sandy-loam"}},
                           {{"type", "sensitivity"}, {"parameter", "phi"}, {"slip_count", 2.5}}}}};
    const Result<Script> s = read(script);
    ASSERT_FALSE(s.ok());
    const std::string m = s.message();
    for (const char* part :
         {"s.json: title: expected a string", "s.json: soil: ", "moon-dust",
          "s.json: set.phii_deg: unknown key; did you mean \"phi_deg\"?",
          "s.json: export.width: 10 is outside the allowed range [200, 8000]",
          "s.json: export.formats[1]: \"gif\" is not one of png, svg, pdf",
          "analyses[0].expect[0]: \"value\" needs \"tolerance\"", "analyses[1].scenario: missing",
          "analyses[1].soil: unknown key", "analyses[2].parameter: \"phi\" is not one of",
          "analyses[2].slip_count: 2.5 is not a whole number"}) {
        EXPECT_TRUE(contains(m, part)) << part << "\n" << m;
    }
}

TEST(Script, AWrongSoilOnThisWheelIsFoundBeforeRunning) {
    // k_c = −500 with k_φ = 10 on wheel A: K_s = k_c/b + k_φ < 0 (contact_parameters.h).
    const json script = {{"set", {{"kc", -500}, {"kphi", 10}}},
                         {"analyses", {{{"type", "forces"}}}}};
    const Result<Script> s = read(script);
    ASSERT_FALSE(s.ok());
    EXPECT_TRUE(contains(s.message(), "analyses[0].soil: K_s = kc/b + kphi")) << s.message();
}

Table table() {
    return {{"slip", "slip_angle_deg", "Fx_N"},
            {{0.1, 5, 1.0}, {0.3, 5, 3.0}, {0.3, 15, 4.0}, {0.6, 15, 7.0}}};
}

TEST(Expectations, TheRowNearestToAtAndTheBounds) {
    Expectation e;
    e.column = "Fx_N";
    e.at = {{"slip", 0.31}, {"slip_angle_deg", 14}};
    e.min = 3.5;
    e.max = 4.5;
    ExpectationOutcome o = check(e, table());
    EXPECT_TRUE(o.passed) << o.text;
    EXPECT_EQ(o.text, "Fx_N at slip = 0.3, slip_angle_deg = 15: 4 in [3.5, 4.5]");
    e.max = 3.9;
    EXPECT_FALSE(check(e, table()).passed);
    e.column = "Fy_N";
    EXPECT_EQ(check(e, table()).text, "Fy_N: no such column in the results");
    EXPECT_FALSE(check(e, Table{{"Fy_N"}, {}}).passed);
}

TEST(Report, FailuresFirstAndTheManifestListsEveryOutcome) {
    Script script;
    script.title = "check";
    RunRecord ok{"a", "forces", {"a-Fx_N.png"}, {"a.csv"}, {{"x in [0, 1]", true}}, "", {}, 0.5};
    RunRecord bad{"b", "stresses", {}, {}, {{"y NOT in [0, 1]", false}}, "", {"note"}, 0.25};
    const std::string md = reportMarkdown(script, "s.json", {ok, bad});
    EXPECT_EQ(md.rfind("# check\n", 0), 0u);
    EXPECT_TRUE(contains(md, "**1 expectation(s) or analyses FAILED.**"));
    EXPECT_LT(md.find("## Failures"), md.find("## a (forces)"));
    EXPECT_TRUE(contains(md, "- `b`: y NOT in [0, 1]"));
    EXPECT_TRUE(contains(md, "![a-Fx_N.png](a-Fx_N.png)"));
    const json m = manifest(script, "s.json", {ok, bad}, "terrastudio test");
    EXPECT_EQ(m["failed"], 1);
    EXPECT_EQ(m["analyses"][1]["expectations"][0]["passed"], false);
}

}  // namespace
}  // namespace terra::project
