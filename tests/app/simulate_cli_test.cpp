// `terrastudio simulate` as a user runs it: outputs, summary keys, errors, and Ctrl-C.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;

using SimRun = terra::test::CliRun;

SimRun simulate(const std::string& arguments) { return terra::test::run("simulate " + arguments); }

fs::path outDir(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("terra_sim_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    return dir;
}

int countLines(const fs::path& file) {
    std::ifstream in(file);
    int n = 0;
    for (std::string line; std::getline(in, line);) ++n;
    return n;
}

TEST(SimulateCli, WritesTheTimeSeriesAndTheSummary) {
    const fs::path dir = outDir("straight");
    const SimRun r = simulate("--scenario straight --duration 2 --out " + dir.string() + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    for (const char* key :
         {"duration_s", "x_m", "y_m", "yaw_rad", "distance_m", "mean_slip", "energy_J"}) {
        EXPECT_TRUE(j.contains(key)) << key;
    }
    for (const char* wheel : {"FL", "FR", "RL", "RR"}) EXPECT_TRUE(j["mean_slip"].contains(wheel));
    EXPECT_EQ(j["status"], "completed");
    EXPECT_DOUBLE_EQ(j["duration_s"].get<double>(), 2.0);
    EXPECT_EQ(j["y_m"].get<double>(), 0.0);  // straight, symmetric
    // The file holds the same summary; one row per 10 ms output interval plus the header.
    std::ifstream summary(dir / "summary.json");
    EXPECT_EQ(nlohmann::json::parse(summary), j);
    EXPECT_EQ(countLines(dir / "timeseries.csv"), 1 + 201);
    fs::remove_all(dir);
}

TEST(SimulateCli, ScenarioFileByPathAndHumanOutput) {
    const fs::path dir = outDir("file");
    const SimRun r = simulate(
        "--scenario " + std::string(TERRA_RESOURCE_DIR) +
        "/scenarios/pulse-steering.json --duration 1 --model quadratic --out " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("mean slip"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(dir / "timeseries.csv"));
    EXPECT_EQ(r.err.find('\r'),
              std::string::npos);  // no progress bar when stderr is not a terminal
    fs::remove_all(dir);
}

TEST(SimulateCli, BadScenarioExitsTwoNamingTheField) {
    const fs::path dir = outDir("bad");
    fs::create_directories(dir);
    const fs::path file = dir / "bad.json";
    std::ofstream(file) << R"({"duration_s": 10, "time_step_s": 0.2, "terrain": "sandy-loam",
                              "wheels": {"all": {"omega_rad_s": 0.4}}})";
    SimRun r = simulate("--scenario " + file.string() + " --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("time_step_s"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out"));

    r = simulate("--scenario no-such-thing --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("pulse-steering"), std::string::npos) << r.err;  // lists the scenarios
    r = simulate("--scenario straight --duration -1 --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--duration"), std::string::npos) << r.err;
    fs::remove_all(dir);
}

