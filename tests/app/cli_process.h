#pragma once
// Starts the real `terrastudio` executable (TERRASTUDIO_EXE) as a child process that a test can
// signal while it runs: stdout and stderr go to files, the test waits for it and reads its
// status. Shared by the tests of tests/app/ that stop or kill a running command.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace terra::test {

/// A running `terrastudio ARGUMENTS...` (no shell: arguments are passed as they are).
class CliProcess {
public:
    CliProcess(const std::vector<std::string>& arguments, const std::filesystem::path& log_stem)
        : out_(log_stem.string() + ".stdout"), err_(log_stem.string() + ".stderr") {
        pid_ = ::fork();
        if (pid_ != 0) return;
        const int out = ::open(out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int err = ::open(err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(out, STDOUT_FILENO);
        ::dup2(err, STDERR_FILENO);
        std::vector<char*> argv{const_cast<char*>(TERRASTUDIO_EXE)};
        for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(TERRASTUDIO_EXE, argv.data());
        ::_exit(127);
    }
    CliProcess(const CliProcess&) = delete;
    CliProcess& operator=(const CliProcess&) = delete;
    ~CliProcess() {
        if (!waited_) {
            ::kill(pid_, SIGKILL);
            wait();
        }
        std::filesystem::remove(out_);
        std::filesystem::remove(err_);
    }

    pid_t pid() const { return pid_; }
    void signal(int number) const { ::kill(pid_, number); }

    /// True once the process catches `number` (its handler is installed), polled from
    /// /proc/PID/status; false if it has not within `timeout` or has exited.
    bool waitUntilCatching(int number, std::chrono::milliseconds timeout) const {
        const auto end = std::chrono::steady_clock::now() + timeout;
        while (std::chrono::steady_clock::now() < end) {
            std::ifstream status("/proc/" + std::to_string(pid_) + "/status");
            for (std::string line; std::getline(status, line);) {
                if (line.rfind("SigCgt:", 0) != 0) continue;
                const unsigned long long caught = std::stoull(line.substr(7), nullptr, 16);
                if (caught & (1ull << (number - 1))) return true;
            }
            if (exited()) return false;
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        return false;
    }

    /// Polls the process's open files until `predicate(target of /proc/PID/fd/N)` holds for one
    /// of them; false when the process exits first or `timeout` passes.
    bool waitUntilOpen(const std::function<bool(const std::string&)>& predicate,
                       std::chrono::milliseconds timeout) const {
        namespace fs = std::filesystem;
        const fs::path fds = "/proc/" + std::to_string(pid_) + "/fd";
        const auto end = std::chrono::steady_clock::now() + timeout;
        while (std::chrono::steady_clock::now() < end) {
            std::error_code ec;
            for (fs::directory_iterator it(fds, ec), last; !ec && it != last; it.increment(ec)) {
                std::error_code link_error;
                const fs::path target = fs::read_symlink(it->path(), link_error);
                if (!link_error && predicate(target.string())) return true;
            }
            if (ec || exited()) return false;
        }
        return false;
    }

    /// True when the process has ended (it is then reaped; wait() gives its status).
    bool exited() const {
        if (!waited_ && ::waitpid(pid_, &status_, WNOHANG) == pid_) waited_ = true;
        return waited_;
    }

    /// Waits for the process to end; its raw wait status.
    int wait() {
        if (!waited_) {
            ::waitpid(pid_, &status_, 0);
            waited_ = true;
        }
        return status_;
    }

    std::string out() const { return slurp(out_); }
    std::string err() const { return slurp(err_); }

private:
    static std::string slurp(const std::filesystem::path& path) {
        std::ifstream in(path);
        return {std::istreambuf_iterator<char>(in), {}};
    }
    pid_t pid_ = -1;
    mutable bool waited_ = false;
    mutable int status_ = 0;
    std::filesystem::path out_, err_;
};

}  // namespace terra::test
