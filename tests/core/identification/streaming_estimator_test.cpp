// The streaming estimator of issue #13 (streaming_estimator.h): slip sweeps at loads that change
// every 50 samples (30, 58.86, 90 N), 1 % noise (of each channel's largest value over the run),
// sandy loam then clayey soil on wheel A. The truth is Table 2.1 written out by hand.
#include "core/identification/streaming_estimator.h"

#include <gtest/gtest.h>

#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/identification/synthetic.h"
#include "tests/core/contact/test_soils.h"
#include "tests/core/identification/identification_test_support.h"
#include "tests/core/test_support.h"

namespace terra::identification {
namespace {

using testing::truthOf;

namespace soils = contact::testing;
using terra::testing::kDeg;
using testing::kWheelA;
// 1 % of the largest |F_x|, |F_z|, |M_y| of sandy loam's sweeps at 30–90 N [N, N, N·m].
constexpr std::array<double, 3> kNoise{0.136, 0.90, 0.0195};

// `blocks` blocks of 50 samples; the load cycles through 30, 58.86, 90 N from block to block and
// the slip sweeps 0.05 → 0.85, back in the next block.
std::vector<Sample> drive(const contact::ContactParameters<double>& soil, int blocks,
                          std::uint64_t seed) {
    const double loads[3] = {30.0, 58.86, 90.0};
    boost::random::mt19937_64 engine(seed);
    boost::random::normal_distribution<double> normal(0.0, 1.0);
    std::vector<Sample> out;
    for (int b = 0; b < blocks; ++b) {
        SyntheticSpec spec;
        spec.loads_n = {loads[b % 3]};
        for (int i = 0; i < 50; ++i) {
            const double t = i / 49.0;
            spec.slips.push_back(0.05 + 0.8 * (b % 2 ? 1.0 - t : t));
        }
        for (Sample s : synthesize(soil, spec).data.samples) {
            s.load_n = loads[b % 3];
            s.fx_n += kNoise[0] * normal(engine);
            s.fz_n += kNoise[1] * normal(engine);
            s.my_nm += kNoise[2] * normal(engine);
            out.push_back(s);
        }
    }
    return out;
}

StreamingEstimatorOptions estimatorOptions() {
    StreamingEstimatorOptions o;
    o.fit.max_shear_deformation_m = 0.02;  // both soils' j_max here (a setting of the model)
    return o;
}

// Counts, per parameter, the estimates of samples [from, to) more than 3 std from the truth.
struct Band {
    std::array<int, kFullParameterCount> outside{};
    int judged = 0;
    double nis = 0.0;
    int nis_count = 0;
};

void judge(const StreamEstimate& e, const ParameterVector& truth, Band& band) {
    if (!e.estimated) return;
    ++band.judged;
    for (int k = 0; k < kJmax; ++k)
        band.outside[k] += std::abs(e.parameters[k] - truth[k]) > 3.0 * e.std[k];
    if (e.channels > 0) band.nis += e.nis / e.channels, ++band.nis_count;
}

TEST(StreamingEstimator, NoFalseAlarmInFiveThousandSamplesOfOneSoilAndHonestBands) {
    const std::vector<Sample> samples = drive(soils::sandyLoam(), 100, 1);
    ASSERT_EQ(samples.size(), 5000u);
    StreamingEstimator estimator(kWheelA, estimatorOptions());
    const ParameterVector truth = truthOf(soils::sandyLoam());
    Band band;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const StreamEstimate e = estimator.push(samples[i]);
        ASSERT_EQ(e.index, i);
        EXPECT_FALSE(e.change_detected) << "false alarm at sample " << i;
        EXPECT_EQ(e.estimated, i + 1 >= estimatorOptions().init_samples) << i;
        if (i >= 300) judge(e, truth, band);  // settled: after six load changes
    }
    for (int k = 0; k < kJmax; ++k) {
        // 3σ bands: 0.27 % outside for a consistent estimate; allow 1 %.
        EXPECT_LE(band.outside[k], band.judged / 100) << parameterInfo()[k].name;
    }
    // The normalised innovations are χ² per channel: mean 1.
    EXPECT_NEAR(band.nis / band.nis_count, 1.0, 0.2);
    const auto covariance = estimator.covariance();
    EXPECT_GT(covariance[kPhi][kPhi], 0.0);
    EXPECT_EQ(covariance[kPhi][kPhi], covariance[kPhi][kPhi]);
}

TEST(StreamingEstimator, SoilBorderIsConfirmedWithinTenSamples) {
    std::vector<Sample> samples = drive(soils::sandyLoam(), 20, 2);
    const std::size_t border = samples.size();
    const contact::ContactParameters<double> clay = soils::clayeySoil(0.02);
    const std::vector<Sample> second = drive(clay, 8, 3);
    samples.insert(samples.end(), second.begin(), second.end());
    StreamingEstimator estimator(kWheelA, estimatorOptions());
    const ParameterVector truth = truthOf(clay);
    int changes = 0;
    Band band;
    StreamEstimate last;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        last = estimator.push(samples[i]);
        if (last.change_detected) {
            ++changes;
            ASSERT_TRUE(last.change_at.has_value());
            std::printf("change at %zu confirmed at %zu (border %zu)\n", *last.change_at, i,
                        border);
            EXPECT_GE(*last.change_at, border);
            EXPECT_LE(*last.change_at, border + 2);
            EXPECT_LT(i, border + 10);
        }
        if (i >= border + 200) judge(last, truth, band);
    }
    EXPECT_EQ(changes, 1);
    for (int k = 0; k < kJmax; ++k)
        EXPECT_LE(band.outside[k], band.judged / 100) << parameterInfo()[k].name;
    EXPECT_NEAR(last.parameters[kPhi], 13.0 * kDeg, 3.0 * last.std[kPhi]);
}

