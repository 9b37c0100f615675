#include "core/compaction/stress_at_depth.h"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <numbers>

#include "core/contact/gauss_rule.h"

namespace terra::compaction {
namespace {

constexpr double kPi = std::numbers::pi;

// A uniform pressure p0 on a disc of radius a, as point loads on a polar Gauss grid.
std::vector<PointLoad> uniformDisc(double p0, double a, int rings = 30, int sectors = 64) {
    const contact::GaussRule& rule = contact::gaussRule(rings);
    std::vector<PointLoad> loads;
    for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
        const double rho = a * rule.nodes[i];
        const double ring_area = 2.0 * kPi * rho * a * rule.weights[i];
        for (int k = 0; k < sectors; ++k) {
            const double phi = 2.0 * kPi * (k + 0.5) / sectors;
            loads.push_back({{rho * std::cos(phi), rho * std::sin(phi), 0.0},
                             {0.0, 0.0, p0 * ring_area / sectors}});
        }
    }
    return loads;
}

// A uniform pressure q on the rectangle [0, B] × [0, L] (Gauss in both directions).
std::vector<PointLoad> uniformRectangle(double q, double b, double l, int nodes = 30) {
    const contact::GaussRule& rule = contact::gaussRule(nodes);
    std::vector<PointLoad> loads;
    for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
        for (std::size_t j = 0; j < rule.nodes.size(); ++j) {
            loads.push_back({{b * rule.nodes[i], l * rule.nodes[j], 0.0},
                             {0.0, 0.0, q * b * l * rule.weights[i] * rule.weights[j]}});
        }
    }
    return loads;
}

// Newmark's influence factor under the corner of a uniformly loaded rectangle (Boussinesq),
// m = B/z, n = L/z, with atan2 taking the branch beyond π/2.
double newmarkCorner(double m, double n) {
    const double s = m * m + n * n + 1.0;
    const double root = std::sqrt(s);
    return (2.0 * m * n * root / (s + m * m * n * n) * (s + 1.0) / s +
            std::atan2(2.0 * m * n * root, s - m * m * n * n)) /
           (4.0 * kPi);
}

// ∫∫ f(ρ, φ) ρ dρ dφ over the plane (adaptive Gauss–Kronrod in ρ on [0, ∞) mapped, and φ).
template <typename F>
double planeIntegral(F f) {
    using boost::math::quadrature::gauss_kronrod;
    auto over_phi = [&](double rho) {
        return gauss_kronrod<double, 31>::integrate([&](double phi) { return f(rho, phi); }, 0.0,
                                                    2.0 * kPi, 8, 1e-10);
    };
    // ρ = t/(1 − t) maps [0, 1) onto [0, ∞).
    return gauss_kronrod<double, 31>::integrate(
        [&](double t) {
            if (t >= 1.0) return 0.0;
            const double rho = t / (1.0 - t);
            return over_phi(rho) * rho / ((1.0 - t) * (1.0 - t));
        },
        0.0, 1.0, 12, 1e-9);
}

TEST(StressAtDepth, UniformDiscOnItsAxisMatchesTheClosedForm) {
    // σ_z = p0 [1 − (z/√(z² + a²))^ν]: 48.8, 59.0, 67.2, 73.8 kPa for p0 = 100 kPa, a = 0.15 m,
    // z = 0.2 m and ν = 3, 4, 5, 6 (docs/compaction.md, C4).
    const double p0 = 100e3, a = 0.15, z = 0.2;
    const double expected_kpa[] = {48.8, 59.0, 67.2, 73.8};
    for (int nu = 3; nu <= 6; ++nu) {
        const StressPropagation propagation(uniformDisc(p0, a), nu);
        const double sigma_z = propagation.verticalStressAt({0.0, 0.0, z});
        const double closed = p0 * (1.0 - std::pow(z / std::hypot(z, a), nu));
        EXPECT_NEAR(sigma_z, closed, 0.005 * closed) << "nu = " << nu;
        EXPECT_NEAR(sigma_z / 1e3, expected_kpa[nu - 3], 0.05) << "nu = " << nu;
        // The full tensor gives the same σ_z.
        EXPECT_NEAR(propagation.stressAt({0.0, 0.0, z})(2, 2), sigma_z, 1e-9 * sigma_z);
    }
    // A non-integer ν goes through pow: the same closed form.
    const StressPropagation fractional(uniformDisc(p0, a), 4.5);
    const double closed = p0 * (1.0 - std::pow(z / std::hypot(z, a), 4.5));
    EXPECT_NEAR(fractional.verticalStressAt({0.0, 0.0, z}), closed, 0.005 * closed);
}

