#include "core/gsa/wheel_studies.h"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss.hpp>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "tests/core/gsa/gsa_test_support.h"
#include "tests/core/test_support.h"

namespace terra::gsa {
namespace {

using testing::kDeg;
using testing::reference;
using testing::sandyLoam;
using testing::wheelA;

// Gauss–Legendre nodes on [low, high] with weights summing to 1: the expectation under U(low,
// high) of a smooth function.
template <unsigned N>
std::vector<std::pair<double, double>> gaussNodes(double low, double high) {
    using Rule = boost::math::quadrature::gauss<double, N>;
    std::vector<std::pair<double, double>> out;
    const double mid = 0.5 * (low + high), half = 0.5 * (high - low);
    for (std::size_t k = 0; k < Rule::abscissa().size(); ++k) {
        const double x = Rule::abscissa()[k], w = 0.5 * Rule::weights()[k];
        out.push_back({mid + half * x, w});
        if (x != 0.0) out.push_back({mid - half * x, w});
    }
    return out;
}

using terra::testing::messageOf;

WheelStudy twoParameterStudy() {
    WheelStudy study;
    study.soil = sandyLoam();
    study.wheel = wheelA();
    study.grid.slips = {0.3};
    study.grid.load_n.reset();
    study.grid.entry_angle_rad = 25 * kDeg;
    study.outputs = {Output::kFx};
    study.parameters.add("phi_deg", Uniform{20.0, 35.0});
    study.parameters.add("K_m", Uniform{0.005, 0.04});
    return study;
}

TEST(WheelSobol, MatchesADoubleLoopEstimateWithTheEntryAngleGiven) {
    // Y = F_x(φ, K) at s = 0.3, θ_f = 25°. The double loop: E[Y | φ] by 15-point Gauss–Legendre
    // over K for each of 15 φ nodes, then V_φ = Var_φ(E[Y | φ]) by the same rule; likewise V_K;
    // S_Tφ = 1 − V_K / V for two parameters. All from the contact API, not the batch.
    const auto phis = gaussNodes<15>(20.0, 35.0), ks = gaussNodes<15>(0.005, 0.04);
    std::vector<std::vector<double>> y(phis.size(), std::vector<double>(ks.size()));
    for (std::size_t a = 0; a < phis.size(); ++a) {
        for (std::size_t b = 0; b < ks.size(); ++b) {
            soil::SoilParameters s = sandyLoam();
            s.friction_angle_rad = phis[a].first * kDeg;
            s.shear_modulus_m = ks[b].first;
            y[a][b] = reference(s, wheelA(), 0.3, 0.0, 0.0, 25 * kDeg).forces.fx;
        }
    }
    double mean = 0.0, square = 0.0, v_phi = 0.0, v_k = 0.0;
    for (std::size_t a = 0; a < phis.size(); ++a) {
        for (std::size_t b = 0; b < ks.size(); ++b) {
            mean += phis[a].second * ks[b].second * y[a][b];
            square += phis[a].second * ks[b].second * y[a][b] * y[a][b];
        }
    }
    for (std::size_t a = 0; a < phis.size(); ++a) {
        double m = 0.0;
        for (std::size_t b = 0; b < ks.size(); ++b) m += ks[b].second * y[a][b];
        v_phi += phis[a].second * (m - mean) * (m - mean);
    }
    for (std::size_t b = 0; b < ks.size(); ++b) {
        double m = 0.0;
        for (std::size_t a = 0; a < phis.size(); ++a) m += phis[a].second * y[a][b];
        v_k += ks[b].second * (m - mean) * (m - mean);
    }
    const double v = square - mean * mean;
    const double s_phi = v_phi / v, s_k = v_k / v;

    const SobolStudyResult r =
        sobolStudy(twoParameterStudy(), {2048, 1, {}, 0.05, 0}, testing::onThreads(2));
    ASSERT_EQ(r.status, StudyStatus::kCompleted) << r.message;
    const Eigen::MatrixXd s1 = r.firstOrder(0), st = r.total(0);
    const Eigen::MatrixXd c1 = r.firstOrderConf(0), ct = r.totalConf(0);
    // Within the 95 % interval and 0.005 of the double loop (docs/sensitivity.md).
    EXPECT_LE(std::abs(s1(0, 0) - s_phi), std::max(c1(0, 0), 1e-3)) << s1(0, 0) << " " << s_phi;
    EXPECT_LE(std::abs(s1(1, 0) - s_k), std::max(c1(1, 0), 1e-3)) << s1(1, 0) << " " << s_k;
    EXPECT_LE(std::abs(st(0, 0) - (1 - s_k)), std::max(ct(0, 0), 1e-3));
    EXPECT_LE(std::abs(st(1, 0) - (1 - s_phi)), std::max(ct(1, 0), 1e-3));
    RecordProperty("S1_phi",
                   std::to_string(s1(0, 0)) + " (double loop " + std::to_string(s_phi) + ")");
    RecordProperty("S1_K", std::to_string(s1(1, 0)) + " (double loop " + std::to_string(s_k) + ")");
    for (int i = 0; i < 2; ++i) {
        EXPECT_NEAR(s1(i, 0), i == 0 ? s_phi : s_k, 0.005);
        EXPECT_NEAR(st(i, 0), i == 0 ? 1 - s_k : 1 - s_phi, 0.005);
    }
    EXPECT_NEAR(r.indices.variance[0], v, 0.02 * v);
    EXPECT_EQ(r.evaluations, 2048u * 4u);
}

TEST(WheelSobol, MatchesADoubleLoopEstimateWithEntryAngleSolves) {
    // Three parameters, θ_f solved for W = 58.86 N at s = 0.2: S_i from Var(E[Y | X_i]) and S_Ti
    // from 1 − Var(E[Y | X_~i]) / V on a 7 × 7 × 7 Gauss–Legendre grid of cold solves.
    const auto phis = gaussNodes<7>(22.0, 34.0), cs = gaussNodes<7>(0.0, 4.0),
               ks = gaussNodes<7>(0.01, 0.035);
    const std::size_t n = phis.size();
    std::vector<double> y(n * n * n), w(n * n * n);
    for (std::size_t a = 0; a < n; ++a) {
        for (std::size_t b = 0; b < n; ++b) {
            for (std::size_t c = 0; c < n; ++c) {
                soil::SoilParameters s = sandyLoam();
                s.friction_angle_rad = phis[a].first * kDeg;
                s.cohesion_pa = cs[b].first * 1e3;
                s.shear_modulus_m = ks[c].first;
                const testing::Reference ref = reference(s, wheelA(), 0.2, 0.0, 58.86);
                ASSERT_TRUE(ref.ok);
                y[(a * n + b) * n + c] = ref.forces.fx;
                w[(a * n + b) * n + c] = phis[a].second * cs[b].second * ks[c].second;
            }
        }
    }
    double mean = 0.0, square = 0.0;
    for (std::size_t k = 0; k < y.size(); ++k) mean += w[k] * y[k], square += w[k] * y[k] * y[k];
    const double v = square - mean * mean;
    const std::vector<std::pair<double, double>>* nodes[3] = {&phis, &cs, &ks};
    auto index = [&](std::size_t i, std::size_t fixed, std::size_t o1, std::size_t o2) {
        std::size_t idx[3];
        idx[i] = fixed, idx[(i + 1) % 3] = o1, idx[(i + 2) % 3] = o2;
        return (idx[0] * n + idx[1]) * n + idx[2];
    };
    double s1[3], st[3];
    for (std::size_t i = 0; i < 3; ++i) {
        const auto& ni = *nodes[i];
        const auto& n1 = *nodes[(i + 1) % 3];
        const auto& n2 = *nodes[(i + 2) % 3];
        double vi = 0.0, v_rest = 0.0;
        for (std::size_t f = 0; f < n; ++f) {  // Var over X_i of E[Y | X_i]
            double m = 0.0;
            for (std::size_t o1 = 0; o1 < n; ++o1) {
                for (std::size_t o2 = 0; o2 < n; ++o2) {
                    m += n1[o1].second * n2[o2].second * y[index(i, f, o1, o2)];
                }
            }
            vi += ni[f].second * (m - mean) * (m - mean);
        }
        for (std::size_t o1 = 0; o1 < n; ++o1) {  // Var over X_~i of E[Y | X_~i]
            for (std::size_t o2 = 0; o2 < n; ++o2) {
                double m = 0.0;
                for (std::size_t f = 0; f < n; ++f) m += ni[f].second * y[index(i, f, o1, o2)];
                v_rest += n1[o1].second * n2[o2].second * (m - mean) * (m - mean);
            }
        }
        s1[i] = vi / v, st[i] = 1.0 - v_rest / v;
    }
    WheelStudy study;
    study.soil = sandyLoam();
    study.wheel = wheelA();
    study.grid.slips = {0.2};
    study.parameters.add("phi_deg", Uniform{22.0, 34.0});
    study.parameters.add("c_kPa", Uniform{0.0, 4.0});
    study.parameters.add("K_m", Uniform{0.01, 0.035});
    const SobolStudyResult r = sobolStudy(study, {1024, 3, {}, 0.05, 0}, testing::onThreads(2));
    ASSERT_EQ(r.status, StudyStatus::kCompleted) << r.message;
    for (int i = 0; i < 3; ++i) {
        SCOPED_TRACE(r.parameters[i]);
        RecordProperty("S1_" + r.parameters[i], std::to_string(r.indices.first_order(i, 0)) +
                                                    " (double loop " + std::to_string(s1[i]) + ")");
        RecordProperty("ST_" + r.parameters[i], std::to_string(r.indices.total(i, 0)) +
                                                    " (double loop " + std::to_string(st[i]) + ")");
        const double c1 = r.indices.first_order_conf(i, 0), ct = r.indices.total_conf(i, 0);
        EXPECT_LE(std::abs(r.indices.first_order(i, 0) - s1[i]), std::max(c1, 1e-3))
            << r.indices.first_order(i, 0) << " vs " << s1[i];
        EXPECT_LE(std::abs(r.indices.total(i, 0) - st[i]), std::max(ct, 1e-3))
            << r.indices.total(i, 0) << " vs " << st[i];
        EXPECT_NEAR(r.indices.first_order(i, 0), s1[i], 0.005);
        EXPECT_NEAR(r.indices.total(i, 0), st[i], 0.005);
    }
}

WheelStudy smallStudyWithLoad() {
    WheelStudy study;
    study.soil = sandyLoam();
    study.wheel = wheelA();
    study.grid.slips = {0.1, 0.6};
    study.outputs = {Output::kFx, Output::kSinkage, Output::kEntryAngle};
    study.parameters.add("phi_deg", Uniform{20.0, 35.0});
    study.parameters.add("n", Uniform{0.5, 1.1});
    return study;
}

TEST(WheelSobol, ChunksEvaluatedSeparatelyAssembleIntoTheSameBits) {
    // What a distributed run does: cut the design's rows into chunks, evaluate each on its own,
    // concatenate, estimate. Bit-identical to the local run, on any thread count.
    const WheelStudy study = smallStudyWithLoad();
    const SobolOptions options{64, 5, {200, 0.95, 2}, 0.05, 0};
    const SobolStudyResult local = sobolStudy(study, options, testing::onThreads(1));
    const SobolStudyResult threaded = sobolStudy(study, options, testing::onThreads(2));
    const WheelTarget target(study);
    const SaltelliDesign design(study.parameters, 64, 5);
    std::vector<TargetValues> chunks;
    const std::size_t bounds[] = {0, 5, 100, 101, 256};  // some cut base samples apart
    for (std::size_t c = 0; c + 1 < std::size(bounds); ++c) {
        chunks.push_back(
            target.evaluate(design.rows(bounds[c], bounds[c + 1]), testing::onThreads(1)));
    }
    const SobolStudyResult distributed = sobolResult(target, design, concatenate(chunks), options);
    for (const SobolStudyResult* other : {&threaded, &distributed}) {
        ASSERT_EQ(other->status, StudyStatus::kCompleted);
        for (const auto& [a, b] :
             {std::pair{&local.indices.first_order, &other->indices.first_order},
              std::pair{&local.indices.total, &other->indices.total},
              std::pair{&local.indices.first_order_conf, &other->indices.first_order_conf},
              std::pair{&local.indices.total_conf, &other->indices.total_conf}}) {
            ASSERT_EQ(a->size(), b->size());
            EXPECT_EQ(std::memcmp(a->data(), b->data(), a->size() * sizeof(double)), 0);
        }
    }
    EXPECT_EQ(local.indices.first_order.cols(), 6);  // 3 outputs × 2 slips
    EXPECT_EQ(local.evaluations, 64u * 4u * 2u);
}

TEST(WheelSobol, FailedSamplesAreCountedDroppedAndRefusedAboveTheThreshold) {
    // c ~ N(0.5, 1²) untruncated: P(c < 0) = Φ(−0.5) = 30.9 % of the values fall outside c's range
    // [0, 200] kPa. Those rows are flagged, never evaluated; a base sample is dropped when its A
    // or its B value of c is negative.
    WheelStudy study;
    study.soil = sandyLoam();
    study.wheel = wheelA();
    study.grid.slips = {0.3};
    study.grid.load_n.reset();
    study.grid.entry_angle_rad = 20 * kDeg;
    study.parameters.add("phi_deg", Uniform{25.0, 32.0});
    study.parameters.add("c_kPa", Normal{0.5, 1.0});
    const SaltelliDesign design(study.parameters, 512, 4);
    const Eigen::MatrixXd rows = design.rows(0, design.rows());
    std::size_t negative_rows = 0, dropped = 0;
    for (std::size_t j = 0; j < 512; ++j) {
        bool any = false;
        for (std::size_t k = 0; k < 4; ++k) {
            const bool negative = rows(j * 4 + k, 1) < 0.0;
            negative_rows += negative, any = any || negative;
        }
        dropped += any;
    }
    const SobolStudyResult refused =
        sobolStudy(study, {512, 4, {100, 0.95, 1}, 0.05, 0}, testing::onThreads(2));
    EXPECT_EQ(refused.status, StudyStatus::kTooManyFailures);
    EXPECT_FALSE(refused.usable());
    EXPECT_EQ(refused.indices.first_order.size(), 0);
    EXPECT_EQ(refused.failures[0].invalid_soil, negative_rows);
    EXPECT_EQ(refused.dropped_samples[0], dropped);
    EXPECT_NE(refused.message.find("s = 0.3, β = 0°: " + std::to_string(dropped) +
                                   " of 512 base samples"),
              std::string::npos)
        << refused.message;
    EXPECT_NE(refused.message.find("with a soil outside its allowed range"), std::string::npos);
    EXPECT_NE(refused.message.find("above max_failed_fraction = 5 %"), std::string::npos);
    EXPECT_NEAR(static_cast<double>(dropped) / 512, 1 - std::pow(1 - 0.3085, 2), 0.05);
    // Allowed: the indices use the remaining samples and are finite.
    const SobolStudyResult kept =
        sobolStudy(study, {512, 4, {100, 0.95, 1}, 1.0, 0}, testing::onThreads(2));
    ASSERT_EQ(kept.status, StudyStatus::kCompleted);
    EXPECT_EQ(kept.indices.samples_used[0], 512 - dropped);
    EXPECT_TRUE(kept.indices.first_order.allFinite());
    EXPECT_TRUE(kept.indices.total_conf.allFinite());
}

TEST(WheelSobol, SamplesWithoutEquilibriumAreCountedAsTheContactApiFindsThem) {
    // W = 600 N on wheel A: at s = 0.3 the soil carries that load before θ_f = 90° only when
    // k_φ is above about 335 kN/m^(n+2), so part of k_φ ∈ [50, 1550] has no equilibrium.
    WheelStudy study;
    study.soil = sandyLoam();
    study.wheel = wheelA();
    study.grid.slips = {0.3};
    study.grid.load_n = 600.0;
    study.parameters.add("phi_deg", Uniform{25.0, 32.0});
    study.parameters.add("kphi", Uniform{50.0, 1550.0});
    const SaltelliDesign design(study.parameters, 32, 6);
    const Eigen::MatrixXd rows = design.rows(0, design.rows());
    std::size_t failed = 0;
    for (Eigen::Index r = 0; r < rows.rows(); ++r) {
        soil::SoilParameters s = sandyLoam();
        s.friction_angle_rad = rows(r, 0) * kDeg;
        s.frictional_modulus = rows(r, 1) * 1e3;
        failed += !reference(s, wheelA(), 0.3, 0.0, 600.0).ok;
    }
    ASSERT_GT(failed, 0u);
    const SobolStudyResult r =
        sobolStudy(study, {32, 6, {50, 0.95, 1}, 0.05, 0}, testing::onThreads(2));
    EXPECT_EQ(r.failures[0].no_equilibrium, failed);
    EXPECT_EQ(r.status, StudyStatus::kTooManyFailures);
    EXPECT_NE(r.message.find(std::to_string(failed) + " without equilibrium"), std::string::npos)
        << r.message;
}

TEST(WheelSobol, CancelKeepsWhatWasEvaluated) {
    WheelStudy study = twoParameterStudy();
    std::atomic<bool> cancel{false};
    RunControl control{1,
                       [&](double f) {
                           if (f > 0.3) cancel = true;
                       },
                       &cancel};
    const SobolStudyResult r = sobolStudy(study, {1024, 1, {50, 0.95, 1}, 0.05, 512}, control);
    EXPECT_EQ(r.status, StudyStatus::kCancelled);
    EXPECT_LT(r.evaluations, 4096u);
    EXPECT_GT(r.evaluations, 0u);
    EXPECT_TRUE(r.indices.first_order.allFinite());
    EXPECT_NE(r.message.find("cancelled"), std::string::npos);
}

TEST(WheelSobol, BadSettingsNameTheFieldTheValueAndTheRange) {
    WheelStudy study = twoParameterStudy();
    study.parameters = {};
    study.parameters.add("phi_deg", Uniform{20.0, 75.0});
    study.parameters.add("friction", Uniform{0.0, 1.0});
    study.grid.slips = {0.1, 1.5};
    const std::string m = messageOf([&] { sobolStudy(study, {}); });
    EXPECT_NE(m.find("parameters.phi_deg: the range [20, 75] reaches 75, outside the allowed "
                     "range [0, 60) deg"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("parameters.friction: is not a soil field"), std::string::npos);
    EXPECT_NE(m.find("slip: 1.5 is outside the allowed range [-1, 1]"), std::string::npos);
    EXPECT_NE(messageOf([&] {
                  sobolStudy(twoParameterStudy(), {64, 1, {}, 2.0, 0});
              }).find("max_failed_fraction: 2 is outside the allowed range [0, 1]"),
              std::string::npos);
    EXPECT_NE(messageOf([&] {
                  sobolStudy(twoParameterStudy(), {1, 1, {}, 0.05, 0});
              }).find("samples: 1 is outside the allowed range [2, 1e+12]"),
              std::string::npos);
    WheelStudy truncated = twoParameterStudy();
    truncated.parameters = {};
    truncated.parameters.add("c_kPa", Normal{1.0, 1.0, -1.0, INFINITY});
    EXPECT_NE(messageOf([&] { WheelTarget{truncated}; })
                  .find("parameters.c_kPa: the truncation [-1, inf] reaches -1, outside the "
                        "allowed range [0, 200] kPa"),
              std::string::npos);
    WheelStudy twice = twoParameterStudy();
    twice.outputs = {Output::kFx, Output::kFx};
    EXPECT_NE(messageOf([&] { WheelTarget{twice}; }).find("outputs: Fx_N is given twice"),
              std::string::npos);
    EXPECT_NE(messageOf([&] {
                  morrisStudy(twoParameterStudy(), {8, 3, 1, {}, 0.05});
              }).find("levels: 3 must be an even number"),
              std::string::npos);
}

TEST(WheelMorris, ElementaryEffectsAreTheModelsDifferences) {
    // Two trajectories recomputed from the contact API: μ_i is the mean of their elementary
    // effects (F_x difference over the signed step, in units of the whole range).
    const WheelStudy study = twoParameterStudy();
    const MorrisOptions options{2, 4, 9, {0, 0.95, 1}, 0.05};
    const MorrisStudyResult r = morrisStudy(study, options, testing::onThreads(1));
    ASSERT_EQ(r.status, StudyStatus::kCompleted);
    const MorrisDesign design(study.parameters, 2, 4, 9);
    const Eigen::MatrixXd rows = design.rows(0, design.rows());
    double sum[2] = {0, 0};
    for (std::size_t t = 0; t < 2; ++t) {
        const MorrisTrajectory path = design.trajectory(t);
        double previous = 0.0;
        for (std::size_t k = 0; k < 3; ++k) {
            soil::SoilParameters s = sandyLoam();
            s.friction_angle_rad = rows(t * 3 + k, 0) * kDeg;
            s.shear_modulus_m = rows(t * 3 + k, 1);
            const double fx = reference(s, wheelA(), 0.3, 0.0, 0.0, 25 * kDeg).forces.fx;
            if (k > 0) {
                const std::size_t i = path.order[k - 1];
                sum[i] += (fx - previous) / (path.direction[i] * 2.0 / 3.0);
            }
            previous = fx;
        }
    }
    EXPECT_NEAR(r.indices.mu(0, 0), sum[0] / 2, 1e-9 * std::abs(sum[0]));
    EXPECT_NEAR(r.indices.mu(1, 0), sum[1] / 2, 1e-9 * std::abs(sum[1]));
    EXPECT_GT(r.indices.mu_star(0, 0), 0.0);
}

}  // namespace
}  // namespace terra::gsa
