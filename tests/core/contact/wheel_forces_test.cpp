#include "core/contact/wheel_forces.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/contact/reference_forces.h"
#include "tests/core/contact/test_soils.h"

namespace terra::contact {
namespace {

using testing::kDeg;

constexpr double kAgreement = 1e-8;  // relative, fast integrator vs adaptive reference
// relative, the Gauss rule alone (IntegrationOptions::gauss_only) vs adaptive reference
constexpr double kGaussAlone = 1e-4;

struct SoilCase {
    const char* soil;
    ContactParameters<double> params;
};

std::vector<SoilCase> thesisSoils() {
    return {{"sandy loam", testing::sandyLoam()},
            {"dry sand", testing::drySand()},
            {"clayey soil", testing::clayeySoil()},
            {"sandy loam, no j_max", testing::sandyLoam(INFINITY)},
            {"n = 0.3", testing::thesisSoil(0.3, 4.14, 13.0, 13.2, 692.2, 0.01, 13.24, 0.009)},
            {"n = 1.6", testing::thesisSoil(1.6, 1.03, 19.7, 4.37, 196.72, 0.03, 2.5, INFINITY)}};
}

// Largest force/moment error relative to the force and moment scales of the case.
double relativeError(const WheelForces<double>& a, const WheelForces<double>& b) {
    const double force_scale = std::abs(b.fz) + std::abs(b.fx);
    const double moment_scale = std::abs(b.my) + 0.092 * std::abs(b.fz);
    return std::max({std::abs(a.fx - b.fx) / force_scale, std::abs(a.fy - b.fy) / force_scale,
                     std::abs(a.fz - b.fz) / force_scale, std::abs(a.mx - b.mx) / moment_scale,
                     std::abs(a.my - b.my) / moment_scale, std::abs(a.mz - b.mz) / moment_scale});
}

TEST(WheelForces, AgreesWithAdaptiveTanhSinhAndGaussKronrod) {
    for (const SoilCase& c : thesisSoils()) {
        for (double s : {0.0, 0.05, 0.3, 0.9, -0.2, -0.7}) {
            for (double beta : {0.0, 5.0, 30.0}) {
                for (double theta_f : {8.0, 30.0, 60.0}) {
                    for (double theta_r : {0.0, -6.0}) {
                        const OperatingPoint<double> op{s, beta * kDeg, theta_f * kDeg,
                                                        theta_r * kDeg, std::nullopt};
                        const auto fast = computeForces(c.params, op);
                        const auto ts = computeForcesReference(c.params, op);
                        const auto gk = computeForcesReference(
                            c.params, op, BulldozingModel::kBekker, ReferenceMethod::kGaussKronrod);
                        EXPECT_LT(relativeError(fast, ts), kAgreement)
                            << c.soil << " s=" << s << " beta=" << beta << " tf=" << theta_f
                            << " tr=" << theta_r;
                        EXPECT_LT(relativeError(gk, ts), kAgreement) << c.soil << " (GK vs TS)";
                    }
                }
            }
        }
    }
}

TEST(WheelForces, NoLateralForceOrMomentsWithoutSlipAngle) {
    for (const SoilCase& c : thesisSoils()) {
        for (double s : {0.0, 0.4, -0.3}) {
            const OperatingPoint<double> op{s, 0.0, 25.0 * kDeg, 0.0, std::nullopt};
            const auto f = computeForces(c.params, op);
            EXPECT_EQ(f.fy, 0.0) << c.soil;
            EXPECT_EQ(f.mx, 0.0);
            EXPECT_EQ(f.mz, 0.0);
            EXPECT_EQ(f.fs, 0.0);  // bulldozing only with lateral motion
            EXPECT_GT(f.fb, 0.0);
        }
    }
}

TEST(WheelForces, MirroredSlipAngleMirrorsLateralQuantities) {
    const auto p = testing::sandyLoam();
    const OperatingPoint<double> left{0.3, 15.0 * kDeg, 30.0 * kDeg, 0.0, std::nullopt};
    OperatingPoint<double> right = left;
    right.slip_angle_rad = -left.slip_angle_rad;
    const auto a = computeForces(p, left), b = computeForces(p, right);
    EXPECT_DOUBLE_EQ(a.fx, b.fx);
    EXPECT_DOUBLE_EQ(a.fz, b.fz);
    EXPECT_DOUBLE_EQ(a.my, b.my);
    EXPECT_DOUBLE_EQ(a.fy, -b.fy);
    EXPECT_DOUBLE_EQ(a.mx, -b.mx);
    EXPECT_DOUBLE_EQ(a.mz, -b.mz);
    EXPECT_DOUBLE_EQ(a.fs, -b.fs);
    // docs/model.md, Lateral signs: β > 0 → F_y, M_x, M_z < 0, F_s = F_y − F_b.
    EXPECT_LT(a.fy, 0.0);
    EXPECT_LT(a.mx, 0.0);
    EXPECT_LT(a.mz, 0.0);
    EXPECT_DOUBLE_EQ(a.fs, a.fy - a.fb);
}

TEST(WheelForces, FrictionlessContactMatchesClosedForm) {
    // With c = φ = 0 there is no shear, and with θ_m = θ_r = 0 only the front law of Eq. 2.17
    // acts: ∫_0^θf (cos θ − cos θ_f)^n sin θ dθ = (1 − cos θ_f)^(n+1)/(n+1) exactly, so
    // F_x = −r b K_s r^n (1 − cos θ_f)^(n+1)/(n+1). n < 1 has the singular end derivative.
    for (double n : {0.3, 0.5, 0.7, 1.1, 1.7}) {
        ContactParameters<double> p =
            testing::thesisSoil(n, 0.0, 0.0, 5.3, 1515.0, 0.025, 15.2, INFINITY);
        // Down to 1e-4°: the cosine difference must not cancel (regression, item 3 of the review).
        for (double theta_f : {1e-4, 0.01, 3.0, 30.0, 80.0}) {
            const double tf = theta_f * kDeg;
            const OperatingPoint<double> op{0.2, 0.0, tf, 0.0, 0.0};
            const auto f = computeForces(p, op);
            const double scale = 0.092 * 0.107 * p.pressure_modulus * std::pow(0.092, n);
            const double versine = 2.0 * std::pow(std::sin(tf / 2), 2);  // 1 − cos θ_f, exact
            const double fx = -scale * std::pow(versine, n + 1.0) / (n + 1.0);
            EXPECT_NEAR(f.fx, fx, 1e-9 * std::abs(fx)) << "n = " << n << ", theta_f = " << theta_f;
            EXPECT_EQ(f.my, 0.0);
        }
    }
}

TEST(WheelForces, LinearSoilVerticalForceClosedForm) {
    // n = 1, no shear, θ_m = θ_r = 0: F_z = r b K_s r (θ_f/2 − sin 2θ_f / 4).
    ContactParameters<double> p =
        testing::thesisSoil(1.0, 0.0, 0.0, 5.3, 1515.0, 0.025, 15.2, INFINITY);
    const double tf = 40.0 * kDeg;
    const auto f = computeForces(p, OperatingPoint<double>{0.1, 0.0, tf, 0.0, 0.0});
    const double fz = 0.092 * 0.107 * p.pressure_modulus * 0.092 * (tf / 2 - std::sin(2 * tf) / 4);
    EXPECT_NEAR(f.fz, fz, 1e-12 * fz);
}

TEST(WheelForces, ShearLimitActsExactlyBelowTheLargestDeformation) {
    // Driving, θ_r = 0: j(θ) grows monotonically from θ_f to θ_r (Eq. 2.14), so the largest
    // deformation on the contact is j(θ_r), written out here by hand. A limit just above it
    // changes nothing (no kink, no clipped node: identical to no limit); half of it clips the rear
    // part of the contact, lowers F_x and M_y (smaller τ), and must still agree with the
    // independent reference integration.
    const double s = 0.6, beta = 10.0 * kDeg, tf = 35.0 * kDeg, r = 0.092;
    const OperatingPoint<double> op{s, beta, tf, 0.0, std::nullopt};
    const double jt = r * (tf - (1 - s) * std::sin(tf));
    const double jl = r * (1 - s) * std::tan(beta) * tf;
    const double j_rear = std::hypot(jt, jl);
    const auto unlimited = computeForces(testing::sandyLoam(INFINITY), op);
    const auto above = computeForces(testing::sandyLoam(j_rear * (1 + 1e-9)), op);
    EXPECT_EQ(above.fx, unlimited.fx);
    EXPECT_EQ(above.fy, unlimited.fy);
    EXPECT_EQ(above.my, unlimited.my);
    const auto clipped_params = testing::sandyLoam(0.5 * j_rear);
    const auto clipped = computeForces(clipped_params, op);
    EXPECT_LT(clipped.fx, unlimited.fx - 1e-3 * std::abs(unlimited.fz));
    EXPECT_LT(clipped.my, unlimited.my * (1 - 1e-3));
    EXPECT_LT(relativeError(clipped, computeForcesReference(clipped_params, op)), kAgreement);
}

TEST(WheelForces, AShearLimitNeverReachedChangesNothingToTheBit) {
    // shearLimitUnreached (what lets the identification skip j_max's difference where the data
    // do not reach it): for a driven wheel the largest deformation is j(θ_r) plus j₀, written out
    // here by hand (Eq. 2.14, on the shearing radius). Any j_max above it gives the forces without
    // a limit to the bit (no clipped node, no kink, the same pieces); just below it the predicate
    // is false. Braking and the locked wheel are never claimed.
    const double r = testing::kRadiusA;
    int unreached = 0;
    for (const ContactParameters<double>& soil :
         {testing::sandyLoam(), testing::clayeySoil(), testing::heavyClay(), testing::drySand()}) {
        for (double lug : {0.0, 0.004}) {
            for (double offset : {0.0, 0.002}) {
                ContactParameters<double> p = soil;
                p.lug_shear_offset_m = lug;
                p.shear_offset_m = offset;
                const double rs = p.lugged() ? p.shearRadius() : r;
                for (double s : {0.0, 0.05, 0.2, 0.5, 0.9}) {
                    for (double beta : {0.0, 5.0 * kDeg}) {
                        for (double tf : {10.0 * kDeg, 25.0 * kDeg, 40.0 * kDeg}) {
                            const double tr = -3.0 * kDeg;
                            const OperatingPoint<double> op{s, beta, tf, tr, std::nullopt};
                            const double kappa = 1.0 - s;
                            const double jt =
                                rs * ((tf - tr) - kappa * (std::sin(tf) - std::sin(tr)));
                            const double jl = rs * kappa * std::tan(beta) * (tf - tr);
                            const double peak = std::hypot(jt, jl) + offset;
                            EXPECT_FALSE(shearLimitUnreached(p, op, peak * (1 - 1e-6)));
                            const double limit = peak * (1 + 1e-6);
                            ASSERT_TRUE(shearLimitUnreached(p, op, limit)) << s << " " << tf;
                            ++unreached;
                            p.max_shear_deformation_m = INFINITY;
                            const auto none = computeForces(p, op);
                            for (double jmax : {limit, 2.0 * limit, 50.0 * limit}) {
                                p.max_shear_deformation_m = jmax;
                                const auto f = computeForces(p, op);
                                EXPECT_EQ(f.fx, none.fx);
                                EXPECT_EQ(f.fy, none.fy);
                                EXPECT_EQ(f.fz, none.fz);
                                EXPECT_EQ(f.my, none.my);
                                EXPECT_EQ(f.mz, none.mz);
                            }
                        }
                    }
                }
                for (double s : {-0.3, -1.0})
                    EXPECT_FALSE(shearLimitUnreached(p, {s, 0.0, 0.4, 0.0, std::nullopt}, 10.0));
            }
        }
    }
    EXPECT_EQ(unreached, 4 * 2 * 2 * 5 * 2 * 3);
}

TEST(WheelForces, DrawbarPullGrowsWithSlipAndBrakingPullsBack) {
    const auto p = testing::sandyLoam();
    double previous = -1e9;
    for (double s : {0.0, 0.1, 0.2, 0.4, 0.6}) {
        const auto f =
            computeForces(p, OperatingPoint<double>{s, 0.0, 25.0 * kDeg, 0.0, std::nullopt});
        EXPECT_GT(f.fx, previous) << "s = " << s;
        EXPECT_GT(f.my, 0.0);
        previous = f.fx;
    }
    const auto braking =
        computeForces(p, OperatingPoint<double>{-0.5, 0.0, 25.0 * kDeg, 0.0, std::nullopt});
    EXPECT_LT(braking.fx, 0.0);
    EXPECT_LT(braking.my, 0.0);  // the soil drives the wheel forward: a braking torque is needed
}

TEST(WheelForces, TighterToleranceConverges) {
    const OperatingPoint<double> op{0.3, 15.0 * kDeg, 30.0 * kDeg, -3.0 * kDeg, std::nullopt};
    const auto p = testing::clayeySoil();
    const auto reference = computeForcesReference(p, op);
    const auto loose = computeForces(p, op, BulldozingModel::kBekker, {1e-4, 24, 0});
    const auto tight = computeForces(p, op, BulldozingModel::kBekker, {1e-13, 64, 0});
    EXPECT_LT(relativeError(tight, reference), 1e-12);
    EXPECT_LE(relativeError(tight, reference), relativeError(loose, reference));
}

// Errors relative to each group's own size, each with a floor of 1e-6 of the other group: the
// in-plane forces (F_x, F_z, M_y) and the lateral ones (F_y, M_x, M_z), so that a tiny F_y at a
// tiny slip angle must be right too (relativeError measures F_y against |F_z| + |F_x|).
double inPlaneError(const WheelForces<double>& a, const WheelForces<double>& b) {
    const double force_scale = std::abs(b.fz) + std::abs(b.fx) + 1e-6 * std::abs(b.fy);
    const double moment_scale =
        std::abs(b.my) + 0.092 * std::abs(b.fz) + 1e-6 * (std::abs(b.mx) + std::abs(b.mz));
    return std::max({std::abs(a.fx - b.fx) / force_scale, std::abs(a.fz - b.fz) / force_scale,
                     std::abs(a.my - b.my) / moment_scale});
}
double lateralError(const WheelForces<double>& a, const WheelForces<double>& b) {
    const double force_scale = std::abs(b.fy) + 1e-6 * (std::abs(b.fz) + std::abs(b.fx));
    const double moment_scale =
        std::abs(b.mx) + std::abs(b.mz) + 1e-6 * (std::abs(b.my) + 0.092 * std::abs(b.fz));
    return std::max({std::abs(a.fy - b.fy) / force_scale, std::abs(a.mx - b.mx) / moment_scale,
                     std::abs(a.mz - b.mz) / moment_scale});
}

// The cases the first agreement grid avoided (review item 9): strong braking, β near 0 and near
// 90°, tiny and near-right entry angles, θ_m fixed at θ_f (no front region), a full-depth rut,
// N = 0.5 and 0.13, and j_max down to 1e-7 m. Regressions: F_y was 24–73 % off for heavy clay
// with j_max = 1e-7, s = 0, β = 0.01° (the shear direction turns within ~0.02 rad of θ = 0, in
// the middle of a long piece), and braking with β = 0.01° at θ_f = 80° missed 1e-8 (a feature
// 2e-4 rad wide at θ* = acos(1/κ)).
TEST(WheelForces, AgreesWithTheReferenceInHardCases) {
    const std::pair<const char*, ContactParameters<double>> soils[] = {
        {"clayey soil (N = 0.5)", testing::clayeySoil()},
        {"heavy clay, j_max = 1e-7", testing::heavyClay(1e-7)},
        {"sandy loam, j_max = 1e-7", testing::sandyLoam(1e-7)}};
    int cases = 0;
    for (const auto& [name, p] : soils) {
        for (double s : {-0.99, -0.5, 0.0, 1e-3, 0.5}) {
            for (double beta : {0.01, 89.0}) {
                for (double theta_f : {0.05, 30.0, 80.0, 89.9}) {
                    for (double rear : {0.0, -0.3, -1.0}) {
                        for (bool theta_m_at_front : {false, true}) {
                            const double tf = theta_f * kDeg;
                            const OperatingPoint<double> op{
                                s, beta * kDeg, tf, rear * tf,
                                theta_m_at_front ? std::optional<double>(tf) : std::nullopt};
                            IntegrationReport report;
                            const auto fast =
                                computeForces(p, op, BulldozingModel::kBekker, {}, &report);
                            const auto reference = computeForcesReference(p, op);
                            EXPECT_LT(inPlaneError(fast, reference), kAgreement)
                                << name << " s=" << s << " beta=" << beta << " tf=" << theta_f
                                << " tr=" << rear << " tf, theta_m fixed=" << theta_m_at_front;
                            EXPECT_LT(lateralError(fast, reference), kAgreement)
                                << name << " s=" << s << " beta=" << beta << " tf=" << theta_f
                                << " tr=" << rear << " tf, theta_m fixed=" << theta_m_at_front
                                << ": Fy " << fast.fy << " vs " << reference.fy;
                            EXPECT_TRUE(report.converged) << name << " " << report.pieces;
                            ++cases;
                        }
                    }
                }
            }
        }
    }
    EXPECT_EQ(cases, 720);
}

TEST(WheelForces, GaussRuleAloneIsCloseToTheReferenceWhereNoPieceIsBisected) {
    // IntegrationOptions::gauss_only (the identification's screening and descents): the 7-point
    // Gauss rule on the initial pieces, against the adaptive tanh-sinh reference, over the
    // measured tests' range (driving and braking, θ_f 5–35°, θ_r = 0, small slip angles).
    IntegrationOptions gauss;
    gauss.gauss_only = true;
    double worst = 0.0, worst_unbisected = 0.0;
    int unbisected = 0;
    for (const SoilCase& c : thesisSoils()) {
        for (double s : {0.0, 0.05, 0.2, 0.5, 0.9, -0.3}) {
            for (double beta : {0.0, 5.0}) {
                for (double theta_f : {5.0, 15.0, 35.0}) {
                    const OperatingPoint<double> op{s, beta * kDeg, theta_f * kDeg, 0.0,
                                                    std::nullopt};
                    IntegrationReport adaptive, alone;
                    computeForces(c.params, op, BulldozingModel::kBekker, {}, &adaptive);
                    const auto f =
                        computeForces(c.params, op, BulldozingModel::kBekker, gauss, &alone);
                    const double error = relativeError(f, computeForcesReference(c.params, op));
                    worst = std::max(worst, error);
                    EXPECT_LT(error, kGaussAlone)
                        << c.soil << " s=" << s << " beta=" << beta << " tf=" << theta_f;
                    // The pieces before bisection: never more than the adaptive rule's.
                    EXPECT_LE(alone.pieces, adaptive.pieces);
                    if (alone.pieces == adaptive.pieces) {
                        worst_unbisected = std::max(worst_unbisected, error);
                        ++unbisected;
                    }
                    EXPECT_GE(alone.pieces, 1);
                    EXPECT_TRUE(std::isnan(alone.error_estimate));
                }
            }
        }
    }
    // Not the adaptive rule's own answer: the Gauss sums differ from it.
    EXPECT_GT(worst, 1e-12);
    // Where the adaptive rule bisects nothing (173 of the 216 cases; 7.9e-8 measured), the Gauss
    // rule differs by less than the adaptive rule's own tolerance, 1e-7.
    EXPECT_GT(unbisected, 100);
    EXPECT_LT(worst_unbisected, 1e-7);
}

TEST(WheelForces, ReportsWhenThePieceCapIsHit) {
    // Braking with a tiny slip angle on a long contact needs many pieces; with a cap of 4 the
    // tolerance cannot be met, and the report says so (it used to stop silently at 24).
    const auto p = testing::sandyLoam();
    const OperatingPoint<double> op{-0.5, 0.01 * kDeg, 80.0 * kDeg, -5.0 * kDeg, std::nullopt};
    IntegrationReport capped, full;
    computeForces(p, op, BulldozingModel::kBekker, {1e-7, 4, 0}, &capped);
    EXPECT_FALSE(capped.converged);
    EXPECT_GT(capped.error_estimate, 1e-7);
    const auto f = computeForces(p, op, BulldozingModel::kBekker, {}, &full);
    EXPECT_TRUE(full.converged);
    EXPECT_GT(full.pieces, capped.pieces);
    EXPECT_LE(full.pieces, IntegrationOptions{}.max_pieces);
    const auto reference = computeForcesReference(p, op);
    EXPECT_LT(inPlaneError(f, reference), kAgreement);
    EXPECT_LT(lateralError(f, reference), kAgreement);
}

}  // namespace
}  // namespace terra::contact
