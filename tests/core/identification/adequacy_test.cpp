// The trend test of adequacy.h against what is independent of its code: the F statistic by the
// normal equations of the cubic (not the QR), its calibration on normal noise (exact F: the share
// of p below a level is that level), the limit cases, and sweeps counted apart.
#include "core/identification/adequacy.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>
#include <random>

namespace terra::identification {
namespace {

// n residuals at slips 0 … 0.9 of one sweep: trend(s) + noise.
template <typename Trend>
std::vector<OrderedResidual> sweep(int n, Trend trend, std::mt19937_64& engine, double noise,
                                   double load = 0.0) {
    std::normal_distribution<double> normal(0.0, noise);
    std::vector<OrderedResidual> out;
    for (int i = 0; i < n; ++i) {
        const double s = 0.9 * i / (n - 1);
        out.push_back({load, 0.0, s, trend(s) + normal(engine)});
    }
    return out;
}

TEST(TrendTest, TheFStatisticOfTheCubicByTheNormalEquations) {
    std::mt19937_64 engine(3);
    const std::vector<OrderedResidual> r = sweep(
        40, [](double s) { return 1.5 * s - 2.5 * s * s; }, engine, 0.1);
    // Least squares of e on 1, s, s², s³ by the normal equations (raw slips, no scaling).
    Eigen::MatrixXd x(40, 4);
    Eigen::VectorXd e(40);
    for (int i = 0; i < 40; ++i) {
        const double s = r[static_cast<std::size_t>(i)].slip;
        x.row(i) << 1.0, s, s * s, s * s * s;
        e(i) = r[static_cast<std::size_t>(i)].value;
    }
    const Eigen::VectorXd beta = (x.transpose() * x).ldlt().solve(x.transpose() * e);
    const double rest = (e - x * beta).squaredNorm(), trend = e.squaredNorm() - rest;
    const double f = (trend / 4.0) / (rest / 36.0);
    const TrendTest t = trendTest(r);
    EXPECT_EQ(t.values, 40);
    EXPECT_EQ(t.sweeps, 1);
    EXPECT_EQ(t.trend_dof, 4);
    EXPECT_NEAR(t.f, f, 1e-8 * f);
    EXPECT_NEAR(t.p, boost::math::cdf(boost::math::complement(boost::math::fisher_f(4, 36), f)),
                1e-10);
    EXPECT_LT(t.p, 1e-6);  // a trend of 0.2–0.7 under noise 0.1, coherent over 40 samples
}

TEST(TrendTest, CalibratedOnNormalNoise) {
    // 3000 residual vectors of three sweeps of 30 (any noise level): P(p < 0.01) = 0.01 and
    // P(p < 0.1) = 0.1 exactly; binomial sd 0.0018 and 0.0055, bounds at 3.5 sd.
    std::mt19937_64 engine(11);
    int below_1 = 0, below_10 = 0;
    constexpr int kVectors = 3000;
    for (int k = 0; k < kVectors; ++k) {
        std::vector<OrderedResidual> r;
        for (double load : {30.0, 58.86, 90.0}) {
            const auto one = sweep(
                30, [](double) { return 0.0; }, engine, 0.5 + k % 3, load);
            r.insert(r.end(), one.begin(), one.end());
        }
        const TrendTest t = trendTest(r);
        ASSERT_TRUE(t.tested());
        ASSERT_EQ(t.sweeps, 3);
        below_1 += t.p < 0.01;
        below_10 += t.p < 0.1;
    }
    EXPECT_NEAR(below_1 / double(kVectors), 0.01, 0.0065);
    EXPECT_NEAR(below_10 / double(kVectors), 0.1, 0.019);
}

TEST(TrendTest, LimitCases) {
    std::mt19937_64 engine(5);
    // A cubic alone: nothing left over but rounding, p ≈ 0.
    const TrendTest exact = trendTest(sweep(
        20, [](double s) { return s * s * s; }, engine, 0.0));
    EXPECT_LT(exact.p, 1e-100);
    EXPECT_NEAR(exact.trend_share, 1.0, 1e-12);
    // Alternating signs are no trend.
    std::vector<OrderedResidual> alternating;
    for (int i = 0; i < 30; ++i) alternating.push_back({0.0, 0.0, 0.03 * i, i % 2 ? 1.0 : -1.0});
    EXPECT_GT(trendTest(alternating).p, 0.9);
    // Too few residuals: not tested.
    EXPECT_FALSE(trendTest(sweep(
                               9, [](double s) { return s; }, engine, 0.1))
                     .tested());
}

TEST(TrendTest, SweepsAreFittedApartOrPooledWhenTheLoadVariesByRow) {
    std::mt19937_64 engine(9);
    // Opposite trends at two loads: each sweep's own cubic sees them; one cubic over both would
    // see their sum, nothing.
    std::vector<OrderedResidual> r = sweep(
        30, [](double s) { return s; }, engine, 0.05, 30.0);
    const auto other = sweep(
        30, [](double s) { return -s; }, engine, 0.05, 90.0);
    r.insert(r.end(), other.begin(), other.end());
    const TrendTest apart = trendTest(r);
    EXPECT_EQ(apart.sweeps, 2);
    EXPECT_EQ(apart.trend_dof, 8);
    EXPECT_LT(apart.p, 1e-10);
    // A load that differs in every row: one sweep of all.
    for (std::size_t i = 0; i < r.size(); ++i) r[i].load_n = 30.0 + static_cast<double>(i);
    const TrendTest pooled = trendTest(r);
    EXPECT_EQ(pooled.sweeps, 1);
    EXPECT_EQ(pooled.trend_dof, 4);
}

}  // namespace
}  // namespace terra::identification
