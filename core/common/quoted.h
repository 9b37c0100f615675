#pragma once
/// @file quoted.h
/// User text in messages, quoted short.

#include <cstddef>
#include <string>
#include <string_view>

namespace terra {

/// User text (a name, a path, a cell) for a message, between `mark`s: at most `max_chars`
/// characters, a longer one cut at a UTF-8 character boundary with its length given
/// ("'xxxx…' (1500 characters)"), so that a message never echoes a huge input whole
/// (docs/reliability.md: a bad value is quoted to ~80 characters). Control characters show as
/// escapes ("\n", "\x1b").
std::string quoteText(std::string_view text, char mark = '\'', std::size_t max_chars = 80);

/// A file's path for a message, its end kept: the path itself when it has at most `max_chars`
/// characters, else "…" and its last `max_chars` − 1 characters, so that the file name shows
/// ("…/deep/folder/points.csv"); control characters shown as escapes ("\n"). No quotes.
std::string pathTail(std::string_view path, std::size_t max_chars = 80);

/// A file's path as the place an issue names (its `where`): the path itself when it has at most
/// `max_chars` characters, else quoted short like quoteText, so that a huge path given for a file
/// that does not exist is not echoed whole (fuzz finding, docs/reliability.md).
std::string pathLabel(std::string_view path, std::size_t max_chars = 80);

}  // namespace terra
