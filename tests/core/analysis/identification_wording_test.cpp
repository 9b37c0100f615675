// How the identification's texts name the parameters (issue 26, one vocabulary): the solver's
// advice and the steps' names are written once, through the field table, and worded by each
// renderer — by key in `identify --json` (what --prior and --fix take), by symbol in the summary
// that the command line prints and the studio's report shows. The keys and symbols expected are
// typed here.
#include <gtest/gtest.h>

#include <regex>

#include "core/analysis/identification.h"
#include "core/identification/parameter_text.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace {

using terra::testing::contains;

// The table's keys (and the old "Ks", "phi"), as whole words: what a summary must not show.
const std::regex kWordingKeyWords(R"(\b(a0|a1|Ks_kPa|Ks|n0|n1|c_kPa|phi_deg|phi|K_m|jmax_m)\b)");
// The symbols that differ from their keys (c and K are one letter each): what JSON must not show.
const char* const kWordingSymbols[] = {"a₀", "a₁", "K_s", "n₀", "n₁", "φ", "j_max"};

TEST(IdentificationWording, TheAdviceNamesParametersByKeyInJsonAndBySymbolInTheSummary) {
    // One load cannot separate c and φ (docs/identification.md): the fit says so.
    IdentificationSettings s;
    s.synthetic.loads_n = {58.86};
    s.synthetic.noise_percent = 2.0;
    const IdentificationResult r = computeIdentification(terra::testing::sandyLoamOnA(), s);
    ASSERT_EQ(r.status, Outcome::Status::kCompleted) << r.message;
    ASSERT_TRUE(r.usable());
    const nlohmann::json j = toJson(r);
    const Summary summary = identificationSummary(r);

    bool json_says = false, summary_says = false;
    ASSERT_TRUE(j["flags"].is_array());
    for (const nlohmann::json& flag : j["flags"]) {
        const std::string text = flag.get<std::string>();
        json_says |= text.starts_with("c_kPa and phi_deg trade off");
        for (const char* symbol : kWordingSymbols) EXPECT_FALSE(contains(text, symbol)) << text;
    }
    int notes = 0;
    for (const SummaryRow& row : summary) {
        if (!row.json.starts_with("/flags/")) continue;
        ++notes;
        summary_says |= row.value.starts_with("c and φ trade off");
        EXPECT_FALSE(std::regex_search(row.value, kWordingKeyWords)) << row.value;
    }
    EXPECT_TRUE(json_says) << j["flags"].dump();
    EXPECT_TRUE(summary_says);
    EXPECT_EQ(notes, static_cast<int>(j["flags"].size()));
    // Each note is its JSON flag with the keys worded as symbols.
    terra::testing::expectSummaryIsTheJson(summary, j);
}

TEST(IdentificationWording, TheDecoupledStepsNameTheirParametersByKeyInJsonBySymbolInTheSummary) {
    IdentificationSettings s;
    s.refine = false;
    s.synthetic.slip_count = 12;
    const IdentificationResult r = computeIdentification(terra::testing::sandyLoamOnA(), s);
    ASSERT_EQ(r.status, Outcome::Status::kCompleted) << r.message;
    const nlohmann::json j = toJson(r);
    ASSERT_EQ(j["steps"].size(), 3u);
    EXPECT_EQ(j["steps"][1]["step"], "II: Ks_kPa, n0, n1 (Fz, Eq. 4.17)");
    EXPECT_EQ(j["steps"][2]["step"], "III: c_kPa, phi_deg, K_m (My, Eq. 4.18)");
    std::vector<std::string> labels;
    for (const SummaryRow& row : identificationSummary(r)) {
        if (!row.json.starts_with("/steps/")) continue;
        labels.push_back(row.label);
        EXPECT_FALSE(std::regex_search(row.label, kWordingKeyWords)) << row.label;
    }
    EXPECT_EQ(labels, (std::vector<std::string>{"step I: a₀, a₁ (Fx, Eq. 4.12), |r|^2",
                                                "step II: K_s, n₀, n₁ (Fz, Eq. 4.17), |r|^2",
                                                "step III: c, φ, K (My, Eq. 4.18), |r|^2"}));
}

