#pragma once
/// @file json_reader.h
/// Reading the fields of JSON objects into typed values, the one way every input file is read.
/// Each read names the field by its path (`analyses[2].slip_count`), checks the type (naming the
/// expected one), the range (integers too: `1e308` is out of range, never a wrapped int), the
/// allowed names of an enumeration; missing required keys and, at finish(), unknown keys (with the
/// nearest known key: "did you mean conditions?") are problems too. Every problem is collected;
/// nothing throws. Keys starting with '_' are comments and ignored ("_comment").
///
/// Usage, for an object with a number and a nested object:
/// @code
///   std::vector<Issue> issues;
///   ObjectReader r(json, issues, "script.json");
///   r.integer("slip_count", settings.slip_count, 2, 10000);
///   ObjectReader c = r.object("conditions");
///   c.field(kLoadField, conditions.load_n, Presence::kRequired);
///   c.finish();
///   r.finish();
/// @endcode
/// New checks (cross-field rules, file references) are added by the caller with report().

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/field.h"
#include "core/common/issue.h"
#include "core/common/quoted.h"
#include "core/common/range.h"
#include "core/io/atomic_file.h"
#include "core/io/json.h"

namespace terra::io {

/// Whether a key must be present.
enum class Presence { kOptional, kRequired };

/// One allowed name of an enumerated field and the value it stands for.
template <typename E>
struct Choice {
    const char* name;
    E value;
};

/// The JSON type of a value for messages, with the value when short: `string "x"`, `number 5`,
/// `null`, `array [1,2]`.
std::string describeJson(const nlohmann::json& value);

class ObjectReader {
public:
    /// Reads `object` (which must outlive the reader); issues go to `issues`, located as
    /// "SOURCE: PATH.KEY" ("script.json: analyses[2].slip_count"; PATH.KEY alone without a
    /// source). A value that is not an object is one issue ("expected an object"), and the reads
    /// then find nothing.
    ObjectReader(const nlohmann::json& object, std::vector<Issue>& issues, std::string source = {},
                 std::string path = {});

    /// Whether the value is an object.
    bool isObject() const { return object_ != nullptr; }
    /// Whether the object has `key` (without marking it read).
    bool has(std::string_view key) const;

    // Each read marks `key` as known and returns whether `out` was set: the key was present and
    // its value valid. An absent optional key leaves `out` unchanged (its default).

    /// A finite number in `range` (`unit` for the messages).
    bool number(std::string_view key, double& out, const Range& range, std::string_view unit = {},
                Presence presence = Presence::kOptional);
    /// A field of a field table: read in its user unit, checked against its range, stored in SI.
    bool field(const FieldInfo& field, double& si_out, Presence presence = Presence::kOptional);
    /// A whole number in [low, high]; doubles are range-checked before any conversion.
    bool integer(std::string_view key, int& out, int low, int high,
                 Presence presence = Presence::kOptional);
    bool integer(std::string_view key, std::uint64_t& out, std::uint64_t low, std::uint64_t high,
                 Presence presence = Presence::kOptional);
    bool boolean(std::string_view key, bool& out, Presence presence = Presence::kOptional);
    bool text(std::string_view key, std::string& out, Presence presence = Presence::kOptional);
    /// One of the names of `choices`.
    template <typename E>
    bool choice(std::string_view key, E& out, std::initializer_list<Choice<E>> choices,
                Presence presence = Presence::kOptional) {
        std::string name;
        std::vector<std::string> names;
        for (const Choice<E>& c : choices) names.emplace_back(c.name);
        if (!choiceName(key, name, names, presence)) return false;
        for (const Choice<E>& c : choices) {
            if (name == c.name) out = c.value;
        }
        return true;
    }
    /// The name itself, checked against `names`.
    bool choiceName(std::string_view key, std::string& out, const std::vector<std::string>& names,
                    Presence presence = Presence::kOptional);
    /// An array of numbers, each in `range`, with a count in [min_count, max_count].
    bool numbers(std::string_view key, std::vector<double>& out, const Range& range,
                 std::string_view unit = {}, std::size_t min_count = 0,
                 std::size_t max_count = 100000, Presence presence = Presence::kOptional);
    /// An array of strings.
    bool texts(std::string_view key, std::vector<std::string>& out,
               Presence presence = Presence::kOptional);

