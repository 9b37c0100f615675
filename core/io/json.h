#pragma once
/// @file json.h
/// Strict JSON input for every file the product reads (soils, wheels, robots, scenarios, run
/// scripts, .terra projects). nlohmann's parser accepts duplicated keys silently (the last one
/// wins) and throws on numbers beyond a double; this parser reports both, with the position, so a
/// file is never half-understood:
/// - a syntax error (RFC 8259 grammar, well-formed UTF-8), with line and column; it ends the parse;
/// - every duplicated key of an object, with both positions;
/// - every number a double cannot hold: overflow (`1e999`), underflow to zero (`1e-400`) and
///   subnormal values (`1e-310`, which keep only a few significant digits).
/// Issues are located as "SOURCE:LINE:COLUMN" (1-based; columns count characters, not bytes).

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/issue.h"

namespace terra::io {

/// Parses `text`; `source` names it in the issues (a file path, "edited scenario"). Integers that
/// fit 64 bits stay integers; every other number is a double.
Result<nlohmann::json> parseJson(std::string_view text, const std::string& source);

/// Reads a file and parses it with its path as the source.
Result<nlohmann::json> readJsonFile(const std::filesystem::path& path);

/// A number of a JSON text that no double holds: overflow, underflow to zero, subnormal.
struct BadNumber {
    Issue issue;       ///< as parseJson reports it: "SOURCE:LINE:COLUMN", "PATH: 1e999 is too …"
    std::string path;  ///< the key path of the value ("wheels.all.steer_deg.amplitude", "a[2]")
};

/// parseJson, except that numbers a double cannot hold do not fail the parse: each is a NaN in
/// the value (no JSON text holds one, so a NaN marks it) and is listed in `bad_numbers`, so that
/// a reader can name the allowed range of its field (readJsonFileWith in json_reader.h). A
/// syntax error or a duplicated key still fails.
Result<nlohmann::json> parseJsonMarkingNumbers(std::string_view text, const std::string& source,
                                               std::vector<BadNumber>& bad_numbers);

/// A value as JSON text for a message, cut to at most `max_chars` characters ("…" marks the cut).
std::string quoteJson(const nlohmann::json& value, std::size_t max_chars = 80);

}  // namespace terra::io
