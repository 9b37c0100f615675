// How the identification's texts name the parameters (issue 26, one vocabulary): the solver's
// advice and the steps' names are written once, through the field table, and worded by each
// renderer — by key in `identify --json` (what --prior and --fix take), by symbol in the summary
// that the command line prints and the studio's report shows. The keys and symbols expected are
// typed here.
#include <gtest/gtest.h>

#include <regex>

#include "core/analysis/identification.h"
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

}  // namespace
}  // namespace terra::analysis
