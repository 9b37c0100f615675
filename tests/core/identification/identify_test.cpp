// The global identification of issue #13 (identify.h): one answer from any start, from the load
// alone, honest errors, priors, robust losses, held-out errors. The truth is Table 2.1 written out
// by hand (test_soils.h); data from the full model with noise (synthetic.h).
#include "core/identification/identify.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/contact/quadratic_model.h"
#include "core/identification/fit_problem.h"
#include "core/identification/observation_model.h"
#include "core/identification/screening.h"
#include "core/identification/synthetic.h"
#include "core/io/parameters_json.h"
#include "tests/core/contact/test_soils.h"
#include "tests/core/identification/identification_test_support.h"
#include "tests/core/test_support.h"

namespace terra::identification {
namespace {

using testing::truthOf;

using contact::ContactParameters;
namespace soils = contact::testing;
using terra::testing::kDeg;
using terra::testing::kLocations;
using testing::kWheelA;
const wheel::WheelParameters kWheelB{"B", "", 0.135, 0.165};

ContactParameters<double> clayOnB() {
    return soils::thesisSoil(0.5, 4.14, 13.0, 13.2, 692.2, 0.01, 13.24, 0.009, 0.135, 0.165);
}

// Slip sweeps s = 0 : 0.03 : 0.9 at each load, noise a fraction of each channel's largest value.
DataSet sweeps(const ContactParameters<double>& soil, std::vector<double> loads, double noise,
               std::uint64_t seed, int slips = 31) {
    SyntheticSpec spec;
    for (int i = 0; i < slips; ++i) spec.slips.push_back(0.9 * i / (slips - 1));
    spec.loads_n = std::move(loads);
    spec.noise.fx.relative = spec.noise.fz.relative = spec.noise.my.relative = noise;
    spec.seed = seed;
    return synthesize(soil, spec).data;
}

// The same data as a robot sees them: the load W per sample, no entry angle, no F_z.
DataSet fromLoadOnly(DataSet data, double load_n) {
    data.columns.entry_angle = false;
    data.columns.fz = false;
    for (Sample& s : data.samples) {
        s.load_n = s.load_n.value_or(load_n);
        s.entry_angle_rad = 0.0;
        s.fz_n = 0.0;
    }
    return data;
}

IdentifyOptions optionsFor(const ContactParameters<double>& soil) {
    IdentifyOptions o;
    o.max_shear_deformation_m = soil.max_shear_deformation_m;
    return o;
}

void expectWithinStd(const IdentificationReport& r, const ParameterVector& truth, double n_std) {
    ASSERT_TRUE(r.uncertainty.computed);
    for (int k = 0; k < kFullParameterCount; ++k) {
        if (r.parameters[k] == truth[k]) continue;  // held at the truth (j_max: +inf too)
        EXPECT_LE(std::abs(r.parameters[k] - truth[k]), n_std * r.uncertainty.std[k])
            << parameterInfo()[k].name << " = " << r.parameters[k] << ", truth " << truth[k]
            << ", std " << r.uncertainty.std[k];
    }
}

struct StartCase {
    const char* name;
    ContactParameters<double> soil;
    wheel::WheelParameters wheel;
    std::vector<double> loads;
};

TEST(Identify, SameOptimumFromSixStartingSoils) {
    // Issue #13: from sandy loam, dry sand, lete sand, heavy clay, clayey soil and snow (whose
    // starts sent the local fit to φ = 25.6° or 60° on the first case and 8.6° on the second).
    const StartCase cases[] = {
        {"sandy loam, wheel A", soils::sandyLoam(), kWheelA, {30.0, 58.86, 90.0}},
        {"clayey soil, wheel B", clayOnB(), kWheelB, {60.0, 98.0, 140.0}}};
    const char* starts[] = {"sandy-loam", "dry-sand",    "lete-sand",
                            "heavy-clay", "clayey-soil", "snow"};
    for (const StartCase& c : cases) {
        const DataSet data = sweeps(c.soil, c.loads, 0.01, 7);
        const ParameterVector truth = truthOf(c.soil);
        std::vector<ParameterVector> found;
        for (const char* start : starts) {
            IdentifyOptions o = optionsFor(c.soil);
            o.starts = startsFromSoils({io::resolveSoil(kLocations, start).value()}, c.wheel);
            const IdentificationReport r = identify(data, c.wheel, o);
            ASSERT_EQ(r.status, IdentifyStatus::kConverged) << c.name << " from " << start;
            expectWithinStd(r, truth, 3.0);
            EXPECT_TRUE(r.ambiguity.empty()) << c.name << " from " << start;
            EXPECT_LT(r.newton_decrement, 1e-2);  // the χ² one more step would remove
            found.push_back(r.parameters);
        }
        for (const ParameterVector& p : found) {
            EXPECT_NEAR(p[kPhi], found[0][kPhi], 0.05 * kDeg) << c.name;
            EXPECT_NEAR(p[kC], found[0][kC], 20.0) << c.name;  // 0.02 kPa
            EXPECT_NEAR(p[kK], found[0][kK], 0.005 * found[0][kK]) << c.name;
        }
    }
}

TEST(Identify, TheSearchFindsTheMinimumTheTruthsOwnStartReaches) {
    // Issue 25, item 7: the search's shortcuts (a descent ends in the basin of a minimum found
    // before it; a parameter crawling toward a bound is tried on it; docs/identification.md §9)
    // must not lose the global minimum. Three soils, both wheels, one load (91 slips) and three
    // (31 each), 1 % noise, three seeds: the search's χ² is at most that of a search started at
    // the truth alone (no design) plus kSlack. The noise levels are given, so that both minimise
    // one objective.
    constexpr double kSlack = 0.01;  // χ² (the ambiguity threshold of 7 parameters is 18.5)
    struct Soil {
        double n, c_kpa, phi_deg, kc, kphi, k_m, gamma, jmax_m;
    };
    const Soil table[] = {{0.7, 1.7, 29.0, 5.3, 1515.0, 0.025, 15.2, 0.02},
                          {1.1, 1.0, 30.0, 0.9, 1523.4, 0.025, 16.18, 0.02},
                          {0.5, 4.14, 13.0, 13.2, 692.2, 0.01, 13.24, 0.009}};
    int cases = 0;
    for (const Soil& t : table) {
        for (const wheel::WheelParameters& w : {kWheelA, kWheelB}) {
            const ContactParameters<double> soil =
                soils::thesisSoil(t.n, t.c_kpa, t.phi_deg, t.kc, t.kphi, t.k_m, t.gamma, t.jmax_m,
                                  w.radius_m, w.width_m);
            const double load = w.name == "A" ? 58.86 : 98.0;
            for (const bool three : {false, true}) {
                for (const std::uint64_t seed : {11u, 12u, 13u}) {
                    const DataSet data =
                        three ? sweeps(soil, {0.5 * load, load, 1.5 * load}, 0.01, seed)
                              : sweeps(soil, {load}, 0.01, seed, 91);
                    IdentifyOptions o = optionsFor(soil);
                    for (const Sample& s : data.samples) {
                        o.noise[kFxChannel] =
                            std::max(o.noise[kFxChannel], 0.01 * std::abs(s.fx_n));
                        o.noise[kFzChannel] =
                            std::max(o.noise[kFzChannel], 0.01 * std::abs(s.fz_n));
                        o.noise[kMyChannel] =
                            std::max(o.noise[kMyChannel], 0.01 * std::abs(s.my_nm));
                    }
                    const IdentificationReport search = identify(data, w, o);
                    IdentifyOptions from_truth = o;
                    from_truth.design_points = 0;
                    from_truth.starts = {{"truth", truthOf(soil)}};
                    const IdentificationReport truth = identify(data, w, from_truth);
                    ASSERT_TRUE(search.usable() && truth.usable());
                    EXPECT_LE(search.chi2, truth.chi2 + kSlack)
                        << "wheel " << w.name << ", n " << t.n
                        << (three ? ", three loads" : ", one load") << ", seed " << seed;
                    ++cases;
                }
            }
        }
    }
    EXPECT_EQ(cases, 36);
}

TEST(Identify, TwoThreadsGiveTheSameAnswerAsOne) {
    // IdentifyOptions::threads shares the screening's starts and each evaluation's samples among
    // threads; every sum is still taken in sample order, so the report is the same bit for bit:
    // clay on B at one load (the crawl toward a₀'s bound, two noise rounds) with j_max held and
    // identified (its prior refit), and three loads.
    const ContactParameters<double> soil = clayOnB();
    for (const bool three : {false, true}) {
        for (const bool fit_jmax : {false, true}) {
            const DataSet data = three ? sweeps(soil, {49.0, 98.0, 147.0}, 0.01, 5)
                                       : sweeps(soil, {98.0}, 0.01, 5, 91);
            IdentifyOptions one = optionsFor(soil);
            one.fit_max_shear_deformation = fit_jmax;
            IdentifyOptions two = one;
            two.threads = 2;
            const IdentificationReport a = identify(data, kWheelB, one);
            const IdentificationReport b = identify(data, kWheelB, two);
            const std::string where = std::string(three ? "three loads" : "one load") +
                                      (fit_jmax ? ", j_max identified" : ", j_max held");
            ASSERT_TRUE(a.usable()) << where;
            EXPECT_EQ(a.chi2, b.chi2) << where;
            EXPECT_EQ(a.iterations, b.iterations) << where;
            for (int k = 0; k < kFullParameterCount; ++k) {
                EXPECT_EQ(a.parameters[k], b.parameters[k]) << where << ", parameter " << k;
                EXPECT_EQ(a.uncertainty.std[k], b.uncertainty.std[k]) << where << ", std " << k;
            }
            ASSERT_EQ(a.starts.size(), b.starts.size()) << where;
            for (std::size_t s = 0; s < a.starts.size(); ++s)
                EXPECT_EQ(a.starts[s].screening_cost, b.starts[s].screening_cost) << where;
            EXPECT_EQ(a.uncertainty.flags, b.uncertainty.flags) << where;
        }
    }
    // Out of range: an error naming the option.
    IdentifyOptions bad = optionsFor(soil);
    bad.threads = -1;
    const IdentificationReport r = identify(sweeps(soil, {98.0}, 0.01, 5), kWheelB, bad);
    EXPECT_FALSE(r.usable());
    EXPECT_NE(r.message.find("threads"), std::string::npos) << r.message;
}

TEST(Identify, ThePolishHoldsAParameterAtAKinkOfItsBound) {
    // At one load the minimum can put a₀ on its bound 0, where the model has a kink: the gradient
    // pulls a₀ inside, but χ² rises as soon as a₀ leaves 0. The Gauss–Newton polish (polish(),
    // fit_problem.h) then tries a₀ inside twice (the full step and a thousandth of it) and,
    // failing, takes its step with a₀ held, ending
    // on its tolerance; before, every trial of its line search failed, it reported ~1 of χ² left
    // (1.064 here), and the solver on the default rule ran again for 7e-6 of χ² (~35 ms).
    // Clayey soil on A, one load, 1 % noise, j_max held (the globalIdentificationMatrix cell).
    const ContactParameters<double> clay =
        soils::thesisSoil(0.5, 4.14, 13.0, 13.2, 692.2, 0.01, 13.24, 0.009);
    const DataSet data = sweeps(clay, {58.86}, 0.01, 8, 91);
    const IdentificationReport r = identify(data, kWheelA, optionsFor(clay));
    ASSERT_TRUE(r.usable()) << r.message;
    ASSERT_TRUE(r.at_bound[kA0]);
    ASSERT_EQ(r.parameters[kA0], 0.0);

    const ObservationModel model(data, kWheelA, r.setup);
    detail::Objective objective;
    objective.model = &model;
    objective.sigma = r.noise;
    objective.fixed[kJmax] = true;
    const std::vector<std::size_t> all = detail::allSamples(model.size());
    const detail::FitProblem problem(objective, all);
    const ParameterVector solver = toSolver(r.parameters);
    std::vector<double> u(solver.begin(), solver.end());
    const double chi2 = detail::chiSquare(problem, u);
    // The kink, computed independently of the polish: ∂χ²/∂a₀ < 0 at a₀ = 0, yet χ² is higher
    // at a₀ = 1e-4 (the others kept).
    double cost = 0.0;
    std::vector<double> gradient;
    ASSERT_TRUE(detail::evaluateCost(problem.box(), u, cost, &gradient));
    EXPECT_LT(gradient[kA0], 0.0);
    std::vector<double> inside = u;
    inside[kA0] = 1e-4;
    EXPECT_GT(detail::chiSquare(problem, inside), chi2);

    double remaining = -1.0;
    detail::polish(objective, all, u, 4, 1e-6, &remaining);
    EXPECT_EQ(remaining, 0.0);
    EXPECT_EQ(u[kA0], 0.0);
    EXPECT_LE(detail::chiSquare(problem, u), chi2);
}

TEST(Identify, TheSearchEndsAtTheMinimumOfAFlatOneLoadValley) {
    // At one load with j_max identified the minimum lies in a flat valley that curves away from
    // the Gauss–Newton model: each polish step gains ~1.7 times what the model predicts, and its
    // steps shrink by ~0.6 each, so that four of them ended 3e-4 of χ² above the minimum. A step
    // stretched to the minimum of the parabola along it (polish(), fit_problem.cpp) ends there.
    // Checked against Ceres' trust region run from the search's answer on the same objective with
    // a budget of 2000 iterations (an independent walk to the minimum). Sandy loam on A, one load,
    // 91 slips, 1 % noise, seed 5: the globalIdentificationMatrix cell.
    const ContactParameters<double> loam =
        soils::thesisSoil(0.7, 1.7, 29.0, 5.3, 1515.0, 0.025, 15.2, 0.02);
    const DataSet data = sweeps(loam, {58.86}, 0.01, 5, 91);
    IdentifyOptions o;
    o.fit_max_shear_deformation = true;
    const IdentificationReport r = identify(data, kWheelA, o);
    ASSERT_TRUE(r.usable()) << r.message;
    ASSERT_FALSE(r.shear_limit_prior);  // the objective has no prior

    const ObservationModel model(data, kWheelA, r.setup);
    detail::Objective objective;
    objective.model = &model;
    objective.sigma = r.noise;
    objective.bounds = o.bounds;
    const std::vector<std::size_t> all = detail::allSamples(model.size());
    const detail::FitProblem problem(objective, all);
    const ParameterVector start = toSolver(r.parameters);
    std::vector<double> u(start.begin(), start.end());
    const double at_answer = detail::chiSquare(problem, u);
    EXPECT_NEAR(at_answer, r.chi2, 1e-9 * r.chi2);  // the objective the search ended on
    detail::BoxOptions long_walk = detail::refinementOptions();
    long_walk.max_iterations = 2000;
    long_walk.iterations_per_pass = 500;
    long_walk.max_passes = 20;
    const detail::BoxSummary walked = detail::solveInBox(problem.box(), u, long_walk);
    ASSERT_TRUE(walked.usable) << walked.termination;
    const double minimum = detail::chiSquare(problem, u);
    EXPECT_LE(at_answer - minimum, 3e-5) << "answer " << at_answer << ", minimum " << minimum;
}

TEST(Identify, TheProjectionIsTheBoundedMinimumOverTheLinearParameters) {
    // With θ_f measured, K_s, c and φ follow (a₀, a₁, n, K) as a bounded linear least-squares
    // problem (screening.h), solved face by face, stopping at the first face that meets the KKT
    // conditions. Checked against the full model: χ² at the projected (K_s, c, φ) is the
    // projection's, and no point of a grid over the feasible (K_s, c, φ) around it is lower.
    // Clay on B, one load, 1 % noise; the default bounds, then bounds that cut off the truth's
    // c (≤ 1 kPa) and φ (≤ 10°), alone and together, so that one or two bounds hold.
    const ContactParameters<double> clay = clayOnB();
    const DataSet data = sweeps(clay, {98.0}, 0.01, 8, 31);
    const ObservationModel model(
        data, kWheelB, setupModel(data, DataSource::kEntryAngle, std::nullopt, 0.009).value());
    const std::vector<std::size_t> all = detail::allSamples(model.size());
    struct Case {
        const char* name;
        double c_upper, phi_upper;
        bool c_held, phi_held;  // the bound that must hold at the truth's projection
    };
    const double default_c = IdentifyOptions{}.bounds.upper[kC],
                 default_phi = IdentifyOptions{}.bounds.upper[kPhi];
    const std::vector<Case> cases = {{"default bounds", default_c, default_phi, false, false},
                                     {"c <= 1 kPa", 1e3, default_phi, true, false},
                                     {"phi <= 10 deg", default_c, 10.0 * kDeg, false, true},
                                     {"both", 1e3, 10.0 * kDeg, true, true}};
    // The truth's (a₀, a₁, n, K) and a point off it.
    std::vector<ParameterVector> points = {truthOf(clay), truthOf(clay)};
    points[1][kA0] = 0.3;
    points[1][kN] = 0.6;
    points[1][kK] = 0.015;
    for (const Case& c : cases) {
        detail::Objective objective;
        objective.model = &model;
        objective.sigma = {0.01 * 40.0, 0.01 * 98.0, 0.01 * 4.0};
        objective.fixed[kJmax] = true;
        objective.bounds = IdentifyOptions{}.bounds;
        objective.bounds.upper[kC] = c.c_upper;
        objective.bounds.upper[kPhi] = c.phi_upper;
        const detail::LinearProjection projection(objective, all, kWheelB);
        const detail::FitProblem problem(objective, all);
        const auto chi2At = [&](const ParameterVector& p) {
            const ParameterVector u = toSolver(p);
            return detail::chiSquare(problem, std::vector<double>(u.begin(), u.end()));
        };
        for (std::size_t i = 0; i < points.size(); ++i) {
            SCOPED_TRACE(std::string(c.name) + ", point " + std::to_string(i));
            ParameterVector p = points[i];
            const double projected = projection.project(p);
            ASSERT_TRUE(std::isfinite(projected));
            const double full = chi2At(p);
            EXPECT_NEAR(full, projected, 1e-5 * projected);
            EXPECT_GE(p[kC], objective.bounds.lower[kC] - 1e-9);
            EXPECT_LE(p[kC], c.c_upper * (1 + 1e-9));
            EXPECT_LE(p[kPhi], c.phi_upper * (1 + 1e-9));
            if (i == 0 && c.c_held) {
                EXPECT_NEAR(p[kC], c.c_upper, 1e-6 * c.c_upper);
            }
            if (i == 0 && c.phi_held) {
                EXPECT_NEAR(p[kPhi], c.phi_upper, 1e-9);
            }
            // A grid around it, K_s ± 20 %, c and φ ± 20 % of their upper bound, clipped to the
            // bounds: no point of it is lower, nor is any point a hundredth of the way to one
            // (the feasible directions' first-order test, which a coarse grid alone would miss
            // at a face with a wrong sign: c on 0 where it should be on 1 kPa). A point clipped
            // back onto the projection's own is no lower: rounding allowed.
            double lowest = INFINITY, lowest_near = INFINITY;
            for (int a = -3; a <= 3; ++a) {
                for (int b = -3; b <= 3; ++b) {
                    for (int d = -3; d <= 3; ++d) {
                        ParameterVector q = p;
                        q[kKs] = p[kKs] * (1.0 + 0.2 * a / 3.0);
                        q[kC] = std::clamp(p[kC] + 0.2 * b / 3.0 * c.c_upper,
                                           objective.bounds.lower[kC], c.c_upper);
                        q[kPhi] = std::clamp(p[kPhi] + 0.2 * d / 3.0 * c.phi_upper,
                                             objective.bounds.lower[kPhi], c.phi_upper);
                        lowest = std::min(lowest, chi2At(q));
                        for (int k : {kKs, kC, kPhi}) q[k] = p[k] + 0.01 * (q[k] - p[k]);
                        lowest_near = std::min(lowest_near, chi2At(q));
                    }
                }
            }
            EXPECT_GE(lowest, full * (1.0 - 1e-9));
            EXPECT_GE(lowest_near, full * (1.0 - 1e-9));
        }
    }
}

TEST(Identify, TheGaussRuleSearchEndsAtTheDefaultRulesMinimum) {
    // IdentifyOptions::gauss_rule_search walks the screening, the descents and the refinement's
    // rounds on the Gauss rule alone and finishes on the default rule: the same minimum as a
    // search on the default rule throughout, to a small fraction of each std. Sandy loam on A and
    // clay on B (a crawl toward a₀'s bound), one and three loads with 1 % noise (the rounds on
    // the Gauss rule), j_max held and identified (its prior refit), θ_f measured; and from the
    // load; and noise-free data (the rounds on the default rule).
    struct Case {
        const char* name;
        ContactParameters<double> soil;
        wheel::WheelParameters wheel;
        std::vector<double> loads;
        double noise;
        bool fit_jmax, from_load;
    };
    const std::vector<Case> cases = {
        {"sandy loam A, one load", soils::sandyLoam(), kWheelA, {58.86}, 0.01, false, false},
        {"sandy loam A, one load, j_max", soils::sandyLoam(), kWheelA, {58.86}, 0.01, true, false},
        {"clay B, one load", clayOnB(), kWheelB, {98.0}, 0.01, false, false},
        {"clay B, three loads, j_max", clayOnB(), kWheelB, {49.0, 98.0, 147.0}, 0.01, true, false},
        {"sandy loam A, three loads, from the load",
         soils::sandyLoam(),
         kWheelA,
         {29.43, 58.86, 88.29},
         0.01,
         false,
         true},
        {"sandy loam A, one load, noise-free",
         soils::sandyLoam(),
         kWheelA,
         {58.86},
         0.0,
         false,
         false}};
    for (const Case& c : cases) {
        DataSet data = sweeps(c.soil, c.loads, c.noise, 5, c.loads.size() == 1 ? 91 : 30);
        if (c.from_load) data = fromLoadOnly(data, c.loads[1]);
        IdentifyOptions gauss = optionsFor(c.soil);
        gauss.fit_max_shear_deformation = c.fit_jmax;
        IdentifyOptions exact = gauss;
        exact.gauss_rule_search = false;
        const IdentificationReport a = identify(data, c.wheel, gauss);
        const IdentificationReport b = identify(data, c.wheel, exact);
        ASSERT_TRUE(a.usable()) << c.name << ": " << a.message;
        ASSERT_TRUE(b.usable()) << c.name << ": " << b.message;
        ASSERT_TRUE(b.uncertainty.computed) << c.name;
        EXPECT_EQ(a.status, b.status) << c.name;
        // No worse in χ² (measured: equal to 1e-8 where the data determine the soil; where one
        // load leaves a flat valley the Gauss rule's search ended 7e-4 and 1e-4 lower), and every
        // parameter within 0.05 std (measured up to 0.037 in those valleys; noise-free, within
        // rounding of a std of ~1e-17 relative).
        EXPECT_LE(a.chi2, b.chi2 + 1e-6 * std::max(b.chi2, 1.0)) << c.name;
        for (int k = 0; k < kFullParameterCount; ++k) {
            EXPECT_LE(std::abs(a.parameters[k] - b.parameters[k]),
                      0.05 * b.uncertainty.std[k] + 1e-9 * std::abs(b.parameters[k]))
                << c.name << ", " << parameterInfo()[k].name;
        }
        EXPECT_EQ(a.uncertainty.flags.size(), b.uncertainty.flags.size()) << c.name;
        // The option is taken: the starts' screening costs are the Gauss rule's (documented), so
        // they differ from the default rule's (by ~1e-5 relative, or more on noise-free data).
        ASSERT_EQ(a.starts.size(), b.starts.size()) << c.name;
        EXPECT_NE(a.starts.back().screening_cost, b.starts.back().screening_cost) << c.name;
    }
}

TEST(Identify, NoiseFreeThesisDataGiveTheTruthWithoutAGuess) {
    // Table 5.2: one load of 6 kg, s = 0 : 0.01 : 0.9, θ_f measured.
    const DataSet data = sweeps(soils::sandyLoam(), {58.86}, 0.0, 1, 91);
    const IdentificationReport r = identify(data, kWheelA, optionsFor(soils::sandyLoam()));
    ASSERT_TRUE(r.usable()) << r.message;
    const ParameterVector truth = truthOf(soils::sandyLoam());
    for (int k = 0; k < kJmax; ++k)
        EXPECT_NEAR(r.parameters[k], truth[k], 1e-6 * std::abs(truth[k]))
            << parameterInfo()[k].name;
}

TEST(Identify, QuadraticModelDataGiveTheTruthWhenTheQuadraticModelIsFitted) {
    // The rover's data under `"model": "quadratic"`: Table 5.2's sweep with F_x, F_z, M_y of the
    // quadratic approximation's closed forms at each sample's θ_f (contact::computeQuadraticForces,
    // evaluated here). Fitting that model gives the truth; fitting the full model does not.
    DataSet data = sweeps(soils::sandyLoam(), {58.86}, 0.0, 1, 91);
    for (Sample& s : data.samples) {
        const contact::OperatingPoint<double> op{s.slip, 0.0, s.entry_angle_rad, 0.0, std::nullopt};
        const contact::WheelForces<double> f =
            contact::computeQuadraticForces(soils::sandyLoam(), op);
        s.fx_n = f.fx;
        s.fz_n = f.fz;
        s.my_nm = f.my;
    }
    IdentifyOptions o = optionsFor(soils::sandyLoam());
    o.model = contact::ContactModel::kQuadratic;
    const IdentificationReport quadratic = identify(data, kWheelA, o);
    ASSERT_TRUE(quadratic.usable()) << quadratic.message;
    EXPECT_EQ(quadratic.setup.model, contact::ContactModel::kQuadratic);
    const ParameterVector truth = truthOf(soils::sandyLoam());
    for (int k = 0; k < kJmax; ++k)
        EXPECT_NEAR(quadratic.parameters[k], truth[k], 1e-6 * std::abs(truth[k]))
            << parameterInfo()[k].name;
    const IdentificationReport full = identify(data, kWheelA, optionsFor(soils::sandyLoam()));
    ASSERT_TRUE(full.usable()) << full.message;
    double worst = 0.0;  // the largest relative error of a parameter fitted with the full model
    for (int k = 0; k < kJmax; ++k)
        if (truth[k] != 0.0) worst = std::max(worst, std::abs(full.parameters[k] / truth[k] - 1));
    EXPECT_GT(worst, 1e-3);
}

TEST(Identify, NoiseFreeFromTheLoadAloneGivesTheTruth) {
    // No θ_f and no F_z column: θ_f is solved from W inside every residual.
    for (const StartCase& c :
         {StartCase{"sandy loam, A", soils::sandyLoam(), kWheelA, {30.0, 58.86, 90.0}},
          StartCase{"clayey soil, B", clayOnB(), kWheelB, {60.0, 98.0, 140.0}}}) {
        const DataSet data = fromLoadOnly(sweeps(c.soil, c.loads, 0.0, 1, 21), 0.0);
        const IdentificationReport r = identify(data, c.wheel, optionsFor(c.soil));
        ASSERT_TRUE(r.usable()) << r.message;
        EXPECT_EQ(r.setup.source, DataSource::kLoad);
        EXPECT_FALSE(r.setup.channels[kFzChannel]);
        const ParameterVector truth = truthOf(c.soil);
        for (int k = 0; k < kJmax; ++k) {
            EXPECT_NEAR(r.parameters[k], truth[k], 1e-6 * std::abs(truth[k]))
                << c.name << ": " << parameterInfo()[k].name;
        }
    }
}

TEST(Identify, MeasuredSinkageIsAChannelOfTheLoadModel) {
    // One load, the load and the sinkage h = r (1 − cos θ_f) measured instead of θ_f.
    DataSet data = sweeps(soils::sandyLoam(), {58.86}, 0.0, 1, 31);
    for (Sample& s : data.samples) s.sinkage_m = 0.092 * (1.0 - std::cos(s.entry_angle_rad));
    data = fromLoadOnly(std::move(data), 58.86);
    const IdentificationReport r = identify(data, kWheelA, optionsFor(soils::sandyLoam()));
    ASSERT_TRUE(r.usable()) << r.message;
    EXPECT_TRUE(r.setup.channels[kSinkageChannel]);
    const ParameterVector truth = truthOf(soils::sandyLoam());
    for (int k = 0; k < kJmax; ++k)
        EXPECT_NEAR(r.parameters[k], truth[k], 1e-5 * std::abs(truth[k]))
            << parameterInfo()[k].name;
}

TEST(Identify, ThreeSigmaIntervalsCoverTheTruthInNineOfTenRuns) {
    // 20 seeds × 1 % noise, three loads, noise levels estimated per channel.
    const ParameterVector truth = truthOf(soils::sandyLoam());
    std::array<int, kFullParameterCount> covered{};
    int runs = 0;
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        const DataSet data = sweeps(soils::sandyLoam(), {30.0, 58.86, 90.0}, 0.01, seed);
        const IdentificationReport r = identify(data, kWheelA, optionsFor(soils::sandyLoam()));
        ASSERT_TRUE(r.usable() && r.uncertainty.computed) << seed;
        ++runs;
        for (int k = 0; k < kJmax; ++k)
            covered[k] += std::abs(r.parameters[k] - truth[k]) <= 3.0 * r.uncertainty.std[k];
    }
    for (int k = 0; k < kJmax; ++k) {
        std::printf("%s covered %d / %d\n", parameterInfo()[k].name, covered[k], runs);
        EXPECT_GE(covered[k], 18) << parameterInfo()[k].name;
    }
}

TEST(Identify, APriorStaysWhereOneLoadCannotSee) {
    // One load sees c + σ tan φ but barely c or K_s alone: their posterior std stays near the
    // prior's; with three loads the data determine them.
    const soil::SoilParameters preset = io::resolveSoil(kLocations, "sandy-loam").value();
    IdentifyOptions o = optionsFor(soils::sandyLoam());
    o.priors = priorsFromSoil(preset, kWheelA);
    const IdentificationReport one =
        identify(sweeps(soils::sandyLoam(), {58.86}, 0.01, 1), kWheelA, o);
    ASSERT_TRUE(one.usable()) << one.message;
    EXPECT_GT(one.prior[kC].std_ratio, 0.7);
    EXPECT_GT(one.prior[kKs].std_ratio, 0.7);
    EXPECT_LT(one.prior[kK].std_ratio, 0.3);  // K is seen at any load
    const IdentificationReport three =
        identify(sweeps(soils::sandyLoam(), {30.0, 58.86, 90.0}, 0.01, 1), kWheelA, o);
    ASSERT_TRUE(three.usable());
    EXPECT_LT(three.prior[kC].std_ratio, 0.3);
    EXPECT_LT(three.prior[kKs].std_ratio, 0.3);
    for (int k = 0; k < kJmax; ++k) {
        EXPECT_TRUE(three.prior[k].active);
        EXPECT_NEAR(three.prior[k].shift_in_prior_std,
                    (three.parameters[k] - o.priors[k]->mean) / o.priors[k]->std, 1e-12);
    }
}

TEST(Identify, AmbiguousMinimaAreReportedWithBothAnswers) {
    // One load with noise: some seeds leave two distinct minima within the noise. Each reported
    // one is checked against its own χ², recomputed here from the predictions.
    int reported = 0;
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
        const DataSet data = sweeps(soils::sandyLoam(), {58.86}, 0.01, seed);
        const IdentifyOptions o = optionsFor(soils::sandyLoam());
        const IdentificationReport r = identify(data, kWheelA, o);
        ASSERT_TRUE(r.usable());
        auto chi2 = [&](const ParameterVector& p) {
            const std::vector<Prediction> predicted = predictAll(data, kWheelA, p, o);
            double sum = 0.0;
            for (std::size_t i = 0; i < data.samples.size(); ++i) {
                const Sample& s = data.samples[i];
                const double e[3] = {predicted[i].values[0] - s.fx_n,
                                     predicted[i].values[1] - s.fz_n,
                                     predicted[i].values[2] - s.my_nm};
                for (int c = 0; c < 3; ++c) sum += std::pow(e[c] / r.noise[c], 2);
            }
            return sum;
        };
        const double best = chi2(r.parameters);
        EXPECT_NEAR(best, r.chi2, 1e-6 * r.chi2);
        for (const Minimum& m : r.ambiguity) {
            ++reported;
            EXPECT_NEAR(chi2(m.parameters) - best, m.delta_chi2, 1e-6 * r.chi2);
            EXPECT_LE(m.delta_chi2, r.ambiguity_delta_chi2);
            bool distinct = false;
            for (int k = 0; k < kJmax; ++k)
                distinct |= std::abs(m.parameters[k] - r.parameters[k]) > 3 * r.uncertainty.std[k];
            EXPECT_TRUE(distinct);
        }
    }
    EXPECT_GE(reported, 1);
    // The χ²₀.₉₉ quantile of seven degrees of freedom.
    EXPECT_NEAR(identify(sweeps(soils::sandyLoam(), {58.86}, 0.01, 1), kWheelA,
                         optionsFor(soils::sandyLoam()))
                    .ambiguity_delta_chi2,
                18.475, 1e-3);
}