TEST(StressAtDepth, BoussinesqUnderTheCornerOfARectangleIsNewmarks) {
    const double q = 100e3;
    for (const auto& [m, n] : {std::pair{1.0, 1.0}, {0.5, 0.5}, {2.0, 2.0}, {1.0, 2.0}}) {
        const double z = 0.4;
        const StressPropagation propagation(uniformRectangle(q, m * z, n * z), 3.0);
        const double sigma_z = propagation.verticalStressAt({0.0, 0.0, z});
        EXPECT_NEAR(sigma_z / q, newmarkCorner(m, n), 0.002) << m << " x " << n;
    }
    // Published influence factors (Fadum's table): I(1, 1) = 0.1752, I(2, 2) = 0.2325.
    EXPECT_NEAR(newmarkCorner(1.0, 1.0), 0.1752, 5e-5);
    EXPECT_NEAR(newmarkCorner(2.0, 2.0), 0.2325, 5e-5);
}

TEST(StressAtDepth, AHorizontalPointLoadWithNuThreeIsCerrutisVerticalStress) {
    // Cerruti: σ_z = 3 H x z² / (2π R⁵), whatever Poisson's ratio.
    const double h = 1000.0;
    const StressPropagation propagation({{{0.0, 0.0, 0.0}, {h, 0.0, 0.0}}}, 3.0);
    for (const Eigen::Vector3d& p :
         {Eigen::Vector3d{0.1, 0.05, 0.2}, Eigen::Vector3d{-0.3, 0.1, 0.25},
          Eigen::Vector3d{0.02, -0.2, 0.5}}) {
        const double r = p.norm();
        const double cerruti = 3.0 * h * p.x() * p.z() * p.z() / (2.0 * kPi * std::pow(r, 5));
        EXPECT_NEAR(propagation.verticalStressAt(p), cerruti, 1e-12 * std::abs(cerruti) + 1e-12);
    }
}

TEST(StressAtDepth, EveryPlaneCarriesTheWholeForceForAnyConcentration) {
    // ∫σ_z dA = F_z, ∫τ_xz dA = F_x, ∫τ_yz dA = F_y over every horizontal plane below the load
    // (docs/compaction.md, C1–C2), by adaptive quadrature over the plane.
    const Eigen::Vector3d force{150.0, -40.0, 600.0};
    for (const double nu : {3.0, 4.0, 5.5, 6.0}) {
        const StressPropagation propagation({{{0.0, 0.0, 0.0}, force}}, nu);
        const double z = 0.3;
        auto component = [&](int row) {
            return planeIntegral([&](double rho, double phi) {
                return propagation.stressAt({rho * std::cos(phi), rho * std::sin(phi), z})(row, 2);
            });
        };
        EXPECT_NEAR(component(2), force.z(), 1e-4 * force.norm()) << "nu = " << nu;
        EXPECT_NEAR(component(0), force.x(), 1e-4 * force.norm()) << "nu = " << nu;
        EXPECT_NEAR(component(1), force.y(), 1e-4 * force.norm()) << "nu = " << nu;
    }
}

