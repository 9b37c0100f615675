// One wheel's contact from its kinematics: slip and slip angle of Eqs. 2.1–2.2 with the
// regularisation, θ_f from the sinkage (Eq. 2.12), and the forces of the core model.
#include "core/dynamics/wheel_contact.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/contact/quadratic_model.h"
#include "core/soil/soil_parameters.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::dynamics {
namespace {

contact::ContactParameters<double> sandyLoamWheelA() {
    soil::SoilParameters soil;  // the defaults are the thesis's sandy loam (Table 2.1)
    soil.max_shear_deformation_m = 0.02;
    return contact::makeContactParameters(soil, wheel::WheelParameters{});
}

TEST(WheelContact, SlipFollowsEquation21ForDrivingAndBraking) {
    const ContactOptions o;
    EXPECT_DOUBLE_EQ(slipRatio(0.03, 0.04, o), 1.0 - 0.03 / 0.04);  // driving: 1 − v/(rω)
    EXPECT_DOUBLE_EQ(slipRatio(0.05, 0.04, o), 0.04 / 0.05 - 1.0);  // braking: rω/v − 1
    EXPECT_DOUBLE_EQ(slipRatio(0.04, 0.04, o), 0.0);
    EXPECT_EQ(slipRatio(0.0, 0.04, o), 1.0);    // stalled wheel: spinning in place
    EXPECT_EQ(slipRatio(0.04, 0.0, o), -1.0);   // locked wheel: sliding
    EXPECT_EQ(slipRatio(-0.01, 0.04, o), 1.0);  // rolling backwards: kept in the domain
    EXPECT_EQ(slipRatio(0.04, -0.01, o), -1.0);
    EXPECT_DOUBLE_EQ(slipRatio(0.0, 0.0, o), 0.0);  // standing still: regularised, finite
    // Below v_reg the denominator is v_reg: continuous through zero speed.
    EXPECT_DOUBLE_EQ(slipRatio(0.0, 0.5e-3, o), 0.5);
}

TEST(WheelContact, SlipAngleIsPositiveForLeftwardMotion) {
    const ContactOptions o;
    EXPECT_DOUBLE_EQ(slipAngle(0.1, 0.1, o), std::atan(1.0));
    EXPECT_DOUBLE_EQ(slipAngle(0.1, -0.1, o), -std::atan(1.0));
    EXPECT_DOUBLE_EQ(slipAngle(0.0, 0.0, o), 0.0);
    EXPECT_LT(std::abs(slipAngle(0.0, 1.0, o)), M_PI / 2);  // stays inside the model's domain
}

TEST(WheelContact, ForcesAreTheCoreModelsAtTheEntryAngleOfTheSinkage) {
    const auto p = sandyLoamWheelA();
    ContactOptions o;
    const WheelKinematics k{0.03, 0.004, 0.04, 0.005};
    const WheelContact c = evaluateContact(p, k, o);
    ASSERT_TRUE(c.in_contact);
    EXPECT_NEAR(p.radius_m * (1.0 - std::cos(c.entry_angle_rad)), 0.005, 1e-15);  // Eq. 2.12
    const contact::OperatingPoint<double> op{0.25, std::atan(0.004 / 0.03), c.entry_angle_rad, 0.0,
                                             std::nullopt};
    const auto f = contact::computeForces(p, op);
    EXPECT_DOUBLE_EQ(c.forces.fz, f.fz);
    EXPECT_DOUBLE_EQ(c.forces.my, f.my);
    // β ≈ 7.6° ≫ β_reg: the side force is the model's F_y − F_b (docs/model.md, Side force).
    EXPECT_DOUBLE_EQ(c.forces.fs, f.fs);
    EXPECT_LT(c.forces.fs, 0.0);  // against the leftward slip

    o.model = contact::ContactModel::kQuadratic;
    EXPECT_DOUBLE_EQ(evaluateContact(p, k, o).forces.fz, contact::computeQuadraticForces(p, op).fz);
}

TEST(WheelContact, BulldozingSignIsSmoothedThroughZeroSlipAngle) {
    const auto p = sandyLoamWheelA();
    const ContactOptions o;
    // β = β_reg / 2: half the bulldozing force.
    const double vy = 0.03 * std::tan(0.5 * o.slip_angle_regularisation_rad);
    const WheelContact c = evaluateContact(p, {0.03, vy, 0.04, 0.005}, o);
    EXPECT_NEAR(c.forces.fs, c.forces.fy - 0.5 * c.forces.fb, 1e-12 * c.forces.fb);
    const WheelContact zero = evaluateContact(p, {0.03, 0.0, 0.04, 0.005}, o);
    EXPECT_EQ(zero.forces.fs, 0.0);
}

TEST(WheelContact, NoForceOutOfTheSoil) {
    const WheelContact c = evaluateContact(sandyLoamWheelA(), {0.03, 0.0, 0.04, -0.001}, {});
    EXPECT_FALSE(c.in_contact);
    EXPECT_EQ(c.forces.fz, 0.0);
    EXPECT_EQ(c.forces.my, 0.0);
}

// A stuck robot: the wheel spins in place (v_x = 0) or is locked and dragged (ω = 0). The contact
// is the core model's at s = ±1, finite (no longer clamped to ±0.99).
TEST(WheelContact, StalledAndLockedWheelsUseTheModelAtFullSlip) {
    const auto p = sandyLoamWheelA();
    const ContactOptions o;
    for (const auto& [k, slip] : {std::pair{WheelKinematics{0.0, 0.0, 0.04, 0.005}, 1.0},
                                  std::pair{WheelKinematics{0.04, 0.0, 0.0, 0.005}, -1.0}}) {
        const WheelContact c = evaluateContact(p, k, o);
        ASSERT_TRUE(c.in_contact);
        EXPECT_EQ(c.slip, slip);
        const contact::OperatingPoint<double> op{slip, 0.0, c.entry_angle_rad, 0.0, std::nullopt};
        const auto f = contact::computeForces(p, op);
        EXPECT_DOUBLE_EQ(c.forces.fx, f.fx) << slip;
        EXPECT_DOUBLE_EQ(c.forces.my, f.my) << slip;
        EXPECT_TRUE(std::isfinite(c.forces.fx) && std::isfinite(c.forces.fz)) << slip;
        // Spinning: the soil resists the spin (M_y > 0 against ω > 0); locked and dragged: the
        // shear opposes the travel (F_x < 0) and M_y < 0 tries to turn the wheel forward.
        if (slip > 0) {
            EXPECT_GT(c.forces.my, 0.0);
        } else {
            EXPECT_LT(c.forces.fx, 0.0);
            EXPECT_LT(c.forces.my, 0.0);
        }
    }
}

}  // namespace
}  // namespace terra::dynamics
