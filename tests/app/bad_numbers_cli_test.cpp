// Item 1 of issue 11 through the real executable, for every kind of input file: an overflowing
// number (1e999), a non-finite one (NaN: not JSON), a subnormal one (1e-320) and an absurd
// magnitude within a double (1e-300) in soil, wheel, robot, scenario (and its signals), run
// script and .terra files are exit-2 errors naming the file, the line or the key, and the value;
// range errors name the allowed range (docs/reliability.md). The CSV columns are covered by
// csv_input_cli_test.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../core/test_temp_dir.h"
#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;
using terra::test::CliRun;
using terra::test::readText;
using terra::test::run;

class BadNumbers : public ::testing::Test {
protected:
    std::string write(const std::string& name, const std::string& text) {
        const fs::path path = dir_ / name;
        std::ofstream(path) << text;
        return path.string();
    }
    // Runs `command`, expects exit 2 and every piece in stderr.
    void expectRejected(const std::string& command, const std::vector<std::string>& pieces) {
        const CliRun r = run(command);
        EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.err << r.out;
        for (const std::string& piece : pieces)
            EXPECT_NE(r.err.find(piece), std::string::npos)
                << command << "\nmissing: " << piece << "\nin: " << r.err;
    }
    terra::testing::TempDir temp_;  // a fresh directory per test, removed afterwards
    const std::filesystem::path dir_ = temp_.path();
};

std::string soilWith(const std::string& c_kpa) {
    return "{\"name\": \"s\", \"n\": 0.7, \"c_kPa\": " + c_kpa +
           ", \"phi_deg\": 29, \"kc\": 5.3, \"kphi\": 1515, \"K_m\": 0.025, \"gamma_kN_m3\": 15.2}";
}
std::string robotWith(const std::string& mass) {
    return "{\"wheel\": \"A\", \"chassis_mass_kg\": " + mass +
           ", \"chassis_inertia_kg_m2\": [0.4, 0.67, 0.94], \"wheel_mass_kg\": 1, "
           "\"wheelbase_m\": 0.5, \"track_m\": 0.4}";
}
std::string scenarioWith(const std::string& robot, const std::string& amplitude) {
    return "{\"robot\": \"" + robot +
           "\", \"duration_s\": 0.01, \"time_step_s\": 0.001, \"terrain\": \"sandy-loam\",\n"
           "\"wheels\": {\"all\": {\"omega_rad_s\": 0.4, \"steer_deg\": {\"type\": \"pulse\", "
           "\"value\": 0, \"amplitude\": " +
           amplitude + ", \"start_s\": 0, \"duration_s\": 1}}}}";
}

TEST_F(BadNumbers, OverflowAndSubnormalInEveryJsonFileNameFileLineKeyAndValue) {
    for (const std::string v : {"1e999", "1e-320"}) {
        const std::string what =
            v == "1e999" ? v + " is too large for a number" : v + " is too small for a number";
        const std::string soil = write("soil.json", soilWith(v));
        expectRejected("wheel --soil " + soil + " --slip 0.2 --load 58",
                       {soil + ":1:34: c_kPa: " + what, "; allowed range [0, 200] kPa"});
        const std::string wheel =
            write("wheel.json", "{\"name\": \"w\", \"r_m\": " + v + ", \"b_m\": 0.1}");
        expectRejected("wheel --wheel " + wheel + " --slip 0.2 --load 58",
                       {wheel + ":1:22: r_m: " + what, "; allowed range [0.01, 5] m"});
        const std::string robot = write("robot.json", robotWith(v));
        const std::string with_robot = write("with-robot.json", scenarioWith(robot, "5"));
        expectRejected(
            "simulate --scenario " + with_robot + " --out " + (dir_ / "o").string(),
            {robot + ":1:", "chassis_mass_kg: " + what, "; allowed range [0.01, 1e+06] kg"});
        const std::string signal = write("signal.json", scenarioWith("default", v));
        expectRejected("simulate --scenario " + signal + " --out " + (dir_ / "o").string(),
                       {signal + ":2:", "wheels.all.steer_deg.amplitude: " + what,
                        "; allowed range [-1e+09, 1e+09] deg"});
        const std::string script =
            write("script.json", "{\"conditions\": {\"load_N\": " + v + "}, \"analyses\": []}");
        expectRejected(
            "run " + script + " --out " + (dir_ / "o").string(),
            {script + ":1:", "conditions.load_N: " + what, "; allowed range [0.01, 1e+05] N"});
        const std::string project = write("p.terra",
                                          "{\"format\": \"terrastudio-project\", \"version\": 1,\n"
                                          "\"conditions\": {\"load_N\": " +
                                              v + "}}");
        expectRejected(project, {project + ":2:", "conditions.load_N: " + what,
                                 "; allowed range [0.01, 1e+05] N"});
    }
}

