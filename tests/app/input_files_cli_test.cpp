// Inputs that end (issue 28, finding 2): every data input of the real executable must be a
// regular file below the input limit. /dev/zero, a FIFO, a folder are refused by their kind
// (exit 2) without reading a byte or blocking, and a file over TERRASTUDIO_MAX_INPUT_BYTES is
// refused with the limit named (docs/cli.md, "Input files"). Inputs are never outputs (finding 4).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "../core/test_temp_dir.h"
#include "cli_process.h"
#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using terra::test::CliProcess;
using terra::test::CliRun;
using terra::test::kDing;
using terra::test::run;

class InputFiles : public ::testing::Test {
protected:
    fs::path write(const std::string& name, const std::string& text) {
        const fs::path path = dir_ / name;
        std::ofstream(path) << text;
        return path;
    }
    // Runs `arguments` (no shell) and expects it to end within 30 s with exit 2 and `piece` in
    // stderr: a reader blocked on a FIFO or reading /dev/zero for ever fails here, not hangs.
    void expectRefused(const std::vector<std::string>& arguments, const std::string& piece) {
        std::string command;
        for (const std::string& a : arguments) command += a + " ";
        CliProcess p(arguments, dir_ / "process");
        const auto end = std::chrono::steady_clock::now() + 30s;
        while (!p.exited() && std::chrono::steady_clock::now() < end)
            std::this_thread::sleep_for(10ms);
        if (!p.exited()) {
            p.signal(SIGKILL);
            p.wait();
            ADD_FAILURE() << command << ": still running after 30 s (blocked or reading forever)";
            return;
        }
        const int status = p.wait();
        ASSERT_TRUE(WIFEXITED(status)) << command;
        EXPECT_EQ(WEXITSTATUS(status), 2) << command << "\n" << p.err();
        EXPECT_NE(p.err().find(piece), std::string::npos)
            << command << "\nmissing: " << piece << "\nin: " << p.err();
    }
    terra::testing::TempDir temp_;  // a fresh directory per test, removed afterwards
    const fs::path dir_ = temp_.path();
};

constexpr const char* kCharDevice = " is not a regular file (a character device)";
constexpr const char* kFifo = " is not a regular file (a FIFO (named pipe))";
constexpr const char* kFolder = " is not a regular file (a directory)";

TEST_F(InputFiles, DevZeroIsRefusedByEveryDataInput) {
    const std::string zero = "/dev/zero";
    const std::string devzero = zero + kCharDevice;
    expectRefused({"wheel", "--input", zero}, devzero);
    expectRefused({"identify", "--data", zero}, devzero);
    expectRefused({"identify", "--stream", zero}, devzero);
    expectRefused({"validate", "--experiments", zero, "--soil", "hit-lss1", "--wheel", "A"},
                  devzero);
    expectRefused({"run", zero}, devzero);
    expectRefused({"wheel", "--soil", zero, "--load", "58"}, devzero);
    expectRefused({"wheel", "--wheel", zero, "--load", "58"}, devzero);
    expectRefused({"simulate", "--scenario", zero, "--out", (dir_ / "o").string()}, devzero);
    // The sidecar's data_file names the device.
    const fs::path sidecar =
        write("sidecar.json",
              R"({"format": "terrastudio-experiment", "format_version": 1, "data_file": ")" +
                  std::string("../../../../../../../../dev/zero") + "\"}");
    expectRefused(
        {"validate", "--experiments", sidecar.string(), "--soil", "hit-lss1", "--wheel", "A"},
        "dev/zero" + std::string(kCharDevice));
}

TEST_F(InputFiles, AFifoIsRefusedWithoutBlocking) {
    const fs::path fifo = dir_ / "pipe.csv";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string piece = fifo.string() + kFifo;
    expectRefused({"wheel", "--input", fifo.string()}, piece);
    expectRefused({"identify", "--data", fifo.string()}, piece);
    expectRefused(
        {"validate", "--experiments", fifo.string(), "--soil", "hit-lss1", "--wheel", "A"}, piece);
    const fs::path script = dir_ / "script.json";
    ASSERT_EQ(::mkfifo(script.c_str(), 0600), 0);
    expectRefused({"run", script.string()}, script.string() + kFifo);
    const fs::path soil = dir_ / "soil.json";
    ASSERT_EQ(::mkfifo(soil.c_str(), 0600), 0);
    expectRefused({"wheel", "--soil", soil.string(), "--load", "58"}, soil.string() + kFifo);
}

TEST_F(InputFiles, AFolderIsNamedAsAFolderAlsoAsASidecarsDataFile) {
    fs::create_directories(dir_ / "data");
    const std::string folder = (dir_ / "data").string();
    expectRefused({"wheel", "--input", folder}, folder + kFolder);
    expectRefused({"identify", "--data", folder}, folder + kFolder);
    const fs::path sidecar =
        write("test.json",
              R"({"format": "terrastudio-experiment", "format_version": 1, "data_file": "data"})");
    expectRefused(
        {"validate", "--experiments", sidecar.string(), "--soil", "hit-lss1", "--wheel", "A"},
        folder + kFolder);
}

