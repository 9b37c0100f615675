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
/// (docs/reliability.md: a bad value is quoted to ~80 characters).
std::string quoteText(std::string_view text, char mark = '\'', std::size_t max_chars = 80);

}  // namespace terra
