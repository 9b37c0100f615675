#pragma once
/// @file atomic_file.h
/// Writing files so that nothing is ever half-written and a killed write leaves nothing behind;
/// reading input files with a bound.
///
/// The content goes to an unnamed file in the target's directory (Linux `O_TMPFILE`): a process
/// killed while writing it leaves no trace, the kernel frees the inode. Once complete and synced,
/// the file is linked as `.NAME.tmp` and renamed over `NAME`. The temporary name is fixed, so the
/// instant between link and rename is the only moment a kill leaves a file, and the next write of
/// `NAME` removes it first. Where `O_TMPFILE` is not supported (file systems without it, no
/// /proc), the content is written to `.NAME.tmp` directly, truncating whatever an earlier killed
/// write left there, then renamed.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace terra::io {

/// Writes `content` to `path` atomically. Returns an error message, or nothing on success; on
/// failure the previous file (if any) is untouched and no temporary file is left behind.
std::optional<std::string> writeFileAtomically(const std::filesystem::path& path,
                                               std::string_view content);

/// The fixed temporary name a write of `path` links or writes before renaming it over `path`
/// (".NAME.tmp" in the same directory).
std::filesystem::path temporaryPathFor(const std::filesystem::path& path);

namespace detail {
/// writeFileAtomically, with the unnamed temporary file allowed or not (false: the named fallback
/// alone, so that tests can exercise it on a system that supports `O_TMPFILE`).
std::optional<std::string> writeFileAtomically(const std::filesystem::path& path,
                                               std::string_view content, bool allow_unnamed);
}  // namespace detail

/// The most bytes an input file may have by default: 256 MiB. Every data input (CSV, JSON, run
/// script) is read whole into memory and then parsed into cells several times its size; a
/// limit keeps a mistaken input (a disk image, /dev/zero) from eating the machine's memory,
/// while a 10^6-row data set (~150 MB) still fits.
inline constexpr std::uint64_t kDefaultMaxInputBytes = 256ull << 20;

/// The environment variable that overrides kDefaultMaxInputBytes (docs/cli.md, "Input files").
inline constexpr const char* kMaxInputBytesVariable = "TERRASTUDIO_MAX_INPUT_BYTES";

/// The input limit in bytes: TERRASTUDIO_MAX_INPUT_BYTES when set (a whole number of bytes
/// in [1, 2^62]), else kDefaultMaxInputBytes; an error message when the variable is malformed.
std::optional<std::string> maxInputBytes(std::uint64_t& bytes);

/// Reads a whole input file; an error message on failure. The file must be a regular file (or a
/// link to one): a directory, a FIFO, a socket or a device is refused by its kind ("… is not a
/// regular file (a character device)"), checked on the opened descriptor, which is opened
/// without blocking so that a FIFO with no writer cannot hang the reader. At most
/// maxInputBytes() bytes are read, whatever size the file claims: a longer file is refused
/// with the limit named.
std::optional<std::string> readFile(const std::filesystem::path& path, std::string& content);

/// readFile with an explicit limit in bytes.
std::optional<std::string> readFile(const std::filesystem::path& path, std::string& content,
                                    std::uint64_t max_bytes);

}  // namespace terra::io