TEST_F(InputFiles, AFileOverTheInputLimitIsRefusedWithTheLimitNamed) {
    // 2,812 bytes of points, a 1,016-byte script, a data set of some kB: all above a 1,000-byte
    // limit, which the presets read too (at most 639 bytes) stay below.
    std::string rows = "slip,load_N\n";
    for (int i = 0; i < 200; ++i) rows += "0.1,58\n0.2,58\n";
    const fs::path points = write("points.csv", rows);
    const fs::path script_file =
        write("script.json", "{\"_comment\": \"" + std::string(1000, 'x') + "\"}");
    const fs::path data_file = dir_ / "data.csv";
    ASSERT_EQ(run("synth --slips 0:0.9:60 --out " + data_file.string()).exit_code, 0);
    ASSERT_EQ(run("wheel --input " + points.string()).exit_code, 0);
    ::setenv("TERRASTUDIO_MAX_INPUT_BYTES", "1000", 1);
    const CliRun small = run("wheel --input " + points.string());
    const CliRun script = run("run " + script_file.string());
    const CliRun data = run("identify --data " + data_file.string());
    ::setenv("TERRASTUDIO_MAX_INPUT_BYTES", "lots", 1);
    const CliRun malformed = run("wheel --input " + points.string());
    ::unsetenv("TERRASTUDIO_MAX_INPUT_BYTES");
    EXPECT_EQ(small.exit_code, 2) << small.err;
    EXPECT_NE(small.err.find("/points.csv has 2812 bytes, larger than the input limit of 1000 "
                             "bytes (set TERRASTUDIO_MAX_INPUT_BYTES to read more)"),
              std::string::npos)
        << small.err;
    EXPECT_EQ(script.exit_code, 2) << script.err;
    EXPECT_NE(script.err.find("larger than the input limit"), std::string::npos) << script.err;
    EXPECT_EQ(data.exit_code, 2) << data.err;
    EXPECT_NE(data.err.find("larger than the input limit"), std::string::npos) << data.err;
    EXPECT_EQ(malformed.exit_code, 2) << malformed.err;
    EXPECT_NE(malformed.err.find("TERRASTUDIO_MAX_INPUT_BYTES: 'lots' is not a whole number of "
                                 "bytes"),
              std::string::npos)
        << malformed.err;
}

// Inputs are never outputs (issue 28, finding 4): an output that names an input file (the same
// file after resolving links) is exit 2, and the input is left as it was.
class InputsAreNotOutputs : public InputFiles {
protected:
    static std::string readText(const fs::path& path) {
        std::ifstream in(path);
        return {std::istreambuf_iterator<char>(in), {}};
    }
    void expectKept(const std::string& command, const fs::path& input, const std::string& piece) {
        const std::string before = readText(input);
        const CliRun r = run(command);
        EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.err;
        EXPECT_NE(r.err.find(piece), std::string::npos) << command << "\n" << r.err;
        EXPECT_EQ(readText(input), before) << command << ": the input was replaced";
    }
};

TEST_F(InputsAreNotOutputs, WheelBatchOutputThatIsItsInputIsRefused) {
    const fs::path points = write("p.csv", "slip,load_N\n0.1,58\n");
    // Paths are named by their ends (the temporary folder's path is long).
    expectKept("wheel --input " + points.string() + " --output " + points.string(), points,
               "/p.csv' is the input --input '");
    expectKept("wheel --input " + points.string() + " --output " + points.string(), points,
               "/p.csv': writing it would replace the input; choose another file");
    // Through a link and a relative path: the same file all the same.
    fs::create_symlink(points, dir_ / "link.csv");
    expectKept("wheel --input " + points.string() + " --output " + (dir_ / "link.csv").string(),
               points, "is the input --input");
    expectKept("wheel --input " + points.string() + " --output " +
                   (dir_ / "." / ".." / dir_.filename() / "p.csv").string(),
               points, "is the input --input");
    const fs::path soil =
        write("soil.json", readText(std::string(TERRA_RESOURCE_DIR) + "/soils/sandy-loam.json"));
    expectKept("sweep --soil " + soil.string() + " --out " + soil.string(), soil,
               "/soil.json' is the input --soil '");
    expectKept("synth --soil " + soil.string() + " --out " + soil.string(), soil,
               "is the input --soil");
}

TEST_F(InputsAreNotOutputs, CalibratedSoilNeverReplacesTheTest) {
    const fs::path test = write("e.csv", readText(kDing));
    expectKept("validate --experiments " + test.string() + " --soil hit-lss1 --wheel " +
                   "ding2011-smooth --calibrate --save-soil " + test.string(),
               test, "/e.csv' is the input --experiments '");
}

TEST_F(InputsAreNotOutputs, ASimulateFolderUsedBeforeKeepsNoStaleStreamingFile) {
    const fs::path out = dir_ / "s";
    CliRun r = run("simulate --scenario soil-border --duration 0.5 --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_TRUE(fs::exists(out / "streaming.csv"));
    r = run("simulate --scenario straight --duration 0.5 --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_FALSE(fs::exists(out / "streaming.csv")) << "a stale streaming.csv was kept";
    EXPECT_TRUE(fs::exists(out / "timeseries.csv"));
    // A scenario file inside the output folder under a name simulate writes is refused.
    const fs::path scenario = out / "summary.json";
    std::ofstream(scenario) << readText(std::string(TERRA_RESOURCE_DIR) +
                                        "/scenarios/straight.json");
    expectKept("simulate --scenario " + scenario.string() + " --out " + out.string(), scenario,
               "is the input --scenario");
}

}  // namespace