TEST(Identify, TheTrendTestFlagsAMissingShearLimitAndNotTheRightModel) {
    // Issue 25, item 3: data with j_max = 20 mm fitted by a model without it leave a smooth misfit
    // along slip and a tight, wrong φ; with the data's j_max the residuals are noise. Ten seeds
    // each, three loads, 1 % noise.
    const ParameterVector truth = truthOf(soils::sandyLoam());
    int flagged_wrong = 0, flagged_right = 0;
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
        const DataSet data = sweeps(soils::sandyLoam(), {30.0, 58.86, 90.0}, 0.01, seed);
        const IdentificationReport right = identify(data, kWheelA, optionsFor(soils::sandyLoam()));
        const IdentificationReport wrong = identify(data, kWheelA);  // no j_max
        ASSERT_TRUE(right.usable() && wrong.usable()) << seed;
        flagged_right += right.adequacy.flag;
        flagged_wrong += wrong.adequacy.flag;
        EXPECT_GT(right.adequacy.p, 1e-3) << seed;
        EXPECT_LT(wrong.adequacy.p, 1e-3) << seed;  // measured 4e-6 to 1.2e-4
        // What the flag is for: the wrong model's φ is many of its own std from the truth.
        EXPECT_GT(std::abs(wrong.parameters[kPhi] - truth[kPhi]), 5.0 * wrong.uncertainty.std[kPhi])
            << seed;
    }
    EXPECT_EQ(flagged_right, 0);
    EXPECT_EQ(flagged_wrong, 10);
}

