// Texts that name identified parameters through the field table (issue 26): worded by key for
// JSON and the command line's inputs, by symbol for a summary; the steps' names and the
// solver's advice are such texts. The expected words are typed here, not read from the table.
#include "core/identification/parameter_text.h"

#include <gtest/gtest.h>

#include "core/identification/decoupled_fit.h"
#include "core/identification/full_fit.h"
#include "core/identification/parameters.h"
#include "core/identification/synthetic.h"
#include "tests/core/contact/test_soils.h"
#include "tests/core/identification/identification_test_support.h"

namespace terra::identification {
namespace {

TEST(ParameterText, NamesEachParameterByKeyOrBySymbol) {
    const ParameterText advice = reference(kC) + " and " + reference(kPhi) + " trade off; " +
                                 reference(kKs) + ", " + reference(&DecoupledParameters::n1) +
                                 ", " + reference(kJmax) + ", " + reference(kC);
    EXPECT_EQ(advice.worded(ParameterNaming::kKey),
              "c_kPa and phi_deg trade off; Ks_kPa, n1, jmax_m, c_kPa");
    EXPECT_EQ(advice.worded(ParameterNaming::kSymbol), "c and φ trade off; K_s, n₁, j_max, c");
    EXPECT_EQ(advice.parameters(),
              (std::vector<std::string>{"c_kPa", "phi_deg", "Ks_kPa", "n1", "jmax_m"}));
}

TEST(ParameterText, AnOldKeyIsItsParameterAndOtherBracesArePlainText) {
    // "{Ks}": the key of before issue 26 names K_s, worded by its key of now.
    EXPECT_EQ(ParameterText("{Ks} and {n}").worded(ParameterNaming::kKey), "Ks_kPa and n0");
    EXPECT_EQ(ParameterText("{Ks} and {n}").worded(ParameterNaming::kSymbol), "K_s and n₀");
    // Braces around no key, an unclosed one, and a text saved before texts named parameters.
    for (const char* plain : {"{not a key} {", "a0 {} }{phi_deg", "Ks_kPa ended at its bound"}) {
        EXPECT_EQ(ParameterText(plain).worded(ParameterNaming::kSymbol), plain);
        EXPECT_EQ(ParameterText(plain).worded(ParameterNaming::kKey), plain);
        EXPECT_TRUE(ParameterText(plain).parameters().empty()) << plain;
    }
}

// The steps' names came spelt by hand ("IV: full model (a0, a1, Ks, n, c, phi, K)"), in neither
// the table's keys nor its symbols.
TEST(ParameterText, TheStepsNameTheirParametersThroughTheTable) {
    SyntheticSpec spec;
    for (int i = 0; i < 20; ++i) spec.slips.push_back(0.9 * i / 19);
    spec.loads_n = {58.86};
    const DataSet data = synthesize(contact::testing::sandyLoam(), spec).data;
    const DecoupledFit fit = fitDecoupled(data, testing::kWheelA, DecoupledParameters{});
    ASSERT_EQ(fit.steps.size(), 3u);
    EXPECT_EQ(fit.steps[0].name.worded(ParameterNaming::kKey), "I: a0, a1 (Fx, Eq. 4.12)");
    EXPECT_EQ(fit.steps[1].name.worded(ParameterNaming::kKey), "II: Ks_kPa, n0, n1 (Fz, Eq. 4.17)");
    EXPECT_EQ(fit.steps[2].name.worded(ParameterNaming::kKey),
              "III: c_kPa, phi_deg, K_m (My, Eq. 4.18)");
    EXPECT_EQ(fit.steps[0].name.worded(ParameterNaming::kSymbol), "I: a₀, a₁ (Fx, Eq. 4.12)");
    EXPECT_EQ(fit.steps[1].name.worded(ParameterNaming::kSymbol), "II: K_s, n₀, n₁ (Fz, Eq. 4.17)");
    EXPECT_EQ(fit.steps[2].name.worded(ParameterNaming::kSymbol), "III: c, φ, K (My, Eq. 4.18)");
    RefineOptions options;
    options.max_shear_deformation_m = 0.02;  // the forward model's j_max (Table 2.6)
    const RefineResult refined = refineFullModel(data, testing::kWheelA, fit.parameters, options);
    EXPECT_EQ(refined.report.name.worded(ParameterNaming::kKey),
              "IV: full model (a0, a1, Ks_kPa, n0, c_kPa, phi_deg, K_m)");
    EXPECT_EQ(refined.report.name.worded(ParameterNaming::kSymbol),
              "IV: full model (a₀, a₁, K_s, n₀, c, φ, K)");
}

}  // namespace
}  // namespace terra::identification
