// contact::computeLinearForces: F_x, F_z and M_y as linear forms in α = (K_s, c, K_s tan φ),
// checked against the integrator of the stresses themselves (computeForces in double) and
// against the Jet derivatives of computeForces.
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/contact/wheel_forces.h"
#include "tests/core/contact/test_soils.h"

namespace terra::contact {
namespace linear_forces_test {

using testing::kDeg;

struct LinearCase {
    std::string name;
    ContactParameters<double> soil;
};

std::vector<LinearCase> linearCases() {
    ContactParameters<double> lugged = testing::sandyLoam();
    lugged.lug_shear_offset_m = 0.004;  // r_s = r + λ_s h_g
    ContactParameters<double> carried = testing::sandyLoam();
    carried.shear_offset_m = 0.005;  // j₀ from earlier passes
    ContactParameters<double> rut = testing::clayeySoil();
    rut.rut_depth_m = 0.01;  // a rut without reload: σ = K_s (z_p + d)^N, still linear
    ContactParameters<double> slip_exponent = testing::drySand();
    slip_exponent.sinkage_exponent_slip = 0.3;  // N = n₀ + n₁ s
    return {{"sandy loam", testing::sandyLoam()},
            {"sandy loam, j0 = 5 mm", carried},
            {"clayey soil, rut", rut},
            {"dry sand, n1 = 0.3", slip_exponent},
            {"dry sand", testing::drySand()},
            {"clayey soil", testing::clayeySoil()},
            {"sandy loam, no j_max", testing::sandyLoam(INFINITY)},
            {"n = 1.6", testing::thesisSoil(1.6, 1.03, 19.7, 4.37, 196.72, 0.03, 2.5, INFINITY)},
            {"sandy loam, lugs", lugged}};
}

std::vector<OperatingPoint<double>> linearPoints() {
    std::vector<OperatingPoint<double>> out;
    for (double s : {0.0, 0.05, 0.3, 0.9, -0.2, -1.0}) {
        for (double beta : {0.0, 5.0}) {
            for (double theta_f : {8.0, 30.0}) {
                out.push_back({s, beta * kDeg, theta_f * kDeg, -3.0 * kDeg, std::nullopt});
            }
        }
        out.push_back({s, 0.0, 20.0 * kDeg, 0.0, 6.0 * kDeg});  // θ_m given
    }
    return out;
}

std::array<double, 3> linearAlphaOf(const ContactParameters<double>& p) {
    return {p.pressure_modulus, p.cohesion_pa, p.pressure_modulus * std::tan(p.friction_angle_rad)};
}

double combineForm(const std::array<double, 3>& form, const std::array<double, 3>& alpha) {
    return form[0] * alpha[0] + form[1] * alpha[1] + form[2] * alpha[2];
}

TEST(LinearForces, CombinedWithTheSoilsCoefficientsGiveTheIntegratedForces) {
    // Judged at the soil's own α, the adaptive rule makes the same pieces as computeForces: the
    // forms combined must equal its forces to rounding, on the default rule and the Gauss rule.
    for (const LinearCase& c : linearCases()) {
        const std::array<double, 3> alpha = linearAlphaOf(c.soil);
        for (const OperatingPoint<double>& op : linearPoints()) {
            for (bool gauss : {false, true}) {
                IntegrationOptions options;
                options.gauss_only = gauss;
                const WheelForces<double> f =
                    computeForces(c.soil, op, BulldozingModel::kBekker, options);
                const LinearForces l = computeLinearForces(c.soil, op, alpha, options);
                const double scale =
                    std::abs(f.fx) + std::abs(f.fz) + std::abs(f.my) / c.soil.shearRadius();
                const std::string where = c.name + " s=" + std::to_string(op.slip) +
                                          " beta=" + std::to_string(op.slip_angle_rad / kDeg) +
                                          " tf=" + std::to_string(op.entry_angle_rad / kDeg) +
                                          (gauss ? " gauss" : " default");
                EXPECT_NEAR(combineForm(l.fx, alpha), f.fx, 1e-12 * scale) << where;
                EXPECT_NEAR(combineForm(l.fz, alpha), f.fz, 1e-12 * scale) << where;
                EXPECT_NEAR(combineForm(l.my, alpha), f.my, 1e-12 * scale * c.soil.shearRadius())
                    << where;
            }
        }
    }
}

TEST(LinearForces, FormsAreTheDerivativesOfTheForces) {
    // ∂F/∂c = Q, ∂F/∂φ = K_s R / cos²φ, ∂F/∂K_s = P + tan φ R, by forward-mode autodiff of
    // computeForces (the stresses' own arithmetic on Jets).
    using J = ceres::Jet<double, 3>;
    for (const LinearCase& c : linearCases()) {
        const std::array<double, 3> alpha = linearAlphaOf(c.soil);
        ContactParameters<J> p = c.soil.cast<J>();
        p.pressure_modulus = J(c.soil.pressure_modulus, 0);
        p.cohesion_pa = J(c.soil.cohesion_pa, 1);
        p.friction_angle_rad = J(c.soil.friction_angle_rad, 2);
        const double tan_phi = std::tan(c.soil.friction_angle_rad);
        const double sec2 = 1.0 + tan_phi * tan_phi;
        for (const OperatingPoint<double>& op : linearPoints()) {
            const WheelForces<J> f = computeForces(p, op.cast<J>());
            const LinearForces l = computeLinearForces(c.soil, op, alpha);
            const J* channel[3] = {&f.fx, &f.fz, &f.my};
            const std::array<double, 3>* form[3] = {&l.fx, &l.fz, &l.my};
            // One scale for the three channels (F_x alone may be near 0 where K_s P is not).
            const double r_s = c.soil.shearRadius();
            const double scale = std::abs(f.fx.a) + std::abs(f.fz.a) + std::abs(f.my.a) / r_s;
            for (int k = 0; k < 3; ++k) {
                const auto& [pk, q, r] = *form[k];
                const double tolerance = 1e-11 * scale * (k == 2 ? r_s : 1.0);
                EXPECT_NEAR(q * c.soil.cohesion_pa, channel[k]->v[1] * c.soil.cohesion_pa,
                            tolerance)
                    << c.name << " channel " << k << " s=" << op.slip;
                EXPECT_NEAR(r * c.soil.pressure_modulus * sec2, channel[k]->v[2], tolerance)
                    << c.name << " channel " << k << " s=" << op.slip;
                EXPECT_NEAR((pk + tan_phi * r) * c.soil.pressure_modulus,
                            channel[k]->v[0] * c.soil.pressure_modulus, tolerance)
                    << c.name << " channel " << k << " s=" << op.slip;
            }
        }
    }
}

TEST(LinearForces, ANominalCoefficientFarFromTheSoilsKeepsTheIntegrationAccuracy) {
    // The adaptive rule judges its pieces at the nominal α; at another α the forms still hold
    // the forces to the integration's accuracy (1e-8 relative, as computeForces against its
    // reference, wheel_forces_test.cpp).
    const std::array<double, 3> nominal{1e6, 1e3, 1e6 * std::tan(0.5)};
    for (const LinearCase& c : linearCases()) {
        const std::array<double, 3> alpha = linearAlphaOf(c.soil);
        for (const OperatingPoint<double>& op : linearPoints()) {
            const WheelForces<double> f = computeForces(c.soil, op);
            const LinearForces l = computeLinearForces(c.soil, op, nominal);
            const double scale =
                std::abs(f.fx) + std::abs(f.fz) + std::abs(f.my) / c.soil.shearRadius();
            EXPECT_NEAR(combineForm(l.fx, alpha), f.fx, 1e-8 * scale) << c.name << " s=" << op.slip;
            EXPECT_NEAR(combineForm(l.fz, alpha), f.fz, 1e-8 * scale) << c.name << " s=" << op.slip;
            EXPECT_NEAR(combineForm(l.my, alpha), f.my, 1e-8 * scale * c.soil.shearRadius())
                << c.name << " s=" << op.slip;
        }
    }
}

TEST(LinearForces, TheAdaptiveRuleMakesThePiecesOfTheForcesAtTheNominalCoefficients) {
    // With the tolerance at 1e-10 the rule bisects; judged at the soil's own α it must make the
    // pieces computeForces makes there and report the same error estimate (to 1e-15: once the
    // pieces meet the tolerance their Kronrod–Gauss differences are ~1e-13 of F, a few hundred
    // roundings, and the two sums round differently).
    IntegrationOptions options;
    options.tolerance = 1e-10;
    int bisected = 0;
    for (const LinearCase& c : linearCases()) {
        const std::array<double, 3> alpha = linearAlphaOf(c.soil);
        for (const OperatingPoint<double>& op : linearPoints()) {
            IntegrationReport forces, forms;
            computeForces(c.soil, op, BulldozingModel::kBekker, options, &forces);
            computeLinearForces(c.soil, op, alpha, options, &forms);
            EXPECT_EQ(forms.pieces, forces.pieces) << c.name << " s=" << op.slip;
            EXPECT_EQ(forms.converged, forces.converged) << c.name << " s=" << op.slip;
            EXPECT_NEAR(forms.error_estimate, forces.error_estimate, 1e-15)
                << c.name << " s=" << op.slip;
            IntegrationReport plain;
            computeForces(c.soil, op, BulldozingModel::kBekker, IntegrationOptions{}, &plain);
            bisected += forces.pieces > plain.pieces;
        }
    }
    EXPECT_GT(bisected, 50);  // the rule did bisect, and the pieces were compared there
}

TEST(LinearForces, RefuseARememberedTrack) {
    // Behind the rut's bottom the soil reloads with k_u d, not K_s z^N: not linear in K_s.
    ContactParameters<double> p = testing::sandyLoam();
    p.rut_depth_m = 0.01;
    p.reload_depth_m = 0.002;
    p.reload_modulus_pa_m = 4e6;
    const OperatingPoint<double> op{0.3, 0.0, 20.0 * kDeg, 0.0, std::nullopt};
    EXPECT_THROW(computeLinearForces(p, op, linearAlphaOf(p)), std::invalid_argument);
}

}  // namespace linear_forces_test
}  // namespace terra::contact
