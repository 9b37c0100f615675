#include "core/gsa/morris.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace terra::gsa {
namespace {

ParameterSpace unitBox(int d, double high = 1.0) {
    ParameterSpace space;
    for (int i = 0; i < d; ++i) space.add("x" + std::to_string(i + 1), Uniform{0.0, high});
    return space;
}

Eigen::MatrixXd evaluate(const MorrisDesign& design, double (*f)(const Eigen::RowVectorXd&)) {
    const Eigen::MatrixXd x = design.rows(0, design.rows());
    Eigen::MatrixXd y(x.rows(), 1);
    for (Eigen::Index r = 0; r < x.rows(); ++r) y(r, 0) = f(x.row(r));
    return y;
}

TEST(Morris, TrajectoriesMoveOneParameterAtATimeOnTheGrid) {
    const MorrisDesign design(unitBox(5), 20, 4, 7);
    const Eigen::MatrixXd x = design.rows(0, design.rows());
    const double delta = 2.0 / 3.0;  // p / (2 (p − 1)) for p = 4
    EXPECT_DOUBLE_EQ(design.delta(), delta);
    for (std::size_t t = 0; t < 20; ++t) {
        std::vector<int> moved(5, 0);
        for (std::size_t k = 1; k <= 5; ++k) {
            const Eigen::RowVectorXd step = x.row(t * 6 + k) - x.row(t * 6 + k - 1);
            int changed = 0;
            for (int i = 0; i < 5; ++i) {
                if (step[i] != 0.0) {
                    ++changed, ++moved[i];
                    EXPECT_NEAR(std::abs(step[i]), delta, 1e-15);
                }
            }
            EXPECT_EQ(changed, 1);
        }
        for (int i = 0; i < 5; ++i) EXPECT_EQ(moved[i], 1);
        for (std::size_t k = 0; k <= 5; ++k) {
            for (int i = 0; i < 5; ++i) {
                const double level = x(t * 6 + k, i) * 3.0;  // grid {0, 1/3, 2/3, 1}
                EXPECT_NEAR(level, std::round(level), 1e-12);
                EXPECT_GE(x(t * 6 + k, i), 0.0);
                EXPECT_LE(x(t * 6 + k, i), 1.0);
            }
        }
    }
}

TEST(Morris, RowsAreBitIdenticalInChunks) {
    const MorrisDesign design(unitBox(3, 2.0), 10, 6, 3);
    const Eigen::MatrixXd whole = design.rows(0, design.rows());
    Eigen::MatrixXd pieces(whole.rows(), whole.cols());
    const std::size_t bounds[] = {0, 3, 5, 21, 40};
    for (std::size_t c = 0; c + 1 < std::size(bounds); ++c) {
        pieces.middleRows(bounds[c], bounds[c + 1] - bounds[c]) =
            design.rows(bounds[c], bounds[c + 1]);
    }
    EXPECT_EQ(std::memcmp(whole.data(), pieces.data(), whole.size() * sizeof(double)), 0);
}

TEST(Morris, LinearFunctionGivesItsGradientTimesTheRange) {
    // f = 10 x1 − 4 x2 + x3 on [0, 2]³: every elementary effect is the gradient × range
    // (20, −8, 2), so μ = that, μ* = |that| and σ = 0.
    const MorrisDesign design(unitBox(3, 2.0), 30, 4, 1);
    const MorrisIndices m = estimateMorris(
        design,
        evaluate(design, [](const Eigen::RowVectorXd& x) { return 10 * x[0] - 4 * x[1] + x[2]; }),
        {}, {});
    const double expected[] = {20.0, -8.0, 2.0};
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(m.mu(i, 0), expected[i], 1e-12);
        EXPECT_NEAR(m.mu_star(i, 0), std::abs(expected[i]), 1e-12);
        EXPECT_NEAR(m.sigma(i, 0), 0.0, 1e-12);
    }
    EXPECT_EQ(m.trajectories_used[0], 30u);
}

TEST(Morris, RanksByTheKnownGradient) {
    // f = 8 x1 + 5 x2² + 2 sin(x3) + 0·x4 on [0, 1]⁴ with p = 4 (Δ = 2/3, start levels 0 or 1/3):
    // EE1 = 8; EE2 = 5 (2 x + Δ) ∈ {10/3, 20/3}; |EE3| = 2 |sin(x + Δ) − sin x| / Δ ∈
    // [2 (sin 1 − sin(1/3))/Δ, 2 sin(2/3)/Δ] = [1.55, 1.85]; EE4 = 0. So μ*1 > μ*2 > μ*3 > μ*4.
    const MorrisDesign design(unitBox(4), 50, 4, 5);
    const MorrisIndices m = estimateMorris(design,
                                           evaluate(design,
                                                    [](const Eigen::RowVectorXd& x) {
                                                        return 8 * x[0] + 5 * x[1] * x[1] +
                                                               2 * std::sin(x[2]) + 0 * x[3];
                                                    }),
                                           {}, {});
    EXPECT_NEAR(m.mu_star(0, 0), 8.0, 1e-12);
    EXPECT_GE(m.mu_star(1, 0), 10.0 / 3.0 - 1e-12);
    EXPECT_LE(m.mu_star(1, 0), 20.0 / 3.0 + 1e-12);
    EXPECT_GE(m.mu_star(2, 0), 2 * (std::sin(1.0) - std::sin(1.0 / 3.0)) / (2.0 / 3.0) - 1e-12);
    EXPECT_LE(m.mu_star(2, 0), 2 * std::sin(2.0 / 3.0) / (2.0 / 3.0) + 1e-12);
    EXPECT_EQ(m.mu_star(3, 0), 0.0);
    EXPECT_GT(m.sigma(1, 0), 0.0);  // x2 is non-linear: its effects vary
    EXPECT_GT(m.mu_star_conf(1, 0), 0.0);
}

TEST(Morris, NeedsUniformRangesAndAnEvenGrid) {
    ParameterSpace space = unitBox(2);
    space.add("c_kPa", Normal{1.0, 0.5});
    try {
        MorrisDesign(space, 10, 4, 1);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("parameters.c_kPa: Morris screening needs a uniform"),
                  std::string::npos);
    }
    EXPECT_THROW(MorrisDesign(unitBox(2), 10, 5, 1), std::invalid_argument);
    EXPECT_THROW(MorrisDesign(unitBox(2), 1, 4, 1), std::invalid_argument);
}

}  // namespace
}  // namespace terra::gsa