TEST(Identify, AShearLimitTheDataReachIsIdentified) {
    // Issue 25, item 3: the README tour's data (sandy loam, j_max = 20 mm, three loads, 1 %
    // noise) identified with j_max as an eighth parameter: every parameter, j_max among them,
    // within three std of the truth, and the residuals are noise again. Five seeds, and the same
    // from the load alone (the sinkage measured, no θ_f).
    const ParameterVector truth = truthOf(soils::sandyLoam());
    ASSERT_EQ(truth[kJmax], 0.02);
    IdentifyOptions o;
    o.fit_max_shear_deformation = true;
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        const DataSet data = sweeps(soils::sandyLoam(), {30.0, 58.86, 90.0}, 0.01, seed);
        const IdentificationReport r = identify(data, kWheelA, o);
        ASSERT_TRUE(r.usable()) << seed << ": " << r.message;
        EXPECT_FALSE(r.shear_limit_prior) << seed;
        EXPECT_EQ(r.free_parameters, 8);
        expectWithinStd(r, truth, 3.0);
        EXPECT_LT(r.uncertainty.std[kJmax], 0.2 * truth[kJmax]) << seed;
        EXPECT_FALSE(r.adequacy.flag) << seed << ": p = " << r.adequacy.p;
    }
    DataSet load = testing::fromLoad(soils::sandyLoam(), {30.0, 58.86, 90.0});
    const IdentificationReport r = identify(load, kWheelA, o);
    ASSERT_TRUE(r.usable()) << r.message;
    EXPECT_NEAR(r.parameters[kJmax], truth[kJmax], 1e-4 * truth[kJmax]);  // noise-free
    EXPECT_NEAR(r.parameters[kPhi], truth[kPhi], 1e-4 * truth[kPhi]);
}

