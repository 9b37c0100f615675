#include "core/io/atomic_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <system_error>

#include "core/common/quoted.h"

namespace terra::io {
namespace {

// A file descriptor closed on every return path.
struct Descriptor {
    int fd = -1;
    explicit Descriptor(int f) : fd(f) {}
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    ~Descriptor() {
        if (fd >= 0) ::close(fd);
    }
};

std::string reason(int error) { return std::strerror(error); }

// Writes all of `content`, through short writes and interruptions (a signal handler that only
// sets a flag interrupts a write without ending it). Returns 0 or the errno.
int writeAll(int fd, std::string_view content) {
    const char* data = content.data();
    std::size_t left = content.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, data, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            return errno;
        }
        data += n;
        left -= static_cast<std::size_t>(n);
    }
    // Synced before the rename, so that the name never points at data still in flight (a power
    // cut after the rename must not leave an empty file where the old one was).
    while (::fdatasync(fd) != 0) {
        if (errno != EINTR) return errno;
    }
    return 0;
}

// Holds an exclusive advisory lock on the target's directory: writers of one directory (other
// processes, other threads) take turns at the shared temporary name, so one writer can never
// rename a file another is still writing or has just linked. Released on every return path, and
// by the kernel when a process dies. Without lock support (some network file systems) writes go
// ahead unserialised.
class DirectoryLock {
public:
    explicit DirectoryLock(int dir) : dir_(dir) {
        while (::flock(dir_, LOCK_EX) != 0) {
            if (errno != EINTR) {
                dir_ = -1;
                return;
            }
        }
    }
    DirectoryLock(const DirectoryLock&) = delete;
    DirectoryLock& operator=(const DirectoryLock&) = delete;
    ~DirectoryLock() {
        if (dir_ >= 0) ::flock(dir_, LOCK_UN);
    }

private:
    int dir_;
};

// Links the complete unnamed file `fd` as `temporary` in `dir` and renames it over `name`, under
// the directory lock. A `temporary` left by a write killed between its link and rename is removed
// first. Returns 0, or the errno of the failed step with `step` naming it.
int linkIntoPlace(int fd, int dir, const std::string& temporary, const std::string& name,
                  const char*& step) {
    const std::string self = "/proc/self/fd/" + std::to_string(fd);
    const DirectoryLock lock(dir);
    if (::unlinkat(dir, temporary.c_str(), 0) != 0 && errno != ENOENT) {
        step = "remove";
        return errno;
    }
    if (::linkat(AT_FDCWD, self.c_str(), dir, temporary.c_str(), AT_SYMLINK_FOLLOW) != 0) {
        step = "link";
        return errno;
    }
    if (::renameat(dir, temporary.c_str(), dir, name.c_str()) != 0) {
        const int error = errno;
        step = "rename";
        ::unlinkat(dir, temporary.c_str(), 0);
        return error;
    }
    return 0;
}

}  // namespace

std::filesystem::path temporaryPathFor(const std::filesystem::path& path) {
    // Appended, not "." + name + ".tmp": GCC 12 at -O3 warns of a bound it cannot prove (a false
    // -Wstringop-overflow inside char_traits).
    std::string name = ".";
    name += path.filename().string();
    name += ".tmp";
    return path.parent_path() / name;
}

namespace detail {

std::optional<std::string> writeFileAtomically(const std::filesystem::path& path,
                                               std::string_view content, bool allow_unnamed) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path directory = path.has_parent_path() ? path.parent_path() : fs::path(".");
    if (!fs::is_directory(directory, ec)) {
        return "cannot write " + path.string() + ": directory " + directory.string() +
               " does not exist";
    }
    const std::string name = path.filename().string();
    const std::string temporary = temporaryPathFor(path).filename().string();
    const Descriptor dir(::open(directory.c_str(), O_DIRECTORY | O_RDONLY | O_CLOEXEC));
    if (dir.fd < 0) return "cannot write " + path.string() + ": " + reason(errno);

    if (allow_unnamed) {
        const Descriptor file(::openat(dir.fd, ".", O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666));
        if (file.fd >= 0) {
            if (const int error = writeAll(file.fd, content)) {
                return "cannot write " + path.string() + ": " + reason(error);  // nothing named
            }
            const char* step = "";
            const int error = linkIntoPlace(file.fd, dir.fd, temporary, name, step);
            if (error == 0) return std::nullopt;
            // No /proc to link through: write the content again under the temporary name.
            if (!(std::string(step) == "link" && error == ENOENT)) {
                return "cannot replace " + path.string() + " (" + step + "): " + reason(error);
            }
        }
        // O_TMPFILE unsupported here (EOPNOTSUPP, EISDIR or EINVAL): the named fallback below.
    }

