// The quadratic closed form on a remembered track (docs/model.md, "The quadratic reload branch"):
// against the integrated contact of the same track, which integrates the reload law's kink
// exactly (wheel_forces.h splits its pieces there).
#include <gtest/gtest.h>

#include <cmath>

#include "core/compaction/track_memory.h"
#include "core/contact/quadratic_model.h"
#include "core/contact/wheel_forces.h"
#include "tests/core/contact/test_soils.h"

namespace terra::contact {
namespace {

using testing::kDeg;

// The quadratic model's own error on untouched soil at such points (IsCloseToTheFullModel: 6 %
// for F_z and M_y); the reload branch is held to the same.
constexpr double kQuadraticTolerance = 0.06;

// A track one wheel left at 2 cm (Wong's law, default k₀, A_u), reloaded by a wheel whose rim
// reaches `depth_m` below the untouched surface.
struct Case {
    ContactParameters<double> params;
    OperatingPoint<double> op;
};

Case remembered(const ContactParameters<double>& soil, double depth_m, double slip,
                double slip_angle_rad) {
    const compaction::ReloadLaw law;
    const compaction::TrackMemory memory =
        compaction::afterPass({}, law, soil, 0.02, soil.sinkage_exponent, 0.0);
    Case c;
    c.params = compaction::onTrack(soil, memory, law);
    const double below_rut = depth_m - memory.rut_depth_m;
    const double entry = std::acos(1.0 - below_rut / soil.radius_m);
    c.op = {slip, slip_angle_rad, entry, 0.0, std::nullopt};
    return c;
}

TEST(QuadraticReload, IsAsCloseToTheIntegratedTrackAsTheModelIsOnUntouchedSoil) {
    int split = 0;
    for (const auto& soil : {testing::sandyLoam(), testing::drySand(), testing::clayeySoil()}) {
        const compaction::TrackMemory memory = compaction::afterPass(
            {}, compaction::ReloadLaw{}, soil, 0.02, soil.sinkage_exponent, 0.0);
        // Depths: on the elastic branch only (no kink), across the kink (the rim deeper than the
        // earlier wheel), well below it.
        for (const double depth :
             {memory.rut_depth_m + 0.5 * (0.02 - memory.rut_depth_m), 0.022, 0.03}) {
            for (const double slip : {0.1, 0.3, 0.6}) {
                for (const double beta : {0.0, 10.0 * kDeg}) {
                    const Case c = remembered(soil, depth, slip, beta);
                    ASSERT_TRUE(c.params.remembers());
                    const WheelForces<double> full = computeForces(c.params, c.op);
                    const WheelForces<double> quad = computeQuadraticForces(c.params, c.op);
                    SCOPED_TRACE(::testing::Message()
                                 << "depth " << depth << " slip " << slip << " beta " << beta);
                    EXPECT_NEAR(quad.fz, full.fz, kQuadraticTolerance * full.fz);
                    EXPECT_NEAR(quad.my, full.my, kQuadraticTolerance * std::abs(full.my));
                    // F_x is a difference of thrust and resistance: relative to F_z.
                    EXPECT_NEAR(quad.fx, full.fx, kQuadraticTolerance * full.fz);
                    const auto kinks = detail::reloadKinks(StressField<double>(c.params, c.op));
                    split += std::isfinite(kinks[0]) ? 1 : 0;
                }
            }
        }
    }
    EXPECT_GT(split, 10);  // the kink was inside the contact in most cases
}

TEST(QuadraticReload, AnUntouchedSoilIsTheThesisClosedFormBitForBit) {
    // The reload branch only acts on a remembered track: onTrack of an untouched memory is the
    // soil itself, and the closed form is the same expression.
    const ContactParameters<double> soil = testing::sandyLoam();
    const ContactParameters<double> on =
        compaction::onTrack(soil, compaction::TrackMemory{}, compaction::ReloadLaw{});
    const OperatingPoint<double> op{0.3, 12.0 * kDeg, 30.0 * kDeg, 0.0, std::nullopt};
    EXPECT_FALSE(on.remembers());
    const WheelForces<double> a = computeQuadraticForces(soil, op);
    const WheelForces<double> b = computeQuadraticForces(on, op);
    EXPECT_EQ(a.fx, b.fx);
    EXPECT_EQ(a.fz, b.fz);
    EXPECT_EQ(a.my, b.my);
}

}  // namespace
}  // namespace terra::contact