// A test rig's log: at each load in turn the slip sweeps monotonically 0 → 0.9 (`per_load`
// samples), 1 % noise as above. The initialisation then sees only the first sweep's low slips,
// and every later sample lies at a slip or load it has not seen.
std::vector<Sample> monotone(const contact::ContactParameters<double>& soil,
                             const std::vector<double>& loads, int per_load, std::uint64_t seed,
                             double noise_scale = 1.0) {
    boost::random::mt19937_64 engine(seed);
    boost::random::normal_distribution<double> normal(0.0, 1.0);
    std::vector<Sample> out;
    for (double load : loads) {
        SyntheticSpec spec;
        spec.loads_n = {load};
        for (int i = 0; i < per_load; ++i) spec.slips.push_back(0.9 * i / (per_load - 1));
        for (Sample s : synthesize(soil, spec).data.samples) {
            s.load_n = load;
            s.fx_n += noise_scale * kNoise[0] * normal(engine);
            s.fz_n += noise_scale * kNoise[1] * normal(engine);
            s.my_nm += noise_scale * kNoise[2] * normal(engine);
            out.push_back(s);
        }
    }
    return out;
}

// Streams `first` then `second` and checks: one change, placed at the border (±2), confirmed
// within 10 samples of it, and the clay's friction angle at the end within 3 std.
void expectOneBorder(const std::vector<Sample>& first, const std::vector<Sample>& second) {
    std::vector<Sample> samples = first;
    samples.insert(samples.end(), second.begin(), second.end());
    const std::size_t border = first.size();
    StreamingEstimator estimator(kWheelA, estimatorOptions());
    int changes = 0;
    StreamEstimate last;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        last = estimator.push(samples[i]);
        if (!last.change_detected) continue;
        ++changes;
        ASSERT_TRUE(last.change_at.has_value());
        EXPECT_GE(*last.change_at + 2, border) << "confirmed at " << i;
        EXPECT_LE(*last.change_at, border + 2) << "confirmed at " << i;
        EXPECT_LT(i, border + 10);
    }
    EXPECT_EQ(changes, 1);
    ASSERT_TRUE(last.estimated);
    EXPECT_NEAR(last.parameters[kPhi], 13.0 * kDeg, 3.0 * last.std[kPhi]);
}

// One load, 80 slips of sandy loam then 80 of clayey soil, each swept monotonically (the model's
// j_max is the data's: 0.02 m for both soils).
TEST(StreamingEstimator, MonotoneSweepAtOneLoadBorderPlacedAndNoFalseChange) {
    for (std::uint64_t seed : {1u, 2u}) {
        SCOPED_TRACE(seed);
        expectOneBorder(monotone(soils::sandyLoam(), {58.86}, 80, seed),
                        monotone(soils::clayeySoil(0.02), {58.86}, 80, seed + 10));
    }
}

// Three loads × 30 monotone slips of sandy loam, then three × 20 of clayey soil.
TEST(StreamingEstimator, MonotoneSweepsPerLoadBorderPlacedAndNoFalseChange) {
    for (std::uint64_t seed : {1u, 2u}) {
        SCOPED_TRACE(seed);
        expectOneBorder(monotone(soils::sandyLoam(), {30.0, 58.86, 90.0}, 30, seed),
                        monotone(soils::clayeySoil(0.02), {30.0, 58.86, 90.0}, 20, seed + 10));
    }
}

TEST(StreamingEstimator, ALoneOutlierIsNeitherAChangeNorUsed) {
    std::vector<Sample> samples = drive(soils::sandyLoam(), 4, 4);
    samples[120].fz_n *= 3.0;
    StreamingEstimator estimator(kWheelA, estimatorOptions());
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const StreamEstimate e = estimator.push(samples[i]);
        EXPECT_FALSE(e.change_detected) << i;
        if (i == 120) {
            EXPECT_FALSE(e.used);
            EXPECT_GT(e.nis, 100.0);
            EXPECT_LE(e.cusum, estimatorOptions().max_step_evidence);
        }
    }
}

