// The identification study of issue #3: noise-free recovery on the thesis's 3 soils × 2 wheels,
// and the coverage of the reported standard deviations under 1 % noise, single load vs three loads.
// The tables this prints are the ones in docs/identification.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "core/identification/decoupled_fit.h"
#include "core/identification/full_fit.h"
#include "core/identification/synthetic.h"
#include "tests/core/contact/test_soils.h"
#include "tests/core/identification/identification_test_support.h"

namespace terra::identification {
namespace {

using contact::ContactParameters;
namespace soils = contact::testing;

struct Case {
    const char* soil;
    const char* wheel;
    double radius_m, width_m;
};

ContactParameters<double> soilFor(const std::string& name, double r, double b) {
    // Table 2.1 in thesis units, j_max from Table 2.6, written out independently of the presets.
    if (name == "sandy-loam")
        return soils::thesisSoil(0.7, 1.7, 29.0, 5.3, 1515.0, 0.025, 15.2, 0.02, r, b);
    if (name == "dry-sand")
        return soils::thesisSoil(1.1, 1.0, 30.0, 0.9, 1523.4, 0.025, 16.18, 0.02, r, b);
    return soils::thesisSoil(0.5, 4.14, 13.0, 13.2, 692.2, 0.01, 13.24, 0.009, r, b);
}

using testing::truthOf;

using testing::valuesOf;

SyntheticSpec sweep(std::vector<double> loads, double relative_noise, std::uint64_t seed) {
    SyntheticSpec spec;
    for (int i = 0; i <= 45; ++i) spec.slips.push_back(0.9 * i / 45);  // s = 0 : 0.02 : 0.9
    spec.loads_n = std::move(loads);
    spec.noise.fx.relative = spec.noise.fz.relative = spec.noise.my.relative = relative_noise;
    spec.seed = seed;
    return spec;
}

class NoiseFreeRecovery : public ::testing::TestWithParam<Case> {};

TEST_P(NoiseFreeRecovery, RefinementReturnsEveryParameterToOneMillionth) {
    // Issue #3 figure: full-model data of Table 5.2 (W = 6 kg, β = 0, θ_r = 0, s ∈ [0, 0.9]); the
    // decoupled estimate is biased, the refinement started from it must land on the truth.
    const Case c = GetParam();
    const ContactParameters<double> soil = soilFor(c.soil, c.radius_m, c.width_m);
    const wheel::WheelParameters wheel{c.wheel, "", c.radius_m, c.width_m};
    const DataSet data = synthesize(soil, sweep({58.86}, 0.0, 1)).data;
    ASSERT_GT(data.samples.size(), 40u);
    const DecoupledFit start = fitDecoupled(data, wheel, DecoupledParameters{});
    ASSERT_TRUE(start.usable());
    RefineOptions options;
    options.max_shear_deformation_m = soil.max_shear_deformation_m;
    const RefineResult result = refineFullModel(data, wheel, start.parameters, options);
    ASSERT_TRUE(result.report.usable) << result.report.termination;
    const auto truth = truthOf(soil);
    const auto got = valuesOf(result.parameters);
    const auto decoupled = valuesOf(start.parameters);
    std::printf("| %s | %s |", c.soil, c.wheel);
    for (int k = 0; k < kJmax; ++k) {
        EXPECT_NEAR(got[k], truth[k], 1e-6 * std::abs(truth[k])) << parameterInfo()[k].name;
        std::printf(" %.4g → %.7g |", decoupled[k], got[k]);
    }
    std::printf(" %.1f ms |\n", result.report.wall_time_ms);
}

INSTANTIATE_TEST_SUITE_P(
    ThesisSoilsAndWheels, NoiseFreeRecovery,
    ::testing::Values(Case{"sandy-loam", "A", 0.092, 0.107}, Case{"sandy-loam", "B", 0.135, 0.165},
                      Case{"dry-sand", "A", 0.092, 0.107}, Case{"dry-sand", "B", 0.135, 0.165},
                      Case{"clayey-soil", "A", 0.092, 0.107},
                      Case{"clayey-soil", "B", 0.135, 0.165}),
    [](const auto& info) {
        std::string name = std::string(info.param.soil) + "_" + info.param.wheel;
        std::replace(name.begin(), name.end(), '-', '_');
        return name;
    });

struct Coverage {
    int runs = 0;
    int cphi_flagged = 0;
    std::array<int, kFullParameterCount> judged{}, covered{};
    std::array<double, kFullParameterCount> sum{}, sum2{}, sum_std{};
};

Coverage coverageStudy(const std::vector<double>& loads) {
    // 1 % noise (of each channel's largest value) on F_x, F_z, M_y, 20 seeds, sandy loam, wheel A.
    const ContactParameters<double> soil = soils::sandyLoam();
    const wheel::WheelParameters wheel{"A", "", soils::kRadiusA, soils::kWidthA};
    const auto truth = truthOf(soil);
    Coverage cov;
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        const DataSet data = synthesize(soil, sweep(loads, 0.01, seed)).data;
        const DecoupledFit start = fitDecoupled(data, wheel, DecoupledParameters{});
        RefineOptions options;  // noise levels estimated from the residuals
        options.max_shear_deformation_m = soil.max_shear_deformation_m;
        const RefineResult r = refineFullModel(data, wheel, start.parameters, options);
        if (!r.report.usable) continue;
        ++cov.runs;
        bool cphi = false, flagged[kFullParameterCount] = {};
        for (const ParameterText& flag : r.uncertainty.flags) {
            // The parameters a flag names ("X and Y trade off", "X ended at its bound").
            const std::vector<std::string> named = flag.parameters();
            const auto names = [&named](FullParameter k) {
                return std::find(named.begin(), named.end(), fieldOf(k).key) != named.end();
            };
            if (names(kC) && names(kPhi) && flag.text.find("trade off") != std::string::npos)
                cphi = true;
            for (int k = 0; k < kJmax; ++k) flagged[k] |= names(static_cast<FullParameter>(k));
        }
        cov.cphi_flagged += cphi;
        const auto got = valuesOf(r.parameters);
        for (int k = 0; k < kJmax; ++k) {
            const double err = got[k] - truth[k];
            cov.sum[k] += err / truth[k];
            cov.sum2[k] += err * err / (truth[k] * truth[k]);
            cov.sum_std[k] += r.uncertainty.std[k] / truth[k];
            if (flagged[k] || !r.uncertainty.computed) continue;
            ++cov.judged[k];
            cov.covered[k] += std::abs(err) <= 3.0 * r.uncertainty.std[k];
        }
    }
    return cov;
}

void print(const char* label, const Coverage& cov) {
    std::printf(
        "%s (%d runs, c–phi flagged in %d)\n| parameter | mean error | rms error | mean reported "
        "std "
        "| truth within 3 std |\n",
        label, cov.runs, cov.cphi_flagged);
    for (int k = 0; k < kJmax; ++k) {
        const double mean = cov.sum[k] / cov.runs;
        std::printf("| %s | %+.2f %% | %.2f %% | %.2f %% | %d / %d |\n", parameterInfo()[k].name,
                    100 * mean, 100 * std::sqrt(cov.sum2[k] / cov.runs),
                    100 * cov.sum_std[k] / cov.runs, cov.covered[k], cov.judged[k]);
    }
}

TEST(NoisyIdentification, SingleLoadFlagsCohesionAndFriction) {
    const Coverage cov = coverageStudy({58.86});
    print("single load 58.86 N", cov);
    ASSERT_EQ(cov.runs, 20);
    EXPECT_GE(cov.cphi_flagged, 18);  // the data cannot separate c and φ: say so
    for (int k = 0; k < kJmax; ++k) {
        if (cov.judged[k] == 0) continue;
        EXPECT_GE(cov.covered[k], 0.9 * cov.judged[k]) << parameterInfo()[k].name;
    }
}

TEST(NoisyIdentification, ThreeLoadsDetermineEveryParameterWithHonestErrors) {
    const Coverage cov = coverageStudy({30.0, 58.86, 90.0});
    print("three loads 30, 58.86, 90 N", cov);
    ASSERT_EQ(cov.runs, 20);
    EXPECT_LE(cov.cphi_flagged, 2);
    for (int k = 0; k < kJmax; ++k) {
        EXPECT_GE(cov.judged[k], 12) << parameterInfo()[k].name;  // Ks–n is flagged in a few runs
        EXPECT_GE(cov.covered[k], 0.9 * cov.judged[k]) << parameterInfo()[k].name;
    }
}

}  // namespace
}  // namespace terra::identification
