// The observation model's errors in variables (observation_model.h, docs/identification.md §8,
// "An uncertain slip"): the slip slope g = ∂prediction/∂s against a central difference of the
// prediction at s ± h (a second computation: the model evaluated twice, with θ_f solved again from
// the load at each slip), and the whitened residual and Jacobian against the inverse of the
// covariance I + σ_s² g gᵀ formed and inverted by Eigen.
#include "core/identification/observation_model.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <cmath>

#include "core/identification/identify.h"
#include "core/identification/synthetic.h"
#include "tests/core/contact/test_soils.h"
#include "tests/core/identification/identification_test_support.h"
#include "tests/core/test_support.h"

namespace terra::identification {
namespace {

using terra::testing::kDeg;
using testing::fromLoad;
using testing::kWheelA;
using testing::truthOf;

namespace soils = contact::testing;

// Sandy loam, 58.86 N, slips 0.1 / 0.45 / 0.8, slip angle 0 or 8° (entry angle measured).
DataSet byAngle(double slip_angle_rad) {
    SyntheticSpec spec;
    spec.slips = {0.1, 0.45, 0.8};
    spec.slip_angle_rad = slip_angle_rad;
    return synthesize(soils::sandyLoam(), spec).data;
}

struct ObservationCase {
    const char* name;
    DataSet data;
    DataSource source;
    contact::ContactModel model;
    double slip_sinkage;  // S of Eq. S.1
};

std::vector<ObservationCase> cases() {
    DataSet load = fromLoad(soils::sandyLoam(), {40.0, 80.0});
    return {{"entry angle, full", byAngle(0.0), DataSource::kEntryAngle,
             contact::ContactModel::kFull, 0.0},
            {"entry angle, full, 8 deg", byAngle(8.0 * kDeg), DataSource::kEntryAngle,
             contact::ContactModel::kFull, 0.0},
            {"load, full", load, DataSource::kLoad, contact::ContactModel::kFull, 0.0},
            {"load, full, Lyasko S", load, DataSource::kLoad, contact::ContactModel::kFull, 0.8},
            {"load, quadratic", load, DataSource::kLoad, contact::ContactModel::kQuadratic, 0.0}};
}

ObservationModel modelOf(const ObservationCase& c, const DataSet& data) {
    const Result<ModelSetup> setup =
        setupModel(data, c.source, std::nullopt, 0.02, 0.0, c.slip_sinkage, c.model);
    EXPECT_TRUE(setup.ok()) << setup.message();
    return ObservationModel(data, kWheelA, setup.value());
}

TEST(ObservationModel, SlipSlopeIsTheCentralDifferenceOfThePrediction) {
    const ParameterVector p = truthOf(soils::sandyLoam());
    constexpr double h = 1e-5;
    for (const ObservationCase& c : cases()) {
        SCOPED_TRACE(c.name);
        const ObservationModel model = modelOf(c, c.data);
        for (std::size_t i = 0; i < c.data.samples.size(); i += 2) {
            SCOPED_TRACE(i);
            // s = 0 is a kink of the model: below it j_t (Eq. 2.14) turns negative near θ_f.
            if (c.data.samples[i].slip == 0.0) continue;
            DataSet up = c.data, down = c.data;
            up.samples[i].slip += h;
            down.samples[i].slip -= h;
            const Prediction a = modelOf(c, up).predict(i, p);
            const Prediction b = modelOf(c, down).predict(i, p);
            const std::optional<ChannelValues> g = model.slipSlope(i, p);
            ASSERT_TRUE(a.ok && b.ok && g);
            for (int k = 0; k < kChannelCount; ++k) {
                if (!model.channels(i)[k]) continue;
                const double difference = (a.values[k] - b.values[k]) / (2 * h);
                EXPECT_NEAR((*g)[k], difference, 1e-5 * std::abs(difference) + 1e-9)
                    << channelNames()[k];
            }
            if (c.source == DataSource::kLoad) {
                EXPECT_EQ((*g)[kFzChannel], 0.0);
            }
        }
    }
}

TEST(ObservationModel, AnUncertainSlipWhitensByTheInverseSquareRootOfItsCovariance) {
    const ParameterVector truth = truthOf(soils::sandyLoam());
    ParameterVector p = truth;  // away from the truth, so that the residuals are not zero
    p[kPhi] += 2.0 * kDeg;
    p[kKs] *= 1.1;
    const ParameterVector u = toSolver(p);
    const ChannelValues sigma{0.2, 0.9, 0.02, 2e-4};
    constexpr int n = kFullParameterCount;
    for (const ObservationCase& c : cases()) {
        SCOPED_TRACE(c.name);
        DataSet uncertain = c.data;
        for (Sample& s : uncertain.samples) s.slip_std = 0.03;
        const ObservationModel exact = modelOf(c, c.data), eiv = modelOf(c, uncertain);
        for (std::size_t i = 0; i < c.data.samples.size(); ++i) {
            SCOPED_TRACE(i);
            const int m = exact.residualCount(i);
            Eigen::VectorXd e(m), r(m);
            Eigen::Matrix<double, Eigen::Dynamic, n, Eigen::RowMajor> je(m, n), jr(m, n);
            ASSERT_TRUE(exact.residuals(i, u.data(), sigma, e.data(), je.data()));
            ASSERT_TRUE(eiv.residuals(i, u.data(), sigma, r.data(), jr.data()));
            // Without the Jacobian (θ_f's derivatives then come from the load's Newton solve):
            // the same whitened residual.
            Eigen::VectorXd alone(m);
            ASSERT_TRUE(eiv.residuals(i, u.data(), sigma, alone.data(), nullptr));
            EXPECT_LT((alone - r).norm(), 1e-9 * r.norm());
            // The covariance of the residuals in noise units, from the slope over σ.
            const ChannelValues slope = *exact.slipSlope(i, p);
            Eigen::VectorXd g(m);
            int row = 0;
            for (int k = 0; k < kChannelCount; ++k) {
                if (exact.channels(i)[k]) g[row++] = slope[k] / sigma[k];
            }
            const Eigen::MatrixXd cov =
                Eigen::MatrixXd::Identity(m, m) + 0.03 * 0.03 * g * g.transpose();
            const Eigen::MatrixXd inverse = cov.inverse();
            EXPECT_NEAR(r.squaredNorm(), e.dot(inverse * e), 1e-9 * e.squaredNorm());
            const Eigen::MatrixXd information = je.transpose() * inverse * je;
            const Eigen::MatrixXd whitened = jr.transpose() * jr;
            EXPECT_LT((whitened - information).norm(), 1e-9 * information.norm());
            EXPECT_LT(r.squaredNorm(), e.squaredNorm());  // the slip explains part of e
        }
    }
}

TEST(ObservationModel, ASlipWithoutAStandardErrorIsTakenAsExact) {
    const ObservationCase c = cases()[2];
    DataSet zero = c.data;
    for (Sample& s : zero.samples) s.slip_std = 0.0;
    const ObservationModel exact = modelOf(c, c.data), declared_zero = modelOf(c, zero);
    const ParameterVector u = toSolver(truthOf(soils::sandyLoam()));
    const ChannelValues sigma{0.2, 0.9, 0.02, 2e-4};
    std::array<double, kChannelCount> a{}, b{};
    constexpr std::size_t kRows = kChannelCount, kColumns = kFullParameterCount;
    std::array<double, kRows * kColumns> ja{}, jb{};
    for (std::size_t i = 0; i < c.data.samples.size(); ++i) {
        ASSERT_TRUE(exact.residuals(i, u.data(), sigma, a.data(), ja.data()));
        ASSERT_TRUE(declared_zero.residuals(i, u.data(), sigma, b.data(), jb.data()));
        EXPECT_EQ(a, b);
        EXPECT_EQ(ja, jb);
    }
}

// A batch fit with its noise estimated: the levels come from the unwhitened residuals, which
// hold the uncertain slips' scatter the whitening carries again, so χ² falls below its degrees
// of freedom; the covariance is then not shrunk by χ²/dof (docs/identification.md §8): the std
// are those of the same fit with the estimated levels given (scale 1), not smaller.
TEST(ObservationModel, UncertainSlipsDoNotShrinkAnEstimatedNoiseFitsCovariance) {
    SyntheticSpec spec;
    spec.loads_n = {30.0, 58.86, 90.0};
    for (int i = 0; i < 40; ++i) spec.slips.push_back(0.05 + 0.8 * i / 39.0);
    spec.noise.fx.relative = 0.01;
    spec.noise.fz.relative = 0.01;
    spec.noise.my.relative = 0.01;
    DataSet data = synthesize(soils::sandyLoam(), spec).data;
    boost::random::mt19937_64 engine(3);
    boost::random::normal_distribution<double> normal(0.0, 0.01);
    for (Sample& s : data.samples) {
        s.slip += normal(engine);
        s.slip_std = 0.01;
    }
    IdentifyOptions o;
    o.max_shear_deformation_m = 0.02;
    const IdentificationReport estimated = identify(data, kWheelA, o);
    ASSERT_TRUE(estimated.usable()) << estimated.message;
    ASSERT_TRUE(estimated.noise_estimated);
    const int dof = estimated.residuals - 7;
    EXPECT_LT(estimated.chi2, 0.9 * dof);  // the double-counted scatter
    o.noise = estimated.noise;
    const IdentificationReport given = identify(data, kWheelA, o);
    ASSERT_TRUE(given.usable()) << given.message;
    for (int k = 0; k < kJmax; ++k) {
        EXPECT_NEAR(estimated.parameters[k], given.parameters[k],
                    1e-6 * std::abs(given.parameters[k]));
        EXPECT_NEAR(estimated.uncertainty.std[k], given.uncertainty.std[k],
                    1e-3 * given.uncertainty.std[k])
            << parameterInfo()[k].name;
    }
}

}  // namespace
}  // namespace terra::identification