TEST(Identify, AShearLimitTheDataCannotSeeComesFromItsPrior) {
    // Sandy loam without a limit, slips up to 0.3 only: the shear deformation stays small, a
    // limit beyond it changes nothing, so j_max is the prior's (and the output says so), while
    // the other parameters keep the truth within three std.
    const ContactParameters<double> soil = soils::sandyLoam(INFINITY);
    SyntheticSpec spec;
    for (int i = 0; i <= 20; ++i) spec.slips.push_back(0.3 * i / 20.0);
    spec.loads_n = {30.0, 58.86, 90.0};
    spec.noise.fx.relative = spec.noise.fz.relative = spec.noise.my.relative = 0.01;
    spec.seed = 4;
    const DataSet data = synthesize(soil, spec).data;
    IdentifyOptions o;
    o.fit_max_shear_deformation = true;
    const IdentificationReport r = identify(data, kWheelA, o);
    ASSERT_TRUE(r.usable()) << r.message;
    EXPECT_TRUE(r.shear_limit_prior);
    ASSERT_TRUE(r.prior[kJmax].active);
    EXPECT_EQ(r.prior[kJmax].prior_mean, kDefaultShearLimitPrior.mean);
    bool said = false;
    for (const ParameterText& flag : r.uncertainty.flags)
        said |= flag.worded(ParameterNaming::kSymbol).find("do not determine j_max") !=
                std::string::npos;
    EXPECT_TRUE(said);
    ParameterVector truth = truthOf(soil);
    truth[kJmax] = r.parameters[kJmax];  // no truth to compare: the prior's estimate
    expectWithinStd(r, truth, 3.0);
    // A limit the data cannot see: at or beyond the largest shear deformation they reach.
    IdentifyOptions held;
    held.max_shear_deformation_m = r.parameters[kJmax];
    const IdentificationReport same = identify(data, kWheelA, held);
    EXPECT_NEAR(same.chi2, r.chi2, 0.05 * r.chi2);
}

