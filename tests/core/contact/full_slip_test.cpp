// Full slip (docs/model.md, "Full slip"): s = 1, the wheel spinning in place (κ = 0), and s = −1,
// the locked wheel dragged over the soil (ω = 0, κ → ∞). Each is checked against values computed
// independently here: the stresses by hand, the forces by tanh-sinh quadrature of hand-written
// integrands or in closed form, and against the model at s = ±0.999999 (continuity).
#include <gtest/gtest.h>

#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <limits>

#include "core/contact/kinks.h"
#include "core/contact/quadratic_model.h"
#include "core/contact/reference_forces.h"
#include "core/contact/sinkage.h"
#include "core/contact/stress_field.h"
#include "core/contact/wheel_forces.h"
#include "tests/core/contact/test_soils.h"

namespace terra::contact {
namespace {

using testing::kDeg;
constexpr double kInf = std::numeric_limits<double>::infinity();

// ∫ f over [a, b] by Boost's tanh-sinh quadrature (double exponential, indifferent to the
// endpoint singularities of σ ~ (θ_f − θ)^n): a method the model's integrator does not use.
template <typename F>
double integrate(F f, double a, double b) {
    boost::math::quadrature::tanh_sinh<double> rule;
    return rule.integrate(f, a, b, 1e-13);
}

// σ of Eqs. 2.17 and 2.19, written out for θ_r = 0: the front law, and behind θ_m the same
// with θ_e = θ_f − θ (θ_f − θ_m)/θ_m.
double sigmaByHand(const ContactParameters<double>& p, double tf, double tm, double theta) {
    const double te = theta >= tm ? theta : tf - theta * (tf - tm) / tm;
    const double base = std::cos(te) - std::cos(tf);
    return base > 0.0 ? p.pressure_modulus * std::pow(p.radius_m * base, p.sinkage_exponent) : 0.0;
}

// At s = 1 (κ = 0) Eq. 2.14 gives j_t = r (θ_f − θ), j_l = 0 whatever β, and the shear velocity
// (1 − κ cos θ, κ tan β) is (1, 0): the shear acts straight along the rim.
TEST(FullSlip, SpinningWheelShearIsTheArcAlongTheRim) {
    const auto p = testing::sandyLoam(kInf);
    const double tf = 25.0 * kDeg;
    for (double beta : {0.0, 12.0 * kDeg}) {
        const StressField<double> field(p, {1.0, beta, tf, 0.0, std::nullopt});
        EXPECT_EQ(field.velocityRatio(), 0.0);
        for (double theta : {-0.0, 0.1, 0.3, 0.4}) {
            const StressSample<double> st = field.at(theta);
            EXPECT_DOUBLE_EQ(st.shear_t, p.radius_m * (tf - theta)) << theta;
            EXPECT_EQ(st.shear_l, 0.0);
            EXPECT_DOUBLE_EQ(st.tau_t, st.tau);
            EXPECT_EQ(st.tau_l, 0.0);
        }
    }
}

// F_x, F_z and M_y at s = 1, β = 0 on sandy loam (n = 0.7: σ singular in slope at both ends),
// θ_m from Eq. 2.18, against tanh-sinh quadrature of the hand-written integrands
// τ = (c + σ tan φ)(1 − exp(−min(r (θ_f − θ), j_max)/K)), τ_t = τ.
TEST(FullSlip, SpinningWheelForcesMatchAnIndependentIntegration) {
    for (double jmax : {kInf, 0.02, 0.004}) {
        const auto p = testing::sandyLoam(jmax);
        const double tf = 22.0 * kDeg, tm = (p.max_stress_a0 + p.max_stress_a1) * tf;
        auto tau = [&](double theta) {
            const double j = std::min(p.radius_m * (tf - theta), jmax);
            return (p.cohesion_pa +
                    sigmaByHand(p, tf, tm, theta) * std::tan(p.friction_angle_rad)) *
                   -std::expm1(-j / p.shear_modulus_m);
        };
        auto both = [&](auto f) { return integrate(f, 0.0, tm) + integrate(f, tm, tf); };
        const double rb = p.radius_m * p.width_m;
        const double fx = rb * both([&](double t) {
                              return tau(t) * std::cos(t) - sigmaByHand(p, tf, tm, t) * std::sin(t);
                          });
        const double fz = rb * both([&](double t) {
                              return sigmaByHand(p, tf, tm, t) * std::cos(t) + tau(t) * std::sin(t);
                          });
        const double my = rb * p.radius_m * both(tau);
        const WheelForces<double> f = computeForces(p, {1.0, 0.0, tf, 0.0, std::nullopt});
        const double scale = std::abs(fz) + std::abs(fx);
        EXPECT_NEAR(f.fx, fx, 1e-8 * scale) << "j_max " << jmax;
        EXPECT_NEAR(f.fz, fz, 1e-8 * scale) << "j_max " << jmax;
        EXPECT_NEAR(f.my, my, 1e-8 * (std::abs(my) + p.radius_m * std::abs(fz))) << jmax;
        EXPECT_EQ(f.fy, 0.0);
    }
}

// The locked wheel in closed form. With n = 1, θ_m = θ_r = 0 and β = 0 the shear is fully
// developed, τ = D (c + σ tan φ) with D = 1 (no j_max) or 1 − exp(−j_max/K), against the travel
// (τ_t = −τ), and σ = K_s r (cos θ − cos θ_f) on [0, θ_f]. With
//   I_c = ∫ (cos θ − cos θ_f) cos θ dθ = θ_f/2 − sin 2θ_f/4,
//   I_s = ∫ (cos θ − cos θ_f) sin θ dθ = (1 − cos θ_f)²/2,
//   I_1 = ∫ (cos θ − cos θ_f) dθ = sin θ_f − θ_f cos θ_f:
//   F_x = −r b [D (c sin θ_f + tan φ K_s r I_c) + K_s r I_s],
//   F_z = r b [K_s r I_c − D (c (1 − cos θ_f) + tan φ K_s r I_s)],
//   M_y = −r² b D (c θ_f + tan φ K_s r I_1).
TEST(FullSlip, LockedWheelForcesAreTheFullyDevelopedShearInClosedForm) {
    for (double jmax : {kInf, 0.01}) {
        ContactParameters<double> p = testing::sandyLoam(jmax);
        p.sinkage_exponent = 1.0;
        const double r = p.radius_m, b = p.width_m, ks = p.pressure_modulus, c = p.cohesion_pa;
        const double tan_phi = std::tan(p.friction_angle_rad);
        const double d = std::isinf(jmax) ? 1.0 : 1.0 - std::exp(-jmax / p.shear_modulus_m);
        for (double tf : {5.0 * kDeg, 30.0 * kDeg, 75.0 * kDeg}) {
            const double ic = tf / 2 - std::sin(2 * tf) / 4;
            const double is = std::pow(1 - std::cos(tf), 2) / 2;
            const double i1 = std::sin(tf) - tf * std::cos(tf);
            const double fx =
                -r * b * (d * (c * std::sin(tf) + tan_phi * ks * r * ic) + ks * r * is);
            const double fz =
                r * b * (ks * r * ic - d * (c * (1 - std::cos(tf)) + tan_phi * ks * r * is));
            const double my = -r * r * b * d * (c * tf + tan_phi * ks * r * i1);
            const WheelForces<double> f = computeForces(p, {-1.0, 0.0, tf, 0.0, 0.0});
            const double scale = std::abs(fz) + std::abs(fx);
            EXPECT_NEAR(f.fx, fx, 1e-9 * scale) << tf << " " << jmax;
            EXPECT_NEAR(f.fz, fz, 1e-9 * scale) << tf << " " << jmax;
            EXPECT_NEAR(f.my, my, 1e-9 * (std::abs(my) + r * std::abs(fz))) << tf << " " << jmax;
            EXPECT_EQ(f.fy, 0.0);
        }
    }
}

// With β ≠ 0 the locked wheel's shear direction is the limit of (1 − κ cos θ, κ tan β)/|…|,
// (−cos θ, tan β)/√(cos²θ + tan²β): F_y = −r b ∫ τ tan β/√(cos²θ + tan²β) dθ by quadrature.
TEST(FullSlip, LockedWheelShearsAlongTheSlidingDirection) {
    const ContactParameters<double> p = testing::clayeySoil(kInf);
    // θ_m fixed: Eq. 2.18 gives (a₀ − a₁) θ_f < 0 at s = −1, clamped to θ_r (no rear region).
    const double tf = 40.0 * kDeg, tm = 0.4 * tf;
    for (double beta : {3.0 * kDeg, 30.0 * kDeg, 80.0 * kDeg}) {
        const double t = std::tan(beta);
        auto tau = [&](double theta) {
            return p.cohesion_pa + sigmaByHand(p, tf, tm, theta) * std::tan(p.friction_angle_rad);
        };
        auto norm = [&](double theta) { return std::hypot(std::cos(theta), t); };
        auto both = [&](auto f) { return integrate(f, 0.0, tm) + integrate(f, tm, tf); };
        const double rb = p.radius_m * p.width_m;
        const double fy = -rb * both([&](double th) { return tau(th) * t / norm(th); });
        const double fx = rb * both([&](double th) {
                              return -tau(th) * std::cos(th) / norm(th) * std::cos(th) -
                                     sigmaByHand(p, tf, tm, th) * std::sin(th);
                          });
        const double my =
            rb * p.radius_m * both([&](double th) { return -tau(th) * std::cos(th) / norm(th); });
        const WheelForces<double> f = computeForces(p, {-1.0, beta, tf, 0.0, tm});
        const double scale = std::abs(f.fz) + std::abs(f.fx);
        EXPECT_NEAR(f.fy, fy, 1e-8 * (std::abs(fy) + 1e-3 * scale)) << beta;
        EXPECT_NEAR(f.fx, fx, 1e-8 * scale) << beta;
        EXPECT_NEAR(f.my, my, 1e-8 * (std::abs(my) + p.radius_m * std::abs(f.fz))) << beta;
        // The stress field itself: the direction by hand at one angle.
        const StressSample<double> st = StressField<double>(p, {-1.0, beta, tf, 0.0, tm}).at(0.3);
        EXPECT_NEAR(st.tau_t, -st.tau * std::cos(0.3) / norm(0.3), 1e-12 * st.tau);
        EXPECT_NEAR(st.tau_l, st.tau * t / norm(0.3), 1e-12 * st.tau);
    }
}

// At θ_f itself j = 0 for every κ, so the locked wheel's τ is 0 there; just inside it is fully
// developed. No kinks are searched (there are none), and no NaN reaches the scale splits.
TEST(FullSlip, LockedWheelFrontEndAndKinks) {
    const auto p = testing::sandyLoam();
    const double tf = 20.0 * kDeg;
    const StressField<double> field(p, {-1.0, 10.0 * kDeg, tf, 0.0, std::nullopt});
    EXPECT_TRUE(field.locked());
    EXPECT_EQ(field.at(tf).tau, 0.0);
    EXPECT_EQ(field.at(tf).shear, 0.0);
    const StressSample<double> inside = field.at(std::nextafter(tf, 0.0));
    EXPECT_EQ(inside.shear, 0.02);  // j → ∞, limited to j_max
    // σ is all but 0 there: τ is the cohesion's fully developed share, (1 − exp(−j_max/K)) c.
    EXPECT_NEAR(inside.tau, p.cohesion_pa * -std::expm1(-0.02 / p.shear_modulus_m),
                1e-9 * p.cohesion_pa);
    const ShearGeometry g = detail::shearGeometry(p, field);
    EXPECT_EQ(findKinks(g).count, 0);
    const Kinks splits = findScaleSplits(g);
    for (int i = 0; i < splits.count; ++i) EXPECT_TRUE(std::isfinite(splits.angles[i]));
}

WheelForces<double> forces(const ContactParameters<double>& p, const OperatingPoint<double>& op,
                           ContactModel model) {
    return model == ContactModel::kFull ? computeForces(p, op) : computeQuadraticForces(p, op);
}

// The model is continuous into s = ±1. 1e-6 away from it the forces differ by O(1e-6) relative
// (the shear-velocity direction moves by O(1 − |s|), and the locked wheel's layer behind θ_f where
// the shear is not yet developed is O(K (1 + s)/r) wide), except for braking at θ_f = 90°: there
// dj/dθ vanishes at θ_f to first order in κ, j grows like κ r (θ_f − θ)²/2, and the layer is
// O(√(2K (1 + s)/r)) wide, so the difference falls like √(1 + s) (2.4e-5 relative on heavy clay at
// 1e-6, 1.9e-6 at 1e-8; both equal the reference integration to 1e-9). Checked at 1 − |s| = 1e-6
// and 1e-8.
TEST(FullSlip, ContinuousFromInsideTheSlipRange) {
    for (const auto& p : {testing::sandyLoam(), testing::clayeySoil(kInf), testing::heavyClay()}) {
        for (ContactModel model : {ContactModel::kFull, ContactModel::kQuadratic}) {
            for (double beta : {0.0, 0.01 * kDeg, 15.0 * kDeg, 60.0 * kDeg}) {
                for (double tf : {3.0 * kDeg, 30.0 * kDeg, 90.0 * kDeg}) {
                    for (double s : {1.0, -1.0}) {
                        const auto a = forces(p, {s, beta, tf, -0.2 * tf, std::nullopt}, model);
                        const double scale = std::abs(a.fz) + std::abs(a.fx) + std::abs(a.fy) +
                                             std::abs(a.my) / p.radius_m;
                        for (const auto& [gap, tolerance] : {std::pair{1e-6, 5e-5}, {1e-8, 5e-6}}) {
                            const double near = s * (1.0 - gap);
                            const auto b =
                                forces(p, {near, beta, tf, -0.2 * tf, std::nullopt}, model);
                            for (auto [x, y] : {std::pair{a.fx, b.fx},
                                                {a.fy, b.fy},
                                                {a.fz, b.fz},
                                                {a.my / p.radius_m, b.my / p.radius_m}}) {
                                ASSERT_TRUE(std::isfinite(x));
                                EXPECT_NEAR(x, y, tolerance * scale)
                                    << "s " << near << " beta " << beta / kDeg << " tf "
                                    << tf / kDeg
                                    << (model == ContactModel::kFull ? " full" : " quadratic");
                            }
                        }
                        // Away from θ_f = 90° the approach is linear: already 2e-5 at 1e-6.
                        if (tf < 80.0 * kDeg) {
                            const auto b =
                                forces(p, {s * 0.999999, beta, tf, -0.2 * tf, std::nullopt}, model);
                            EXPECT_NEAR(a.fz, b.fz, 2e-5 * scale);
                            EXPECT_NEAR(a.fx, b.fx, 2e-5 * scale);
                        }
                    }
                }
            }
        }
    }
}

// The integrator at s = ±1 against the reference integration (tanh-sinh at 1e-12, no end mapping
// and no scale splits) over the hard cases of docs/model.md's grid 2.
TEST(FullSlip, IntegratorMatchesTheReferenceIntegration) {
    for (const auto& p : {testing::clayeySoil(), testing::heavyClay(), testing::sandyLoam(1e-7)}) {
        for (double s : {1.0, -1.0}) {
            for (double beta : {0.0, 0.01 * kDeg, 89.0 * kDeg}) {
                for (double tf : {0.05 * kDeg, 30.0 * kDeg, 89.9 * kDeg}) {
                    const OperatingPoint<double> op{s, beta, tf, -0.3 * tf, std::nullopt};
                    IntegrationReport report;
                    const auto f = computeForces(p, op, BulldozingModel::kBekker, {}, &report);
                    const auto ref = computeForcesReference(p, op);
                    const double in_plane = std::abs(ref.fz) + std::abs(ref.fx);
                    const double lateral = std::abs(ref.fy) + std::abs(ref.mz) / p.radius_m;
                    EXPECT_TRUE(report.converged);
                    EXPECT_NEAR(f.fx, ref.fx, 1e-8 * in_plane) << s << " " << beta << " " << tf;
                    EXPECT_NEAR(f.fz, ref.fz, 1e-8 * in_plane) << s << " " << beta << " " << tf;
                    EXPECT_NEAR(f.fy, ref.fy, 1e-8 * std::max(lateral, 1e-6 * in_plane))
                        << s << " " << beta << " " << tf;
                }
            }
        }
    }
}

// The entry-angle solver carries the load at s = ±1 like anywhere else.
TEST(FullSlip, EntryAngleSolverCarriesTheLoad) {
    const auto p = testing::sandyLoam();
    for (double s : {1.0, -1.0}) {
        for (ContactModel model : {ContactModel::kFull, ContactModel::kQuadratic}) {
            EntryAngleProblem problem;
            problem.slip = s;
            problem.slip_angle_rad = 10.0 * kDeg;
            problem.model = model;
            const SinkageSolution solution = solveEntryAngle(p, problem);
            ASSERT_TRUE(solution.ok()) << solution.message;
            EXPECT_NEAR(verticalForce(p, problem, solution.entry_angle_rad), 58.86, 1e-9 * 58.86);
        }
    }
}

TEST(FullSlip, TheDomainIsClosedAtPlusMinusOne) {
    EXPECT_NO_THROW(requireValid(OperatingPoint<double>{1.0, 0.0, 0.3, 0.0, std::nullopt}));
    EXPECT_NO_THROW(requireValid(OperatingPoint<double>{-1.0, 0.0, 0.3, 0.0, std::nullopt}));
    for (double s : {std::nextafter(1.0, 2.0), std::nextafter(-1.0, -2.0)}) {
        try {
            requireValid(OperatingPoint<double>{s, 0.0, 0.3, 0.0, std::nullopt});
            ADD_FAILURE() << s;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("outside the allowed range [-1, 1]"),
                      std::string::npos)
                << e.what();
        }
    }
}

}  // namespace
}  // namespace terra::contact
