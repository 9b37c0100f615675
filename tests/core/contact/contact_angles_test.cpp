#include "core/contact/contact_angles.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <optional>

#include "core/contact/sinkage.h"
#include "core/contact/stress_field.h"
#include "tests/core/contact/test_soils.h"

namespace terra::contact {
namespace {

using testing::kDeg;

// The rules of docs/model.md: θ_r clamp (θ_r ≥ −θ_f) and θ_m clamp (θ_m ∈ [θ_r, θ_f], θ_r clamped
// first), with θ_m = (a₀ + a₁ s) θ_f (Eq. 2.18) unless fixed. Expected values are worked out by
// hand from the rules.

OperatingPoint<double> point(double s, double theta_f_deg, double theta_r_deg,
                             std::optional<double> theta_m_deg = std::nullopt) {
    std::optional<double> theta_m;
    if (theta_m_deg) theta_m = *theta_m_deg * kDeg;
    return {s, 0.0, theta_f_deg * kDeg, theta_r_deg * kDeg, theta_m};
}

TEST(ContactAngles, ExitAngleInsideTheContactIsKept) {
    EXPECT_EQ(clampedExitAngle(-0.1, 0.5), -0.1);
    EXPECT_EQ(clampedExitAngle(0.0, 0.5), 0.0);
    EXPECT_EQ(clampedExitAngle(-0.5, 0.5), -0.5);  // the limit θ_r = −θ_f itself
}

TEST(ContactAngles, ExitAngleBelowMinusEntryAngleBecomesMinusEntryAngle) {
    EXPECT_EQ(clampedExitAngle(-30.0 * kDeg, 10.0 * kDeg), -10.0 * kDeg);
    EXPECT_EQ(clampedExitAngle(-0.5000001, 0.5), -0.5);
}

TEST(ContactAngles, MaxStressAngleFollowsEquation218InsideTheContact) {
    // a₀ = 0.2, a₁ = 0.3 (Table 2.6), s = 0.3, θ_f = 30°: θ_m = 0.29 × 30° = 8.7°.
    const ContactParameters<double> p = testing::sandyLoam();
    EXPECT_NEAR(clampedMaxStressAngle(p, point(0.3, 30.0, 0.0)), 8.7 * kDeg, 1e-15);
    // A fixed θ_m inside [θ_r, θ_f] is used as given, whatever a₀ and a₁ (Table 2.3: 15°).
    EXPECT_EQ(clampedMaxStressAngle(p, point(0.3, 30.0, 0.0, 15.0)), 15.0 * kDeg);
    EXPECT_EQ(clampedMaxStressAngle(p, point(0.3, 30.0, -20.0, -5.0)), -5.0 * kDeg);
}

TEST(ContactAngles, NegativeEquation218FactorIsClampedToTheExitAngle) {
    // Strong braking: a₀ + a₁ s = 0.2 − 0.3 × 0.9 = −0.07 < 0, so (a₀ + a₁ s) θ_f = −2.1° at θ_f =
    // 30°.
    const ContactParameters<double> p = testing::sandyLoam();
    EXPECT_EQ(clampedMaxStressAngle(p, point(-0.9, 30.0, 0.0)), 0.0);           // below θ_r = 0
    EXPECT_EQ(clampedMaxStressAngle(p, point(-0.9, 30.0, -1.5)), -1.5 * kDeg);  // below θ_r
    // Inside a contact reaching behind the vertical, −2.1° is a valid θ_m and is kept.
    EXPECT_NEAR(clampedMaxStressAngle(p, point(-0.9, 30.0, -10.0)), -2.1 * kDeg, 1e-15);
}

TEST(ContactAngles, MaxStressAngleOutsideTheContactIsClamped) {
    const ContactParameters<double> p = testing::sandyLoam();
    // A fixed 15° on a wheel with θ_f = 10° becomes θ_f.
    EXPECT_EQ(clampedMaxStressAngle(p, point(0.3, 10.0, 0.0, 15.0)), 10.0 * kDeg);
    // A fixed θ_m behind θ_r becomes θ_r.
    EXPECT_EQ(clampedMaxStressAngle(p, point(0.3, 10.0, -5.0, -8.0)), -5.0 * kDeg);
    // θ_r is clamped first: θ_r = −30° with θ_f = 10° is −10°, so a fixed −20° becomes −10°.
    EXPECT_EQ(clampedMaxStressAngle(p, point(0.3, 10.0, -30.0, -20.0)), -10.0 * kDeg);
    // The same for Eq. 2.18 far below the contact: a₁ = 2, s = −0.9 gives (0.2 − 1.8) θ_f.
    ContactParameters<double> steep = p;
    steep.max_stress_a1 = 2.0;
    EXPECT_EQ(clampedMaxStressAngle(steep, point(-0.9, 10.0, -30.0)), -10.0 * kDeg);
    // And a factor above 1 gives θ_f: 0.2 + 2 × 0.9 = 2.
    EXPECT_EQ(clampedMaxStressAngle(steep, point(0.9, 10.0, 0.0)), 10.0 * kDeg);
}

TEST(ContactAngles, ClampedAngleCarriesNoDerivativeOfTheFactor) {
    // With ceres::Jet: dθ_m/da₀ = θ_f inside the contact, 0 once θ_m is held at a bound.
    using Jet = ceres::Jet<double, 1>;
    ContactParameters<Jet> p = testing::sandyLoam().cast<Jet>();
    p.max_stress_a0 = Jet(0.2, 0);
    const double theta_f = 30.0 * kDeg;
    const OperatingPoint<Jet> inside = point(0.3, 30.0, 0.0).cast<Jet>();
    const Jet free = clampedMaxStressAngle(p, inside);
    EXPECT_NEAR(free.v[0], theta_f, 1e-15);
    const OperatingPoint<Jet> braking = point(-0.9, 30.0, 0.0).cast<Jet>();
    EXPECT_EQ(clampedMaxStressAngle(p, braking).v[0], 0.0);
}

TEST(ContactAngles, StressFieldAndEntryAngleProblemUseTheClampedAngles) {
    const ContactParameters<double> p = testing::sandyLoam();
    const StressField<double> field(p, point(0.3, 10.0, -30.0, 15.0));
    EXPECT_EQ(field.exitAngle(), -10.0 * kDeg);
    EXPECT_EQ(field.maxStressAngle(), 10.0 * kDeg);
    EntryAngleProblem problem;
    problem.exit = {ExitCondition::Kind::kAngle, -30.0 * kDeg};
    EXPECT_EQ(operatingPoint(problem, 10.0 * kDeg).exit_angle_rad, -10.0 * kDeg);
}

}  // namespace
}  // namespace terra::contact