TEST(Identify, ShearLimitOptionsAreChecked) {
    const DataSet data = sweeps(soils::sandyLoam(), {58.86}, 0.0, 1, 10);
    IdentifyOptions o;
    o.fit_max_shear_deformation = true;
    o.fixed[kJmax] = 0.02;
    IdentificationReport r = identify(data, kWheelA, o);
    EXPECT_EQ(r.status, IdentifyStatus::kInvalidInput);
    EXPECT_NE(r.message.find("fix.jmax_m"), std::string::npos) << r.message;
    IdentifyOptions bad;
    bad.max_shear_deformation_m = -0.01;
    r = identify(data, kWheelA, bad);
    EXPECT_EQ(r.status, IdentifyStatus::kInvalidInput);
    EXPECT_NE(r.message.find("max_shear_deformation_m"), std::string::npos) << r.message;
}

TEST(Identify, HeldOutErrorsMatchTheNoiseOnlyForTheRightModel) {
    const DataSet data = sweeps(soils::sandyLoam(), {30.0, 58.86, 90.0}, 0.01, 3);
    IdentifyOptions o = optionsFor(soils::sandyLoam());
    o.folds = 5;
    const IdentificationReport r = identify(data, kWheelA, o);
    ASSERT_TRUE(r.holdout.computed);
    EXPECT_EQ(r.holdout.samples, data.samples.size());
    for (int c : {kFxChannel, kFzChannel, kMyChannel}) {
        EXPECT_GT(r.holdout.rms_over_noise[c], 0.8) << channelNames()[c];
        EXPECT_LT(r.holdout.rms_over_noise[c], 1.4) << channelNames()[c];
        EXPECT_GE(r.holdout.rms[c], r.holdout.rms_in_fit[c]) << channelNames()[c];
    }
    // φ held 9° off: the other parameters absorb part of it, the held-out samples show the rest.
    o.fixed[kPhi] = 20.0 * kDeg;
    o.folds = 0;
    o.holdout_fraction = 0.25;
    const IdentificationReport wrong = identify(data, kWheelA, o);
    ASSERT_TRUE(wrong.holdout.computed);
    EXPECT_EQ(wrong.holdout.folds, 1);
    EXPECT_EQ(wrong.holdout.samples, 23u);
    const double worst = std::max({wrong.holdout.rms[kFxChannel] / r.noise[kFxChannel],
                                   wrong.holdout.rms[kMyChannel] / r.noise[kMyChannel]});
    std::printf("held out with phi 9 deg off: %.2f noise std\n", worst);
    EXPECT_GT(worst, 2.0);
}

