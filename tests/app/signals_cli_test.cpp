// Clean shutdown of the real executable: SIGINT, SIGTERM and SIGHUP stop every long command, which
// writes what it computed, marked cancelled, and exits with 128 + the signal; a second signal ends
// it at once; a write killed with SIGKILL leaves nothing behind (docs/cli.md, "Exit codes").
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_process.h"
#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using terra::test::CliProcess;
using terra::test::lines;
using terra::test::readText;

class Signals : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("terra_signals_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    // Starts the command, waits until its handlers are installed and it has worked a little,
    // sends `number`, and returns the exit code (-1 if it did not exit normally).
    int stopWith(CliProcess& process, int number) {
        EXPECT_TRUE(process.waitUntilCatching(SIGTERM, 60s)) << process.err();
        std::this_thread::sleep_for(300ms);
        process.signal(number);
        const int status = process.wait();
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
    fs::path dir_;
};

std::set<std::string> listing(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename());
    return names;
}

TEST_F(Signals, SimulateWritesACancelledRunOnEachSignal) {
    for (const auto& [number, name, code] :
         {std::tuple{SIGTERM, "SIGTERM", 143}, {SIGHUP, "SIGHUP", 129}, {SIGINT, "SIGINT", 130}}) {
        const fs::path out = dir_ / name;
        // Long enough (~10 min of robot time) that it is still running at the signal.
        CliProcess p({"simulate", "--scenario", "straight", "--duration", "600", "--out", out},
                     dir_ / name);
        EXPECT_EQ(stopWith(p, number), code) << name << ": " << p.err();
        EXPECT_NE(p.err().find(std::string("by ") + name), std::string::npos) << p.err();
        const auto summary = nlohmann::json::parse(readText(out / "summary.json"));
        EXPECT_EQ(summary["status"], "cancelled") << name;
        const double duration = summary["duration_s"].get<double>();
        EXPECT_GT(duration, 0.0) << name;
        EXPECT_LT(duration, 600.0) << name;
        // Rows up to where it stopped: 100 per simulated second, plus the header.
        const auto rows = lines(readText(out / "timeseries.csv"));
        EXPECT_NEAR(static_cast<double>(rows.size()), 1 + 100 * duration, 2) << name;
        EXPECT_EQ(listing(out), (std::set<std::string>{"summary.json", "timeseries.csv"}));
    }
}

// Two different signals stay pending while the process is stopped and arrive one after the other
// when it continues: the first asks for a clean stop, the second ends the process at once.
TEST_F(Signals, ASecondSignalEndsTheProcessAtOnce) {
    const fs::path out = dir_ / "run";
    CliProcess p({"simulate", "--scenario", "straight", "--duration", "600", "--out", out},
                 dir_ / "second");
    ASSERT_TRUE(p.waitUntilCatching(SIGTERM, 60s));
    p.signal(SIGSTOP);
    p.signal(SIGTERM);
    p.signal(SIGINT);
    p.signal(SIGCONT);
    const int status = p.wait();
    ASSERT_TRUE(WIFSIGNALED(status)) << "exit " << WEXITSTATUS(status) << ": " << p.err();
    EXPECT_TRUE(WTERMSIG(status) == SIGTERM || WTERMSIG(status) == SIGINT) << WTERMSIG(status);
    EXPECT_FALSE(fs::exists(out / "summary.json"));
}

TEST_F(Signals, SweepWritesTheRowsSoFarWithAClosingNote) {
    const fs::path csv = dir_ / "sweep.csv";
    CliProcess p({"sweep", "--slips", "0:0.99:20000", "--slip-angles", "5", "--out", csv},
                 dir_ / "sweep");
    ASSERT_EQ(stopWith(p, SIGTERM), 143) << p.err();
    const auto text = lines(readText(csv));
    ASSERT_GE(text.size(), 3u);
    EXPECT_EQ(text.front().rfind("slip_angle_deg,slip,", 0), 0u) << text.front();
    const std::string note =
        "# cancelled by SIGTERM after " + std::to_string(text.size() - 2) + " rows";
    EXPECT_EQ(text.back(), note);
    EXPECT_LT(text.size() - 2, 20000u);
    EXPECT_NE(p.err().find(note.substr(2)), std::string::npos) << p.err();
}

TEST_F(Signals, SweepJsonIsMarkedCancelled) {
    const fs::path file = dir_ / "sweep.json";
    CliProcess p(
        {"sweep", "--slips", "0:0.99:20000", "--slip-angles", "5", "--json", "--out", file},
        dir_ / "sweep");
    ASSERT_EQ(stopWith(p, SIGHUP), 129) << p.err();
    const auto j = nlohmann::json::parse(readText(file));
    EXPECT_EQ(j["cancelled"], true);
    EXPECT_GT(j["rows"].size(), 0u);
    EXPECT_LT(j["rows"].size(), 20000u);
    EXPECT_EQ(j["note"], "cancelled by SIGHUP after " + std::to_string(j["rows"].size()) + " rows");
}

