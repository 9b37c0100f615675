// Lyasko's slip sinkage h = h₀ (1 + S s) (docs/model.md, "Slip sinkage", Eq. S.1) in the forward
// model: S = 0 is the thesis model bit for bit, the load-bearing contact (θ_f, every force) does
// not depend on S, the sinkage at one point equals the factor typed by hand times an entry angle
// found by an independent bisection, and the sinkage grows with driving slip.
#include <gtest/gtest.h>

#include <cmath>

#include "core/analysis/operating_point.h"
#include "core/contact/sinkage.h"
#include "core/contact/wheel_forces.h"
#include "core/io/parameters_json.h"
#include "tests/core/contact/test_soils.h"

namespace terra::contact {
namespace {

namespace soils = testing;

// θ_f with F_z(θ_f) = W by plain bisection on the full model (not the solver under test).
double bisectEntryAngle(const ContactParameters<double>& p, double slip, double load_n) {
    double lo = 1e-4, hi = 1.5;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        const OperatingPoint<double> op{slip, 0.0, mid, 0.0, std::nullopt};
        (computeForces(p, op).fz < load_n ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

EntryAngleProblem problemAt(double slip, double load_n) {
    EntryAngleProblem problem;
    problem.load_n = load_n;
    problem.slip = slip;
    return problem;
}

TEST(LyaskoSlipSinkage, ZeroCoefficientIsTheThesisModelExactly) {
    const ContactParameters<double> p = soils::sandyLoam();
    ASSERT_EQ(p.slip_sinkage_coefficient, 0.0);  // the default: off
    for (double s : {0.0, 0.2, 0.6, -0.3}) {
        const SinkageSolution a = solveEntryAngle(p, problemAt(s, 58.86));
        ASSERT_TRUE(a.ok()) << a.message;
        EXPECT_EQ(a.sinkage_m, p.radius_m * (1.0 - std::cos(a.entry_angle_rad))) << "s = " << s;
        EXPECT_EQ(slipSinkage(p.radius_m, a.entry_angle_rad, s, 0.0),
                  p.radius_m * (1.0 - std::cos(a.entry_angle_rad)));
    }
    EXPECT_EQ(slipSinkageFactor(0.7, 0.0), 1.0);
}

TEST(LyaskoSlipSinkage, TheLoadBearingContactDoesNotDependOnS) {
    ContactParameters<double> with = soils::sandyLoam();
    with.slip_sinkage_coefficient = 4.0;
    const ContactParameters<double> without = soils::sandyLoam();
    for (double s : {0.1, 0.5}) {
        const SinkageSolution a = solveEntryAngle(with, problemAt(s, 58.86));
        const SinkageSolution b = solveEntryAngle(without, problemAt(s, 58.86));
        ASSERT_TRUE(a.ok() && b.ok());
        EXPECT_EQ(a.entry_angle_rad, b.entry_angle_rad);
        EXPECT_EQ(a.vertical_force_n, b.vertical_force_n);
        const OperatingPoint<double> op{s, 0.0, a.entry_angle_rad, 0.0, std::nullopt};
        const WheelForces<double> fa = computeForces(with, op), fb = computeForces(without, op);
        EXPECT_EQ(fa.fx, fb.fx);
        EXPECT_EQ(fa.fz, fb.fz);
        EXPECT_EQ(fa.my, fb.my);
    }
}

// Dry sand on wheel A at W = 58.86 N and s = 0.4 with S = 2.5: Eq. S.1's factor is
// 1 + 2.5 · 0.4 = 2 (typed here), times r (1 − cos θ_f) at the bisected θ_f.
TEST(LyaskoSlipSinkage, SinkageAtOnePointIsTheFactorTimesTheIndependentRut) {
    ContactParameters<double> p = soils::drySand();
    p.slip_sinkage_coefficient = 2.5;
    const double theta = bisectEntryAngle(p, 0.4, 58.86);
    const double expected = 2.0 * soils::kRadiusA * (1.0 - std::cos(theta));
    const SinkageSolution solved = solveEntryAngle(p, problemAt(0.4, 58.86));
    ASSERT_TRUE(solved.ok()) << solved.message;
    constexpr double kSinkageTolM = 1e-9;  // θ_f to ~1e-8 rad through both solvers
    EXPECT_NEAR(solved.sinkage_m, expected, kSinkageTolM);
    // Lyasko's fixed coefficient (1 + i)/(1 − 0.5 i) is 1.4/0.8 = 1.75 at i = 0.4: the linear
    // form takes it with S = 0.75/0.4 = 1.875.
    EXPECT_DOUBLE_EQ(slipSinkageFactor(0.4, 1.875), 1.75);
    // Towed and braking wheels dig no slip rut.
    EXPECT_EQ(slipSinkageFactor(0.0, 2.5), 1.0);
    EXPECT_EQ(slipSinkageFactor(-0.5, 2.5), 1.0);
}

TEST(LyaskoSlipSinkage, SinkageGrowsWithSlip) {
    ContactParameters<double> p = soils::sandyLoam();
    p.slip_sinkage_coefficient = 2.0;
    double previous = 0.0;
    for (int k = 0; k <= 18; ++k) {
        const double s = 0.05 * k;
        const SinkageSolution a = solveEntryAngle(p, problemAt(s, 58.86));
        ASSERT_TRUE(a.ok()) << "s = " << s << ": " << a.message;
        if (k > 0) {
            EXPECT_GT(a.sinkage_m, previous) << "s = " << s;
        }
        previous = a.sinkage_m;
    }
    // And through the service of `terrastudio wheel --load`, from the soil's field.
    soil::SoilParameters soil =
        io::resolveSoil(io::PresetLocations{{TERRA_RESOURCE_DIR}}, "sandy-loam").value();
    const wheel::WheelParameters wheel =
        io::resolveWheel(io::PresetLocations{{TERRA_RESOURCE_DIR}}, "A").value();
    analysis::PointSpec spec;
    spec.load_n = 58.86;
    spec.slip = 0.5;
    const analysis::PointResult off =
        analysis::evaluatePoint(makeContactParameters(soil, wheel), spec);
    soil.slip_sinkage_coefficient = 2.0;
    const analysis::PointResult on =
        analysis::evaluatePoint(makeContactParameters(soil, wheel), spec);
    EXPECT_NEAR(on.sinkage_m, 2.0 * off.sinkage_m, 1e-15);
    EXPECT_EQ(on.forces.fx, off.forces.fx);
    EXPECT_EQ(on.entry_angle_deg, off.entry_angle_deg);
}

}  // namespace
}  // namespace terra::contact