TEST_F(BadNumbers, NanIsNotJsonAndIsNamedWithItsPosition) {
    const std::string soil = write("soil.json", soilWith("NaN"));
    expectRejected("wheel --soil " + soil + " --slip 0.2 --load 58",
                   {soil + ":1:", "invalid JSON", "got 'N'"});
}

// Finite but absurd magnitudes (a radius of 1e-300 m is not a wheel): the physical ranges of
// docs/reliability.md reject them, naming the range.
TEST_F(BadNumbers, AbsurdMagnitudesAreOutsideThePhysicalRanges) {
    const std::string wheel =
        write("wheel.json", "{\"name\": \"w\", \"r_m\": 1e-300, \"b_m\": 5e-300}");
    expectRejected("wheel --wheel " + wheel + " --slip 0.2 --load 58",
                   {wheel, "r_m: 1e-300 is outside the allowed range [0.01, 5] m",
                    "b_m: 5e-300 is outside the allowed range [0.005, 5] m"});
    std::string soil_text = soilWith("1.7");
    soil_text.replace(soil_text.find("0.025"), 5, "1e-300");
    soil_text.replace(soil_text.find("15.2"), 4, "1e-300");
    const std::string soil = write("soil.json", soil_text);
    expectRejected("wheel --soil " + soil + " --slip 0.2 --load 58",
                   {soil, "K_m: 1e-300 is outside the allowed range [1e-04, 0.5] m",
                    "gamma_kN_m3: 1e-300 is outside the allowed range [0.5, 30] kN/m³"});
    const std::string robot = write("robot.json", robotWith("1e-300"));
    const std::string scenario = write("scenario.json", scenarioWith(robot, "5"));
    expectRejected(
        "simulate --scenario " + scenario + " --out " + (dir_ / "o").string(),
        {robot, "chassis_mass_kg: 1e-300 is outside the allowed range [0.01, 1e+06] kg"});
    expectRejected("wheel --slip 0.2 --load 1e-300",
                   {"1e-300", "outside the allowed range [0.01, 1e+05] N"});
    const std::string points = write("points.csv", "slip,load_N\n0.2,1e-300\n");
    expectRejected("wheel --input " + points,
                   {points + ":2: load_N = 1e-300 is outside the allowed range [0.01, 1e+05] N"});
}

// Every numeric value of the shipped soil, wheel, robot, scenarios and script, replaced in turn by
// a number a double cannot hold (1e999, -1e999) or by a subnormal one (1e-320): exit 2, and the
// message names the file with line and column, the key path, the value and the field's range.
// The paths of the numbers in `j` ("a.b", "a[2]"), as the messages spell them.
void numberPaths(const nlohmann::json& j, const std::string& path, std::vector<std::string>& out) {
    if (j.is_number()) out.push_back(path);
    if (j.is_object()) {
        for (const auto& [key, value] : j.items())
            numberPaths(value, path.empty() ? key : path + "." + key, out);
    }
    if (j.is_array()) {
        for (std::size_t i = 0; i < j.size(); ++i)
            numberPaths(j[i], path + "[" + std::to_string(i) + "]", out);
    }
}

nlohmann::json::json_pointer pointerOf(const std::string& path) {
    std::string pointer;
    std::string segment;
    auto flush = [&] {
        if (!segment.empty()) pointer += "/" + segment;
        segment.clear();
    };
    for (char c : path) {
        if (c == '.' || c == '[') {
            flush();
        } else if (c != ']') {
            segment += c;
        }
    }
    flush();
    return nlohmann::json::json_pointer(pointer);
}

