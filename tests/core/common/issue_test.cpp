// formatIssues(): every problem in one message, but bounded (issue 28: 100,000 unknown keys gave
// 12.3 MB on stderr): the first kMaxIssuesShown, then their count; each line kMaxIssueChars long
// at most, a long place giving way first.
#include "core/common/issue.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace terra {
namespace {

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

TEST(FormatIssues, ListsTwentyThenCountsTheRest) {
    std::vector<Issue> issues;
    for (int i = 0; i < 25; ++i) issues.push_back({"f.csv:" + std::to_string(i + 2), "bad"});
    const std::vector<std::string> text = lines(formatIssues(issues));
    ASSERT_EQ(text.size(), kMaxIssuesShown + 1);
    EXPECT_EQ(text.front(), "f.csv:2: bad");
    EXPECT_EQ(text.back(), "… and 5 more (25 problems in all)");
    issues.resize(kMaxIssuesShown);
    EXPECT_EQ(lines(formatIssues(issues)).size(), kMaxIssuesShown);  // no count line
}

TEST(FormatIssue, ALongPlaceKeepsItsEndAndALongMessageIsCut) {
    const std::string place = "/" + std::string(1000, 'd') + "/points.csv:3";
    const std::string line = formatIssue({place, "slip = 1.5 is outside the allowed range"});
    EXPECT_LT(line.size(), kMaxIssueChars + 50);
    EXPECT_NE(line.find("/points.csv:3: slip = 1.5 is outside the allowed range"),
              std::string::npos);
    const std::string cut = formatIssue({"", std::string(2000, 'm')});
    EXPECT_EQ(cut, std::string(kMaxIssueChars, 'm') + "… (2000 characters)");
}

}  // namespace
}  // namespace terra