TEST_F(Signals, SynthWritesAPartialDataSetThatIdentifyReads) {
    const fs::path csv = dir_ / "data.csv";
    CliProcess p({"synth", "--slips", "0:0.9:100000", "--out", csv}, dir_ / "synth");
    ASSERT_EQ(stopWith(p, SIGTERM), 143) << p.err();
    const auto text = lines(readText(csv));
    ASSERT_GE(text.size(), 3u);
    EXPECT_EQ(text.back(),
              "# cancelled by SIGTERM after " + std::to_string(text.size() - 2) + " samples");
    // The data set reader skips the note: the partial file is a valid data set. The decoupled fit
    // reads it as the global search would (with the search, the ~30,000 samples that synth
    // writes in 0.3 s made this test take 11.5 s).
    const auto r = terra::test::run("identify --data " + csv.string() + " --json --no-refine");
    EXPECT_NE(r.exit_code, 2) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["samples"], text.size() - 2);
}

TEST_F(Signals, WheelBatchMarksTheRowsNotComputed) {
    const fs::path input = dir_ / "points.csv";
    const fs::path output = dir_ / "forces.csv";
    constexpr int kRows = 100000;
    {
        std::ofstream in(input);
        in << "slip,load_N\n";
        for (int i = 0; i < kRows; ++i) in << 0.9 * i / kRows << ",58.86\n";
    }
    CliProcess p({"wheel", "--input", input, "--output", output}, dir_ / "wheel");
    ASSERT_EQ(stopWith(p, SIGTERM), 143) << p.err();
    const auto text = lines(readText(output));
    ASSERT_EQ(text.size(), kRows + 1u);  // every input row, in order
    std::size_t ok = 0, cancelled = 0;
    for (std::size_t i = 1; i < text.size(); ++i) {
        const bool is_cancelled = text[i].find(",cancelled,") != std::string::npos;
        if (is_cancelled) {
            ++cancelled;
        } else {
            EXPECT_EQ(cancelled, 0u) << "computed row after a cancelled one: line " << i + 1;
            EXPECT_NE(text[i].find(",ok,"), std::string::npos) << text[i];
            ++ok;
        }
    }
    EXPECT_GT(ok, 0u);
    EXPECT_GT(cancelled, 0u);
    EXPECT_NE(p.err().find(std::to_string(cancelled) + " row(s) not computed"), std::string::npos)
        << p.err();
}

TEST_F(Signals, StreamingIdentificationStopsAfterTheSampleInHand) {
    const fs::path sample = dir_ / "sample.csv";
    ASSERT_EQ(terra::test::run("synth --slips 0:0.9:60 --out " + sample.string()).exit_code, 0);
    const auto rows = lines(readText(sample));
    const fs::path data = dir_ / "stream.csv";
    constexpr int kRepeats = 1000;
    {
        std::ofstream out(data);
        out << rows[0] << '\n';
        for (int k = 0; k < kRepeats; ++k) {
            for (std::size_t i = 1; i < rows.size(); ++i) out << rows[i] << '\n';
        }
    }
    const std::size_t total = kRepeats * (rows.size() - 1);
    CliProcess p({"identify", "--stream", data, "--json"}, dir_ / "stream");
    ASSERT_EQ(stopWith(p, SIGTERM), 143) << p.err();
    const auto out = lines(p.out());
    ASSERT_GE(out.size(), 2u);
    const auto last = nlohmann::json::parse(out.back());
    EXPECT_EQ(last["cancelled"], true);
    const std::size_t fed = out.size() - 1;  // one JSON line per sample fed
    EXPECT_LT(fed, total);
    EXPECT_EQ(last["note"], "cancelled by SIGTERM after " + std::to_string(fed) + " of " +
                                std::to_string(total) + " samples");
    EXPECT_EQ(nlohmann::json::parse(out[fed - 1])["sample"], fed - 1);
}

