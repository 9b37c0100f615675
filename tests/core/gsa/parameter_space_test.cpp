#include "core/gsa/parameter_space.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/gsa/sobol_sequence.h"
#include "tests/core/test_support.h"

namespace terra::gsa {
namespace {

// Φ from the error function (std::erfc), independent of Boost.Math's quantile used by the code.
double phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

using terra::testing::messageOf;

TEST(ParameterSpace, UniformIsAffine) {
    ParameterSpace space;
    space.add("phi_deg", Uniform{20.0, 35.0});
    double x = 0.0;
    const double u = 0.25;
    space.transform({&u, 1}, {&x, 1});
    EXPECT_DOUBLE_EQ(x, 23.75);
    EXPECT_TRUE(space.allUniform());
}

TEST(ParameterSpace, NormalInvertsTheCdf) {
    ParameterSpace space;
    space.add("c_kPa", Normal{2.0, 0.5});
    EXPECT_FALSE(space.allUniform());
    for (double z : {-3.0, -1.0, 0.0, 0.7, 2.5}) {
        const double u = phi(z);
        double x = 0.0;
        space.transform({&u, 1}, {&x, 1});
        EXPECT_NEAR(x, 2.0 + 0.5 * z, 1e-12) << "z = " << z;
    }
}

TEST(ParameterSpace, TruncatedNormalStaysInsideItsBounds) {
    // N(1, 1) truncated to [0, 4]: u = 0 → 0, u = 1 → 4, and the median solves
    // Φ(m − 1) = (Φ(−1) + Φ(3)) / 2.
    ParameterSpace space;
    space.add("K_m", Normal{1.0, 1.0, 0.0, 4.0});
    auto at = [&](double u) {
        double x = 0.0;
        space.transform({&u, 1}, {&x, 1});
        return x;
    };
    EXPECT_NEAR(at(1e-15), 0.0, 1e-12);
    EXPECT_NEAR(at(1.0 - 1e-15), 4.0, 1e-9);
    const double median = at(0.5);
    EXPECT_NEAR(phi(median - 1.0), 0.5 * (phi(-1.0) + phi(3.0)), 1e-12);
    // An upper-tail truncation far from the mean keeps its digits: N(0, 1) on [6, 7].
    ParameterSpace tail;
    tail.add("x", Normal{0.0, 1.0, 6.0, 7.0});
    double x = 0.0;
    const double u = 0.5;
    tail.transform({&u, 1}, {&x, 1});
    EXPECT_GT(x, 6.0);
    EXPECT_LT(x, 6.2);  // the mass is concentrated just above 6 (density ratio e^-6.5 per unit)
}

TEST(ParameterSpace, MultivariateNormalHasItsCovariance) {
    Eigen::Vector3d mean(29.0, 1.7, 0.025);
    Eigen::Matrix3d cov;
    cov << 4.0, -0.6, 0.001, -0.6, 0.25, -0.0002, 0.001, -0.0002, 1e-5;
    ParameterSpace space;
    space.add("n", Uniform{0.5, 1.1});
    space.addMultivariateNormal({"phi_deg", "c_kPa", "K_m"}, mean, cov);
    ASSERT_EQ(space.dimension(), 4u);
    EXPECT_EQ(space.names()[1], "phi_deg");
    EXPECT_EQ(space.marginal(1), nullptr);
    const std::size_t count = 1 << 14;
    SobolSequence sequence(4, 5);
    std::vector<double> u(count * 4);
    sequence.generate(0, count, u);
    Eigen::MatrixXd x(count, 3);
    std::vector<double> row(4);
    for (std::size_t k = 0; k < count; ++k) {
        space.transform({&u[4 * k], 4}, row);
        for (int j = 0; j < 3; ++j) x(k, j) = row[1 + j];
        EXPECT_GE(row[0], 0.5);
        EXPECT_LE(row[0], 1.1);
    }
    const Eigen::RowVectorXd m = x.colwise().mean();
    const Eigen::MatrixXd centred = x.rowwise() - m;
    const Eigen::MatrixXd sample_cov = centred.transpose() * centred / (count - 1.0);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(m[i], mean[i], 1e-3 * std::sqrt(cov(i, i)));
        for (int j = 0; j < 3; ++j) {
            // Correlations to 0.01 (quasi-random points: far better than 1/√M = 0.008 on average).
            EXPECT_NEAR(sample_cov(i, j) / std::sqrt(cov(i, i) * cov(j, j)),
                        cov(i, j) / std::sqrt(cov(i, i) * cov(j, j)), 0.01);
        }
    }
}

TEST(ParameterSpace, BadSettingsNameTheParameterAndTheValues) {
    ParameterSpace space;
    EXPECT_NE(messageOf([&] {
                  space.add("phi_deg", Uniform{35.0, 20.0});
              }).find("parameters.phi_deg: uniform range low = 35 must be below high = 20"),
              std::string::npos);
    EXPECT_NE(messageOf([&] {
                  space.add("c_kPa", Normal{1.0, -2.0});
              }).find("sd = -2"),
              std::string::npos);
    EXPECT_NE(messageOf([&] {
                  space.add("c_kPa", Normal{0.0, 1.0, 40.0, 41.0});
              }).find("keeps almost none"),
              std::string::npos);
    space.add("n", Uniform{0.5, 1.1});
    EXPECT_NE(messageOf([&] {
                  space.add("n", Uniform{0.6, 1.0});
              }).find("parameters.n: given twice"),
              std::string::npos);
    Eigen::Matrix2d singular;
    singular << 1.0, 1.0, 1.0, 1.0;
    EXPECT_NE(messageOf([&] {
                  space.addMultivariateNormal({"a", "b"}, Eigen::Vector2d(0, 0), singular);
              }).find("not positive definite"),
              std::string::npos);
    Eigen::Matrix2d asymmetric;
    asymmetric << 1.0, 0.5, 0.2, 1.0;
    EXPECT_NE(messageOf([&] {
                  space.addMultivariateNormal({"a", "b"}, Eigen::Vector2d(0, 0), asymmetric);
              }).find("not symmetric: (b, a) = 0.2 but (a, b) = 0.5"),
              std::string::npos);
    EXPECT_NE(messageOf([&] {
                  space.addMultivariateNormal({"a", "b"}, Eigen::Vector3d(0, 0, 0),
                                              Eigen::Matrix2d::Identity());
              }).find("needs a mean of 2 values"),
              std::string::npos);
    EXPECT_EQ(space.dimension(), 1u);  // failed additions left nothing behind
}

}  // namespace
}  // namespace terra::gsa