TEST(Identify, RobustLossesResistOutliers) {
    DataSet data = sweeps(soils::sandyLoam(), {30.0, 58.86, 90.0}, 0.01, 5);
    for (std::size_t i : {7u, 30u, 48u, 66u, 85u}) data.samples[i].fx_n += 3.0;  // ~20 σ
    const ParameterVector truth = truthOf(soils::sandyLoam());
    IdentifyOptions o = optionsFor(soils::sandyLoam());
    o.noise = {0.136, 0.82, 0.0195, 0.0};  // the sweeps' 1 %
    const IdentificationReport squared = identify(data, kWheelA, o);
    ASSERT_TRUE(squared.usable());
    EXPECT_GT(squared.chi2, 2.0 * squared.residuals);  // the outliers show
    for (Loss loss : {Loss::kHuber, Loss::kCauchy}) {
        o.loss = loss;
        const IdentificationReport r = identify(data, kWheelA, o);
        ASSERT_TRUE(r.usable()) << r.message;
        expectWithinStd(r, truth, 3.0);
    }
}

TEST(Identify, FixedParametersAndStartsAreReported) {
    const DataSet data = sweeps(soils::sandyLoam(), {30.0, 90.0}, 0.0, 1, 16);
    IdentifyOptions o = optionsFor(soils::sandyLoam());
    o.fixed[kA0] = 0.2;
    o.fixed[kA1] = 0.3;
    o.design_points = 8;
    o.starts = {{"guess", ParameterVector{0.2, 0.3, 1e6, 0.5, 3e3, 0.4, 0.02, INFINITY}}};
    const IdentificationReport r = identify(data, kWheelA, o);
    ASSERT_TRUE(r.usable());
    EXPECT_EQ(r.parameters[kA0], 0.2);
    EXPECT_EQ(r.uncertainty.std[kA0], 0.0);
    EXPECT_EQ(r.free_parameters, 5);
    ASSERT_EQ(r.starts.size(), 9u);
    EXPECT_EQ(r.starts[0].label, "guess");
    EXPECT_NEAR(r.parameters[kPhi], 29.0 * kDeg, 1e-7);
}