TEST(StressAtDepth, MeasuresOfAPureVerticalLoadOnItsAxis) {
    // On the axis of a vertical point load the stress is σ_R along z only: σ_z = σ₁ = 3p.
    const StressPropagation propagation({{{0.0, 0.0, 0.0}, {0.0, 0.0, 1000.0}}}, 5.0);
    const StressMeasures m = propagation.measuresAt({0.0, 0.0, 0.5});
    const double expected = 5.0 * 1000.0 / (2.0 * kPi * 0.25);  // ν Q / (2π z²)
    EXPECT_NEAR(m.sigma_z, expected, 1e-9 * expected);
    EXPECT_NEAR(m.major, expected, 1e-9 * expected);
    EXPECT_NEAR(m.mean, expected / 3.0, 1e-9 * expected);
    EXPECT_NEAR(m.sigma_x, 0.0, 1e-9 * expected);
}

TEST(StressAtDepth, TheLargestValueDuringAPassOfASymmetricLoadIsUnderItsCentre) {
    const StressPropagation propagation(uniformDisc(100e3, 0.1, 10, 32), 4.0);
    for (const double z : {0.1, 0.3, 0.6}) {
        const PassMaxima max = passMaxima(propagation, 0.0, z);
        const double centre = propagation.verticalStressAt({0.0, 0.0, z});
        EXPECT_NEAR(max.maxima.sigma_z, centre, 1e-6 * centre) << z;
        EXPECT_NEAR(max.x_sigma_z, 0.0, 1e-3 * z) << z;
    }
}

// The cells across a wheel's width (docs/field.md F13) take σ_z's peak along x near the centre
// line's: the parabola's vertex (or Brent's method, or the full scan where that does not hold)
// equals the full scan + Brent of maxVerticalStress, on a driven wheel's footprint — a strip
// 0.1 m wide and 0.06 m long whose pressure rises towards the front and that carries a shear
// backwards — at depths from 3 cm to 0.6 m and offsets across and beyond the width.
TEST(StressAtDepth, ThePeakNearANeighbouringOnesIsTheFullScans) {
    std::vector<PointLoad> loads;
    for (int i = 0; i < 12; ++i) {
        const double x = -0.03 + 0.06 * (i + 0.5) / 12.0;
        const double pressure = 80e3 * (0.4 + 0.6 * (x + 0.03) / 0.06);
        for (int j = 0; j < 7; ++j) {
            const double y = -0.05 + 0.1 * (j + 0.5) / 7.0;
            const double area = (0.06 / 12.0) * (0.1 / 7.0);
            loads.push_back({{x, y, 0.004 * std::cos(20.0 * x)},
                             {-0.3 * pressure * area, 0.02 * pressure * area, pressure * area}});
        }
    }
    const StressPropagation propagation(loads, 5.0);
    for (const double z : {0.03, 0.1, 0.3, 0.6}) {
        const VerticalStressPeak centre = verticalStressPeak(propagation, 0.0, z);
        for (const double y : {0.01, 0.02, 0.04, 0.05, 0.2, 1.0}) {
            const double full = maxVerticalStress(propagation, y, z);
            EXPECT_NEAR(maxVerticalStressNear(propagation, centre, y, z), full, 1e-5 * full)
                << "z " << z << " y " << y;
        }
    }
}

TEST(StressAtDepth, RefusesABadConcentrationOrAPointAboveTheLoads) {
    EXPECT_THROW(StressPropagation({}, 2.0), std::invalid_argument);
    EXPECT_THROW(StressPropagation({}, std::nan("")), std::invalid_argument);
    EXPECT_THROW(StressPropagation({{{0, 0, -0.1}, {0, 0, 1}}}, 4.0), std::invalid_argument);
    const StressPropagation deep({{{0, 0, 0.05}, {0, 0, 1}}}, 4.0);
    EXPECT_THROW(passMaxima(deep, 0.0, 0.05), std::invalid_argument);
}

}  // namespace
}  // namespace terra::compaction
