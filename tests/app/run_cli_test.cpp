// `terrastudio run SCRIPT.json --out DIR` on the real executable: outputs, expectations and exit
// codes (0 all met, 1 an expectation failed, 2 a broken script).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;

using terra::test::CliRun;
using terra::test::readText;
using terra::test::run;

class RunCommand : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("terra_run_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path writeScript(const nlohmann::json& script) {
        const fs::path path = dir_ / "script.json";
        std::ofstream(path) << script.dump(2);
        return path;
    }
    fs::path dir_;
};

// F_x at s = 0.3, β = 5° from the single-point `wheel` command: an independent path through the
// CLI.
double singlePointFx() {
    const CliRun r =
        run("wheel --soil sandy-loam --wheel A --slip 0.3 --slip-angle 5 --load 58.86 --json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out)["Fx_N"].get<double>();
}

nlohmann::json forcesScript(double low, double high) {
    return {{"title", "test"},
            {"soil", "sandy-loam"},
            {"wheel", "A"},
            {"conditions",
             {{"load_N", 58.86},
              {"slip_angles_deg", {5, 15}},
              {"slip_count", 100},
              {"slip_max", 0.99}}},
            {"export", {{"width", 640}, {"height", 480}, {"formats", {"png", "svg"}}}},
            {"analyses",
             {{{"name", "fx"},
               {"type", "forces"},
               {"plots", {"Fx_N"}},
               {"expect",
                {{{"column", "Fx_N"},
                  {"at", {{"slip", 0.3}, {"slip_angle_deg", 5}}},
                  {"min", low},
                  {"max", high}}}}}}}};
}

TEST_F(RunCommand, MetExpectationsExitZeroAndWritePlotsDataReport) {
    const double fx = singlePointFx();
    const fs::path script = writeScript(forcesScript(fx - 1e-6, fx + 1e-6));
    const CliRun r = run("run " + script.string() + " --out " + (dir_ / "out").string());
    ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
    for (const char* file :
         {"fx-Fx_N.png", "fx-Fx_N.svg", "fx.csv", "report.md", "manifest.json"}) {
        EXPECT_TRUE(fs::exists(dir_ / "out" / file)) << file;
    }
    const std::string report = readText(dir_ / "out" / "report.md");
    EXPECT_NE(report.find("All expectations met"), std::string::npos) << report;
    EXPECT_NE(report.find("![fx-Fx_N.png](fx-Fx_N.png)"), std::string::npos);
    const auto manifest = nlohmann::json::parse(readText(dir_ / "out" / "manifest.json"));
    EXPECT_EQ(manifest["failed"], 0);
    EXPECT_EQ(manifest["inputs"]["soil"], "sandy-loam");
}

TEST_F(RunCommand, FailedExpectationExitsOneAndIsListedInTheReport) {
    const fs::path script = writeScript(forcesScript(1000.0, 2000.0));
    const CliRun r = run("run " + script.string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.out.find("FAIL: fx: Fx_N at slip = 0.3"), std::string::npos) << r.out;
    const std::string report = readText(dir_ / "out" / "report.md");
    EXPECT_NE(report.find("## Failures"), std::string::npos) << report;
    EXPECT_NE(report.find("NOT in [1000, 2000]"), std::string::npos) << report;
    EXPECT_TRUE(fs::exists(dir_ / "out" / "fx-Fx_N.png"));  // outputs are still written
}

TEST_F(RunCommand, BrokenScriptExitsTwoNamingTheField) {
    nlohmann::json script = forcesScript(0, 1);
    script["analyses"][0]["type"] = "forcez";
    const CliRun bad_type =
        run("run " + writeScript(script).string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(bad_type.exit_code, 2);
    EXPECT_NE(bad_type.err.find("analyses[0].type"), std::string::npos) << bad_type.err;

    script = forcesScript(0, 1);
    script["set"] = {{"phi_deg", 75}};
    const CliRun bad_value =
        run("run " + writeScript(script).string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(bad_value.exit_code, 2);
    EXPECT_NE(bad_value.err.find("phi_deg"), std::string::npos) << bad_value.err;
    EXPECT_NE(bad_value.err.find("[0, 60)"), std::string::npos) << bad_value.err;

    const CliRun missing =
        run("run " + (dir_ / "nope.json").string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(missing.exit_code, 2);
}

// A short straight-line rover run (3 s of the thesis scenario): physical bounds only.
nlohmann::json roverScript(double yaw_min_deg, double yaw_max_deg) {
    const double no_slip_m = 0.092 * 0.4 * 3.0;  // r ω T: wheel A at Table 2.6's 0.4 rad/s
    return {{"export", {{"width", 640}, {"height", 480}, {"formats", {"png", "svg"}}}},
            {"analyses",
             {{{"name", "straight"},
               {"type", "rover"},
               {"scenario", "straight"},
               {"duration_s", 3.0},
               {"plots", {"path", "slip", "top-view"}},
               {"expect",
                {{{"column", "yaw_deg"}, {"min", yaw_min_deg}, {"max", yaw_max_deg}},
                 {{"column", "x_m"}, {"min", 0.0}, {"max", no_slip_m}},
                 {{"column", "y_m"}, {"min", -1e-9}, {"max", 1e-9}},
                 {{"column", "mean_slip_FL"}, {"min", 0.0}, {"max", 1.0}},
                 {{"column", "lateral_m_s"},
                  {"table", "timeseries"},
                  {"at", {{"t_s", 2.0}}},
                  {"min", -1e-9},
                  {"max", 1e-9}}}}}}}};
}

TEST_F(RunCommand, RoverAnalysisWritesFiguresSeriesAndTheSameSummaryAsSimulate) {
    const fs::path script = writeScript(roverScript(-1e-9, 1e-9));
    const CliRun r = run("run " + script.string() + " --out " + (dir_ / "out").string());
    ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
    for (const char* file :
         {"straight-path.png", "straight-path.svg", "straight-slip.png", "straight-top-view.png",
          "straight-timeseries.csv", "straight-summary.json", "report.md"}) {
        EXPECT_TRUE(fs::exists(dir_ / "out" / file)) << file;
    }
    EXPECT_FALSE(fs::exists(dir_ / "out" / "straight-yaw.png"));  // only the plots asked for
    // The same scenario through `simulate`: an independent path to the same (deterministic) run.
    const CliRun sim = run("simulate --scenario straight --duration 3 --out " +
                           (dir_ / "sim").string() + " --json");
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    const auto expected = nlohmann::json::parse(sim.out);
    const auto summary = nlohmann::json::parse(readText(dir_ / "out" / "straight-summary.json"));
    for (const char* key : {"x_m", "y_m", "yaw_rad", "energy_J", "duration_s"}) {
        EXPECT_EQ(summary[key].get<double>(), expected[key].get<double>()) << key;
    }
    EXPECT_EQ(readText(dir_ / "out" / "straight-timeseries.csv"),
              readText(dir_ / "sim" / "timeseries.csv"));
}

// A traction and a compaction analysis wrote their JSON to files named as the analysis, with no
// extension ("best", "soil"). Each JSON document is now <name>.json and is what the subcommand's
// --json prints for the same settings; the stress field's is written too.
TEST_F(RunCommand, EachAnalysisWritesItsJsonToANameEndingInJson) {
    const fs::path script = writeScript(nlohmann::json::parse(R"({"analyses": [
        {"name": "best", "type": "traction"},
        {"name": "soil", "type": "compaction", "passes": 2},
        {"name": "field", "type": "stresses", "step_deg": 0.5}]})"));
    const CliRun r = run("run " + script.string() + " --out " + (dir_ / "out").string());
    ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
    for (const auto& entry : fs::directory_iterator(dir_ / "out"))
        EXPECT_TRUE(entry.path().has_extension()) << entry.path();
    const std::array<std::pair<const char*, const char*>, 3> runs{{
        {"best", "traction --json"},
        {"soil", "compaction --passes 2 --json"},
        {"field", "stresses --step 0.5 --json"},
    }};
    for (const auto& [name, command] : runs) {
        const fs::path file = dir_ / "out" / (std::string(name) + ".json");
        ASSERT_TRUE(fs::exists(file)) << file;
        const CliRun direct = run(command);
        ASSERT_EQ(direct.exit_code, 0) << command << ": " << direct.err;
        EXPECT_EQ(nlohmann::json::parse(readText(file)), nlohmann::json::parse(direct.out))
            << command;
    }
}

TEST_F(RunCommand, FailedRoverExpectationExitsOne) {
    // A straight run does not turn 5–10°: the expectation fails, the outputs are still written.
    const fs::path script = writeScript(roverScript(5.0, 10.0));
    const CliRun r = run("run " + script.string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.out.find("FAIL: straight: yaw_deg"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("pass: straight: x_m"), std::string::npos) << r.out;
    EXPECT_NE(readText(dir_ / "out" / "report.md").find("NOT in [5, 10]"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir_ / "out" / "straight-path.png"));
}

TEST_F(RunCommand, BrokenRoverAnalysisExitsTwoNamingTheField) {
    nlohmann::json script = roverScript(0, 1);
    script["analyses"][0]["scenario"] = "no-such-scenario";
    CliRun r = run("run " + writeScript(script).string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("analyses[0].scenario"), std::string::npos) << r.err;
    script = roverScript(0, 1);
    script["analyses"][0]["time_step_s"] = 0.5;
    r = run("run " + writeScript(script).string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("analyses[0].time_step_s"), std::string::npos) << r.err;
    script = roverScript(0, 1);
    script["analyses"][0]["plots"] = {"pathh"};
    r = run("run " + writeScript(script).string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("\"pathh\" is not one of"), std::string::npos) << r.err;
}

TEST_F(RunCommand, ShippedExampleScriptsRunAndMeetTheirExpectations) {
    for (const auto& entry : fs::directory_iterator(TERRA_RESOURCE_DIR "/scripts")) {
        if (entry.path().extension() != ".json") continue;
        const fs::path out = dir_ / entry.path().stem();
        const CliRun r = run("run " + entry.path().string() + " --out " + out.string());
        EXPECT_EQ(r.exit_code, 0) << entry.path() << "\n" << r.err << r.out;
        EXPECT_TRUE(fs::exists(out / "report.md")) << entry.path();
    }
}

// Issue 28, finding 6: a stress field at a load the soil cannot carry is a failed analysis (exit 1,
// the reason in the report), not an empty grid, a table of zero errors and "All expectations met".
TEST_F(RunCommand, StressesWithoutEquilibriumFailWithTheReason) {
    nlohmann::json script = forcesScript(0, 1);
    script["conditions"]["load_N"] = 5000;
    script["analyses"] = {{{"name", "st"},
                           {"type", "stresses"},
                           {"slip", 0.2},
                           {"expect",
                            {{{"table", "errors"},
                              {"column", "rmse_kPa"},
                              {"at", {{"stress_index", 0}}},
                              {"min", 0},
                              {"max", 100}}}}}};
    const fs::path path = writeScript(script);
    const CliRun r = run("run " + path.string() + " --out " + (dir_ / "out").string());
    EXPECT_EQ(r.exit_code, 1) << r.err << r.out;
    EXPECT_NE(r.out.find("FAIL: st: no equilibrium"), std::string::npos) << r.out;
    const std::string report = readText(dir_ / "out" / "report.md");
    EXPECT_EQ(report.find("All expectations met"), std::string::npos) << report;
    EXPECT_NE(report.find("FAILED"), std::string::npos) << report;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "st.csv")) << "an empty grid was written";
    EXPECT_FALSE(fs::exists(dir_ / "out" / "st-errors.csv")) << "a table of zero errors";
    const auto manifest = nlohmann::json::parse(readText(dir_ / "out" / "manifest.json"));
    EXPECT_GE(manifest["failed"].get<int>(), 1);
}

}  // namespace

// The broken scripts measured in issue 10, each through the real executable: exit 2, the field
// named on stderr, nothing written (the output directory is not even created).
class StrictScript : public RunCommand {
protected:
    CliRun runText(const std::string& text) {
        const fs::path path = dir_ / "script.json";
        std::ofstream(path) << text;
        return run("run " + path.string() + " --out " + (dir_ / "out").string());
    }
    CliRun runJson(const nlohmann::json& script) { return runText(script.dump(2)); }
    void expectRejected(const CliRun& r, const std::string& message) {
        EXPECT_EQ(r.exit_code, 2) << r.err << r.out;
        EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
        EXPECT_LT(r.err.size(), 600u) << r.err;  // a short message, not a dump
        EXPECT_FALSE(fs::exists(dir_ / "out")) << "something was written";
    }
};

TEST_F(StrictScript, ConditionsThatAreNotAnObject) {
    nlohmann::json script = forcesScript(0, 1);
    script["conditions"] = "x";
    expectRejected(runJson(script),
                   "script.json: conditions: expected a JSON object, got string \"x\"");
}

TEST_F(StrictScript, NumericTitle) {
    nlohmann::json script = forcesScript(0, 1);
    script["title"] = 12;
    expectRejected(runJson(script), "script.json: title: expected a string, got number 12");
    script = forcesScript(0, 1);
    script["analyses"][0]["title"] = 3.5;
    expectRejected(runJson(script), "analyses[0].title: expected a string, got number 3.5");
}

TEST_F(StrictScript, MisspeltKeyNamesTheNearestOne) {
    nlohmann::json script = forcesScript(0, 1);
    script["condtions"] = script["conditions"];
    script.erase("conditions");
    expectRejected(runJson(script), "condtions: unknown key; did you mean \"conditions\"?");
    script = forcesScript(0, 1);
    script["analyses"][0]["expect"][0]["colum"] = "Fx_N";
    expectRejected(runJson(script), "analyses[0].expect[0].colum: unknown key; did you mean");
}

TEST_F(StrictScript, DuplicatedKeyIsNamedWithItsPosition) {
    // Line 2 holds the second "title" at column 3.
    expectRejected(runText("{\"title\": \"a\",\n  \"title\": \"b\", \"analyses\": []}"),
                   "script.json:2:3: duplicated key \"title\" at the top level (first at line 1, "
                   "column 2)");
}

TEST_F(StrictScript, HugeSlipCountIsARangeError) {
    nlohmann::json script = forcesScript(0, 1);
    script["analyses"].push_back({{"name", "s"}, {"type", "sensitivity"}, {"slip_count", 1e308}});
    expectRejected(runJson(script),
                   "script.json: analyses[1].slip_count: 1e+308 is outside the allowed range "
                   "[2, 10000]");
    // Beyond a double, in the text itself: the position and the key.
    expectRejected(runText("{\"analyses\": [{\"type\": \"sensitivity\", \"slip_count\": 1e999}]}"),
                   "script.json:1:53: analyses[0].slip_count: 1e999 is too large for a number");
}

TEST_F(StrictScript, EveryProblemIsListedAtOnce) {
    nlohmann::json script = forcesScript(0, 1);
    script["title"] = 1;
    script["conditions"]["load_N"] = -5;
    script["analyses"][0]["type"] = "forcez";
    script["analyses"].push_back({{"type", "stresses"}, {"slip", "0.2"}});
    const CliRun r = runJson(script);
    EXPECT_EQ(r.exit_code, 2);
    for (const char* part : {"title", "conditions.load_N", "analyses[0].type",
                             "did you mean \"forces\"", "analyses[1].slip: expected a number"}) {
        EXPECT_NE(r.err.find(part), std::string::npos) << part << "\n" << r.err;
    }
    EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(StrictScript, DuplicatedAnalysisNamesWouldOverwriteEachOther) {
    nlohmann::json script = forcesScript(0, 1);
    script["analyses"].push_back(script["analyses"][0]);
    expectRejected(runJson(script), "analyses[1].name: \"fx\" is also the name of analyses[0]");
}

TEST_F(StrictScript, ExpectationTablesAndFiguresAreChecked) {
    nlohmann::json script = forcesScript(0, 1);
    script["analyses"][0]["expect"][0]["table"] = "sweeps";
    expectRejected(runJson(script),
                   "analyses[0].expect[0].table: \"sweeps\" is not a table of forces (sweep); "
                   "did you mean \"sweep\"?");
    script = forcesScript(0, 1);
    script["analyses"][0]["plots"] = {"Fx"};
    expectRejected(runJson(script), "analyses[0].plots[0]: \"Fx\" is not one of Fx_N");
}

// Issue 28, finding 9: an analysis name with a line break (or any control character) became
// file names holding it; it is refused like a '/' (exit 2, nothing written), shown escaped.
TEST_F(StrictScript, AnAnalysisNameWithALineBreakIsRefused) {
    nlohmann::json script = forcesScript(0, 1);
    script["analyses"][0]["name"] = "f\nx";
    expectRejected(runJson(script), "analyses[0].name: \"f\\nx\" cannot start a file name");
    script["analyses"][0]["name"] = "f\x1b[2Jx";
    expectRejected(runJson(script), "analyses[0].name: \"f\\x1b[2Jx\" cannot start a file name");
}

// An analysis named "manifest" would write manifest.json over the run's own (a reviewer's
// finding, once stresses, traction and compaction write NAME.json): the name is reserved.
TEST_F(StrictScript, TheRunsOwnFileNamesAreReserved) {
    nlohmann::json script = forcesScript(0, 1);
    for (const char* name : {"manifest", "report"}) {
        script["analyses"][0]["name"] = name;
        expectRejected(runJson(script), std::string("analyses[0].name: \"") + name +
                                            "\" is reserved: the run writes manifest.json and "
                                            "report.md");
    }
}

TEST_F(StrictScript, CommentsAreAllowedWhereverAKeyIs) {
    const double fx = singlePointFx();
    nlohmann::json script = forcesScript(fx - 1e-6, fx + 1e-6);
    script["_comment"] = "a note";
    script["analyses"][0]["expect"][0]["why"] = "the single-point command gives the same";
    const CliRun r = runJson(script);
    EXPECT_EQ(r.exit_code, 0) << r.err;
}
