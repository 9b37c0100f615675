// Progress of the long commands through the real executable (docs/cli.md, "Progress and
// stopping"): with stderr on a terminal (a pseudo-terminal here) each draws a bar on stderr; with
// stderr on a file or a pipe nothing of it is written; Ctrl-C on a terminal ends the bar's line,
// writes the work done so far, marked cancelled, and exits 130.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../core/test_temp_dir.h"
#include "cli_runner.h"

namespace {

using terra::test::lines;
using terra::test::readText;

namespace fs = std::filesystem;

struct TerminalRun {
    int exit_code = -1;  ///< -1: did not exit normally
    std::string out;     ///< stdout (a file)
    std::string err;     ///< what the terminal showed (the pty turns "\n" into "\r\n")
};

// `terrastudio ARGUMENTS...` with stderr on a new pseudo-terminal and stdout in a file. `on_output`
// sees the terminal's text so far after each read and may signal the process (once it returns
// true it is not called again).
TerminalRun runOnTerminal(const std::vector<std::string>& arguments, const fs::path& out_file,
                          const std::function<bool(pid_t, const std::string&)>& on_output = {}) {
    TerminalRun r;
    int master = -1, slave = -1;
    if (::openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) {
        ADD_FAILURE() << "openpty failed";
        return r;
    }
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::close(master);
        ::setsid();  // a session of its own: the terminal's signals reach only the test's kill()
        const int out = ::open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int in = ::open("/dev/null", O_RDONLY);
        ::dup2(in, STDIN_FILENO);
        ::dup2(out, STDOUT_FILENO);
        ::dup2(slave, STDERR_FILENO);
        ::close(slave);
        std::vector<char*> argv{const_cast<char*>(TERRASTUDIO_EXE)};
        for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(TERRASTUDIO_EXE, argv.data());
        ::_exit(127);
    }
    ::close(slave);
    bool notified = !on_output;
    char buffer[4096];
    while (true) {
        pollfd p{master, POLLIN, 0};
        if (::poll(&p, 1, 200) < 0 && errno != EINTR) break;
        if (p.revents == 0) continue;
        const ssize_t n = ::read(master, buffer, sizeof buffer);
        if (n <= 0) break;  // EIO: every copy of the terminal's other end is closed
        r.err.append(buffer, static_cast<std::size_t>(n));
        if (!notified) notified = on_output(pid, r.err);
    }
    ::close(master);
    int status = 0;
    ::waitpid(pid, &status, 0);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readText(out_file);
    return r;
}

class Progress : public ::testing::Test {
protected:
    // A data set of `repeats` copies of a 60-sample slip sweep (synth), for identify --stream.
    fs::path streamData(int repeats) {
        const fs::path sample = dir_ / "sample.csv";
        EXPECT_EQ(terra::test::run("synth --slips 0:0.9:60 --out " + sample.string()).exit_code, 0);
        const auto rows = lines(readText(sample));
        const fs::path data = dir_ / ("stream" + std::to_string(repeats) + ".csv");
        std::ofstream out(data);
        out << rows[0] << '\n';
        for (int k = 0; k < repeats; ++k) {
            for (std::size_t i = 1; i < rows.size(); ++i) out << rows[i] << '\n';
        }
        return data;
    }
    fs::path points(int count) {
        const fs::path input = dir_ / ("points" + std::to_string(count) + ".csv");
        std::ofstream in(input);
        in << "slip,load_N\n";
        for (int i = 0; i < count; ++i) in << 0.9 * i / count << ",58.86\n";
        return input;
    }
    fs::path roverScript(double duration_s) {
        const fs::path script = dir_ / "script.json";
        std::ofstream(script) << nlohmann::json{{"analyses",
                                                 {{{"name", "drive"},
                                                   {"type", "rover"},
                                                   {"scenario", "straight"},
                                                   {"duration_s", duration_s}}}}};
        return script;
    }
    // The long commands, each with `big` or small inputs: label of the bar and arguments.
    std::vector<std::pair<std::string, std::vector<std::string>>> commands(bool big) {
        const std::string n = big ? "100000" : "50";
        return {
            {"synth", {"synth", "--slips", "0:0.9:" + n, "--out", (dir_ / "synth.csv").string()}},
            {"identify --stream",
             {"identify", "--stream", streamData(big ? 1700 : 1).string(), "--json"}},
            {"wheel --input",
             {"wheel", "--input", points(big ? 100000 : 50).string(), "--output",
              (dir_ / "forces.csv").string()}},
            {"run drive (1/1)",
             {"run", roverScript(big ? 600 : 0.5).string(), "--out", (dir_ / "run").string()}},
            {"simulate",
             {"simulate", "--scenario", "straight", "--duration", big ? "600" : "0.5", "--out",
              (dir_ / "sim").string()}},
            {"sweep",
             {"sweep", "--slips", "0:0.99:" + n, "--slip-angles", "5", "--out",
              (dir_ / "sweep.csv").string()}},
            {"render",
             {"render", "--soil", "sandy-loam", "--wheel", "A", "--width", "320", "--height", "240",
              "--out", (dir_ / "render").string()}},
        };
    }
    terra::testing::TempDir temp_;
    const fs::path dir_ = temp_.path();
};

