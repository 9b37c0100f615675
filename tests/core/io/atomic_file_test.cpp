#include "core/io/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "tests/core/test_temp_dir.h"

namespace terra::io {
namespace {

namespace fs = std::filesystem;

using terra::testing::TempDir;

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::set<std::string> listing(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename());
    return names;
}

// ---- writeFileAtomically / readFile ----------------------------------------------------------

TEST(AtomicFile, WritesTheContent) {
    TempDir temp;
    const fs::path file = temp.path() / "out.csv";
    const std::string content = std::string("a,b\n1,2\n") + '\0' + "\r\nend";
    EXPECT_EQ(writeFileAtomically(file, content), std::nullopt);
    EXPECT_EQ(slurp(file), content);
    std::string read_back;
    EXPECT_EQ(readFile(file, read_back), std::nullopt);
    EXPECT_EQ(read_back, content);
}

TEST(AtomicFile, EmptyContentCreatesAnEmptyFile) {
    TempDir temp;
    const fs::path file = temp.path() / "empty.txt";
    EXPECT_EQ(writeFileAtomically(file, ""), std::nullopt);
    ASSERT_TRUE(fs::is_regular_file(file));
    EXPECT_EQ(fs::file_size(file), 0u);
}

TEST(AtomicFile, ReplacesAnExistingFile) {
    TempDir temp;
    const fs::path file = temp.path() / "out.csv";
    std::ofstream(file) << "old content that is longer than the new one\n";
    EXPECT_EQ(writeFileAtomically(file, "new\n"), std::nullopt);
    EXPECT_EQ(slurp(file), "new\n");
}

TEST(AtomicFile, LeavesNoTemporaryFileBehind) {
    TempDir temp;
    const fs::path file = temp.path() / "out.csv";
    ASSERT_EQ(writeFileAtomically(file, "first"), std::nullopt);
    ASSERT_EQ(writeFileAtomically(file, "second"), std::nullopt);
    ASSERT_EQ(writeFileAtomically(temp.path() / "other.json", "{}"), std::nullopt);
    EXPECT_EQ(listing(temp.path()), (std::set<std::string>{"out.csv", "other.json"}));
}

TEST(AtomicFile, MissingDirectoryIsAnErrorNotAnException) {
    TempDir temp;
    const fs::path file = temp.path() / "no-such-dir" / "out.csv";
    std::optional<std::string> error;
    EXPECT_NO_THROW(error = writeFileAtomically(file, "content"));
    ASSERT_TRUE(error.has_value());
    EXPECT_NE(error->find(file.string()), std::string::npos) << *error;
    EXPECT_FALSE(fs::exists(file));
    EXPECT_FALSE(fs::exists(temp.path() / "no-such-dir"));
    EXPECT_TRUE(listing(temp.path()).empty());
}

TEST(AtomicFile, FailedReplaceKeepsTheTargetAndRemovesTheTemporary) {
    TempDir temp;
    const fs::path target = temp.path() / "taken";
    fs::create_directory(target);  // a directory cannot be replaced by a file
    std::ofstream(target / "keep.txt") << "kept";
    std::optional<std::string> error;
    EXPECT_NO_THROW(error = writeFileAtomically(target, "content"));
    ASSERT_TRUE(error.has_value());
    EXPECT_TRUE(fs::is_directory(target));
    EXPECT_EQ(slurp(target / "keep.txt"), "kept");
    EXPECT_EQ(listing(temp.path()), (std::set<std::string>{"taken"}));
}

TEST(AtomicFile, ReadingAMissingFileIsAnError) {
    TempDir temp;
    std::string content = "unchanged";
    const std::optional<std::string> error = readFile(temp.path() / "absent.txt", content);
    ASSERT_TRUE(error.has_value());
    EXPECT_NE(error->find("absent.txt"), std::string::npos) << *error;
}

TEST(AtomicFile, TheTemporaryNameIsFixedBesideTheTarget) {
    EXPECT_EQ(temporaryPathFor("/a/b/out.csv"), fs::path("/a/b/.out.csv.tmp"));
    EXPECT_EQ(temporaryPathFor("out.csv"), fs::path(".out.csv.tmp"));
}

// Where O_TMPFILE is missing the content is written under the temporary name: same results.
TEST(AtomicFile, NamedFallbackWritesReplacesAndLeavesNothing) {
    TempDir temp;
    const fs::path file = temp.path() / "out.csv";
    ASSERT_EQ(detail::writeFileAtomically(file, "first\n", false), std::nullopt);
    ASSERT_EQ(detail::writeFileAtomically(file, "second\n", false), std::nullopt);
    EXPECT_EQ(slurp(file), "second\n");
    EXPECT_EQ(listing(temp.path()), (std::set<std::string>{"out.csv"}));
}

// A killed write can leave the temporary name (named fallback: killed while writing; unnamed:
// killed between link and rename). The next write of the same file reuses and removes it, in
// either mode, and a bigger leftover does not leak into the new content.
TEST(AtomicFile, TheNextWriteRemovesWhatAKilledWriteLeft) {
    for (const bool unnamed : {true, false}) {
        TempDir temp;
        const fs::path file = temp.path() / "timeseries.csv";
        std::ofstream(file) << "old complete content\n";
        std::ofstream(temporaryPathFor(file)) << std::string(100000, 'x');
        ASSERT_EQ(detail::writeFileAtomically(file, "new\n", unnamed), std::nullopt) << unnamed;
        EXPECT_EQ(slurp(file), "new\n") << unnamed;
        EXPECT_EQ(listing(temp.path()), (std::set<std::string>{"timeseries.csv"})) << unnamed;
    }
}

// The new file gets the usual permissions (0666 less the umask), as std::ofstream would give.
TEST(AtomicFile, PermissionsFollowTheUmask) {
    TempDir temp;
    const fs::path file = temp.path() / "out.txt";
    const mode_t previous = ::umask(027);
    const auto error = writeFileAtomically(file, "content");
    ::umask(previous);
    ASSERT_EQ(error, std::nullopt);
    EXPECT_EQ(fs::status(file).permissions(),
              fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
}

// Two writers of one file at once (one unnamed, one through the named fallback) share the
// temporary name: each write still succeeds, the file always holds one writer's complete
// content, and nothing is left over.
TEST(AtomicFile, ConcurrentWritersOfOneFileEachLandWhole) {
    TempDir temp;
    const fs::path file = temp.path() / "shared.csv";
    const std::string a(50000, 'a'), b(70000, 'b');
    std::vector<std::optional<std::string>> errors;
    std::mutex mutex;
    auto writer = [&](const std::string& content, bool unnamed) {
        for (int i = 0; i < 200; ++i) {
            const auto error = detail::writeFileAtomically(file, content, unnamed);
            if (error) {
                const std::lock_guard lock(mutex);
                errors.push_back(error);
            }
            const std::string now = slurp(file);
            if (now != a && now != b) {
                const std::lock_guard lock(mutex);
                errors.push_back("torn content of " + std::to_string(now.size()) + " bytes");
            }
        }
    };
    { std::jthread first(writer, a, true), second(writer, b, false); }
    EXPECT_TRUE(errors.empty()) << (errors.empty() ? "" : *errors.front());
    EXPECT_EQ(listing(temp.path()), (std::set<std::string>{"shared.csv"}));
}

// ---- readFile: inputs that end (issue 28) ------------------------------------------------

TEST(ReadFile, RefusesDevicesFifosAndFoldersByTheirKind) {
    TempDir temp;
    std::string content;
    auto error = readFile("/dev/zero", content);
    ASSERT_TRUE(error.has_value());
    EXPECT_EQ(*error, "/dev/zero is not a regular file (a character device)");
    error = readFile(temp.path(), content);
    ASSERT_TRUE(error.has_value());
    EXPECT_NE(error->find("is not a regular file (a directory)"), std::string::npos) << *error;
    const fs::path fifo = temp.path() / "pipe";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    error = readFile(fifo, content);  // returns at once: no writer is waited for
    ASSERT_TRUE(error.has_value());
    EXPECT_NE(error->find("is not a regular file (a FIFO (named pipe))"), std::string::npos);
}

TEST(ReadFile, ReadsAtMostTheLimit) {
    TempDir temp;
    const fs::path file = temp.path() / "big.csv";
    std::ofstream(file) << std::string(1000, 'x');
    std::string content = "kept";
    auto error = readFile(file, content, 999);
    ASSERT_TRUE(error.has_value());
    EXPECT_NE(error->find("big.csv has 1000 bytes, larger than the input limit of 999 bytes"),
              std::string::npos)
        << *error;
    EXPECT_EQ(content, "kept");  // untouched on failure
    EXPECT_EQ(readFile(file, content, 1000), std::nullopt);
    EXPECT_EQ(content.size(), 1000u);
}

}  // namespace
}  // namespace terra::io
