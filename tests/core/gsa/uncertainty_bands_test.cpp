#include "core/gsa/uncertainty_bands.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "tests/core/gsa/gsa_test_support.h"

namespace terra::gsa {
namespace {

using testing::kDeg;
using testing::reference;
using testing::sandyLoam;
using testing::wheelA;

// The q-th percentile of unsorted values by selection (std::nth_element) and the same
// interpolation rule, written independently of gsa::percentile.
double selectPercentile(std::vector<double> v, double q) {
    const double h = (v.size() - 1) * q / 100.0;
    const auto k = static_cast<std::size_t>(h);
    std::nth_element(v.begin(), v.begin() + k, v.end());
    const double lo = v[k];
    if (k + 1 == v.size()) return lo;
    const double hi = *std::min_element(v.begin() + k + 1, v.end());
    return lo + (h - k) * (hi - lo);
}

TEST(Percentile, AgreesWithNumpysDefault) {
    // numpy.percentile (linear): [1,2,3,4] → 25 %: 1.75, 50 %: 2.5; [1..5] → 90 %: 4.6.
    const std::vector<double> four{1, 2, 3, 4}, five{1, 2, 3, 4, 5};
    EXPECT_DOUBLE_EQ(percentile(four, 25), 1.75);
    EXPECT_DOUBLE_EQ(percentile(four, 50), 2.5);
    EXPECT_DOUBLE_EQ(percentile(five, 90), 4.6);
    EXPECT_DOUBLE_EQ(percentile(five, 0), 1.0);
    EXPECT_DOUBLE_EQ(percentile(five, 100), 5.0);
    EXPECT_THROW(percentile(std::vector<double>{}, 50), std::invalid_argument);
}

WheelStudy bandStudy() {
    WheelStudy study;
    study.soil = sandyLoam();
    study.wheel = wheelA();
    study.grid.slips = {0.1, 0.5};
    study.grid.slip_angles_rad = {0.0, 10 * kDeg};
    study.outputs = {Output::kFx, Output::kSinkage};
    return study;
}

void checkAgainstReference(const WheelStudy& study, const BandOptions& options) {
    const BandResult r = uncertaintyBands(study, options, testing::onThreads(2));
    ASSERT_EQ(r.status, StudyStatus::kCompleted) << r.message;
    const BandSample sample(study.parameters, options.samples, options.seed);
    const Eigen::MatrixXd rows = sample.rows(0, sample.rows());
    for (std::size_t p = 0; p < study.grid.size(); ++p) {
        std::vector<double> fx, h;
        for (Eigen::Index k = 0; k < rows.rows(); ++k) {
            soil::SoilParameters s = sandyLoam();
            for (std::size_t i = 0; i < study.parameters.dimension(); ++i) {
                soil::setUserValue(s, *soil::findSoilField(study.parameters.names()[i]),
                                   rows(k, i));
            }
            const testing::Reference ref =
                reference(s, wheelA(), study.grid.slip(p), study.grid.slipAngle(p), 58.86);
            if (!ref.ok) continue;
            fx.push_back(ref.forces.fx);
            h.push_back(0.092 * (1 - std::cos(ref.entry_angle_rad)));
        }
        EXPECT_EQ(r.used[p], fx.size());
        for (std::size_t q = 0; q < options.percentiles.size(); ++q) {
            const double pq = options.percentiles[q];
            EXPECT_NEAR(r.bands[0](q, p), selectPercentile(fx, pq), 1e-12 * std::abs(fx[0]))
                << "F_x p" << pq << " at point " << p;
            EXPECT_NEAR(r.bands[1](q, p), selectPercentile(h, pq), 1e-15)
                << "sinkage p" << pq << " at point " << p;
        }
        for (std::size_t q = 1; q < options.percentiles.size(); ++q) {
            EXPECT_LE(r.bands[0](q - 1, p), r.bands[0](q, p));
        }
    }
}

TEST(UncertaintyBands, PercentilesOfRangesMatchAnIndependentComputation) {
    WheelStudy study = bandStudy();
    study.parameters.add("phi_deg", Uniform{20.0, 35.0});
    study.parameters.add("K_m", Uniform{0.005, 0.04});
    checkAgainstReference(study, {101, 3, {5.0, 50.0, 95.0}, 0.05});
}

TEST(UncertaintyBands, PercentilesOfAPosteriorMatchAnIndependentComputation) {
    // An identification-like posterior of (φ, c, K) with correlations.
    WheelStudy study = bandStudy();
    Eigen::Matrix3d cov;
    cov << 1.0, -0.3, 0.0005, -0.3, 0.16, -0.0001, 0.0005, -0.0001, 4e-6;
    study.parameters.addMultivariateNormal({"phi_deg", "c_kPa", "K_m"},
                                           Eigen::Vector3d(29.0, 1.7, 0.025), cov);
    checkAgainstReference(study, {64, 8, {2.5, 50.0, 97.5}, 0.05});
}

TEST(UncertaintyBands, TableHasOneRowPerPointAndNamedColumns) {
    WheelStudy study = bandStudy();
    study.grid.load_n.reset();
    study.grid.entry_angle_rad = 20 * kDeg;
    study.parameters.add("phi_deg", Uniform{20.0, 35.0});
    const BandResult r = uncertaintyBands(study, {32, 1, {5.0, 95.0}, 0.05}, testing::onThreads(1));
    const Table t = r.table();
    ASSERT_EQ(t.rows.size(), 4u);
    EXPECT_EQ(t.columns[3], "Fx_N_mean");
    EXPECT_EQ(t.columns[4], "Fx_N_p5");
    EXPECT_EQ(t.columns[8], "sinkage_m_p95");
    EXPECT_EQ(t.rows[3][t.column("slip_angle_deg")], 10.0);
    EXPECT_EQ(t.rows[3][t.column("slip")], 0.5);
    EXPECT_EQ(t.rows[3][t.column("samples")], 32.0);
    EXPECT_LT(t.rows[0][t.column("Fx_N_p5")], t.rows[0][t.column("Fx_N_p95")]);
}

TEST(UncertaintyBands, BadSettingsNameTheFieldTheValueAndTheRange) {
    WheelStudy study = bandStudy();
    study.parameters.add("phi_deg", Uniform{20.0, 35.0});
    try {
        uncertaintyBands(study, {64, 1, {5.0, 150.0}, 0.05});
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(
            std::string(e.what()).find("percentiles: 150 is outside the allowed range [0, 100] %"),
            std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace terra::gsa
