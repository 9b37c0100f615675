#include "core/identification/streaming.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
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

// The estimate's covariance (docs/traction.md §8) against the spread of the estimates themselves:
// windows of decoupled-model data (the fit's own model, so its estimate is unbiased) with known
// Gaussian noise, refitted over many noise draws; the predicted standard deviation of a₀, n₀ and φ
// must match the empirical one.
TEST(StreamingIdentifier, CovarianceMatchesTheSpreadOfTheEstimatesOverNoiseDraws) {
    DecoupledParameters truth;
    truth.a0 = 0.2;
    truth.a1 = 0.3;
    truth.pressure_modulus = 1.515e6;
    truth.n0 = 0.7;
    truth.n1 = 0.0;
    truth.cohesion_pa = 1700.0;
    truth.friction_angle_rad = 0.5061;
    truth.shear_modulus_m = 0.025;
    const double sigma[3] = {0.2, 0.5, 0.02};  // F_x, F_z [N], M_y [N·m]
    constexpr int kWindows = 60, kSamples = 60;
    const int tracked[3] = {0, 3, 6};  // a₀, n₀, φ
    double sum[3] = {}, sum_sq[3] = {}, predicted[3] = {};
    std::mt19937_64 random(7);
    std::normal_distribution<double> normal;
    for (int w = 0; w < kWindows; ++w) {
        StreamingOptions options;
        options.window = options.min_samples = kSamples;
        options.initial = truth;  // warm start, as the rover's identifier on its expected soil
        options.covariance = true;
        StreamingIdentifier id(kWheelA, options);
        StreamUpdate u;
        for (int i = 0; i < kSamples; ++i) {
            const double slip = 0.1 + 0.7 * i / (kSamples - 1);
            const double theta_f = 0.25 + 0.15 * ((i * 7) % kSamples) / (kSamples - 1);
            const DecoupledForces f = decoupledForward(truth, kWheelA, slip, theta_f);
            Sample s;
            s.slip = slip;
            s.entry_angle_rad = theta_f;
            s.fx_n = f.fx_n + sigma[0] * normal(random);
            s.fz_n = f.fz_n + sigma[1] * normal(random);
            s.my_nm = f.my_nm + sigma[2] * normal(random);
            u = id.push(s);
        }
        ASSERT_TRUE(u.estimated);
        const auto x = decoupledVector(u.parameters);
        for (int k = 0; k < 3; ++k) {
            sum[k] += x[tracked[k]];
            sum_sq[k] += x[tracked[k]] * x[tracked[k]];
            predicted[k] += std::sqrt(u.covariance[tracked[k]][tracked[k]]) / kWindows;
        }
    }
    for (int k = 0; k < 3; ++k) {
        const double mean = sum[k] / kWindows;
        const double empirical = std::sqrt((sum_sq[k] - kWindows * mean * mean) / (kWindows - 1));
        // 60 draws estimate a standard deviation to ≈ ±9 % (1/√(2·59)); the steps' conditional
        // blocks and the linearisation allow a little more.
        EXPECT_GT(predicted[k], 0.75 * empirical) << "parameter " << tracked[k];
        EXPECT_LT(predicted[k], 1.33 * empirical) << "parameter " << tracked[k];
    }
}

TEST(StreamingIdentifier, RejectsAnInvalidWheel) {
    EXPECT_THROW(StreamingIdentifier(wheel::WheelParameters{"bad", "", -1.0, 0.1}),
                 std::invalid_argument);
}

}  // namespace
}  // namespace terra::identification
