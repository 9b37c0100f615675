#pragma once
/// @file atomic_file.h
/// Writing files so that nothing is ever half-written: the content goes to a temporary file in
/// the same directory, which is flushed and then renamed over the target.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace terra::io {

/// Writes `content` to `path` atomically. Returns an error message, or nothing on success; on
/// failure the previous file (if any) is untouched and no temporary file is left behind.
std::optional<std::string> writeFileAtomically(const std::filesystem::path& path,
                                               std::string_view content);

/// Reads a whole file; an error message on failure.
std::optional<std::string> readFile(const std::filesystem::path& path, std::string& content);

}  // namespace terra::io
