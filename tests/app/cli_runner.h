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
#include <string>

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

}  // namespace terra::test
