#include "core/gsa/batch.h"

#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <vector>

#include "tests/core/gsa/gsa_test_support.h"

namespace terra::gsa {
namespace {

using testing::kDeg;
using testing::reference;
using testing::sandyLoam;
using testing::wheelA;

std::string messageOf(const soil::SoilParameters& soil, const BatchInput& input) {
    try {
        evaluateBatch(soil, wheelA(), input, {});
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "(no exception)";
}

TEST(Batch, MatchesTheContactApiPointByPointWithTheLoadGiven) {
    const std::vector<double> slip{0.0, 0.1, 0.3, 0.6, 0.9, -0.3};
    const std::vector<double> beta{0.0, 5 * kDeg, 0.0, 15 * kDeg, 0.0, 0.0};
    const std::vector<double> phi{29.0, 20.0, 35.0, 25.0, 31.0, 29.0};
    const std::vector<double> k{0.025, 0.005, 0.04, 0.01, 0.02, 0.03};
    const double load = 58.86;
    BatchInput input{6, slip, beta, {&load, 1}, {}, {{"phi_deg", phi}, {"K_m", k}}};
    const BatchResult r = evaluateBatch(sandyLoam(), wheelA(), input, {});
    EXPECT_EQ(r.summary.ok, 6u);
    for (std::size_t i = 0; i < 6; ++i) {
        soil::SoilParameters s = sandyLoam();
        s.friction_angle_rad = phi[i] * kDeg;
        s.shear_modulus_m = k[i];
        const testing::Reference expected = reference(s, wheelA(), slip[i], beta[i], load);
        ASSERT_TRUE(expected.ok);
        ASSERT_TRUE(r.ok(i));
        // The same arithmetic: bit-identical.
        EXPECT_EQ(r.entry_angle_rad[i], expected.entry_angle_rad) << i;
        EXPECT_EQ(r.fx_n[i], expected.forces.fx) << i;
        EXPECT_EQ(r.fs_n[i], expected.forces.fs) << i;
        EXPECT_EQ(r.my_nm[i], expected.forces.my) << i;
        EXPECT_NEAR(r.fz_n[i], load, 1e-9 * load);
        EXPECT_DOUBLE_EQ(r.sinkage_m[i], 0.092 * (1 - std::cos(expected.entry_angle_rad)));
    }
}

TEST(Batch, MatchesTheContactApiWithTheEntryAngleGiven) {
    const std::vector<double> slip{0.1, 0.5};
    const std::vector<double> theta{20 * kDeg, 35 * kDeg};
    const std::vector<double> c{0.0, 5.0};
    BatchInput input{2, slip, {}, {}, theta, {{"c_kPa", c}}};
    const BatchResult r = evaluateBatch(sandyLoam(), wheelA(), input, {});
    for (std::size_t i = 0; i < 2; ++i) {
        soil::SoilParameters s = sandyLoam();
        s.cohesion_pa = c[i] * 1e3;
        const testing::Reference expected = reference(s, wheelA(), slip[i], 0.0, 0.0, theta[i]);
        EXPECT_EQ(r.fx_n[i], expected.forces.fx);
        EXPECT_EQ(r.fz_n[i], expected.forces.fz);
        EXPECT_EQ(r.entry_angle_rad[i], theta[i]);
    }
}

TEST(Batch, ResultsDoNotDependOnTheThreadCount) {
    constexpr std::size_t n = 150;
    std::vector<double> slip(n), phi(n), n_exp(n);
    for (std::size_t i = 0; i < n; ++i) {
        slip[i] = 0.9 * i / n;
        phi[i] = 20.0 + 15.0 * ((i * 37) % n) / n;
        n_exp[i] = 0.5 + 0.6 * ((i * 11) % n) / n;
    }
    const double load = 58.86;
    BatchInput input{n, slip, {}, {&load, 1}, {}, {{"phi_deg", phi}, {"n", n_exp}}};
    const BatchResult one = evaluateBatch(sandyLoam(), wheelA(), input, {}, testing::onThreads(1));
    for (int threads : {2, 3}) {
        const BatchResult many =
            evaluateBatch(sandyLoam(), wheelA(), input, {}, testing::onThreads(threads));
        EXPECT_EQ(std::memcmp(one.fx_n.data(), many.fx_n.data(), n * sizeof(double)), 0);
        EXPECT_EQ(std::memcmp(one.entry_angle_rad.data(), many.entry_angle_rad.data(),
                              n * sizeof(double)),
                  0);
        EXPECT_EQ(one.status, many.status);
    }
}

TEST(Batch, OneValueIsBroadcastToEverySample) {
    const std::vector<double> slip{0.2, 0.4, 0.6};
    const double phi = 33.0, beta = 10 * kDeg, theta = 25 * kDeg;
    const std::vector<double> phis(3, phi), betas(3, beta);
    const BatchResult a =
        evaluateBatch(sandyLoam(), wheelA(),
                      {3, slip, {&beta, 1}, {}, {&theta, 1}, {{"phi_deg", {&phi, 1}}}}, {});
    const BatchResult b = evaluateBatch(sandyLoam(), wheelA(),
                                        {3, slip, betas, {}, {&theta, 1}, {{"phi_deg", phis}}}, {});
    EXPECT_EQ(a.fx_n, b.fx_n);
    EXPECT_EQ(a.fs_n, b.fs_n);
}

TEST(Batch, BadInputNamesTheArrayTheIndexTheValueAndTheRange) {
    const std::vector<double> slip{0.1, 0.2, 0.3};
    const std::vector<double> phi{29.0, 30.0, 75.0};
    const double load = 58.86;
    EXPECT_NE(messageOf(sandyLoam(), {3, slip, {}, {&load, 1}, {}, {{"phi_deg", phi}}})
                  .find("phi_deg[2]: 75 is outside the allowed range [0, 60) deg"),
              std::string::npos);
    const std::vector<double> bad_slip{0.1, 1.5, 0.3};
    EXPECT_NE(messageOf(sandyLoam(), {3, bad_slip, {}, {&load, 1}, {}, {}})
                  .find("slip[1]: 1.5 is outside the allowed range [-1, 1]"),
              std::string::npos);
    EXPECT_NE(messageOf(sandyLoam(), {3, slip, {}, {&load, 1}, {}, {{"phi", phi}}})
                  .find("phi: is not a soil field"),
              std::string::npos);
    EXPECT_NE(messageOf(sandyLoam(), {4, slip, {}, {&load, 1}, {}, {}})
                  .find("slip: has 3 values, expected 4 (one per sample) or 1"),
              std::string::npos);
    const double theta = 0.3;
    EXPECT_NE(messageOf(sandyLoam(), {3, slip, {}, {&load, 1}, {&theta, 1}, {}})
                  .find("either the load or the entry angle"),
              std::string::npos);
    const double no_load = -5.0;
    EXPECT_NE(messageOf(sandyLoam(), {3, slip, {}, {&no_load, 1}, {}, {}})
                  .find("load_N: -5 is outside the allowed range [0.01, 1e+05] N"),
              std::string::npos);
    std::vector<double> many(40, 999.0);
    const std::string listed =
        messageOf(sandyLoam(), {40,
                                {&slip[0], 1},
                                {},
                                {&load, 1},
                                {},
                                {{"c_kPa", {&many[0], 40}}, {"n", {&many[0], 40}}}});
    EXPECT_NE(listed.find("and 70 more invalid values"), std::string::npos) << listed;
    soil::SoilParameters bad = sandyLoam();
    bad.friction_angle_rad = 1.2;  // 68.75°
    EXPECT_NE(messageOf(bad, {3, slip, {}, {&load, 1}, {}, {}}).find("soil.phi_deg"),
              std::string::npos);
}

TEST(Batch, FlaggedSoilAndMissingEquilibriumAreReportedPerSample) {
    const std::vector<double> slip{0.1, 0.1, 0.1};
    const std::vector<double> phi{29.0, 75.0, 29.0};
    const std::vector<double> load{58.86, 58.86, 5e4};  // 5 t on a 9 cm wheel: sunk to the axle
    const BatchResult r =
        evaluateBatch(sandyLoam(), wheelA(), {3, slip, {}, load, {}, {{"phi_deg", phi}}}, {}, {},
                      InvalidSoil::kFlag);
    EXPECT_EQ(r.status[0], SampleStatus::kOk);
    EXPECT_EQ(r.status[1], SampleStatus::kInvalidSoil);
    EXPECT_EQ(r.status[2], SampleStatus::kNoEquilibrium);
    EXPECT_EQ(r.summary.ok, 1u);
    EXPECT_EQ(r.summary.failed, 2u);
    EXPECT_EQ(r.fx_n[1], 0.0);
    EXPECT_EQ(r.sinkage_m[2], 0.0);
    EXPECT_NE(r.fx_n[0], 0.0);
}

TEST(Batch, ReportsProgressAndStopsOnCancel) {
    constexpr std::size_t n = 400;
    std::vector<double> slip(n, 0.3);
    const double theta = 20 * kDeg;
    std::vector<double> seen;
    RunControl control{2, [&](double f) { seen.push_back(f); }, nullptr};
    evaluateBatch(sandyLoam(), wheelA(), {n, slip, {}, {}, {&theta, 1}, {}}, {}, control);
    ASSERT_FALSE(seen.empty());
    EXPECT_EQ(seen.back(), 1.0);
    for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_GT(seen[i], seen[i - 1]);
    std::atomic<bool> cancel{true};
    const BatchResult r = evaluateBatch(sandyLoam(), wheelA(), {n, slip, {}, {}, {&theta, 1}, {}},
                                        {}, {1, {}, &cancel});
    EXPECT_TRUE(r.summary.cancelled);
    EXPECT_EQ(r.summary.not_evaluated, n);
    EXPECT_EQ(r.status[17], SampleStatus::kNotEvaluated);
}

}  // namespace
}  // namespace terra::gsa