    // O_TRUNC: a temporary left by an earlier killed write is reused, not added to. The lock is
    // held for the whole write: the temporary name is shared by every writer of `path`.
    const DirectoryLock lock(dir.fd);
    const Descriptor file(::openat(dir.fd, temporary.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0666));
    const fs::path temporary_path = directory / temporary;
    if (file.fd < 0) return "cannot create " + temporary_path.string() + ": " + reason(errno);
    if (const int error = writeAll(file.fd, content)) {
        ::unlinkat(dir.fd, temporary.c_str(), 0);
        return "cannot write " + temporary_path.string() + ": " + reason(error);
    }
    if (::renameat(dir.fd, temporary.c_str(), dir.fd, name.c_str()) != 0) {
        const int error = errno;
        ::unlinkat(dir.fd, temporary.c_str(), 0);
        return "cannot replace " + path.string() + ": " + reason(error);
    }
    return std::nullopt;
}

}  // namespace detail

std::optional<std::string> writeFileAtomically(const std::filesystem::path& path,
                                               std::string_view content) {
    return detail::writeFileAtomically(path, content, true);
}

namespace {

// The kind of a file that is not a regular one, for a message.
const char* fileKind(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a file of data";
}

std::string describeBytes(std::uint64_t bytes) {
    if (bytes % (1ull << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
    return std::to_string(bytes) + " bytes";
}

}  // namespace

std::optional<std::string> maxInputBytes(std::uint64_t& bytes) {
    bytes = kDefaultMaxInputBytes;
    const char* text = std::getenv(kMaxInputBytesVariable);
    if (text == nullptr) return std::nullopt;
    const std::string_view value(text);
    std::uint64_t parsed = 0;
    const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), parsed);
    constexpr std::uint64_t kLargest = 1ull << 62;
    if (value.empty() || error != std::errc{} || end != value.data() + value.size() || parsed < 1 ||
        parsed > kLargest) {
        return std::string(kMaxInputBytesVariable) + ": " + quoteText(value) +
               " is not a whole number of bytes in [1, 2^62]";
    }
    bytes = parsed;
    return std::nullopt;
}

std::optional<std::string> readFile(const std::filesystem::path& path, std::string& content) {
    std::uint64_t limit = 0;
    if (auto error = maxInputBytes(limit)) return error;
    return readFile(path, content, limit);
}

std::optional<std::string> readFile(const std::filesystem::path& path, std::string& content,
                                    std::uint64_t max_bytes) {
    // A file that cannot be opened is named as before (pathLabel); one of the wrong kind or size
    // by its end, where its name is.
    const std::string label = pathTail(path.string());
    const std::string opened = pathLabel(path.string());
    // The type by name first (following links), so that a device is never even opened (opening
    // some has effects); then again on the descriptor, so that a file swapped in between cannot
    // slip through. O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer,
    // for ever; a regular file ignores the flag.
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) return "cannot open " + opened + ": " + reason(errno);
    if (!S_ISREG(info.st_mode)) {
        return label + " is not a regular file (" + fileKind(info.st_mode) + ")";
    }
    const Descriptor file(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
    if (file.fd < 0) return "cannot open " + opened + ": " + reason(errno);
    if (::fstat(file.fd, &info) != 0) return "cannot read " + opened + ": " + reason(errno);
    if (!S_ISREG(info.st_mode)) {
        return label + " is not a regular file (" + fileKind(info.st_mode) + ")";
    }
    const std::string limit_text = "larger than the input limit of " + describeBytes(max_bytes) +
                                   " (set " + kMaxInputBytesVariable + " to read more)";
    if (static_cast<std::uint64_t>(info.st_size) > max_bytes) {
        return label + " has " + std::to_string(info.st_size) + " bytes, " + limit_text;
    }
    // Read to the end, not to st_size: a file may grow, and some (in /proc) claim size 0. The
    // bound holds either way.
    std::string text;
    text.reserve(static_cast<std::size_t>(info.st_size));
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::read(file.fd, buffer, sizeof buffer);
        if (n < 0) {
            if (errno == EINTR) continue;
            return "cannot read " + opened + ": " + reason(errno);
        }
        if (n == 0) break;
        if (text.size() + static_cast<std::size_t>(n) > max_bytes) {
            return label + " is " + limit_text;
        }
        text.append(buffer, static_cast<std::size_t>(n));
    }
    content = std::move(text);
    return std::nullopt;
}

}  // namespace terra::io