    /// A nested object's reader (sharing the issues). An absent optional key gives a reader that
    /// finds nothing and reports nothing; a value that is not an object is reported.
    ObjectReader object(std::string_view key, Presence presence = Presence::kOptional);
    /// An array's value, or nullptr (absent, or not an array: reported).
    const nlohmann::json* array(std::string_view key, Presence presence = Presence::kOptional);
    /// A reader of element `index` of array `key` (from array()).
    ObjectReader element(std::string_view key, const nlohmann::json& array, std::size_t index);
    /// The raw value for the caller to read, or nullptr when absent (a missing required key is
    /// reported as "missing; expected `what`").
    const nlohmann::json* value(std::string_view key, Presence presence = Presence::kOptional,
                                std::string_view what = {});
    /// Marks a key as known without reading it (it is read elsewhere).
    void allow(std::string_view key);

    /// Reports every key that was neither read nor allowed, with the nearest known key. Call once,
    /// after the last read.
    void finish();

    /// Adds an issue at `key` (empty: the object itself).
    void report(std::string_view key, std::string message);
    /// "analyses[2].slip_count"
    std::string pathOf(std::string_view key) const;
    /// The location of `key` as issues show it ("script.json: analyses[2].slip_count").
    std::string where(std::string_view key) const;
    const std::string& source() const { return source_; }
    const std::string& path() const { return path_; }
    /// The keys read or allowed so far (what finish() accepts), in the order they were read.
    const std::vector<std::string>& knownKeys() const { return known_; }
    std::vector<Issue>& issues() const { return *issues_; }

private:
    /// The value of `key`, marking it known; nullptr when absent (reported when required).
    const nlohmann::json* find(std::string_view key, Presence presence, std::string_view expected);

    const nlohmann::json* object_;  // nullptr: not an object (or an absent optional object)
    std::vector<Issue>* issues_;
    std::string source_;
    std::string path_;
    std::vector<std::string> known_;
};

/// The issues of `bad_numbers`, each naming the allowed range of its field as a reader run on
/// the marked document (parseJsonMarkingNumbers) states it in `reader_issues`: an ObjectReader
/// reports a NaN at SOURCE: PATH as "nan is not a finite number; allowed range R UNIT", so the
/// issue becomes "SOURCE:LINE:COLUMN: PATH: 1e999 is too large for a number (beyond ±1.8e308);
/// allowed range R UNIT". A number the reader did not check (a comment key, a value kept as it
/// is) keeps its message.
std::vector<Issue> withAllowedRanges(const std::vector<BadNumber>& bad_numbers,
                                     const std::vector<Issue>& reader_issues,
                                     const std::string& source);

/// Reads the JSON file at `path` and hands it to `read(document, source)`, which returns a
/// Result<T> (source: the path). A number a double cannot hold (1e999, 1e-320) is an error as in
/// readJsonFile, with the allowed range of its field: `read` runs on the document with such
/// numbers marked, only to learn the ranges (withAllowedRanges).
template <typename T, typename Read>
Result<T> readJsonTextWith(std::string_view text, const std::string& source, Read read);

template <typename T, typename Read>
Result<T> readJsonFileWith(const std::filesystem::path& path, Read read) {
    std::string text;
    const std::string source = path.string();
    if (const auto error = readFile(path, text))
        return std::vector<Issue>{{pathLabel(source), *error}};
    return readJsonTextWith<T>(text, source, read);
}

/// readJsonFileWith for a text already read (`source` names it).
template <typename T, typename Read>
Result<T> readJsonTextWith(std::string_view text, const std::string& source, Read read) {
    std::vector<BadNumber> bad;
    Result<nlohmann::json> document = parseJsonMarkingNumbers(text, source, bad);
    if (!document) {
        std::vector<Issue> issues = document.issues();
        for (const BadNumber& b : bad) issues.push_back(b.issue);
        return issues;
    }
    Result<T> value = read(document.value(), source);
    if (bad.empty()) return value;
    return withAllowedRanges(bad, value.ok() ? std::vector<Issue>{} : value.issues(), source);
}

}  // namespace terra::io
