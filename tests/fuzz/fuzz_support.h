#pragma once
/// @file fuzz_support.h
/// What every harness of tests/fuzz/ shares: the input as text, the shipped presets (so that a
/// file naming "sandy-loam" or "A" resolves as it does for a user) and the one check each harness
/// makes of a reader's answer. A reader answers bad input with its documented error type, a
/// Result holding issues (core/common/issue.h): never an exception, a crash, a hang or an empty
/// message. An exception escaping a harness aborts it, which libFuzzer and the replay driver
/// (replay_main.cpp) report as a finding.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "core/common/issue.h"
#include "core/io/parameters_json.h"

namespace terra::fuzz {

/// The fuzzer's bytes as text (they need not be UTF-8: the readers must cope).
inline std::string textOf(const std::uint8_t* data, std::size_t size) {
    return std::string(reinterpret_cast<const char*>(data), size);
}

/// The presets of resources/ (TERRA_RESOURCE_DIR, given by tests/fuzz/CMakeLists.txt).
inline const io::PresetLocations& presets() {
    static const io::PresetLocations locations{{TERRA_RESOURCE_DIR}};
    return locations;
}

/// Stops the harness with a message: libFuzzer saves the input as a crash.
[[noreturn]] inline void fail(const std::string& what) {
    std::fprintf(stderr, "fuzz harness: %s\n", what.c_str());
    std::abort();
}

/// Longest issue (location + message) a reader may give: a bad value is quoted to at most ~80
/// characters and a list of allowed names to ~200 (docs/reliability.md), so anything far longer
/// echoes the input.
constexpr std::size_t kMaxIssueChars = 1000;

/// The reader's answer is valid: a value, or at least one issue, each with a message of
/// reasonable length.
template <typename T>
void checkResult(const Result<T>& result) {
    if (result.ok()) return;
    if (result.issues().empty()) fail("a failed read without any issue");
    for (const Issue& issue : result.issues()) {
        if (issue.message.empty()) fail("an issue without a message at '" + issue.where + "'");
        if (issue.where.size() + issue.message.size() > kMaxIssueChars) {
            fail("an issue of " + std::to_string(issue.where.size() + issue.message.size()) +
                 " characters (input echoed?): " + issue.where.substr(0, 200) + ": " +
                 issue.message.substr(0, 200));
        }
    }
}

#ifdef TERRA_FUZZ_REPLAY
/// The replay build's harnesses by name (replay_main.cpp). Each harness file registers its entry
/// point here, so that all of them build as one unity batch into one executable.
using Harness = int (*)(const std::uint8_t* data, std::size_t size);
std::map<std::string, Harness>& harnesses();
inline bool registerHarness(const char* name, Harness harness) {
    harnesses()[name] = harness;
    return true;
}
#endif

}  // namespace terra::fuzz

/// A harness's entry point, named after its file (soil_json for soil_json_fuzz.cpp): libFuzzer's
/// LLVMFuzzerTestOneInput in the fuzzing build (scripts/fuzz), a function registered under that
/// name in the replay build (tests/fuzz/CMakeLists.txt), where nine entry points of one name
/// could not share an executable.
#ifdef TERRA_FUZZ_REPLAY
#define TERRA_FUZZ_HARNESS(name)                                             \
    static int terraFuzz_##name(const std::uint8_t* data, std::size_t size); \
    [[maybe_unused]] static const bool terraFuzzRegistered_##name =          \
        terra::fuzz::registerHarness(#name, &terraFuzz_##name);              \
    static int terraFuzz_##name(const std::uint8_t* data, std::size_t size)
#else
#define TERRA_FUZZ_HARNESS(name) \
    extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
#endif