TEST_F(Signals, RunWritesTheReportAndManifestMarkedCancelled) {
    const fs::path script = dir_ / "script.json";
    std::ofstream(script) << nlohmann::json{
        {"analyses",
         {{{"name", "long"}, {"type", "rover"}, {"scenario", "straight"}, {"duration_s", 600}},
          {{"name", "never"}, {"type", "rover"}, {"scenario", "straight"}}}}};
    const fs::path out = dir_ / "out";
    CliProcess p({"run", script, "--out", out}, dir_ / "run");
    ASSERT_EQ(stopWith(p, SIGTERM), 143) << p.err();
    const auto manifest = nlohmann::json::parse(readText(out / "manifest.json"));
    EXPECT_EQ(manifest["cancelled"], true);
    ASSERT_EQ(manifest["analyses"].size(), 1u);  // the second one never started
    EXPECT_EQ(manifest["analyses"][0]["name"], "long");
    const auto summary = nlohmann::json::parse(readText(out / "long-summary.json"));
    EXPECT_EQ(summary["status"], "cancelled");
    EXPECT_TRUE(fs::exists(out / "long-timeseries.csv"));
    EXPECT_NE(readText(out / "report.md").find("Cancelled by SIGTERM"), std::string::npos);
}

// Issue 28, finding 3: every subcommand with --json or --out and a cancellable long run writes
// its partial result marked cancelled (JSON: an object with "cancelled": true and a "note"; CSV:
// a last comment line), or nothing and says so.
TEST_F(Signals, BandsJsonIsMarkedCancelled) {
    const fs::path file = dir_ / "b.json";
    CliProcess p({"bands", "--samples", "65536", "--json", "--out", file}, dir_ / "bands");
    ASSERT_EQ(stopWith(p, SIGTERM), 143) << p.err();
    EXPECT_EQ(p.err().find("json.exception"), std::string::npos) << p.err();
    const auto j = nlohmann::json::parse(readText(file));
    EXPECT_EQ(j["cancelled"], true);
    EXPECT_EQ(j["note"].get<std::string>().rfind("cancelled by SIGTERM: bands from the samples", 0),
              0u)
        << j["note"];
    ASSERT_TRUE(j["rows"].is_array());
    EXPECT_EQ(j["rows"].size(), 20u);  // every grid point, from the samples evaluated
}

TEST_F(Signals, BandsCsvEndsWithTheNote) {
    const fs::path file = dir_ / "b.csv";
    CliProcess p({"bands", "--samples", "65536", "--out", file}, dir_ / "bands");
    ASSERT_EQ(stopWith(p, SIGINT), 130) << p.err();
    const auto text = lines(readText(file));
    ASSERT_GE(text.size(), 2u);
    EXPECT_EQ(text.back().rfind("# cancelled by SIGINT: bands from the samples", 0), 0u)
        << text.back();
}

TEST_F(Signals, GsaJsonIsMarkedCancelledWithANote) {
    const fs::path file = dir_ / "gsa.json";
    CliProcess p({"gsa", "--slip", "0.3", "--samples", "262144", "--resamples", "10", "--json",
                  "--out", file},
                 dir_ / "gsa");
    ASSERT_EQ(stopWith(p, SIGHUP), 129) << p.err();
    const auto j = nlohmann::json::parse(readText(file));
    EXPECT_EQ(j["cancelled"], true);
    EXPECT_EQ(j["note"].get<std::string>().rfind("cancelled by SIGHUP: indices from the", 0), 0u)
        << j["note"];
}

TEST_F(Signals, SensitivityJsonIsMarkedCancelled) {
    const fs::path file = dir_ / "sens.json";
    CliProcess p({"sensitivity", "--parameter", "phi_deg", "--values", "20:35:50", "--slips",
                  "0:0.99:2000", "--json", "--out", file},
                 dir_ / "sens");
    ASSERT_EQ(stopWith(p, SIGTERM), 143) << p.err();
    const auto j = nlohmann::json::parse(readText(file));
    EXPECT_EQ(j["cancelled"], true);
    EXPECT_GT(j["rows"].size(), 0u);
    EXPECT_LT(j["rows"].size(), 100000u);
    EXPECT_EQ(j["note"],
              "cancelled by SIGTERM after " + std::to_string(j["rows"].size()) + " rows");
}

