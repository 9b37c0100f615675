#include "core/io/json_reader.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/io/csv.h"
#include "core/io/json.h"

namespace terra::io {
namespace {

using nlohmann::json;

const json& emptyObject() {
    static const json empty = json::object();
    return empty;
}

std::string withUnit(const Range& range, std::string_view unit) {
    return range.describe() + (unit.empty() || unit == "-" ? "" : " " + std::string(unit));
}

// A list of names for a message, cut so that the message stays short.
std::string listNames(const std::vector<std::string>& names) {
    std::string list;
    for (const std::string& name : names) {
        if (list.size() + name.size() > 200) return list + ", …";
        list += (list.empty() ? "" : ", ") + name;
    }
    return list;
}

std::string quoteName(std::string_view text) {
    return "\"" +
           (text.size() <= 60 ? std::string(text) : std::string(text.substr(0, 57)) + "...") + "\"";
}

}  // namespace

std::string describeJson(const json& value) {
    if (value.is_null()) return "null";
    return std::string(value.type_name()) + " " + quoteJson(value);
}

ObjectReader::ObjectReader(const json& object, std::vector<Issue>& issues, std::string source,
                           std::string path)
    : object_(&object), issues_(&issues), source_(std::move(source)), path_(std::move(path)) {
    if (!object.is_object()) {
        report({}, "expected a JSON object, got " + describeJson(object));
        object_ = nullptr;
    }
}

bool ObjectReader::has(std::string_view key) const {
    return object_ != nullptr && object_->contains(key);
}

std::string ObjectReader::pathOf(std::string_view key) const {
    if (key.empty()) return path_;
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

std::string ObjectReader::where(std::string_view key) const {
    const std::string path = pathOf(key);
    if (source_.empty()) return path;
    return path.empty() ? source_ : source_ + ": " + path;
}

void ObjectReader::report(std::string_view key, std::string message) {
    issues_->push_back({where(key), std::move(message)});
}

void ObjectReader::allow(std::string_view key) {
    if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.emplace_back(key);
}

const json* ObjectReader::find(std::string_view key, Presence presence, std::string_view expected) {
    allow(key);
    if (object_ == nullptr) return nullptr;
    const auto it = object_->find(key);
    if (it == object_->end()) {
        if (presence == Presence::kRequired) {
            report(key, expected.empty() ? std::string("missing")
                                         : "missing; expected " + std::string(expected));
        }
        return nullptr;
    }
    return &*it;
}

const json* ObjectReader::value(std::string_view key, Presence presence, std::string_view what) {
    return find(key, presence, what);
}

bool ObjectReader::number(std::string_view key, double& out, const Range& range,
                          std::string_view unit, Presence presence) {
    const std::string expected = "a number in " + withUnit(range, unit);
    const json* v = find(key, presence, expected);
    if (v == nullptr) return false;
    if (!v->is_number()) {
        report(key, "expected " + expected + ", got " + describeJson(*v));
        return false;
    }
    const double value = v->get<double>();
    const std::string u = unit == "-" ? std::string() : std::string(unit);
    std::vector<Issue> range_issues;
    if (!checkRange(range_issues, where(key), value, range, u)) {
        issues_->insert(issues_->end(), range_issues.begin(), range_issues.end());
        return false;
    }
    out = value;
    return true;
}

bool ObjectReader::field(const FieldInfo& field, double& si_out, Presence presence) {
    double user = 0.0;
    if (!number(field.key, user, field.range, field.displayUnit(), presence)) return false;
    si_out = field.toSi(user);
    return true;
}

bool ObjectReader::integer(std::string_view key, int& out, int low, int high, Presence presence) {
    const Range range{static_cast<double>(low), static_cast<double>(high)};
    const std::string expected = "a whole number in " + range.describe();
    const json* v = find(key, presence, expected);
    if (v == nullptr) return false;
    if (!v->is_number()) {
        report(key, "expected " + expected + ", got " + describeJson(*v));
        return false;
    }
    // Compared as a double first: a value beyond int (1e308) is a range error, never a cast.
    const double value = v->get<double>();
    std::vector<Issue> range_issues;
    if (!checkRange(range_issues, where(key), value, range)) {
        issues_->insert(issues_->end(), range_issues.begin(), range_issues.end());
        return false;
    }
    if (value != std::floor(value)) {
        report(key, formatNumber(value) + " is not a whole number; expected " + expected);
        return false;
    }
    out = static_cast<int>(value);
    return true;
}

bool ObjectReader::integer(std::string_view key, std::uint64_t& out, std::uint64_t low,
                           std::uint64_t high, Presence presence) {
    const std::string expected =
        "a whole number in [" + std::to_string(low) + ", " + std::to_string(high) + "]";
    const json* v = find(key, presence, expected);
    if (v == nullptr) return false;
    if (!v->is_number()) {
        report(key, "expected " + expected + ", got " + describeJson(*v));
        return false;
    }
    std::uint64_t value = 0;
    if (v->is_number_unsigned()) {
        value = v->get<std::uint64_t>();
    } else if (v->is_number_integer() && v->get<std::int64_t>() >= 0) {
        value = static_cast<std::uint64_t>(v->get<std::int64_t>());
    } else {
        // A negative integer or a double: in range only when whole and below 2^64 (the cast of a
        // double beyond it is undefined).
        const double d = v->get<double>();
        if (!(d >= 0.0 && d < 18446744073709551616.0 && d == std::floor(d))) {
            report(key, quoteJson(*v) + " is not " + expected);
            return false;
        }
        value = static_cast<std::uint64_t>(d);
    }
    if (value < low || value > high) {
        report(key, std::to_string(value) + " is not " + expected);
        return false;
    }
    out = value;
    return true;
}

bool ObjectReader::boolean(std::string_view key, bool& out, Presence presence) {
    const json* v = find(key, presence, "true or false");
    if (v == nullptr) return false;
    if (!v->is_boolean()) {
        report(key, "expected true or false, got " + describeJson(*v));
        return false;
    }
    out = v->get<bool>();
    return true;
}

bool ObjectReader::text(std::string_view key, std::string& out, Presence presence) {
    const json* v = find(key, presence, "a string");
    if (v == nullptr) return false;
    if (!v->is_string()) {
        report(key, "expected a string, got " + describeJson(*v));
        return false;
    }
    out = v->get<std::string>();
    return true;
}

bool ObjectReader::choiceName(std::string_view key, std::string& out,
                              const std::vector<std::string>& names, Presence presence) {
    const std::string expected = "one of " + listNames(names);
    const json* v = find(key, presence, expected);
    if (v == nullptr) return false;
    if (!v->is_string()) {
        report(key, "expected a string, " + expected + ", got " + describeJson(*v));
        return false;
    }
    const std::string name = v->get<std::string>();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
        const std::string near = nearestName(name, names);
        report(key, quoteName(name) + " is not " + expected +
                        (near.empty() ? "" : " (did you mean \"" + near + "\"?)"));
        return false;
    }
    out = name;
    return true;
}

bool ObjectReader::numbers(std::string_view key, std::vector<double>& out, const Range& range,
                           std::string_view unit, std::size_t min_count, std::size_t max_count,
                           Presence presence) {
    const std::string count = max_count >= 100000
                                  ? std::to_string(min_count) + " or more"
                                  : std::to_string(min_count) + " to " + std::to_string(max_count);
    const std::string expected = "an array of " + count + " numbers in " + withUnit(range, unit);
    const json* v = find(key, presence, expected);
    if (v == nullptr) return false;
    if (!v->is_array()) {
        report(key, "expected " + expected + ", got " + describeJson(*v));
        return false;
    }
    if (v->size() < min_count || v->size() > max_count) {
        report(key, std::to_string(v->size()) + " values; expected " + expected);
        return false;
    }
    std::vector<double> values;
    bool ok = true;
    const std::string u = unit == "-" ? std::string() : std::string(unit);
    for (std::size_t i = 0; i < v->size(); ++i) {
        const json& e = (*v)[i];
        const std::string at = std::string(key) + "[" + std::to_string(i) + "]";
        if (!e.is_number()) {
            report(at,
                   "expected a number in " + withUnit(range, unit) + ", got " + describeJson(e));
            ok = false;
            continue;
        }
        std::vector<Issue> range_issues;
        if (!checkRange(range_issues, where(at), e.get<double>(), range, u)) {
            issues_->insert(issues_->end(), range_issues.begin(), range_issues.end());
            ok = false;
        }
        values.push_back(e.get<double>());
    }
    if (!ok) return false;
    out = std::move(values);
    return true;
}

bool ObjectReader::texts(std::string_view key, std::vector<std::string>& out, Presence presence) {
    const json* v = find(key, presence, "an array of strings");
    if (v == nullptr) return false;
    if (!v->is_array()) {
        report(key, "expected an array of strings, got " + describeJson(*v));
        return false;
    }
    std::vector<std::string> values;
    bool ok = true;
    for (std::size_t i = 0; i < v->size(); ++i) {
        const json& e = (*v)[i];
        if (!e.is_string()) {
            report(std::string(key) + "[" + std::to_string(i) + "]",
                   "expected a string, got " + describeJson(e));
            ok = false;
            continue;
        }
        values.push_back(e.get<std::string>());
    }
    if (!ok) return false;
    out = std::move(values);
    return true;
}

ObjectReader ObjectReader::object(std::string_view key, Presence presence) {
    const json* v = find(key, presence, "an object");
    if (v == nullptr) {
        ObjectReader absent(emptyObject(), *issues_, source_, pathOf(key));
        return absent;
    }
    return ObjectReader(*v, *issues_, source_, pathOf(key));
}

const json* ObjectReader::array(std::string_view key, Presence presence) {
    const json* v = find(key, presence, "an array");
    if (v == nullptr) return nullptr;
    if (!v->is_array()) {
        report(key, "expected an array, got " + describeJson(*v));
        return nullptr;
    }
    return v;
}

ObjectReader ObjectReader::element(std::string_view key, const json& array, std::size_t index) {
    return ObjectReader(array[index], *issues_, source_,
                        pathOf(key) + "[" + std::to_string(index) + "]");
}

void ObjectReader::finish() {
    if (object_ == nullptr) return;
    for (const auto& [key, value] : object_->items()) {
        (void)value;
        if (!key.empty() && key[0] == '_') continue;  // a comment
        if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
        const std::string near = nearestName(key, known_);
        // A key is user text: quoted to ~80 characters like a bad value (a fuzzed 1000-character
        // key used to be echoed whole, in the location and the message).
        const std::string shown = key.size() > 80 ? quoteCell(key) : key;
        report(shown, near.empty() ? "unknown key; allowed keys: " + listNames(known_)
                                   : "unknown key; did you mean \"" + near +
                                         "\"? Allowed keys: " + listNames(known_));
    }
}

}  // namespace terra::io

namespace terra::io {

std::vector<Issue> withAllowedRanges(const std::vector<BadNumber>& bad_numbers,
                                     const std::vector<Issue>& reader_issues,
                                     const std::string& source) {
    std::vector<Issue> out;
    for (const BadNumber& bad : bad_numbers) {
        Issue issue = bad.issue;
        const std::string at = source.empty() ? bad.path : source + ": " + bad.path;
        for (const Issue& r : reader_issues) {
            if (r.where != at) continue;
            // number(), field(), integer() and the signals' checks say "allowed range R"; the
            // 64-bit integers "is not a whole number in [a, b]".
            constexpr std::string_view kRange = "allowed range ", kWhole = "a whole number in ";
            if (const auto k = r.message.find(kRange); k != std::string::npos) {
                issue.message += "; " + r.message.substr(k);
                break;
            }
            if (const auto k = r.message.find(kWhole); k != std::string::npos) {
                issue.message +=
                    "; allowed range " + r.message.substr(k + kWhole.size()) + " (whole numbers)";
                break;
            }
        }
        out.push_back(std::move(issue));
    }
    return out;
}

}  // namespace terra::io
