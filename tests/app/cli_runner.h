#pragma once
// Runs the real `terrastudio` executable (TERRASTUDIO_EXE) with arguments through the shell, as a
// user would: exit code, standard output and standard error. Shared by the tests of tests/app/.
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace terra::test {

struct CliRun {
    int exit_code = -1;  ///< -1 when the process did not exit normally
    std::string out;     ///< stdout
    std::string err;     ///< stderr
};

/// `terrastudio ARGUMENTS` (ARGUMENTS go through /bin/sh: quote paths with spaces).
inline CliRun run(const std::string& arguments) {
    // One stderr file per process: ctest runs the tests of these files in parallel processes.
    const std::filesystem::path err_path =
        std::filesystem::temp_directory_path() / ("terra_cli_err_" + std::to_string(::getpid()));
    const std::string command =
        std::string(TERRASTUDIO_EXE) + " " + arguments + " 2>" + err_path.string();
    CliRun r;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) return r;
    std::array<char, 4096> buffer{};
    while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe))
        r.out.append(buffer.data(), n);
    const int status = ::pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream err(err_path);
    r.err.assign(std::istreambuf_iterator<char>(err), {});
    std::filesystem::remove(err_path);
    return r;
}

/// The whole text of a file ("" when it cannot be read).
inline std::string readText(const std::filesystem::path& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), {}};
}

/// The lines of `text`, without their line ends (\n or \r\n).
inline std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        out.push_back(line);
    }
    return out;
}

inline bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

/// The shipped Ding et al. (2011) smooth-wheel test at 80 N (resources/experiments).
inline const std::string kDing =
    std::string(TERRA_RESOURCE_DIR) + "/experiments/ding2011-smooth-hit-lss1-80N.csv";

}  // namespace terra::test