// The batch fit and the validation write nothing when stopped (a fit stopped halfway is no
// result) and say so, naming the signal.
TEST_F(Signals, IdentifyAndValidateWriteNothingAndSaySo) {
    const fs::path data = dir_ / "data.csv";
    ASSERT_EQ(terra::test::run("synth --slips 0:0.9:4000 --load 40,60,80 --noise fx=0.5 --out " +
                               data.string())
                  .exit_code,
              0);
    CliProcess identify({"identify", "--data", data, "--json"}, dir_ / "identify");
    ASSERT_EQ(stopWith(identify, SIGTERM), 143) << identify.err();
    EXPECT_EQ(identify.out(), "");
    EXPECT_NE(identify.err().find("identify cancelled by SIGTERM: nothing written"),
              std::string::npos)
        << identify.err();

    // A measured test of 3000 points at three loads, calibrated.
    const fs::path test = dir_ / "test.csv";
    {
        std::ofstream out(test);
        out << "load_N,slip,Fx_N,sinkage_m\n";
        for (int i = 0; i < 3000; ++i)
            out << 40 + 20 * (i % 3) << ',' << 0.9 * i / 3000 << ",5,0.01\n";
    }
    CliProcess validate({"validate", "--experiments", test, "--soil", "sandy-loam", "--wheel", "A",
                         "--calibrate", "--json"},
                        dir_ / "validate");
    ASSERT_EQ(stopWith(validate, SIGINT), 130) << validate.err();
    EXPECT_EQ(validate.out(), "");
    EXPECT_NE(validate.err().find("validate cancelled by SIGINT: nothing written"),
              std::string::npos)
        << validate.err();
}

// Issue 28, finding 9: SIGKILL during `run` left data files without manifest.json. The manifest
// is written first, marked running, and after every analysis: killed outright, the folder still
// says what it holds.
TEST_F(Signals, RunKilledOutrightLeavesAManifestMarkedRunning) {
    const fs::path script = dir_ / "script.json";
    std::ofstream(script) << nlohmann::json{
        {"analyses",
         {{{"name", "fx"}, {"type", "forces"}},
          {{"name", "long"}, {"type", "rover"}, {"scenario", "straight"}, {"duration_s", 600}}}}};
    const fs::path out = dir_ / "out";
    CliProcess p({"run", script, "--out", out}, dir_ / "run");
    const auto end = std::chrono::steady_clock::now() + 120s;
    while (!fs::exists(out / "fx.csv") && !p.exited() && std::chrono::steady_clock::now() < end)
        std::this_thread::sleep_for(10ms);
    ASSERT_TRUE(fs::exists(out / "fx.csv")) << p.err();
    std::this_thread::sleep_for(500ms);
    p.signal(SIGKILL);
    ASSERT_TRUE(WIFSIGNALED(p.wait()));
    const auto manifest = nlohmann::json::parse(readText(out / "manifest.json"));
    EXPECT_EQ(manifest["status"], "running");
    ASSERT_EQ(manifest["analyses"].size(), 1u);
    EXPECT_EQ(manifest["analyses"][0]["name"], "fx");
    EXPECT_FALSE(fs::exists(out / "long-summary.json"));
    // A run that ends says so.
    std::ofstream(script) << nlohmann::json{{"analyses", {{{"name", "fx"}, {"type", "forces"}}}}};
    ASSERT_EQ(terra::test::run("run " + script.string() + " --out " + out.string()).exit_code, 0);
    EXPECT_EQ(nlohmann::json::parse(readText(out / "manifest.json"))["status"], "completed");
}

// SIGKILL while the 26 MB time series is being written (seen as an open file in the output
// directory): the previous results stay whole and nothing else is left there; the next run
// replaces them and leaves nothing either.
TEST_F(Signals, AWriteKilledMidwayLeavesNothingBehind) {
    const fs::path out = dir_ / "out";
    auto simulate = [&](const char* duration) {
        return std::vector<std::string>{"simulate", "--scenario", "straight", "--duration",
                                        duration,   "--out",      out};
    };
    ASSERT_EQ(terra::test::run("simulate --scenario straight --duration 1 --out " + out.string())
                  .exit_code,
              0);
    const std::set<std::string> results{"summary.json", "timeseries.csv"};
    ASSERT_EQ(listing(out), results);
    const std::string before = readText(out / "timeseries.csv");
    {
        CliProcess p(simulate("300"), dir_ / "killed");
        const std::string inside = out.string() + "/";
        ASSERT_TRUE(p.waitUntilOpen(
            [&](const std::string& target) { return target.rfind(inside, 0) == 0; }, 120s))
            << "the write was not seen: " << p.err();
        p.signal(SIGKILL);
        const int status = p.wait();
        ASSERT_TRUE(WIFSIGNALED(status));
    }
    EXPECT_EQ(listing(out), results);
    // The old series, or (killed just after its rename, while writing the summary) the whole new
    // one: never a part.
    const std::string after = readText(out / "timeseries.csv");
    if (after != before) {
        EXPECT_EQ(lines(after).size(), 1u + 30001u);
    }
    ASSERT_EQ(terra::test::run("simulate --scenario straight --duration 2 --out " + out.string())
                  .exit_code,
              0);
    EXPECT_EQ(listing(out), results);
    EXPECT_EQ(lines(readText(out / "timeseries.csv")).size(), 1u + 201u);
}

}  // namespace
