// The "sensitivity-global" and "uncertainty-bands" analyses against independent values: limit
// cases of the indices (one parameter carries all the variance, a parameter the output does not
// depend on carries none), the nominal curve against the contact model itself, the posterior's
// covariance typed from its definition, and the strict settings reader.
#include "core/analysis/global_sensitivity.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/common/units.h"
#include "core/io/parameters_json.h"
#include "tests/core/gsa/gsa_test_support.h"

namespace terra::analysis {
namespace {

using gsa::testing::kDeg;
using gsa::testing::reference;

Inputs tableSandyLoamOnA() {
    Inputs in;
    in.soil = gsa::testing::sandyLoam();
    in.wheel = gsa::testing::wheelA();
    return in;
}

std::vector<Issue> readIssues(const nlohmann::json& json, GlobalSensitivitySettings& out) {
    std::vector<Issue> issues;
    io::ObjectReader r(json, issues, "s.json", "analyses[0]");
    readGlobalSensitivitySettings(r, out);
    r.finish();
    return issues;
}

bool mentions(const std::vector<Issue>& issues, const std::string& where, const std::string& text) {
    for (const Issue& i : issues) {
        if (i.where == "s.json: analyses[0]." + where && i.message.find(text) != std::string::npos)
            return true;
    }
    return false;
}

// Independent of γ at β = 0: bulldozing (the only place γ enters, Eq. 2.27) acts sideways.
TEST(GlobalSensitivity, UnitWeightDoesNotMoveFxAtZeroSlipAngle) {
    gsa::testing::Reference a, b;
    soil::SoilParameters soil = gsa::testing::sandyLoam();
    soil.unit_weight_n_m3 = 10e3;
    a = reference(soil, gsa::testing::wheelA(), 0.3, 0.0, 58.86);
    soil.unit_weight_n_m3 = 20e3;
    b = reference(soil, gsa::testing::wheelA(), 0.3, 0.0, 58.86);
    ASSERT_TRUE(a.ok && b.ok);
    EXPECT_EQ(a.forces.fx, b.forces.fx);
}

TEST(GlobalSensitivity, ParameterWithoutEffectHasZeroIndicesAndOneParameterCarriesAll) {
    GlobalSensitivitySettings s;
    s.study.parameters = {{"phi_deg", gsa::Uniform{20.0, 35.0}},
                          {"gamma_kN_m3", gsa::Uniform{10.0, 20.0}}};
    s.study.slips = {0.3};
    s.study.outputs = {"Fx_N"};
    s.samples = 512;
    s.resamples = 200;
    const GlobalSensitivityResult r = computeGlobalSensitivity(tableSandyLoamOnA(), s);
    ASSERT_EQ(r.status(), gsa::StudyStatus::kCompleted) << r.message();
    const gsa::SobolIndices& x = r.sobol->indices;
    // γ: f(A) and f(AB_γ) are the same numbers, so Jansen's S_T is 0 exactly; S_1 within its
    // interval of 0.
    EXPECT_EQ(x.total(1, 0), 0.0);
    EXPECT_LE(std::abs(x.first_order(1, 0)), x.first_order_conf(1, 0) + 1e-12);
    // φ carries all the variance: S_1 = S_T = 1 within the intervals.
    EXPECT_NEAR(x.first_order(0, 0), 1.0, x.first_order_conf(0, 0) + 0.02);
    EXPECT_NEAR(x.total(0, 0), 1.0, x.total_conf(0, 0) + 0.02);
    // The table holds the same numbers under the documented column names.
    const Table t = r.table();
    ASSERT_EQ(t.rows.size(), 1u);
    EXPECT_EQ(t.rows[0][t.column("slip")], 0.3);
    EXPECT_EQ(t.rows[0][t.column("slip_angle_deg")], 0.0);
    EXPECT_EQ(t.rows[0][t.column("Fx_N_S1_phi_deg")], x.first_order(0, 0));
    EXPECT_EQ(t.rows[0][t.column("Fx_N_ST_gamma_kN_m3")], 0.0);
    EXPECT_EQ(t.rows[0][t.column("Fx_N_samples")], 512.0);
}

TEST(GlobalSensitivity, SumsOfIndicesBracketOneAndTheSeedReproduces) {
    GlobalSensitivitySettings s;  // the default four parameters
    s.study.slips = {0.2, 0.5};
    s.samples = 256;
    s.resamples = 200;
    const GlobalSensitivityResult r = computeGlobalSensitivity(tableSandyLoamOnA(), s);
    ASSERT_EQ(r.status(), gsa::StudyStatus::kCompleted) << r.message();
    const gsa::SobolIndices& x = r.sobol->indices;
    for (Eigen::Index c = 0; c < x.first_order.cols(); ++c) {
        const double conf1 = x.first_order_conf.col(c).sum(), conft = x.total_conf.col(c).sum();
        EXPECT_LE(x.first_order.col(c).sum(), 1.0 + conf1) << c;
        EXPECT_GE(x.total.col(c).sum(), 1.0 - conft) << c;
    }
    const GlobalSensitivityResult again = computeGlobalSensitivity(tableSandyLoamOnA(), s);
    EXPECT_EQ(again.table().rows, r.table().rows);
    s.study.seed = 2;
    EXPECT_NE(computeGlobalSensitivity(tableSandyLoamOnA(), s).table().rows, r.table().rows);
}

TEST(GlobalSensitivity, MorrisGivesNoEffectToAParameterWithout) {
    GlobalSensitivitySettings s;
    s.method = GsaMethod::kMorris;
    s.study.parameters = {{"phi_deg", gsa::Uniform{20.0, 35.0}},
                          {"gamma_kN_m3", gsa::Uniform{10.0, 20.0}}};
    s.study.slips = {0.3};
    s.samples = 20;
    const GlobalSensitivityResult r = computeGlobalSensitivity(tableSandyLoamOnA(), s);
    ASSERT_EQ(r.status(), gsa::StudyStatus::kCompleted) << r.message();
    EXPECT_EQ(r.morris->indices.mu_star(1, 0), 0.0);
    EXPECT_GT(r.morris->indices.mu_star(0, 0), 1.0);  // φ over 15°: newtons of F_x
    EXPECT_EQ(r.table().rows[0][r.table().column("Fx_N_mu_star_gamma_kN_m3")], 0.0);
}

TEST(GlobalSensitivity, CancelKeepsWhatWasComputed) {
    GlobalSensitivitySettings s;
    s.samples = 64;
    std::atomic<bool> cancel{true};
    const GlobalSensitivityResult r = computeGlobalSensitivity(tableSandyLoamOnA(), s, {&cancel});
    EXPECT_EQ(r.status(), gsa::StudyStatus::kCancelled);
    EXPECT_EQ(globalSensitivityOutcome(r).status, Outcome::Status::kCancelled);
}

TEST(GlobalSensitivity, ProgressIsReportedUpToOne) {
    GlobalSensitivitySettings s;
    s.samples = 64;
    double last = 0.0;
    int calls = 0;
    computeGlobalSensitivity(tableSandyLoamOnA(), s, {nullptr, [&](double f) {
                                                          last = f;
                                                          ++calls;
                                                      }});
    EXPECT_GT(calls, 1);
    EXPECT_DOUBLE_EQ(last, 1.0);
}

TEST(GlobalSensitivity, ReaderNamesFieldValueAndRange) {
    GlobalSensitivitySettings s;
    EXPECT_TRUE(readIssues(nlohmann::json::object(), s).empty());
    const nlohmann::json bad = {{"parameters",
                                 {{{"key", "phi_deg"}, {"range", {20, 95}}},
                                  {{"key", "c_kpa"}, {"range", {0, 5}}},
                                  {{"key", "K_m"}, {"normal", {0.02, -1}}},
                                  {{"key", "n"}, {"range", {0.5, 1}}, {"normal", {0.7, 0.1}}},
                                  {{"key", "kc"}, {"range", {0, 5}}, {"bound", {0, 1}}}}},
                                {"outputs", {"Fx_N", "sinkage"}},
                                {"load_N", 50},
                                {"entry_angle_deg", 20},
                                {"method", "sobel"},
                                {"samples", 1},
                                {"slipz", 1}};
    const std::vector<Issue> issues = readIssues(bad, s);
    EXPECT_TRUE(mentions(issues, "parameters[0].range[1]", "95 is outside the allowed range"))
        << formatIssues(issues);
    EXPECT_TRUE(mentions(issues, "parameters[1].key", "did you mean \"c_kPa\""))
        << formatIssues(issues);
    EXPECT_TRUE(mentions(issues, "parameters[2].normal[1]", "must be above 0"))
        << formatIssues(issues);
    EXPECT_TRUE(mentions(issues, "parameters[3]", "one of them")) << formatIssues(issues);
    EXPECT_TRUE(mentions(issues, "parameters[4].bound", "did you mean \"bounds\""))
        << formatIssues(issues);
    EXPECT_TRUE(mentions(issues, "outputs[1]", "did you mean \"sinkage_m\""))
        << formatIssues(issues);
    EXPECT_TRUE(mentions(issues, "entry_angle_deg", "not both")) << formatIssues(issues);
    EXPECT_TRUE(mentions(issues, "method", "sobol")) << formatIssues(issues);
    EXPECT_TRUE(mentions(issues, "samples", "allowed range")) << formatIssues(issues);
    EXPECT_TRUE(mentions(issues, "slipz", "did you mean \"slips\"")) << formatIssues(issues);
}

TEST(GlobalSensitivity, ReaderChecksTheCorrelatedGroupAndMorrisRanges) {
    GlobalSensitivitySettings s;
    const nlohmann::json not_definite = {
        {"parameters", nlohmann::json::array()},
        {"correlated",
         {{"keys", {"phi_deg", "c_kPa"}}, {"mean", {29, 1.7}}, {"covariance", {{1, 2}, {2, 1}}}}}};
    std::vector<Issue> issues = readIssues(not_definite, s);
    ASSERT_EQ(issues.size(), 1u) << formatIssues(issues);
    EXPECT_EQ(issues[0].where, "s.json: analyses[0].correlated");
    GlobalSensitivitySettings m;
    issues = readIssues(
        {{"method", "morris"}, {"parameters", {{{"key", "phi_deg"}, {"normal", {29, 2}}}}}}, m);
    EXPECT_TRUE(mentions(issues, "parameters[0]", "needs ranges")) << formatIssues(issues);
}

TEST(UncertaintyBands, NominalIsTheContactModelAndTheBandsEncloseIt) {
    UncertaintyBandSettings s;
    s.study.parameters = {{"phi_deg", gsa::Uniform{26.0, 32.0}},
                          {"c_kPa", gsa::Normal{1.7, 0.3, 0.5, 3.0}}};
    s.study.slips = {0.1, 0.3, 0.6};
    s.study.slip_angles_deg = {5.0};
    s.samples = 256;
    const Inputs in = tableSandyLoamOnA();
    const UncertaintyBandResult r = computeUncertaintyBands(in, s);
    ASSERT_TRUE(r.bands.usable()) << r.bands.message;
    const Table t = r.table();
    ASSERT_EQ(t.rows.size(), 3u);
    for (std::size_t p = 0; p < 3; ++p) {
        const gsa::testing::Reference ref =
            reference(in.soil, in.wheel, s.study.slips[p], 5.0 * kDeg, in.conditions.load_n);
        ASSERT_TRUE(ref.ok);
        const auto& row = t.rows[p];
        EXPECT_NEAR(row[t.column("Fx_N_nominal")], ref.forces.fx, 1e-9 * std::abs(ref.forces.fx));
        EXPECT_NEAR(row[t.column("Fs_N_nominal")], ref.forces.fs,
                    1e-9 * std::abs(ref.forces.fs) + 1e-12);
        for (const char* out : {"Fx_N", "Fs_N"}) {
            const std::string o = out;
            const double lo = row[t.column(o + "_p5")], mid = row[t.column(o + "_p50")],
                         hi = row[t.column(o + "_p95")], nominal = row[t.column(o + "_nominal")];
            EXPECT_LE(lo, mid);
            EXPECT_LE(mid, hi);
            EXPECT_LT(lo, hi);
            EXPECT_LE(std::min(lo, hi), nominal) << o << " at " << p;
            EXPECT_GE(std::max(lo, hi), nominal) << o << " at " << p;
        }
    }
}

TEST(UncertaintyBands, DefaultSlipsFollowTheConditions) {
    UncertaintyBandSettings s;
    s.study.parameters = {{"phi_deg", gsa::Uniform{27.0, 31.0}}};
    s.samples = 16;
    s.slip_count = 5;
    Inputs in = tableSandyLoamOnA();
    in.conditions.slip_max = 0.8;
    const UncertaintyBandResult r = computeUncertaintyBands(in, s);
    ASSERT_EQ(r.bands.grid.slips.size(), 5u);
    EXPECT_EQ(r.bands.grid.slips.front(), 0.0);
    EXPECT_EQ(r.bands.grid.slips.back(), 0.8);
}

TEST(Posterior, CovarianceInFileUnitsWithKsCarriedByKphi) {
    identification::DecoupledParameters p;
    p.a0 = 0.2;
    p.a1 = 0.3;
    p.pressure_modulus = 1.6e6;
    p.n0 = 0.7;
    p.cohesion_pa = 1.7e3;
    p.friction_angle_rad = 29.0 * kDeg;
    p.shear_modulus_m = 0.025;
    identification::Uncertainty u;
    u.computed = true;
    // Only φ, c and K_s free: σ_φ = 0.01 rad, σ_c = 200 Pa, σ_Ks = 5e4 Pa/m^n.
    u.std[identification::kPhi] = 0.01;
    u.std[identification::kC] = 200.0;
    u.std[identification::kKs] = 5e4;
    for (auto& row : u.correlation) row.fill(0.0);
    u.correlation[identification::kPhi][identification::kC] = -0.8;
    u.correlation[identification::kC][identification::kPhi] = -0.8;
    u.correlation[identification::kKs][identification::kPhi] = 0.3;
    u.correlation[identification::kPhi][identification::kKs] = 0.3;
    const Inputs in = tableSandyLoamOnA();
    const CorrelatedParameters c = correlatedFromIdentification(p, u, in.soil, in.wheel);
    // FullParameter order: K_s (as k_φ), c, φ.
    ASSERT_EQ(c.keys, (std::vector<std::string>{"kphi", "c_kPa", "phi_deg"}));
    const double kc_over_b = 5.3e3 / 0.107;                   // Pa/m^n
    EXPECT_NEAR(c.mean[0], (1.6e6 - kc_over_b) / 1e3, 1e-9);  // kN/m^(n+2)
    EXPECT_NEAR(c.mean[1], 1.7, 1e-12);
    EXPECT_NEAR(c.mean[2], 29.0, 1e-12);
    const double sd_phi_deg = 0.01 * 180.0 / std::numbers::pi;
    EXPECT_NEAR(c.covariance[2][2], sd_phi_deg * sd_phi_deg, 1e-12);
    EXPECT_NEAR(c.covariance[1][1], 0.2 * 0.2, 1e-12);
    EXPECT_NEAR(c.covariance[0][0], 50.0 * 50.0, 1e-9);
    EXPECT_NEAR(c.covariance[1][2], -0.8 * 0.2 * sd_phi_deg, 1e-12);
    EXPECT_NEAR(c.covariance[2][0], 0.3 * sd_phi_deg * 50.0, 1e-9);
    // The identified soil is the nominal one: its K_s is the identified value.
    const soil::SoilParameters soil = identification::soilOf(in.soil, in.wheel, p);
    EXPECT_NEAR(soil.cohesive_modulus / in.wheel.width_m + soil.frictional_modulus, 1.6e6, 1e-6);
    u.computed = false;
    EXPECT_THROW(correlatedFromIdentification(p, u, in.soil, in.wheel), std::invalid_argument);
}

TEST(Posterior, BandsFromAPosteriorRun) {
    UncertaintyBandSettings s;
    s.study.parameters.clear();
    s.study.correlated =
        CorrelatedParameters{{"phi_deg", "c_kPa"}, {29.0, 1.7}, {{1.0, -0.16}, {-0.16, 0.04}}};
    s.study.slips = {0.2, 0.5};
    s.samples = 128;
    const UncertaintyBandResult r = computeUncertaintyBands(tableSandyLoamOnA(), s);
    ASSERT_TRUE(r.bands.usable()) << r.bands.message;
    EXPECT_EQ(r.bands.used.front(), 128u);
}

}  // namespace
}  // namespace terra::analysis