TEST(Identify, InvalidInputIsReportedNotThrown) {
    DataSet data = fromLoadOnly(sweeps(soils::sandyLoam(), {58.86}, 0.0, 1, 5), 58.86);
    for (Sample& s : data.samples) s.load_n.reset();  // no load at all
    IdentifyOptions o;
    o.folds = 1;
    o.priors[kPhi] = GaussianPrior{0.5, -1.0};
    o.fixed[kN] = 5.0;
    o.starts = {{"guess", ParameterVector{0.2, 0.3, NAN, 0.5, 3e3, 0.4, 0.02, INFINITY}}};
    const IdentificationReport r = identify(data, kWheelA, o);
    EXPECT_EQ(r.status, IdentifyStatus::kInvalidInput);
    const std::string all = r.message;
    for (const char* what : {"folds", "prior.phi_deg.std", "fix.n", "no load", "starts.guess.Ks"})
        EXPECT_NE(all.find(what), std::string::npos) << what << " in " << all;
    EXPECT_THROW(identify(data, wheel::WheelParameters{"bad", "", -1.0, 0.1}),
                 std::invalid_argument);
}

TEST(Identify, CancelKeepsWhatWasFound) {
    const DataSet data = sweeps(soils::sandyLoam(), {30.0, 90.0}, 0.01, 1, 16);
    IdentifyOptions o = optionsFor(soils::sandyLoam());
    double last = -1.0;
    o.progress = [&](double f) {
        EXPECT_GE(f, last);
        last = f;
        return f < 0.5;
    };
    const IdentificationReport r = identify(data, kWheelA, o);
    EXPECT_EQ(r.status, IdentifyStatus::kCancelled);
    EXPECT_FALSE(r.usable());
}

TEST(Minima, TheSameMinimumFromSeveralStartsIsListedOnce) {
    // Issue 25, item 6: the studio listed one solution three times. Three starts that met one
    // minimum (apart by rounding of the refinement, 1e-5 relative; c = 0 against 1e-9 Pa at its
    // bound) and a second minimum 10 % away in φ: two minima, in order.
    ParameterVector a = truthOf(soils::sandyLoam(INFINITY));
    a[kC] = 0.0;  // at its bound
    ParameterVector a_again = a, a_zero = a, b = a;
    for (double& v : a_again) v *= 1.0 + 1e-5;
    a_zero[kC] = 1e-9;
    b[kPhi] *= 1.1;
    const ParameterVector a_at_bound = a;
    std::vector<Minimum> minima(5);
    minima[0].parameters = a_zero;
    minima[1].parameters = a_again;
    minima[2].parameters = b;
    minima[3].parameters = a_at_bound;
    minima[4].parameters = b;
    const std::vector<Minimum> distinct = distinctMinima(minima);
    ASSERT_EQ(distinct.size(), 2u);
    EXPECT_EQ(distinct[0].parameters[kC], 1e-9);
    EXPECT_EQ(distinct[1].parameters[kPhi], b[kPhi]);
    EXPECT_EQ(relativeDistance(a, a), 0.0);
    EXPECT_NEAR(relativeDistance(a, b), 0.1 / 1.1, 1e-12);  // |Δφ| / the larger φ
    ParameterVector limited = a;
    limited[kJmax] = 0.02;
    EXPECT_TRUE(std::isinf(relativeDistance(a, limited)));  // a limit against none
    // j_max on the plateau beyond the data's reach (56 and 36 mm, one χ², seen on one noisy
    // load): one minimum; a j_max that changes χ² is another.
    std::vector<Minimum> plateau(3);
    plateau[0].parameters = plateau[1].parameters = plateau[2].parameters = limited;
    plateau[0].parameters[kJmax] = 0.056;
    plateau[1].parameters[kJmax] = 0.036;
    plateau[2].parameters[kJmax] = 0.012;
    plateau[0].chi2 = plateau[1].chi2 = 268.25;
    plateau[2].chi2 = 271.5;
    const std::vector<Minimum> kept = distinctMinima(plateau);
    ASSERT_EQ(kept.size(), 2u);
    EXPECT_EQ(kept[0].parameters[kJmax], 0.056);
    EXPECT_EQ(kept[1].parameters[kJmax], 0.012);
}

TEST(Priors, ParseUserItemsInUserUnits) {
    Priors priors;
    EXPECT_TRUE(parsePriorItem("phi_deg=30±5", priors).empty());
    EXPECT_NEAR(priors[kPhi]->mean, 30 * kDeg, 1e-15);
    EXPECT_NEAR(priors[kPhi]->std, 5 * kDeg, 1e-15);
    EXPECT_TRUE(parsePriorItem("Ks=1500+-500", priors).empty());
    EXPECT_EQ(priors[kKs]->mean, 1.5e6);
    EXPECT_EQ(priors[kKs]->std, 5e5);
    EXPECT_TRUE(parsePriorItem("c_kPa=2±1", priors).empty());
    EXPECT_EQ(priors[kC]->mean, 2e3);
    for (const char* bad : {"phi=30±5", "phi_deg=30", "phi_deg=x±5", "phi_deg=30±0", "phi_deg"}) {
        Priors p;
        EXPECT_FALSE(parsePriorItem(bad, p).empty()) << bad;
    }
    // A preset's spreads: ±5° on φ, ±50 % on K_s, c at least ±1 kPa.
    const Priors preset = priorsFromSoil(io::resolveSoil(kLocations, "dry-sand").value(), kWheelA);
    EXPECT_NEAR(preset[kPhi]->std, 5 * kDeg, 1e-6);
    EXPECT_NEAR(preset[kKs]->std, 0.5 * (0.9e3 / 0.107 + 1523.4e3), 1e-6);
    EXPECT_EQ(preset[kC]->std, 1e3);
}

// r = (h (x² − 1), y): two minima, (±1, 0), parted at x = 0 by a ridge of cost h²/2.
struct DoubleWell {
    double h = 1.0;
    template <typename T>
    bool operator()(const T* x, T* r) const {
        r[0] = T(h) * (x[0] * x[0] - T(1.0));
        r[1] = x[1];
        return true;
    }
};

detail::BoxProblem doubleWell(double h, std::unique_ptr<ceres::CostFunction>& owner) {
    owner.reset(new ceres::AutoDiffCostFunction<DoubleWell, 2, 2>(new DoubleWell{h}));
    detail::BoxProblem problem;
    problem.costs = {owner.get()};
    problem.losses = {nullptr};
    problem.lower = {-2.0, -2.0};
    problem.upper = {2.0, 2.0};
    problem.fixed = {false, false};
    return problem;
}

