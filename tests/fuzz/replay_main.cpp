// The replay driver: in the normal build every harness is linked with this main() instead of
// libFuzzer, into one executable, and ctest runs it once per harness on the harness's seed corpus
// and on every input that ever made it fail (tests/fuzz/crashes/<harness>/), so a regression
// fails the tests without fuzzing. `terra_fuzz_replay HARNESS PATH...`: each path is a file or a
// directory (all its regular files, sorted). A failing input aborts the run (fuzz_support.h),
// naming it on stderr first.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/fuzz/fuzz_support.h"

std::map<std::string, terra::fuzz::Harness>& terra::fuzz::harnesses() {
    static std::map<std::string, Harness> byName;
    return byName;
}

int main(int argc, char** argv) {
    namespace fs = std::filesystem;
    const auto& harnesses = terra::fuzz::harnesses();
    const auto harness = argc > 1 ? harnesses.find(argv[1]) : harnesses.end();
    if (harness == harnesses.end()) {
        std::string names;
        for (const auto& [name, entry] : harnesses) names += " " + name;
        std::fprintf(stderr, "usage: %s HARNESS PATH...; harnesses:%s\n", argv[0], names.c_str());
        return 2;
    }
    std::vector<fs::path> inputs;
    for (int i = 2; i < argc; ++i) {
        const fs::path arg = argv[i];
        if (fs::is_directory(arg)) {
            std::vector<fs::path> files;
            for (const auto& entry : fs::directory_iterator(arg)) {
                if (entry.is_regular_file() && entry.path().filename() != ".gitkeep")
                    files.push_back(entry.path());
            }
            std::sort(files.begin(), files.end());
            inputs.insert(inputs.end(), files.begin(), files.end());
        } else if (fs::is_regular_file(arg)) {
            inputs.push_back(arg);
        } else {
            std::fprintf(stderr, "replay: no such file or directory: %s\n", argv[i]);
            return 2;
        }
    }
    for (const fs::path& path : inputs) {
        std::ifstream in(path, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());
        std::fprintf(stderr, "replay: %s (%zu bytes)\n", path.string().c_str(), bytes.size());
        harness->second(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    }
    std::printf("replay: %zu inputs, no failure\n", inputs.size());
    return 0;
}
