#include "core/common/issue.h"

#include <algorithm>
#include <cctype>

namespace terra {

namespace {

bool continuation(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }

std::size_t characters(std::string_view text) {
    std::size_t n = 0;
    for (const char c : text) n += continuation(c) ? 0 : 1;
    return n;
}

// The last `keep` characters of `text`, after "…" when cut: a long place ("/a/long/path/f.csv:3")
// keeps its file name and line.
std::string tail(const std::string& text, std::size_t keep) {
    if (characters(text) <= keep) return text;
    std::size_t start = text.size(), kept = 0;
    while (start > 0 && kept < keep) {
        --start;
        if (!continuation(text[start])) ++kept;
    }
    return "…" + text.substr(start);
}

}  // namespace

std::string formatIssue(const Issue& issue) {
    // The place first gives way (its end names the file and line), then the message's end.
    constexpr std::size_t kWhereKept = 160;
    const std::string where =
        characters(issue.where) + characters(issue.message) + 2 > kMaxIssueChars
            ? tail(issue.where, kWhereKept)
            : issue.where;
    const std::string line = where.empty() ? issue.message : where + ": " + issue.message;
    std::size_t chars = 0;
    for (std::size_t k = 0; k < line.size(); ++k) {
        if (continuation(line[k])) continue;
        if (++chars > kMaxIssueChars) {
            return line.substr(0, k) + "… (" + std::to_string(characters(line)) + " characters)";
        }
    }
    return line;
}

std::string moreIssues(std::size_t shown, std::size_t total, const std::string& what) {
    return "… and " + std::to_string(total - shown) + " more (" + std::to_string(total) + " " +
           what + " in all)";
}

std::string formatIssues(const std::vector<Issue>& issues) {
    std::string text;
    const std::size_t shown = std::min(issues.size(), kMaxIssuesShown);
    for (std::size_t i = 0; i < shown; ++i) {
        if (!text.empty()) text += '\n';
        text += formatIssue(issues[i]);
    }
    if (shown < issues.size()) text += '\n' + moreIssues(shown, issues.size());
    return text;
}

namespace {

char lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }

// Optimal string alignment distance (Levenshtein with swaps of neighbours), case ignored.
std::size_t editDistance(std::string_view a, std::string_view b) {
    const std::size_t n = a.size(), m = b.size();
    std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
    for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
    for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
    for (std::size_t i = 1; i <= n; ++i) {
        for (std::size_t j = 1; j <= m; ++j) {
            const std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) &&
                lower(a[i - 2]) == lower(b[j - 1])) {
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
            }
        }
    }
    return d[n][m];
}

}  // namespace

std::string nearestName(std::string_view name, const std::vector<std::string>& candidates) {
    if (name.empty() || name.size() > 64) return {};
    const std::size_t allowed = std::max<std::size_t>(1, name.size() / 3);
    std::string best;
    std::size_t best_distance = allowed + 1;
    for (const std::string& candidate : candidates) {
        // "phi" for "phi_deg": the key without its unit suffix.
        const bool unit_left_out = candidate.size() > name.size() &&
                                   candidate.compare(0, name.size(), name) == 0 &&
                                   candidate[name.size()] == '_' &&
                                   candidate.find('_', name.size() + 1) == std::string::npos;
        const std::size_t distance = unit_left_out ? 0 : editDistance(name, candidate);
        if (distance < best_distance) {
            best = candidate;
            best_distance = distance;
        }
    }
    return best;
}

}  // namespace terra
