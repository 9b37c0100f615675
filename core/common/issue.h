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

/// At most this many issues are listed by formatIssues; the rest are counted ("… and 19980 more").
inline constexpr std::size_t kMaxIssuesShown = 20;
/// The longest line formatIssues prints, in characters (UTF-8 code points): a longer one is cut
/// with its length given. The values in messages are quoted short already (quoteText); this
/// bounds the rest (long paths, lists).
inline constexpr std::size_t kMaxIssueChars = 500;

/// One issue as a line, "where: message" (or the message alone), at most kMaxIssueChars
/// characters.
std::string formatIssue(const Issue& issue);

/// Joins issues into one human-readable message, one line each ("where: message", formatIssue),
/// the first kMaxIssuesShown of them, then "… and N more (M problems in all)": 100,000 bad
/// rows or unknown keys give a screenful, not megabytes.
std::string formatIssues(const std::vector<Issue>& issues);

/// The count line formatIssues ends a cut list with ("… and 5 more (25 problems in all)"),
/// for callers that print issues one by one.
std::string moreIssues(std::size_t shown, std::size_t total, const std::string& what = "problems");

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