TEST(BoxSolver, TheHillValleyTestSeesTheRidgeBetweenTwoWells) {
    std::unique_ptr<ceres::CostFunction> owner;
    const detail::BoxProblem problem = doubleWell(1.0, owner);
    const std::vector<bool> both{true, true};
    const auto cost = [&](std::vector<double> x) {
        double c = 0.0;
        EXPECT_TRUE(detail::evaluateCost(problem, x, c));
        return c;
    };
    // (0.3, 0.4) lies in the well of (1, 0): the cost falls all the way.
    EXPECT_TRUE(
        detail::downhillTo(problem, {0.3, 0.4}, cost({0.3, 0.4}), {1.0, 0.0}, 0.0, both, 0.0));
    // (−0.5, 0) lies in the other well: at x = −0.125 (a quarter of the way) the cost is
    // (1 − 0.125²)²/2 = 0.484, above its 0.281.
    EXPECT_FALSE(
        detail::downhillTo(problem, {-0.5, 0.0}, cost({-0.5, 0.0}), {1.0, 0.0}, 0.0, both, 0.0));
    EXPECT_FALSE(
        detail::downhillTo(problem, {-0.5, 0.0}, cost({-0.5, 0.0}), {1.0, 0.0}, 0.0, both, 0.2));
    // A ridge lower than `ridge` does not count: 0.203 above the start at x = −0.125.
    EXPECT_TRUE(
        detail::downhillTo(problem, {-0.5, 0.0}, cost({-0.5, 0.0}), {1.0, 0.0}, 0.0, both, 0.21));
    // The minimum itself higher than the last point (a minimum of other noise levels) counts as
    // a ridge: the cost at (1, 0) is 0; given as 0.2, the rise from 0.051 at x = 0.825 is one.
    EXPECT_TRUE(
        detail::downhillTo(problem, {0.3, 0.0}, cost({0.3, 0.0}), {1.0, 0.0}, 0.0, both, 0.05));
    EXPECT_FALSE(
        detail::downhillTo(problem, {0.3, 0.0}, cost({0.3, 0.0}), {1.0, 0.0}, 0.2, both, 0.05));
    // Only the walked coordinates move: y held at 3 adds 4.5 to every point, x still falls.
    EXPECT_TRUE(detail::downhillTo(problem, {0.3, 3.0}, cost({0.3, 3.0}), {1.0, 0.0},
                                   cost({1.0, 3.0}), {true, false}, 0.0));
}

// x crawls toward its lower bound 0.45 and stops at 0.5; y follows x: r = (x − 0.5)², 10⁸ (y − x)²
// (the weight makes y's walk to a moved x long: (y − x)⁴ must fall ~10¹⁶ below (x − 0.5)⁴).
struct CrawlToABound {
    template <typename T>
    bool operator()(const T* x, T* r) const {
        r[0] = (x[0] - T(0.5)) * (x[0] - T(0.5));
        r[1] = T(1e8) * (x[1] - x[0]) * (x[1] - x[0]);
        return true;
    }
};

TEST(BoxSolver, ATrialOnABoundThatDoesNotPayIsUndoneWithinEightIterations) {
    // From 0.7, x heads for 0.5 in shrinking steps (Gauss–Newton on a square halves x − 0.5 as y
    // keeps up), toward the lower bound, which comes within ten of them: x is tried on it. There
    // the cost is at least (0.05)⁴/2 = 3.1e-6 whatever y does, above the cost before the trial:
    // the trial must be undone, and the solve end at x = 0.5 as without the shortcuts
    // (box_solver.cpp, BoundWatch::kTrialIterations).
    ceres::AutoDiffCostFunction<CrawlToABound, 2, 2> f(new CrawlToABound);
    detail::BoxProblem problem;
    problem.costs = {&f};
    problem.losses = {nullptr};
    problem.lower = {0.45, -10.0};
    problem.upper = {2.0, 10.0};
    problem.fixed = {false, false};
    detail::BoxOptions options = detail::refinementOptions();
    options.nonmonotonic_steps = false;
    std::vector<double> plain{0.7, 0.7};
    const detail::BoxSummary reference = detail::solveInBox(problem, plain, options);
    options.bound_shortcuts = true;
    std::vector<double> x{0.7, 0.7};
    const detail::BoxSummary s = detail::solveInBox(problem, x, options);
    ASSERT_TRUE(s.usable) << s.termination;
    EXPECT_GT(s.passes, 1);  // the trial's pass
    EXPECT_NEAR(x[0], 0.5, 1e-3);
    EXPECT_NEAR(x[0], plain[0], 1e-3);
    // The trial costs its pass, cut at eight iterations: the solve resumes from the point before
    // it (63 iterations in all against the plain solve's 55; without the cut the pass ran 23
    // while y followed x to the bound, 78 in all).
    EXPECT_LE(s.iterations, reference.iterations + 12);
}

// One parameter whose Gauss–Newton steps converge linearly: r = (x − 1, A − B x²) with A = 6,
// B = 0.05. At the minimum the second residual is large (5.73) and curves against its sign, so
// that each step covers only 1 − q of the way, q = 2B r₂/(1 + 4B²x²) = 0.543 (the one-load
// valleys of the identification, where q was 0.4–0.6: docs/identification.md §9, "eleventh
// pass"). The minimum is the real root of ∂cost/∂x = 2B²x³ + (1 − 2AB)x − 1 = 0.
struct LargeResidualCrawl {
    static constexpr double kA = 6.0, kB = 0.05;
    template <typename T>
    bool operator()(const T* x, T* r) const {
        r[0] = x[0] - T(1.0);
        r[1] = T(kA) - T(kB) * x[0] * x[0];
        return true;
    }
};

TEST(BoxSolver, AGeometricCrawlIsExtrapolatedToItsLimit) {
    // The cubic's real root by Cardano's formula (x³ + p x + q = 0 after dividing by 2B²).
    constexpr double kA = LargeResidualCrawl::kA, kB = LargeResidualCrawl::kB;
    const double p = (1.0 - 2.0 * kA * kB) / (2.0 * kB * kB), q = -1.0 / (2.0 * kB * kB);
    const double root = std::sqrt(q * q / 4.0 + p * p * p / 27.0);
    const double minimum = std::cbrt(-q / 2.0 + root) + std::cbrt(-q / 2.0 - root);
    ASSERT_NEAR(minimum, 2.33987, 1e-5);  // the Newton iteration's value, worked apart

    ceres::AutoDiffCostFunction<LargeResidualCrawl, 2, 1> f(new LargeResidualCrawl);
    detail::BoxProblem problem;
    problem.costs = {&f};
    problem.losses = {nullptr};
    problem.lower = {-10.0};
    problem.upper = {10.0};
    problem.fixed = {false};
    detail::BoxOptions options = detail::refinementOptions();
    options.nonmonotonic_steps = false;
    std::vector<double> plain{0.0};
    const detail::BoxSummary reference = detail::solveInBox(problem, plain, options);
    ASSERT_TRUE(reference.converged) << reference.termination;
    EXPECT_EQ(reference.extrapolations, 0);
    options.extrapolate = true;
    std::vector<double> x{0.0};
    const detail::BoxSummary s = detail::solveInBox(problem, x, options);
    ASSERT_TRUE(s.converged) << s.termination;
    EXPECT_GE(s.extrapolations, 1);
    // The plain crawl ends where its steps' cost change falls below the tolerance, short of the
    // minimum (17 iterations, 8.2e-5 short); the extrapolated solve ends nearer, in fewer
    // iterations even counting a Jacobian more per extrapolation, for the pass that starts from
    // the limit (6 iterations and 2 extrapolations, 3.7e-6 away).
    EXPECT_NEAR(plain[0], minimum, 1e-3);
    EXPECT_LE(std::abs(x[0] - minimum), 0.25 * std::abs(plain[0] - minimum));
    EXPECT_LE(s.iterations + s.extrapolations, reference.iterations * 3 / 5);
}

}  // namespace
}  // namespace terra::identification
