// The compaction and global-sensitivity panels' saved state (core/project/panels.h), read and
// written by declared field lists: the state projects saved before opens to the same settings and
// is written back key for key; a bad value is named with its key and range.
#include <gtest/gtest.h>

#include "core/project/panels.h"
#include "tests/core/test_support.h"

namespace terra::project {
namespace compaction_gsa_panels_test {

using testing::contains;
using testing::kLocations;

TEST(GlobalSensitivityPanelState, AProjectsStateOpensAndIsWrittenBackKeyForKey) {
    // As the panel has always written it.
    const nlohmann::json saved{{"page", "bands"},        {"method", "morris"},
                               {"output", "sinkage_m"},  {"slips", {0.2, 0.5}},
                               {"slip_angle_deg", 10.0}, {"samples", 64},
                               {"band_samples", 128},    {"seed", 42}};
    const Result<GlobalSensitivityPanelSettings> read =
        panelSettingsFromJson<GlobalSensitivityPanelSettings>(saved);
    ASSERT_TRUE(read.ok()) << read.message();
    EXPECT_EQ(read->page, "bands");
    EXPECT_EQ(read->method, "morris");
    EXPECT_EQ(read->output, "sinkage_m");
    EXPECT_EQ(read->slips, (std::vector<double>{0.2, 0.5}));
    EXPECT_EQ(read->slip_angle_deg, 10.0);
    EXPECT_EQ(read->samples, 64);
    EXPECT_EQ(read->band_samples, 128);
    EXPECT_EQ(read->seed, 42u);
    EXPECT_EQ(toJson(read.value()), saved);
    // The defaults: every key written.
    EXPECT_EQ(toJson(GlobalSensitivityPanelSettings{}), (nlohmann::json{{"page", "indices"},
                                                                        {"method", "sobol"},
                                                                        {"output", "Fx_N"},
                                                                        {"slips", {0.1, 0.3, 0.6}},
                                                                        {"slip_angle_deg", 0.0},
                                                                        {"samples", 1024},
                                                                        {"band_samples", 256},
                                                                        {"seed", 1}}));
}

TEST(GlobalSensitivityPanelState, ABadValueIsNamedWithItsKeyAndRange) {
    const Result<GlobalSensitivityPanelSettings> bad =
        panelSettingsFromJson<GlobalSensitivityPanelSettings>(
            {{"page", "index"}, {"output", "Fx"}, {"slips", {1.5}}, {"samples", 1}, {"sed", 3}});
    ASSERT_FALSE(bad.ok());
    const std::string message = bad.message();
    EXPECT_TRUE(contains(message, "page: \"index\" is not one of indices, bands")) << message;
    EXPECT_TRUE(contains(message, "output: \"Fx\" is not one of")) << message;
    EXPECT_TRUE(contains(message, "(did you mean \"Fx_N\"?)")) << message;
    EXPECT_TRUE(contains(message, "slips[0]: 1.5 is outside the allowed range [-1, 1]")) << message;
    EXPECT_TRUE(contains(message, "samples: 1 is outside the allowed range [2, 1048576]"))
        << message;
    EXPECT_TRUE(contains(message, "sed: unknown key; did you mean \"seed\"?")) << message;
}

// The compaction panel stores the analysis's settings: a project's state (as the panel wrote it
// before the field list: its profile as an object, the map it always draws) opens to the same
// settings and is written back key for key.
TEST(CompactionPanelState, AProjectsStateOpensAndIsWrittenBackKeyForKey) {
    const soil::SoilProfile loam = io::resolveProfile(kLocations, "loam-moist").value();
    const nlohmann::json saved{{"slip", 0.25},
                               {"slip_angle_deg", 5.0},
                               {"depths_m", {0.1, 0.2, 0.4, 0.8}},
                               {"passes", 3},
                               {"width", "parabolic"},
                               {"risk_stress", "sigma_z"},
                               {"reload_k0_kPa_m", 50000.0},
                               {"reload_Au_kPa_m2", 0.0},
                               {"shear_memory", true},
                               {"concentration", 4.0},
                               {"profile", io::toJson(loam)},
                               {"map_points", {120, 60}},
                               {"map_pass", 2}};
    const Result<CompactionPanelSettings> read =
        panelSettingsFromJson<CompactionPanelSettings>(saved);
    ASSERT_TRUE(read.ok()) << read.message();
    const analysis::CompactionSettings& s = read->analysis;
    EXPECT_EQ(s.passes, 3);
    EXPECT_EQ(s.width, compaction::WidthProfile::kParabolic);
    ASSERT_TRUE(s.profile.has_value());
    EXPECT_EQ(io::toJson(*s.profile), io::toJson(loam));
    EXPECT_EQ(s.map_x_points, 120);
    EXPECT_EQ(s.map_pass, 2);
    EXPECT_EQ(toJson(read.value()), saved);

    // A profile saved by preset name is found among the presets (a project's "panels" reader).
    std::vector<Issue> issues;
    const nlohmann::json by_name{{"profile", "loam-moist"}, {"passes", 2}};
    io::ObjectReader r(by_name, issues);
    CompactionPanelSettings named;
    readPanelSettings(r, named, &kLocations);
    r.finish();
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    ASSERT_TRUE(named.analysis.profile.has_value());
    EXPECT_EQ(io::toJson(*named.analysis.profile), io::toJson(loam));

    const Result<CompactionPanelSettings> bad =
        panelSettingsFromJson<CompactionPanelSettings>({{"passes", 0}, {"map_point", {2, 2}}});
    ASSERT_FALSE(bad.ok());
    EXPECT_TRUE(contains(bad.message(), "passes: 0 is outside the allowed range [1, 1000]"))
        << bad.message();
    EXPECT_TRUE(contains(bad.message(), "did you mean \"map_points\"")) << bad.message();
}

}  // namespace compaction_gsa_panels_test
}  // namespace terra::project
