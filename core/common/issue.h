#pragma once
/// @file issue.h
/// Problems found in user data (files, CSV rows, command-line flags), reported without throwing:
/// each names where it is (field path, or file:line), the offending value and what is allowed.

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace terra {

/// One problem in user input.
struct Issue {
    std::string where;    ///< field path ("soil.phi_deg") or location ("points.csv:12")
    std::string message;  ///< what is wrong, with the value and the allowed range
};

/// Joins issues into one human-readable message, one line each ("where: message").
std::string formatIssues(const std::vector<Issue>& issues);

/// The candidate a misspelt name most likely meant ("condtions" → "conditions", "phi" →
/// "phi_deg"), or "" when none is close: at most one edit (insertion, deletion, substitution or
/// swap of neighbours) per three characters, case ignored, or the name with its unit suffix left
/// out.
std::string nearestName(std::string_view name, const std::vector<std::string>& candidates);

/// The value parsed from user input, or the list of every problem found.
template <typename T>
class Result {
public:
    Result(T value) : value_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
    Result(std::vector<Issue> issues) : issues_(std::move(issues)) {}  // NOLINT

    bool ok() const { return value_.has_value(); }
    explicit operator bool() const { return ok(); }
    const T& value() const& { return *value_; }
    T&& value() && { return std::move(*value_); }
    const T& operator*() const { return *value_; }
    const T* operator->() const { return &*value_; }
    const std::vector<Issue>& issues() const { return issues_; }
    std::string message() const { return formatIssues(issues_); }

private:
    std::optional<T> value_;
    std::vector<Issue> issues_;
};

}  // namespace terra