TEST_F(Progress, EveryLongCommandDrawsABarOnATerminal) {
    for (const auto& [label, arguments] : commands(false)) {
        const TerminalRun r = runOnTerminal(arguments, dir_ / "stdout");
        EXPECT_EQ(r.exit_code, 0) << label << ": " << r.err;
        // Redrawn in place (carriage return) and complete at the end, then the line is ended.
        EXPECT_NE(r.err.find("\r" + label + " ["), std::string::npos) << label << ": " << r.err;
        EXPECT_NE(r.err.find("] 100 %"), std::string::npos) << label << ": " << r.err;
        EXPECT_NE(r.err.find("#] 100 %\x1b[K\r\n"), std::string::npos) << label << ": " << r.err;
    }
}

TEST_F(Progress, NothingOfItWhenStderrIsAFileOrAPipe) {
    for (const auto& [label, arguments] : commands(false)) {
        std::string command;
        for (const std::string& a : arguments) command += a + " ";
        const terra::test::CliRun r = terra::test::run(command);
        EXPECT_EQ(r.exit_code, 0) << label << ": " << r.err;
        EXPECT_EQ(r.err.find('\r'), std::string::npos) << label << ": " << r.err;
        EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << label << ": " << r.err;
        EXPECT_EQ(r.err.find(label + " ["), std::string::npos) << label << ": " << r.err;
        EXPECT_EQ(r.err.find(" %"), std::string::npos) << label << ": " << r.err;
    }
}

// Ctrl-C once the bar shows that the work has started: the bar's line is ended before the message,
// the output is written and marked cancelled, the exit code is 130.
TEST_F(Progress, CtrlCOnATerminalWritesTheWorkSoFarMarkedCancelled) {
    for (const auto& [label, arguments] : commands(true)) {
        // Signals.* cover these; render's sweep has a fixed size.
        if (label == "simulate" || label == "sweep" || label == "render") continue;
        const TerminalRun r =
            runOnTerminal(arguments, dir_ / "stdout", [&](pid_t pid, const std::string& err) {
                if (err.find(label + " [") == std::string::npos) return false;
                ::kill(pid, SIGINT);
                return true;
            });
        ASSERT_EQ(r.exit_code, 130) << label << ": " << r.err;
        const auto err = lines(r.err);
        ASSERT_FALSE(err.empty()) << label;
        // The message stands on its own line, after the bar's.
        std::size_t message = err.size();
        for (std::size_t i = 0; i < err.size(); ++i) {
            if (err[i].find("by SIGINT") != std::string::npos) message = i;
        }
        ASSERT_LT(message, err.size()) << label << ": " << r.err;
        EXPECT_EQ(err[message].find(" %"), std::string::npos) << label << ": " << r.err;
        EXPECT_NE(r.err.find(label + " ["), std::string::npos) << label;
        EXPECT_EQ(r.err.find("] 100 %"), std::string::npos) << label << ": stopped early";
        if (label == "synth") {
            const auto csv = lines(readText(dir_ / "synth.csv"));
            ASSERT_GE(csv.size(), 2u);
            EXPECT_EQ(csv.back(),
                      "# cancelled by SIGINT after " + std::to_string(csv.size() - 2) + " samples");
        } else if (label == "identify --stream") {
            const auto out = lines(r.out);
            ASSERT_GE(out.size(), 2u);
            const auto last = nlohmann::json::parse(out.back());
            EXPECT_EQ(last["cancelled"], true);
            EXPECT_EQ(last["note"].get<std::string>().rfind("cancelled by SIGINT after " +
                                                                std::to_string(out.size() - 1) +
                                                                " of 102000 samples",
                                                            0),
                      0u)
                << last;
        } else if (label == "wheel --input") {
            const auto csv = lines(readText(dir_ / "forces.csv"));
            ASSERT_EQ(csv.size(), 100001u);
            EXPECT_NE(csv[1].find(",ok,"), std::string::npos) << csv[1];
            EXPECT_NE(csv.back().find(",cancelled,"), std::string::npos) << csv.back();
        } else if (label == "run drive (1/1)") {
            const auto manifest = nlohmann::json::parse(readText(dir_ / "run" / "manifest.json"));
            EXPECT_EQ(manifest["cancelled"], true);
            const auto summary =
                nlohmann::json::parse(readText(dir_ / "run" / "drive-summary.json"));
            EXPECT_EQ(summary["status"], "cancelled");
        }
    }
}

}  // namespace