TEST_F(BadNumbers, EveryNumericFieldOfEveryFileNamesTheRangeOfAnOverflowOrSubnormal) {
    const fs::path resources = TERRA_RESOURCE_DIR;
    struct Case {
        std::string file;                                        // under resources/
        std::function<std::string(const std::string&)> command;  // for the bad file's path
    };
    const std::string out = (dir_ / "o").string();
    const std::vector<Case> cases{
        {"soils/sandy-loam.json",
         [](const std::string& f) { return "wheel --soil " + f + " --slip 0.2 --load 58"; }},
        {"wheels/A.json",
         [](const std::string& f) { return "wheel --wheel " + f + " --slip 0.2 --load 58"; }},
        {"robots/default.json",
         [&](const std::string& f) {
             return "simulate --scenario " + write("uses-robot.json", scenarioWith(f, "5")) +
                    " --out " + out;
         }},
        {"scenarios/pulse-steering.json",
         [&](const std::string& f) { return "simulate --scenario " + f + " --out " + out; }},
        {"scenarios/soil-border.json",
         [&](const std::string& f) { return "simulate --scenario " + f + " --out " + out; }},
        {"scripts/default.json",
         [&](const std::string& f) { return "run " + f + " --out " + out; }},
    };
    int checked = 0;
    for (const Case& c : cases) {
        const nlohmann::json original = nlohmann::json::parse(readText(resources / c.file));
        std::vector<std::string> paths;
        numberPaths(original, "", paths);
        ASSERT_FALSE(paths.empty()) << c.file;
        for (const std::string& path : paths) {
            for (const std::string bad : {"1e999", "-1e999", "1e-320"}) {
                if (bad == "-1e999" && path != paths.front()) continue;  // once per file
                nlohmann::json edited = original;
                edited[pointerOf(path)] = "@BAD@";
                std::string text = edited.dump(1);
                text.replace(text.find("\"@BAD@\""), 7, bad);
                const std::string file = write(fs::path(c.file).filename().string(), text);
                const std::string what =
                    bad == "1e-320" ? " is too small for a number" : " is too large for a number";
                expectRejected(c.command(file),
                               {file + ":", ": " + path + ": " + bad + what, "; allowed range "});
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 60);
}

// Item 3 of the brief for scenarios: a duration just above 0 and signal amplitudes of ±1e9 (the
// edge of the amplitude's range) are clear exit-2 errors naming the key and the range.
TEST_F(BadNumbers, TinyDurationsAndHugeSignalAmplitudesAreNamedWithTheirRange) {
    std::string tiny = scenarioWith("default", "5");
    tiny.replace(tiny.find("\"duration_s\": 0.01"), 18, "\"duration_s\": 1e-300");
    const std::string short_run = write("tiny.json", tiny);
    expectRejected("simulate --scenario " + short_run + " --out " + (dir_ / "o").string(),
                   {short_run, "duration_s: 1e-300 is shorter than one time step (0.001 s)",
                    "allowed range [0.001, 86400] s"});
    expectRejected("simulate --scenario straight --duration 1e-300 --out " + (dir_ / "o").string(),
                   {"duration_s: 1e-300 is shorter than one time step (0.001 s)",
                    "allowed range [0.001, 86400] s"});
    const std::string script =
        write("rover.json",
              "{\"analyses\": [{\"name\": \"r\", \"type\": \"rover\", \"scenario\": "
              "\"straight\", \"duration_s\": 1e-300}]}");
    expectRejected("run " + script + " --out " + (dir_ / "o").string(),
                   {script + ": analyses[0].duration_s: 1e-300 is shorter than one time step",
                    "allowed range [0.001, 86400] s"});
    for (const std::string amplitude : {"1e9", "-1e9", "1e10"}) {
        const std::string signal = write("signal.json", scenarioWith("default", amplitude));
        const std::string range = amplitude == "1e10" ? "allowed range [-1e+09, 1e+09] deg"
                                                      : "allowed range [-60, 60] deg";
        expectRejected("simulate --scenario " + signal + " --out " + (dir_ / "o").string(),
                       {signal, "wheels.all.steer_deg", range});
    }
    const std::string ramp = write(
        "ramp.json",
        "{\"robot\": \"default\", \"duration_s\": 0.01, \"time_step_s\": 0.001,"
        " \"terrain\": \"sandy-loam\", \"wheels\": {\"all\": {\"omega_rad_s\": {\"type\": "
        "\"ramp\", \"value\": 0, \"amplitude\": 1e9, \"start_s\": 0, \"duration_s\": 1e-300}}}}");
    expectRejected("simulate --scenario " + ramp + " --out " + (dir_ / "o").string(),
                   {ramp, "wheels.all.omega_rad_s", "allowed range [0, 1000] rad/s"});
    // A table's times have a range too (they had none: 1e999 named no range).
    for (const std::string t : {"1e999", "-1"}) {
        const std::string table = write(
            "table.json",
            "{\"robot\": \"default\", \"duration_s\": 0.01, \"time_step_s\": 0.001,"
            " \"terrain\": \"sandy-loam\", \"wheels\": {\"all\": {\"omega_rad_s\": {\"type\": "
            "\"table\", \"t_s\": [0, " +
                t + "], \"values\": [0.4, 0.5]}}}}");
        expectRejected(
            "simulate --scenario " + table + " --out " + (dir_ / "o").string(),
            {table, "wheels.all.omega_rad_s.t_s[1]: " + t, "allowed range [0, 1e+06] s"});
    }
}

}  // namespace

namespace {

// The longest line of a command's stderr.
std::size_t longestLine(const std::string& text) {
    std::size_t longest = 0, start = 0;
    while (start <= text.size()) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        longest = std::max(longest, end - start);
        start = end + 1;
    }
    return longest;
}

}  // namespace