// Issue 28, finding 1: a 0.05 s step (inside [1e-6, 0.05]) sent the robot 149.6 m, flipped it,
// reported negative motor energy and an energy balance error of 0.0 as a completed run. The step
// is refused at load, exit 2, with the largest stable step of this robot on this soil; a step
// below it runs and balances its energy.
TEST(SimulateCli, AStepTheDynamicsCannotTakeIsRefusedNamingTheLargestStableStep) {
    const fs::path dir = outDir("step");
    SimRun r = simulate("--scenario straight --out " + dir.string() + " --duration 10 --step 0.05");
    EXPECT_EQ(r.exit_code, 2) << r.err << r.out;
    EXPECT_NE(r.err.find("time_step_s: 0.05 s is above the largest stable step of this robot on "
                         "sandy loam, 0.00"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("turns unstable; docs/dynamics.md"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("allowed range [1e-06, 0.00"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "summary.json"));
    // 10 ms was as bad (the energy balance off by 900 %): refused too.
    r = simulate("--scenario straight --out " + dir.string() + " --duration 10 --step 0.01");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    // Half a stable step runs, completes and balances its energy (the motors' work is positive).
    r = simulate("--scenario straight --out " + dir.string() +
                 " --duration 10 --step 0.004 --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["status"], "completed");
    EXPECT_GT(j["energy_J"].get<double>(), 0.0);
    EXPECT_LT(std::abs(j["energy_balance_error"].get<double>()), 1e-3);
    EXPECT_LT(j["x_m"].get<double>(), 0.37);  // rω T = 0.368 m at most
    // Below the vertical modes' bound the lateral force of slow driving can still chatter: pulse
    // steering at 8 ms. The run stops as diverged, with the reason, exit 1, its results so far
    // written and marked.
    const fs::path pulse = outDir("pulse");
    r = simulate("--scenario pulse-steering --step 0.008 --out " + pulse.string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("error: the simulation diverged at t = "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("the energy balance is off by"), std::string::npos) << r.err;
    std::ifstream summary(pulse / "summary.json");
    const auto s = nlohmann::json::parse(summary);
    EXPECT_EQ(s["status"], "diverged");
    EXPECT_LT(s["duration_s"].get<double>(), 60.0);
    fs::remove_all(dir);
    fs::remove_all(pulse);
}

// A run whose energy balance is off is said once: as a row of the human summary, or on stderr
// beside --json's "warning" key (counter-steer at the largest step the reader allows diverges).
TEST(SimulateCli, TheEnergyBalanceWarningIsSaidOnce) {
    const fs::path dir = outDir("balance");
    const std::string args =
        "--scenario counter-steer --model quadratic --step 0.008 "
        "--duration 10 --out " +
        dir.string();
    auto count = [](const std::string& text, const std::string& what) {
        int n = 0;
        for (std::size_t at = text.find(what); at != std::string::npos;
             at = text.find(what, at + 1))
            ++n;
        return n;
    };
    const SimRun human = simulate(args);
    EXPECT_EQ(human.exit_code, 1) << human.err;  // it diverges: the error names that
    EXPECT_EQ(count(human.out, "warning: the energy balance is off by"), 1) << human.out;
    EXPECT_EQ(count(human.err, "warning"), 0) << human.err;
    const SimRun json = simulate(args + " --json");
    EXPECT_TRUE(nlohmann::json::parse(json.out).contains("warning"));
    EXPECT_EQ(count(json.err, "warning: the energy balance is off by"), 1) << json.err;
    fs::remove_all(dir);
}

TEST(SimulateCli, CtrlCStopsAndStillWritesWhatWasComputed) {
    const fs::path dir = outDir("cancel");
    const fs::path out_file = dir.string() + ".stdout";
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        const int fd = ::open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(fd, STDOUT_FILENO);
        ::dup2(fd, STDERR_FILENO);
        // Long enough (full model, ~10 min of robot time) that it is still running at the signal.
        ::execl(TERRASTUDIO_EXE, TERRASTUDIO_EXE, "simulate", "--scenario", "straight",
                "--duration", "600", "--json", "--out", dir.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    ::kill(pid, SIGINT);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130);
    std::ifstream summary_file(dir / "summary.json");
    ASSERT_TRUE(summary_file.good());
    const auto summary = nlohmann::json::parse(summary_file);
    EXPECT_EQ(summary["status"], "cancelled");
    EXPECT_GT(summary["duration_s"].get<double>(), 0.0);
    EXPECT_LT(summary["duration_s"].get<double>(), 600.0);
    // Rows up to where it stopped: 100 per simulated second, plus the header.
    EXPECT_NEAR(countLines(dir / "timeseries.csv"), 1 + 100 * summary["duration_s"].get<double>(),
                2);
    fs::remove_all(dir);
    fs::remove(out_file);
}

}  // namespace

TEST(SimulateCli, ComparesTheControllers) {
    const fs::path dir = outDir("compare");
    const SimRun r = simulate(
        "--scenario traction-load-change --duration 2 --compare --json --out " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto table = nlohmann::json::parse(r.out);
    ASSERT_EQ(table.size(), 4u);
    const char* names[] = {"constant-speed", "fixed-slip", "optimal", "oracle"};
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(table[i]["controller"], names[i]);
        // Each run's own summary beside the table, with the figures the table took from it.
        std::ifstream in(dir / names[i] / "summary.json");
        const auto summary = nlohmann::json::parse(in);
        EXPECT_EQ(summary["energy_per_m_J"], table[i]["energy_per_m_J"]);
        EXPECT_EQ(summary["slip_tracking_rms"], table[i]["slip_tracking_rms"]);
        EXPECT_EQ(summary["controller"], names[i]);  // which controller drove it
    }
    EXPECT_TRUE(table[0]["slip_tracking_rms"].is_null());  // constant speed has no set-point
    EXPECT_DOUBLE_EQ(table[3]["drawbar_vs_oracle"].get<double>(), 1.0);
    std::ifstream file(dir / "comparison.json");
    EXPECT_EQ(nlohmann::json::parse(file), table);
    fs::remove_all(dir);
}

// The override flags are the rover's settings object read by its reader: its wording, named by
// the flag, exit 2, before anything runs.
TEST(SimulateCli, ABadOverrideGetsTheReadersWordsNamedByTheFlag) {
    const fs::path dir = outDir("flags");
    SimRun r = simulate("--scenario straight --slip 1.5 --out " + dir.string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--slip: 1.5 is outside the allowed range"), std::string::npos) << r.err;
    r = simulate("--scenario straight --duration -1 --out " + dir.string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--duration: -1 is outside the allowed range (0, 86400] s"),
              std::string::npos)
        << r.err;
    r = simulate("--scenario straight --posterior-method sigmapoints --out " + dir.string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--posterior-method: \"sigmapoints\" is not one of sigma-points, samples"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("did you mean \"sigma-points\""), std::string::npos) << r.err;
    r = simulate("--scenario straight --controller optimall --out " + dir.string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--controller: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("did you mean \"optimal\""), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "summary.json"));
    fs::remove_all(dir);
}

TEST(SimulateCli, ControllerOverrideAndBadSlip) {
    const fs::path dir = outDir("controller");
    const SimRun r = simulate(
        "--scenario straight --duration 2 --controller fixed-slip --slip 0.3 "
        "--json --out " +
        dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // Tracking is counted after the first second of the run.
    EXPECT_TRUE(nlohmann::json::parse(r.out)["slip_tracking_rms"].is_number());
    const SimRun bad = simulate("--scenario straight --slip 1.5 --out " + dir.string());
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("--slip"), std::string::npos) << bad.err;
    const SimRun unknown =
        simulate("--scenario straight --controller cruise --out " + dir.string());
    EXPECT_EQ(unknown.exit_code, 2);
    fs::remove_all(dir);
}
