#include "core/common/range.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace terra {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(Range, ClosedRangeContainsBothEnds) {
    const Range range{-1.0, 1.0};
    EXPECT_TRUE(range.contains(-1.0));
    EXPECT_TRUE(range.contains(1.0));
    EXPECT_TRUE(range.contains(0.0));
    EXPECT_FALSE(range.contains(std::nextafter(-1.0, -2.0)));
    EXPECT_FALSE(range.contains(std::nextafter(1.0, 2.0)));
    EXPECT_FALSE(range.contains(5.0));
}

TEST(Range, OpenHighEndExcludesOnlyTheEnd) {
    const Range range{0.0, 60.0, false, true};  // [0, 60)
    EXPECT_TRUE(range.contains(0.0));
    EXPECT_TRUE(range.contains(std::nextafter(60.0, 0.0)));
    EXPECT_FALSE(range.contains(60.0));
    EXPECT_FALSE(range.contains(std::nextafter(0.0, -1.0)));
}

TEST(Range, OpenLowEndExcludesOnlyTheEnd) {
    const Range range{0.0, 0.5, true, false};  // (0, 0.5]
    EXPECT_FALSE(range.contains(0.0));
    EXPECT_FALSE(range.contains(-0.0));
    EXPECT_TRUE(range.contains(std::numeric_limits<double>::denorm_min()));
    EXPECT_TRUE(range.contains(0.5));
    EXPECT_FALSE(range.contains(std::nextafter(0.5, 1.0)));
}

TEST(Range, BothEndsOpen) {
    const Range range{1.0, 2.0, true, true};  // (1, 2)
    EXPECT_FALSE(range.contains(1.0));
    EXPECT_FALSE(range.contains(2.0));
    EXPECT_TRUE(range.contains(1.5));
}

TEST(Range, NaNIsNeverContained) {
    EXPECT_FALSE((Range{0.0, 1.0}).contains(kNaN));
    EXPECT_FALSE((Range{0.0, 1.0, true, true}).contains(kNaN));
    EXPECT_FALSE((Range{-kInf, kInf}).contains(kNaN));
}

TEST(Range, InfinityIsOutsideAFiniteRange) {
    const Range range{0.0, 1.0};
    EXPECT_FALSE(range.contains(kInf));
    EXPECT_FALSE(range.contains(-kInf));
}

TEST(Range, DescribeUsesBracketsForClosedAndParenthesesForOpenEnds) {
    EXPECT_EQ((Range{0.0, 60.0, false, true}).describe(), "[0, 60)");
    EXPECT_EQ((Range{0.0, 0.5, true, false}).describe(), "(0, 0.5]");
    EXPECT_EQ((Range{-1.0, 1.0}).describe(), "[-1, 1]");
    EXPECT_EQ((Range{0.1, 2.0}).describe(), "[0.1, 2]");
    EXPECT_EQ((Range{-500.0, 5000.0, true, true}).describe(), "(-500, 5000)");
}

TEST(FormatNumber, ShortestRoundTripText) {
    EXPECT_EQ(formatNumber(0.025), "0.025");
    EXPECT_EQ(formatNumber(1e-6), "1e-06");
    EXPECT_EQ(formatNumber(1700.0), "1700");
    EXPECT_EQ(formatNumber(0.1), "0.1");
    EXPECT_EQ(formatNumber(-2.5), "-2.5");
    EXPECT_EQ(formatNumber(0.0), "0");
}

TEST(FormatNumber, NonFiniteValues) {
    EXPECT_EQ(formatNumber(kNaN), "nan");
    EXPECT_EQ(formatNumber(kInf), "inf");
    EXPECT_EQ(formatNumber(-kInf), "-inf");
}

TEST(CheckRange, ValueInsideAddsNothing) {
    std::vector<Issue> issues;
    EXPECT_TRUE(checkRange(issues, "phi_deg", 29.0, Range{0.0, 60.0, false, true}, "deg"));
    EXPECT_TRUE(issues.empty());
}

TEST(CheckRange, ValueOutsideNamesFieldValueRangeAndUnit) {
    std::vector<Issue> issues;
    EXPECT_FALSE(checkRange(issues, "phi_deg", 75.0, Range{0.0, 60.0, false, true}, "deg"));
    ASSERT_EQ(issues.size(), 1u);
    EXPECT_EQ(issues[0].where, "phi_deg");
    EXPECT_EQ(issues[0].message, "75 is outside the allowed range [0, 60) deg");
}

TEST(CheckRange, ExcludedEndIsReported) {
    std::vector<Issue> issues;
    EXPECT_FALSE(checkRange(issues, "phi_deg", 60.0, Range{0.0, 60.0, false, true}, "deg"));
    ASSERT_EQ(issues.size(), 1u);
    EXPECT_EQ(issues[0].message, "60 is outside the allowed range [0, 60) deg");
}

TEST(CheckRange, WithoutUnitThereIsNoTrailingText) {
    std::vector<Issue> issues;
    EXPECT_FALSE(checkRange(issues, "n", 3.0, Range{0.1, 2.0}));
    ASSERT_EQ(issues.size(), 1u);
    EXPECT_EQ(issues[0].message, "3 is outside the allowed range [0.1, 2]");
}

TEST(CheckRange, NaNIsReportedAsNotFinite) {
    std::vector<Issue> issues;
    EXPECT_FALSE(checkRange(issues, "c_kPa", kNaN, Range{0.0, 200.0}, "kPa"));
    ASSERT_EQ(issues.size(), 1u);
    EXPECT_EQ(issues[0].where, "c_kPa");
    EXPECT_EQ(issues[0].message, "nan is not a finite number; allowed range [0, 200] kPa");
}

TEST(CheckRange, InfinitiesAreReportedAsNotFinite) {
    std::vector<Issue> issues;
    EXPECT_FALSE(checkRange(issues, "K_m", kInf, Range{0.0, 0.5, true, false}, "m"));
    EXPECT_FALSE(checkRange(issues, "K_m", -kInf, Range{0.0, 0.5, true, false}, "m"));
    ASSERT_EQ(issues.size(), 2u);
    EXPECT_EQ(issues[0].message, "inf is not a finite number; allowed range (0, 0.5] m");
    EXPECT_EQ(issues[1].message, "-inf is not a finite number; allowed range (0, 0.5] m");
}

TEST(CheckRange, AppendsToExistingIssues) {
    std::vector<Issue> issues{{"earlier", "kept"}};
    checkRange(issues, "a", -2.0, Range{-1.0, 1.0});
    checkRange(issues, "b", 0.0, Range{-1.0, 1.0});  // fine: adds nothing
    checkRange(issues, "c", 1.5, Range{-1.0, 1.0});
    ASSERT_EQ(issues.size(), 3u);
    EXPECT_EQ(issues[0].where, "earlier");
    EXPECT_EQ(issues[1].where, "a");
    EXPECT_EQ(issues[1].message, "-2 is outside the allowed range [-1, 1]");
    EXPECT_EQ(issues[2].where, "c");
    EXPECT_EQ(issues[2].message, "1.5 is outside the allowed range [-1, 1]");
}

TEST(FormatIssues, OneLinePerIssueWithLocation) {
    const std::vector<Issue> issues{{"soil.n", "bad n"}, {"", "no location"}, {"f.csv:3", "x"}};
    EXPECT_EQ(formatIssues(issues), "soil.n: bad n\nno location\nf.csv:3: x");
    EXPECT_EQ(formatIssues({}), "");
}

}  // namespace
}  // namespace terra
