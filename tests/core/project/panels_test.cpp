// The panels' saved state (core/project/panels.h): the identification panel stores the
// analysis's settings struct, read and written by its field list, and still opens the state
// projects saved before it did.
#include "core/project/panels.h"

#include <gtest/gtest.h>

#include "tests/core/test_support.h"

namespace terra::project {
namespace {

using testing::contains;

TEST(IdentificationPanelState, TheOldKeysOfAProjectAreReadIntoTheFitsSettings) {
    // As the panel wrote it before it stored the struct (a text of items, a validation name).
    const nlohmann::json old{{"csv", "data/run1.csv"},
                             {"noise_percent", 1.5},
                             {"refine", true},
                             {"three_loads", false},
                             {"page", "fit"},
                             {"stream_csv", ""},
                             {"stream_second_soil", "clayey-soil"},
                             {"stream_noise_percent", 1.0},
                             {"stream_speed", 0.0},
                             {"stream_skip_bad_rows", false},
                             {"prior_soil", "sandy-loam"},
                             {"prior_items", "phi_deg=30±5,  c_kPa=2±1"},
                             {"validation", "folds"},
                             {"loss", "huber"},
                             {"wheel", "project"},
                             {"jmax", "fixed"},
                             {"jmax_mm", 12.0}};
    const Result<IdentificationPanelSettings> read =
        panelSettingsFromJson<IdentificationPanelSettings>(old);
    ASSERT_TRUE(read.ok()) << read.message();
    const analysis::IdentificationSettings& fit = read->fit;
    EXPECT_EQ(fit.csv, "data/run1.csv");
    EXPECT_EQ(fit.synthetic.noise_percent, 1.5);
    EXPECT_EQ(fit.prior_soil_name, "sandy-loam");
    EXPECT_EQ(fit.prior_items, (std::vector<std::string>{"phi_deg=30±5", "c_kPa=2±1"}));
    EXPECT_EQ(fit.folds, kPanelFolds);
    EXPECT_EQ(fit.holdout_fraction, 0.0);
    EXPECT_EQ(fit.loss, identification::Loss::kHuber);
    EXPECT_FALSE(read->three_loads);
    EXPECT_EQ(read->jmax, "fixed");
    EXPECT_EQ(read->jmax_mm, 12.0);

    // Written in the struct's keys, never the old ones; read back the same.
    const nlohmann::json written = toJson(read.value());
    EXPECT_FALSE(written.contains("prior_items")) << written.dump();
    EXPECT_FALSE(written.contains("validation")) << written.dump();
    EXPECT_EQ(written["priors"], nlohmann::json({"phi_deg=30±5", "c_kPa=2±1"}));
    EXPECT_EQ(written["folds"], kPanelFolds);
    EXPECT_FALSE(written.contains("holdout"));  // 0: none
    const Result<IdentificationPanelSettings> again =
        panelSettingsFromJson<IdentificationPanelSettings>(written);
    ASSERT_TRUE(again.ok()) << again.message();
    EXPECT_EQ(again->fit.prior_items, fit.prior_items);
    EXPECT_EQ(again->fit.folds, kPanelFolds);
    EXPECT_EQ(again->fit.loss, identification::Loss::kHuber);
    EXPECT_EQ(again->fit.synthetic.noise_percent, 1.5);
    EXPECT_EQ(again->jmax_mm, 12.0);
}

TEST(IdentificationPanelState, ABadValueIsNamedAsTheAnalysisReaderNamesIt) {
    const Result<IdentificationPanelSettings> bad =
        panelSettingsFromJson<IdentificationPanelSettings>(
            {{"noise_percent", 150}, {"holdout", 1.5}, {"validation", "all"}, {"refnie", true}});
    ASSERT_FALSE(bad.ok());
    const std::string message = bad.message();
    EXPECT_TRUE(contains(message, "noise_percent: 150 is outside the allowed range [0, 100] %"))
        << message;
    EXPECT_TRUE(contains(message, "holdout: 1.5 is outside the allowed range (0, 1)")) << message;
    EXPECT_TRUE(contains(message, "validation: \"all\" is not one of none, holdout, folds"))
        << message;
    EXPECT_TRUE(contains(message, "refnie: unknown key; did you mean \"refine\"?")) << message;
}

// Issue 26: a saved panel state that names a parameter by an old key ("Ks", "n"), in either form
// of the priors or in "fix", is read as the new key with the note the command line gives.
TEST(IdentificationPanelState, AnOldParameterKeyIsReadAsItsNewOneWithTheCommandLinesNote) {
    const char* const ks = "parameter key 'Ks' is deprecated: use 'Ks_kPa'";
    const Result<IdentificationPanelSettings> items =
        panelSettingsFromJson<IdentificationPanelSettings>(
            {{"priors", {"Ks=1500±500", "phi_deg=30±5"}}, {"fix", {{"n", 0.7}}}});
    ASSERT_TRUE(items.ok()) << items.message();
    EXPECT_EQ(items->fit.prior_items,
              (std::vector<std::string>{"Ks_kPa=1500±500", "phi_deg=30±5"}));
    EXPECT_EQ(items->fit.fixed, (std::vector<std::pair<std::string, double>>{{"n0", 0.7}}));
    ASSERT_EQ(items->fit.key_warnings.size(), 2u);
    EXPECT_EQ(items->fit.key_warnings[0].where, "priors");
    EXPECT_EQ(items->fit.key_warnings[0].message, std::string("prior 'Ks=1500±500': ") + ks);
    EXPECT_EQ(items->fit.key_warnings[1].where, "fix.n");
    EXPECT_EQ(items->fit.key_warnings[1].message, "parameter key 'n' is deprecated: use 'n0'");
    // The old text form of the priors, noted where it was.
    const Result<IdentificationPanelSettings> text =
        panelSettingsFromJson<IdentificationPanelSettings>({{"prior_items", "Ks=1500±500"}});
    ASSERT_TRUE(text.ok()) << text.message();
    EXPECT_EQ(text->fit.prior_items, (std::vector<std::string>{"Ks_kPa=1500±500"}));
    ASSERT_EQ(text->fit.key_warnings.size(), 1u);
    EXPECT_EQ(text->fit.key_warnings[0].where, "prior_items");
    // Written back with the new keys; read again, nothing to note.
    const Result<IdentificationPanelSettings> again =
        panelSettingsFromJson<IdentificationPanelSettings>(toJson(items.value()));
    ASSERT_TRUE(again.ok()) << again.message();
    EXPECT_EQ(again->fit.prior_items, items->fit.prior_items);
    EXPECT_TRUE(again->fit.key_warnings.empty());
}

}  // namespace
}  // namespace terra::project