// A robot's slip is an estimate (docs/identification.md §8, "An uncertain slip"): here every
// sample after the first initialisation carries a slip off by N(0, 0.01²) and says so
// (`slip_std`), and the estimator's innovations stay χ² (mean 1 per channel) with no false
// change; the same samples without `slip_std` are far from χ² and raise changes on one soil.
TEST(StreamingEstimator, AnUncertainSlipIsCarriedIntoTheInnovations) {
    constexpr double kSlipStd = 0.01;
    std::vector<Sample> samples = drive(soils::sandyLoam(), 16, 6);
    boost::random::mt19937_64 engine(7);
    boost::random::normal_distribution<double> normal(0.0, kSlipStd);
    for (std::size_t i = 30; i < samples.size(); ++i) samples[i].slip += normal(engine);
    StreamingEstimatorOptions o = estimatorOptions();
    o.fit.noise = {kNoise[0], kNoise[1], kNoise[2], 0.0};
    for (bool declared : {true, false}) {
        SCOPED_TRACE(declared);
        StreamingEstimator estimator(kWheelA, o);
        double nis = 0.0;
        int n = 0, changes = 0;
        for (std::size_t i = 0; i < samples.size(); ++i) {
            Sample sample = samples[i];
            if (declared && i >= 30) sample.slip_std = kSlipStd;
            const StreamEstimate e = estimator.push(sample);
            changes += e.change_detected;
            if (i >= 300 && e.channels > 0) nis += e.nis / e.channels, ++n;
        }
        if (declared) {
            EXPECT_EQ(changes, 0);
            EXPECT_NEAR(nis / n, 1.0, 0.2);
        } else {
            EXPECT_GT(changes, 0);
            EXPECT_GT(nis / n, 1.4);
        }
    }
}

// Per-load monotone sweeps (three loads × 30 slips of sandy loam, then three × 20 of clayey soil)
// of exact forces whose slips are off by N(0, 0.01²), as a robot's slip estimate is. Declared
// (`slip_std`), every fit weighs a sample by what its slip allows — the batch fits of the
// initialisation, the refits and the confirmation as the streaming update does — and the border
// is found once, in its place; undeclared, the same sandy loam alone raises false changes.
TEST(StreamingEstimator, UncertainSlipsOfPerLoadSweepsRaiseNoFalseChangeInTheBatchFits) {
    constexpr double kSlipStd = 0.01;
    int undeclared_changes = 0;
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        SCOPED_TRACE(seed);
        boost::random::mt19937_64 engine(seed + 100);
        boost::random::normal_distribution<double> normal(0.0, kSlipStd);
        std::vector<Sample> sand = monotone(soils::sandyLoam(), {30.0, 58.86, 90.0}, 30, seed, 0);
        std::vector<Sample> clay =
            monotone(soils::clayeySoil(0.02), {30.0, 58.86, 90.0}, 20, seed + 10, 0);
        for (auto* part : {&sand, &clay}) {
            for (Sample& s : *part) s.slip += normal(engine);
        }
        StreamingEstimator plain(kWheelA, estimatorOptions());
        for (const Sample& s : sand) undeclared_changes += plain.push(s).change_detected;
        for (auto* part : {&sand, &clay}) {
            for (Sample& s : *part) s.slip_std = kSlipStd;
        }
        expectOneBorder(sand, clay);
    }
    EXPECT_GE(undeclared_changes, 3);  // 5 measured
}

TEST(StreamingEstimator, GivenNoiseLevelsAreKept) {
    StreamingEstimatorOptions o = estimatorOptions();
    o.fit.noise = {kNoise[0], kNoise[1], kNoise[2], 0.0};
    StreamingEstimator estimator(kWheelA, o);
    for (const Sample& s : drive(soils::sandyLoam(), 1, 5)) estimator.push(s);
    EXPECT_EQ(estimator.noise()[kFxChannel], kNoise[0]);
    EXPECT_EQ(estimator.noise()[kMyChannel], kNoise[2]);
}

TEST(StreamingEstimator, RejectsBadOptions) {
    StreamingEstimatorOptions o;
    o.window = 0;
    EXPECT_THROW(StreamingEstimator(kWheelA, o), std::invalid_argument);
    o = {};
    o.gate_probability = 0.0;
    EXPECT_THROW(StreamingEstimator(kWheelA, o), std::invalid_argument);
    EXPECT_THROW(StreamingEstimator(wheel::WheelParameters{"bad", "", -1.0, 0.1}),
                 std::invalid_argument);
}

}  // namespace
}  // namespace terra::identification
