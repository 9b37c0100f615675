#include "core/identification/streaming.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/identification/synthetic.h"
#include "tests/core/contact/test_soils.h"
#include "tests/core/identification/identification_test_support.h"

namespace terra::identification {
namespace {

namespace soils = contact::testing;
using testing::kWheelA;

// A robot's slip wanders: the sweep's samples in a scrambled (but fixed) order, with 1 % noise.
std::vector<Sample> stream(const contact::ContactParameters<double>& soil, std::uint64_t seed) {
    SyntheticSpec spec;
    for (int i = 0; i < 101; ++i) spec.slips.push_back(0.05 + 0.85 * i / 100);
    spec.noise.fx.relative = spec.noise.fz.relative = spec.noise.my.relative = 0.01;
    spec.seed = seed;
    const DataSet d = synthesize(soil, spec).data;
    std::vector<Sample> out;
    for (std::size_t i = 0; i < d.samples.size(); ++i)
        out.push_back(d.samples[(i * 37) % d.samples.size()]);
    return out;
}

TEST(StreamingIdentifier, NoEstimateBeforeTheMinimumAndNoFalseAlarmOnOneSoil) {
    StreamingOptions options;
    StreamingIdentifier id(kWheelA, options);
    std::vector<Sample> samples = stream(soils::sandyLoam(), 1);
    const std::vector<Sample> more = stream(soils::sandyLoam(), 2);
    samples.insert(samples.end(), more.begin(), more.end());
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const StreamUpdate u = id.push(samples[i]);
        EXPECT_EQ(u.index, i);
        EXPECT_EQ(u.estimated, i + 1 >= options.min_samples) << i;
        EXPECT_FALSE(u.change_detected) << "false alarm at sample " << i;
        EXPECT_LE(u.window_size, options.window);
    }
}

TEST(StreamingIdentifier, DetectsTheBorderFromSandyLoamToClayAndSettles) {
    StreamingOptions options;
    StreamingIdentifier id(kWheelA, options);
    std::vector<Sample> samples = stream(soils::sandyLoam(), 3);
    const std::size_t border = samples.size();
    const std::vector<Sample> clay = stream(soils::clayeySoil(), 4);
    samples.insert(samples.end(), clay.begin(), clay.end());
    std::vector<StreamUpdate> updates;
    for (const Sample& s : samples) updates.push_back(id.push(s));
    int changes = 0;
    for (const StreamUpdate& u : updates) {
        if (!u.change_detected) continue;
        ++changes;
        ASSERT_TRUE(u.change_at.has_value());
        // The first clay sample or the next: its score can stay below the threshold (3.5 with
        // seed 4), since the window's estimate predicts clay's first samples within 8× the noise.
        EXPECT_GE(*u.change_at, border);
        EXPECT_LE(*u.change_at, border + 1);
        EXPECT_EQ(u.index, *u.change_at + options.persistence - 1);
    }
    EXPECT_EQ(changes, 1);
    // Settled: the estimate of the clay window predicts the clay samples about as well as the
    // sandy-loam estimate predicted sandy loam (the score is residual over the window's RMS).
    for (std::size_t i = samples.size() - 20; i < samples.size(); ++i) {
        EXPECT_TRUE(updates[i].estimated);
        EXPECT_LT(updates[i].residual_score, options.threshold) << i;
    }
    // The two soils' estimates differ where the soils do: clay's friction angle (13°) is lower.
    EXPECT_LT(updates.back().parameters.friction_angle_rad,
              updates[border - 1].parameters.friction_angle_rad);
}

TEST(StreamingIdentifier, ALoneOutlierIsNotAChange) {
    StreamingIdentifier id(kWheelA);
    std::vector<Sample> samples = stream(soils::sandyLoam(), 5);
    samples[60].fz_n *= 3.0;  // one wild sample
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const StreamUpdate u = id.push(samples[i]);
        EXPECT_FALSE(u.change_detected) << i;
        if (i == 60) {
            EXPECT_GT(u.residual_score, 8.0);
        }
    }
}

TEST(StreamingIdentifier, RejectsAnInvalidWheel) {
    EXPECT_THROW(StreamingIdentifier(wheel::WheelParameters{"bad", "", -1.0, 0.1}),
                 std::invalid_argument);
}

}  // namespace
}  // namespace terra::identification
