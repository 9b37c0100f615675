#include "core/io/atomic_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
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
    return path.parent_path() / ("." + path.filename().string() + ".tmp");
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

std::optional<std::string> readFile(const std::filesystem::path& path, std::string& content) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return "cannot open " + pathLabel(path.string());
    std::ostringstream buffer;
    buffer << in.rdbuf();
    content = buffer.str();
    return std::nullopt;
}

}  // namespace terra::io