// Issue 27: the steps say how each ended in a user's words ("converged (the fit stopped
// improving)"), not Ceres' "CONVERGENCE: Function tolerance reached. |cost_change|/cost: … <= …";
// the JSON keeps the solver's own termination for a script.
TEST(IdentificationWording, TheStepsSayHowTheyEndedInAUsersWords) {
    for (const bool refine : {false, true}) {
        IdentificationSettings s;
        s.refine = refine;
        const IdentificationResult r = computeIdentification(terra::testing::sandyLoamOnA(), s);
        ASSERT_EQ(r.status, Outcome::Status::kCompleted) << r.message;
        const nlohmann::json j = toJson(r);
        bool ceres_in_json = false;
        for (const nlohmann::json& step : j["steps"])
            ceres_in_json |= step.value("termination", "").starts_with("CONVERGENCE");
        EXPECT_TRUE(ceres_in_json) << j["steps"].dump();
        int steps = 0;
        bool converged = false;
        for (const SummaryRow& row : identificationSummary(r)) {
            if (!row.json.starts_with("/steps/")) continue;
            ++steps;
            converged |= contains(row.detail, "converged");
            for (const char* optimizer : {"CONVERGENCE", "cost_change", "tolerance", "<="})
                EXPECT_FALSE(contains(row.detail, optimizer)) << refine << ": " << row.detail;
        }
        EXPECT_EQ(steps, static_cast<int>(j["steps"].size()));
        EXPECT_TRUE(converged) << refine;
        // The notes a script's report.md shows (`terrastudio run`) say it the same way.
        for (const std::string& note : identificationOutcome(r).notes) {
            for (const char* optimizer : {"CONVERGENCE", "cost_change", "<="})
                EXPECT_FALSE(contains(note, optimizer)) << refine << ": " << note;
        }
    }
}

TEST(IdentificationWording, EachKindOfTerminationHasItsWords) {
    using identification::solverOutcome;
    EXPECT_EQ(solverOutcome("CONVERGENCE: Function tolerance reached. |cost_change|/cost: "
                            "1.2e-07 <= 1e-06"),
              "converged (the fit stopped improving)");
    EXPECT_EQ(solverOutcome("CONVERGENCE: Gradient tolerance reached. Gradient max norm: 1e-11 "
                            "<= 1e-10"),
              "converged (the slope vanished at the minimum)");
    EXPECT_EQ(solverOutcome("CONVERGENCE: every parameter is held"),
              "nothing to fit (every parameter is held)");
    EXPECT_TRUE(solverOutcome("NO_CONVERGENCE: Maximum number of iterations reached.")
                    .starts_with("stopped at its iteration limit"));
    EXPECT_EQ(solverOutcome("STOPPED: the caller's stop condition holds"),
              "stopped in the basin of a minimum found before");
    EXPECT_EQ(solverOutcome("FAILURE: the cost cannot be evaluated at the solution"),
              "failed: the model cannot be evaluated at the solution");
    // The bound watch's end of a pass, left as the last by the budget, and a caller's stop.
    EXPECT_TRUE(solverOutcome("USER_SUCCESS: a parameter reached its bound")
                    .starts_with("stopped when a parameter reached its bound"));
    EXPECT_EQ(solverOutcome("USER_FAILURE: User callback returned SOLVER_ABORT."),
              "stopped by the caller");
    // Which of them converged, and a step's own note, which is no solver's end.
    using identification::solverConverged;
    EXPECT_EQ(solverConverged("CONVERGENCE: Function tolerance reached."), true);
    EXPECT_EQ(solverConverged("CONVERGENCE: every parameter is held"), true);
    EXPECT_EQ(solverConverged("NO_CONVERGENCE: Maximum number of iterations reached."), false);
    EXPECT_EQ(solverConverged("STOPPED: the caller's stop condition holds"), false);
    EXPECT_EQ(solverConverged("USER_SUCCESS: stopped by the callback"), false);
    EXPECT_EQ(solverConverged("FAILURE: the cost cannot be evaluated at the solution"), false);
    EXPECT_EQ(solverConverged("best χ² on the subset after the linear projection"), std::nullopt);
    EXPECT_EQ(solverOutcome("FAILURE: Residual and Jacobian evaluation failed."),
              "the solver failed");
    // A step's own note is not a solver's termination: kept as it is.
    EXPECT_EQ(solverOutcome("best χ² on the subset after the linear projection"),
              "best χ² on the subset after the linear projection");
}

}  // namespace
}  // namespace terra::analysis
