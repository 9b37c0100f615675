// Item 1 of issue 11 through the real executable, for every kind of input file: an overflowing
// number (1e999), a non-finite one (NaN: not JSON), a subnormal one (1e-320) and an absurd
// magnitude within a double (1e-300) in soil, wheel, robot, scenario (and its signals), run
// script and .terra files are exit-2 errors naming the file, the line or the key, and the value;
// range errors name the allowed range (docs/reliability.md). The CSV columns are covered by
// csv_input_cli_test.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../core/test_temp_dir.h"
#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;
using terra::test::CliRun;
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
                       {soil + ":1:", "c_kPa: " + what});
        const std::string wheel =
            write("wheel.json", "{\"name\": \"w\", \"r_m\": " + v + ", \"b_m\": 0.1}");
        expectRejected("wheel --wheel " + wheel + " --slip 0.2 --load 58",
                       {wheel + ":1:", "r_m: " + what});
        const std::string robot = write("robot.json", robotWith(v));
        const std::string with_robot = write("with-robot.json", scenarioWith(robot, "5"));
        expectRejected("simulate --scenario " + with_robot + " --out " + (dir_ / "o").string(),
                       {robot + ":1:", "chassis_mass_kg: " + what});
        const std::string signal = write("signal.json", scenarioWith("default", v));
        expectRejected("simulate --scenario " + signal + " --out " + (dir_ / "o").string(),
                       {signal + ":2:", "wheels.all.steer_deg.amplitude: " + what});
        const std::string script =
            write("script.json", "{\"conditions\": {\"load_N\": " + v + "}, \"analyses\": []}");
        expectRejected("run " + script + " --out " + (dir_ / "o").string(),
                       {script + ":1:", "conditions.load_N: " + what});
        const std::string project = write("p.terra",
                                          "{\"format\": \"terrastudio-project\", \"version\": 1,\n"
                                          "\"conditions\": {\"load_N\": " +
                                              v + "}}");
        expectRejected(project, {project + ":2:", "conditions.load_N: " + what});
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

}  // namespace
