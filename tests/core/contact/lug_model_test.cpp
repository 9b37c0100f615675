// The lug model (docs/model.md, "Lugs"): Ding et al.'s shearing radius r_s = r + λ_s h_g. Off
// (λ_s h_g = 0) it is the thesis model bit for bit; on, its shear part is a smooth wheel of
// radius r_s and its normal part the smooth wheel of radius r (a limit case with a frictionless
// soil, where τ does not depend on σ); the locked wheel on such a soil has a closed-form torque;
// the integrator agrees with the reference quadrature's term-by-term assembly; the quadratic model
// carries it; and at a fixed load higher lugs pull more, as the experiments report.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/contact/quadratic_model.h"
#include "core/contact/reference_forces.h"
#include "core/contact/sinkage.h"
#include "core/contact/wheel_forces.h"
#include "tests/core/contact/test_soils.h"

namespace terra::contact {
namespace {

using testing::kDeg;

// Integration tolerance of computeForces (1e-7 relative, IntegrationOptions) with a margin.
constexpr double kIntegration = 1e-6;

std::vector<OperatingPoint<double>> operatingPoints() {
    return {{0.3, 0.0, 30 * kDeg, 0.0, std::nullopt},   {0.0, 0.0, 20 * kDeg, -5 * kDeg, {}},
            {0.5, 8 * kDeg, 35 * kDeg, -3 * kDeg, {}},  {-0.4, 0.0, 25 * kDeg, 0.0, {}},
            {-1.0, 5 * kDeg, 25 * kDeg, -2 * kDeg, {}}, {1.0, 0.0, 40 * kDeg, 0.0, {}},
            {0.2, -10 * kDeg, 15 * kDeg, 0.0, {}}};
}

void expectSameBits(const WheelForces<double>& a, const WheelForces<double>& b) {
    EXPECT_EQ(a.fx, b.fx);
    EXPECT_EQ(a.fy, b.fy);
    EXPECT_EQ(a.fz, b.fz);
    EXPECT_EQ(a.mx, b.mx);
    EXPECT_EQ(a.my, b.my);
    EXPECT_EQ(a.mz, b.mz);
    EXPECT_EQ(a.fb, b.fb);
    EXPECT_EQ(a.fs, b.fs);
}

void expectNear(double a, double b, double relative, const char* what) {
    EXPECT_NEAR(a, b, relative * (std::abs(b) + 1e-9)) << what;
}

// A frictionless cohesive soil (φ = 0): τ = c (1 − exp(−j/K)) does not depend on σ.
ContactParameters<double> cohesiveSoil(double r) {
    ContactParameters<double> p =
        testing::thesisSoil(0.8, 2.0, 0.0, 5.0, 1500.0, 0.01, 15.0, INFINITY, r, testing::kWidthA);
    return p;
}

TEST(LugModel, OffIsTheThesisModelBitForBit) {
    const soil::SoilParameters soil;  // sandy loam, the struct's defaults
    wheel::WheelParameters smooth{"A", "", 0.092, 0.107};
    // Grousers without λ_s, λ_s without grousers, and grousers without a count: all smooth.
    wheel::WheelParameters no_coefficient = smooth, no_height = smooth, no_count = smooth;
    no_coefficient.grouser_height_m = 0.01, no_coefficient.grouser_count = 18;
    no_height.lug_effect_coefficient = 0.5, no_height.grouser_count = 18;
    no_count.grouser_height_m = 0.01, no_count.lug_effect_coefficient = 0.5;
    const ContactParameters<double> thesis = makeContactParameters(soil, smooth);
    for (const wheel::WheelParameters& w : {no_coefficient, no_height, no_count}) {
        const ContactParameters<double> p = makeContactParameters(soil, w);
        EXPECT_EQ(p.lug_shear_offset_m, 0.0);
        EXPECT_FALSE(p.lugged());
        for (const OperatingPoint<double>& op : operatingPoints()) {
            expectSameBits(computeForces(p, op), computeForces(thesis, op));
            expectSameBits(computeQuadraticForces(p, op), computeQuadraticForces(thesis, op));
        }
        EntryAngleProblem problem;
        problem.load_n = 58.86;
        problem.slip = 0.3;
        EXPECT_EQ(solveEntryAngle(p, problem).entry_angle_rad,
                  solveEntryAngle(thesis, problem).entry_angle_rad);
    }
    // And on: r_s = r + λ_s h_g.
    wheel::WheelParameters lugged = no_coefficient;
    lugged.lug_effect_coefficient = 0.5;
    EXPECT_DOUBLE_EQ(makeContactParameters(soil, lugged).shearRadius(), 0.092 + 0.5 * 0.01);
}

// With φ = 0 the shear stress of the lugged wheel at θ is that of a smooth wheel of radius r_s
// (same θ_f, θ_r, θ_m and slip: j = r_s[(θ_f − θ) − κ(sin θ_f − sin θ)] in both), and its shear
// integrals have r_s's area and lever arm: the pure shear results M_y, F_y, M_x, M_z are those of
// the smooth r_s wheel. The normal stress is the rim's: with τ ≡ 0 (c = 0 too) the lugged wheel is
// the smooth r wheel. F_x and F_z are the sum of the two parts.
TEST(LugModel, ShearIsASmoothWheelOfTheShearingRadiusAndNormalStressTheRims) {
    const double r = testing::kRadiusA, offset = 0.5 * 0.012;
    ContactParameters<double> lugged = cohesiveSoil(r);
    lugged.lug_shear_offset_m = offset;
    const ContactParameters<double> smooth_rs = cohesiveSoil(r + offset);
    auto frictionless = [](ContactParameters<double> p) {
        p.cohesion_pa = 0.0;  // with φ = 0: τ ≡ 0, only σ acts
        return p;
    };
    for (const OperatingPoint<double>& op : operatingPoints()) {
        const WheelForces<double> f = computeForces(lugged, op);
        const WheelForces<double> shear = computeForces(smooth_rs, op);
        expectNear(f.my, shear.my, kIntegration, "My");
        expectNear(f.fy, shear.fy, kIntegration, "Fy");
        expectNear(f.mx, shear.mx, kIntegration, "Mx");
        expectNear(f.mz, shear.mz, kIntegration, "Mz");
        // σ parts: the smooth wheels without shear.
        const WheelForces<double> normal_r = computeForces(frictionless(cohesiveSoil(r)), op);
        const WheelForces<double> normal_rs = computeForces(frictionless(smooth_rs), op);
        const double scale = std::abs(shear.fx) + std::abs(normal_r.fz) + std::abs(shear.fz);
        EXPECT_NEAR(f.fx, (shear.fx - normal_rs.fx) + normal_r.fx, kIntegration * scale);
        EXPECT_NEAR(f.fz, (shear.fz - normal_rs.fz) + normal_r.fz, kIntegration * scale);
        // The side walls are the rim's: bulldozing does not see the lugs.
        EXPECT_EQ(f.fb, computeForces(cohesiveSoil(r), op).fb);
    }
}

// The locked wheel (s = −1) on a frictionless soil: the shear is fully developed, τ = c, and
// points against the travel, τ_t = −c (|θ| < 90°), so M_y = r_s² b ∫τ_t dθ = −r_s² b c (θ_f − θ_r)
// and the shear part of F_x is r_s b ∫τ_t cos θ dθ = −r_s b c (sin θ_f − sin θ_r). docs/model.md
// ("Lugs") works the numbers for the Ding wheel: r = 0.15735 m, b = 0.165 m, h_g = 10 mm,
// λ_s = 0.5, c = 250 Pa, θ_f = 20°, θ_r = 0: M_y = −0.37952 N·m, F_x shear part −2.2905 N.
TEST(LugModel, LockedWheelOnAFrictionlessSoilHasTheClosedFormTorque) {
    const double r = 0.15735, b = 0.165, rs = r + 0.5 * 0.010, c = 250.0;
    ContactParameters<double> p =
        testing::thesisSoil(1.1, c / 1e3, 0.0, 15.6, 2407.4, 0.011, 16.0, INFINITY, r, b);
    p.lug_shear_offset_m = rs - r;
    const double theta_f = 20 * kDeg, theta_r = 0.0;
    const OperatingPoint<double> op{-1.0, 0.0, theta_f, theta_r, std::nullopt};
    const WheelForces<double> f = computeForces(p, op);
    EXPECT_NEAR(-rs * rs * b * c * (theta_f - theta_r), -0.37952, 1e-5);  // the docs' numbers
    EXPECT_NEAR(-rs * b * c * (std::sin(theta_f) - std::sin(theta_r)), -2.2905, 1e-4);
    EXPECT_NEAR(f.my, -rs * rs * b * c * (theta_f - theta_r), kIntegration * 0.38);
    ContactParameters<double> no_shear = p;
    no_shear.cohesion_pa = 0.0;
    no_shear.lug_shear_offset_m = 0.0;
    const double normal_fx = computeForces(no_shear, op).fx;  // −r b ∫σ sin θ dθ
    EXPECT_NEAR(f.fx, -rs * b * c * (std::sin(theta_f) - std::sin(theta_r)) + normal_fx,
                kIntegration * (2.3 + std::abs(normal_fx)));
}

// The reference quadrature assembles the lugged forces term by term with r and r_s
// (reference_forces.cpp), sharing neither the integrator nor the ρ weighting of computeForces.
TEST(LugModel, IntegratorAgreesWithTheReferenceQuadrature) {
    for (ContactParameters<double> p : {testing::sandyLoam(), testing::drySand()}) {
        p.lug_shear_offset_m = 0.6 * 0.015;
        for (const OperatingPoint<double>& op : operatingPoints()) {
            const WheelForces<double> f = computeForces(p, op);
            const WheelForces<double> ref = computeForcesReference(p, op);
            const double in_plane =
                std::abs(ref.fx) + std::abs(ref.fz) + std::abs(ref.my) / p.radius_m;
            const double lateral = std::abs(ref.fy) + std::abs(ref.mx) / p.radius_m +
                                   std::abs(ref.mz) / p.radius_m + 1e-9 * in_plane;
            EXPECT_NEAR(f.fx, ref.fx, kIntegration * in_plane);
            EXPECT_NEAR(f.fz, ref.fz, kIntegration * in_plane);
            EXPECT_NEAR(f.my, ref.my, kIntegration * in_plane * p.radius_m);
            EXPECT_NEAR(f.fy, ref.fy, kIntegration * lateral);
            EXPECT_NEAR(f.mx, ref.mx, kIntegration * lateral * p.radius_m);
            EXPECT_NEAR(f.mz, ref.mz, kIntegration * lateral * p.radius_m);
            EXPECT_EQ(f.fb, ref.fb);
            EXPECT_NEAR(f.fs, ref.fs, kIntegration * lateral + std::abs(ref.fb) * 1e-12);
        }
    }
}

// The quadratic model fits the same τ samples (j on r_s) and weights them with ρ = r_s/r: with
// φ = 0 its pure shear results are those of the smooth r_s wheel's quadratic model, to rounding.
TEST(LugModel, QuadraticModelCarriesTheShearingRadius) {
    const double r = testing::kRadiusA, offset = 0.008;
    ContactParameters<double> lugged = cohesiveSoil(r);
    lugged.lug_shear_offset_m = offset;
    const ContactParameters<double> smooth_rs = cohesiveSoil(r + offset);
    constexpr double kRounding = 1e-12;
    for (const OperatingPoint<double>& op : operatingPoints()) {
        const WheelForces<double> f = computeQuadraticForces(lugged, op);
        const WheelForces<double> shear = computeQuadraticForces(smooth_rs, op);
        expectNear(f.my, shear.my, kRounding, "My");
        expectNear(f.fy, shear.fy, kRounding, "Fy");
        expectNear(f.mx, shear.mx, kRounding, "Mx");
        expectNear(f.mz, shear.mz, kRounding, "Mz");
    }
}

// Ding et al. (2011) measured more drawbar pull with higher lugs on HIT-LSS1, and so do other
// single-wheel tests (Takehana et al., ISTVS 2024: higher grousers, more traction). At a fixed
// load W = 80 N on the Ding wheel with λ_s = 0.5, F_x rises with h_g = 0, 5, 10, 15 mm at every
// driving slip: the larger shearing radius develops more shear (j ∝ r_s) on a longer lever, and
// the shear's share of the load lets the rim sink less.
TEST(LugModel, HigherLugsPullMoreAtAFixedLoad) {
    soil::SoilParameters hit;
    hit.sinkage_exponent = 1.1;
    hit.cohesion_pa = 250.0;
    hit.friction_angle_rad = 31.9 * kDeg;
    hit.cohesive_modulus = 15.6e3;
    hit.frictional_modulus = 2407.4e3;
    hit.shear_modulus_m = 0.011;
    hit.unit_weight_n_m3 = 16.0e3;
    hit.max_stress_a0 = 0.4;
    hit.max_stress_a1 = 0.15;
    for (double slip : {0.0, 0.1, 0.2, 0.4, 0.6}) {
        double previous = -INFINITY;
        for (double h : {0.0, 0.005, 0.010, 0.015}) {
            wheel::WheelParameters w{"Ding", "", 0.15735, 0.165, h, h > 0 ? 24.0 : 0.0, 0.0, 0.5};
            const ContactParameters<double> p = makeContactParameters(hit, w);
            EntryAngleProblem problem;
            problem.load_n = 80.0;
            problem.slip = slip;
            const SinkageSolution sol = solveEntryAngle(p, problem);
            ASSERT_TRUE(sol.ok()) << "s = " << slip << ", h = " << h;
            const OperatingPoint<double> op{slip, 0.0, sol.entry_angle_rad, 0.0, std::nullopt};
            const double fx = computeForces(p, op).fx;
            EXPECT_GT(fx, previous + 0.05) << "s = " << slip << ", h = " << h;
            previous = fx;
        }
    }
}

}  // namespace
}  // namespace terra::contact