// Fuzzing found it (scenario_json, 2026-12-02): a preset name of 1,500 characters was echoed whole
// in "'…' is neither a file nor a preset". Every name, path or text a message quotes is cut to 80
// characters with its length (a choice among names to 60): a robot, soil or wheel preset name, a
// path, a script's table name, sensitivity parameter and analysis name, a file that cannot be
// opened.
TEST_F(BadNumbers, HugeNamesAndPathsAreQuotedShort) {
    const std::string name(1500, 'x');
    const std::string cut = "'" + std::string(80, 'x') + "\u2026' (1500 characters)";
    const std::string o = (dir_ / "o").string();
    struct Case {
        std::string command;
        std::string piece;
    };
    const std::vector<Case> cases{
        {"simulate --scenario " + write("robot.json", scenarioWith(name, "5")) + " --out " + o,
         "robot: robot: " + cut + " is neither a file nor a preset"},
        {"wheel --soil " + name + " --slip 0.2 --load 58", cut + " is neither a file nor a preset"},
        {"wheel --wheel a/" + name + " --slip 0.2 --load 58",
         "file 'a/" + std::string(78, 'x') + "\u2026' (1502 characters) does not exist"},
        {"run " +
             write("table.json", "{\"analyses\": [{\"type\": \"validation\", \"experiments\": \"" +
                                     std::string(TERRA_RESOURCE_DIR) +
                                     "/experiments/ding2011-smooth-hit-lss1-80N.csv\", \"expect\": "
                                     "[{\"column\": \"Fx_N_rmse\", \"table\": \"" +
                                     name + "\", \"max\": 4}]}]}") +
             " --out " + o,
         "\"" + std::string(80, 'x') + "\u2026\" (1500 characters) is not a table of"},
        {"run " +
             write("parameter.json",
                   "{\"analyses\": [{\"type\": \"sensitivity\", \"parameter\": \"" + name +
                       "\", \"values\": [1, 2]}]}") +
             " --out " + o,
         "analyses[0].parameter: \"" + std::string(57, 'x') + "...\" is not one of all, n,"},
        {"run " +
             write("name.json",
                   "{\"analyses\": [{\"type\": \"forces\", \"name\": \"" + name + "\"}]}") +
             " --out " + o,
         "\"" + std::string(80, 'x') + "\u2026\" (1500 characters) cannot start a file name"},
        // Fuzzing found it (script_json, 2026-12-02): a file that cannot be opened was named
        // whole twice ("<path>: cannot open <path>").
        {"run " +
             write("experiments.json",
                   "{\"analyses\": [{\"type\": \"validation\", \"experiments\": \"/nonexistent/" +
                       name + ".csv\"}]}") +
             " --out " + o,
         "experiments: '/nonexistent/" + std::string(67, 'x') +
             "\u2026' (1517 characters): cannot open '/nonexistent/"},
        {"run /nonexistent/" + name + ".json --out " + o,
         "'/nonexistent/" + std::string(67, 'x') + "\u2026' (1518 characters)"},
    };
    for (const Case& c : cases) {
        const CliRun r = run(c.command);
        EXPECT_EQ(r.exit_code, 2) << c.command.substr(0, 200) << "\n" << r.err.substr(0, 600);
        EXPECT_NE(r.err.find(c.piece), std::string::npos)
            << c.command.substr(0, 200) << "\nmissing: " << c.piece
            << "\nin: " << r.err.substr(0, 600);
        EXPECT_LT(longestLine(r.err), 600u) << r.err.substr(0, 600);
    }
}
