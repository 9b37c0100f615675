#pragma once
/// @file atomic_file.h
/// Writing files so that nothing is ever half-written and a killed write leaves nothing behind.
///
/// The content goes to an unnamed file in the target's directory (Linux `O_TMPFILE`): a process
/// killed while writing it leaves no trace, the kernel frees the inode. Once complete and synced,
/// the file is linked as `.NAME.tmp` and renamed over `NAME`. The temporary name is fixed, so the
/// instant between link and rename is the only moment a kill leaves a file, and the next write of
/// `NAME` removes it first. Where `O_TMPFILE` is not supported (file systems without it, no
/// /proc), the content is written to `.NAME.tmp` directly, truncating whatever an earlier killed
/// write left there, then renamed.

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

/// Reads a whole file; an error message on failure.
std::optional<std::string> readFile(const std::filesystem::path& path, std::string& content);

}  // namespace terra::io
