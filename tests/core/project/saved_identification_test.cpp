// Issue 27: the identification's results saved with a project (core/project/saved_identification.h)
// read back to the same numbers: the batch fit (curves, parameters, report, the identified soil
// with j_max = +inf) and a streaming playback's frames; a damaged section is refused by name.
#include "core/project/saved_identification.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/io/parameters_json.h"
#include "core/io/table_json.h"
#include "tests/core/test_support.h"

namespace terra::project {
namespace {

using nlohmann::json;

using terra::testing::kLocations;

using terra::testing::sandyLoamOnA;

/// Cell by cell: equal, or NaN in both (a reader that turned a number into NaN, or NaN into 0,
/// fails here).
void expectSameTable(const Table& read, const Table& written) {
    ASSERT_EQ(read.columns, written.columns);
    ASSERT_EQ(read.rows.size(), written.rows.size());
    for (std::size_t r = 0; r < read.rows.size(); ++r) {
        for (std::size_t c = 0; c < read.columns.size(); ++c) {
            const double a = read.rows[r][c], b = written.rows[r][c];
            EXPECT_EQ(std::isnan(a), std::isnan(b)) << read.columns[c] << " row " << r;
            if (!std::isnan(b)) {
                EXPECT_EQ(a, b) << read.columns[c] << " row " << r;
            }
        }
    }
}

class IdentificationRoundTrip : public ::testing::TestWithParam<bool> {};

TEST_P(IdentificationRoundTrip, ReadsBackToTheSameFitAndReport) {
    analysis::IdentificationSettings s;
    s.refine = GetParam();  // the global identification's report, or the decoupled fit alone
    s.synthetic.slip_count = 20;
    s.holdout_fraction = GetParam() ? 0.2 : 0.0;
    const analysis::IdentificationResult computed =
        analysis::computeIdentification(sandyLoamOnA(), s);
    ASSERT_TRUE(computed.message.empty()) << computed.message;
    const json saved = savedJson(computed);
    // Through text, as the file holds it.
    const Result<analysis::IdentificationResult> read =
        identificationResultFromJson(json::parse(saved.dump()), "identification");
    ASSERT_TRUE(read.ok()) << read.message();
    // The CLI's JSON report (another writer, every reported number) is the same.
    EXPECT_EQ(analysis::toJson(*read), analysis::toJson(computed));
    expectSameTable(read->curves, computed.curves);
    expectSameTable(read->parameters, computed.parameters);
    EXPECT_EQ(read->data.samples.size(), computed.data.samples.size());
    EXPECT_EQ(read->usable(), computed.usable());
    // The summary's heading names the wheel; the report's setup keeps its force model.
    EXPECT_EQ(read->wheel, computed.wheel);
    EXPECT_FALSE(read->wheel.empty());
    EXPECT_EQ(analysis::identificationSummary(*read).front().value,
              analysis::identificationSummary(computed).front().value);
    if (computed.report) {
        // The force model of the report's setup: a quadratic-model fit reopens as one.
        analysis::IdentificationResult quadratic = computed;
        quadratic.report->setup.model = contact::ContactModel::kQuadratic;
        const auto back =
            identificationResultFromJson(json::parse(savedJson(quadratic).dump()), "x");
        ASSERT_TRUE(back.ok()) << back.message();
        EXPECT_EQ(back->report->setup.model, contact::ContactModel::kQuadratic);
    }
    // A file written before the wheel and the force model were saved reads without them.
    json old = saved;
    ASSERT_EQ(old.erase("wheel"), 1u);
    if (computed.report) {
        ASSERT_EQ(old["report"]["setup"].erase("model"), 1u);
    }
    const auto before = identificationResultFromJson(old, "identification");
    ASSERT_TRUE(before.ok()) << before.message();
    EXPECT_TRUE(before->wheel.empty());
    if (computed.report) {
        EXPECT_EQ(before->report->setup.model, contact::ContactModel::kFull);
    }
    EXPECT_EQ(read->start_description, computed.start_description);
    ASSERT_EQ(read->steps().size(), computed.steps().size());
    for (std::size_t i = 0; i < read->steps().size(); ++i) {
        EXPECT_EQ(read->steps()[i].name, computed.steps()[i].name);
        EXPECT_EQ(read->steps()[i].squared_residual_norm,
                  computed.steps()[i].squared_residual_norm);
    }
    // The identified soil, j_max included (+inf without a shear limit, never NaN).
    const identification::DecoupledParameters& a = read->identified;
    const identification::DecoupledParameters& b = computed.identified;
    EXPECT_EQ(a.friction_angle_rad, b.friction_angle_rad);
    EXPECT_EQ(a.cohesion_pa, b.cohesion_pa);
    EXPECT_EQ(a.pressure_modulus, b.pressure_modulus);
    EXPECT_EQ(a.shear_modulus_m, b.shear_modulus_m);
    EXPECT_FALSE(std::isnan(a.max_shear_deformation_m));
    EXPECT_EQ(a.max_shear_deformation_m, b.max_shear_deformation_m);
    ASSERT_EQ(read->report.has_value(), GetParam());
    if (GetParam()) {
        // The covariance the global study takes as its "identified soil" source.
        EXPECT_EQ(analysis::covarianceJson(*read->report),
                  analysis::covarianceJson(*computed.report));
        EXPECT_EQ(read->report->holdout.computed, computed.report->holdout.computed);
        EXPECT_EQ(read->report->adequacy.p, computed.report->adequacy.p);
    }
    // Written again, the same document.
    EXPECT_EQ(savedJson(*read), saved);
}

INSTANTIATE_TEST_SUITE_P(GlobalAndDecoupled, IdentificationRoundTrip, ::testing::Bool());

// A sample's slip standard error (the data file's `slip_std` column) is kept; a section written
// before the key existed reads without it.
TEST(SavedIdentification, TheSlipStandardErrorOfASampleIsKept) {
    analysis::IdentificationSettings s;
    s.refine = false;
    s.synthetic.slip_count = 10;
    analysis::IdentificationResult computed = analysis::computeIdentification(sandyLoamOnA(), s);
    ASSERT_TRUE(computed.message.empty()) << computed.message;
    computed.data.samples[3].slip_std = 0.025;
    json saved = json::parse(savedJson(computed).dump());
    const Result<analysis::IdentificationResult> read =
        identificationResultFromJson(saved, "identification");
    ASSERT_TRUE(read.ok()) << read.message();
    EXPECT_EQ(read->data.samples[3].slip_std, 0.025);
    EXPECT_FALSE(read->data.samples[2].slip_std.has_value());
    for (json& sample : saved["data"]["samples"]) sample.erase("slip_std");
    const Result<analysis::IdentificationResult> older =
        identificationResultFromJson(saved, "identification");
    ASSERT_TRUE(older.ok()) << older.message();
    EXPECT_FALSE(older->data.samples[3].slip_std.has_value());
}

TEST(SavedIdentification, NonFiniteNumbersSurviveAndOthersAreRefused) {
    analysis::IdentificationResult r;
    r.identified.max_shear_deformation_m = std::numeric_limits<double>::infinity();
    r.fit.parameters.cohesion_pa = -std::numeric_limits<double>::infinity();
    r.message = "nothing to fit";  // no curves needed
    const json saved = savedJson(r);
    EXPECT_EQ(saved["identified"][8], "inf");
    const auto read = identificationResultFromJson(json::parse(saved.dump()), "identification");
    ASSERT_TRUE(read.ok()) << read.message();
    EXPECT_EQ(read->identified.max_shear_deformation_m, std::numeric_limits<double>::infinity());
    EXPECT_EQ(read->fit.parameters.cohesion_pa, -std::numeric_limits<double>::infinity());
    // Nothing to fit: reopened with its status (issue 26 item 4), as the outcome reports it.
    EXPECT_EQ(read->status, analysis::Outcome::Status::kInvalidInput);
    // A string that is not an infinity, a missing key, a short list: each refused by name.
    json bad = saved;
    bad["identified"][8] = "lots";
    auto refused = identificationResultFromJson(bad, "identification");
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.message().find("identified"), std::string::npos) << refused.message();
    EXPECT_NE(refused.message().find("lots"), std::string::npos) << refused.message();
    bad = saved;
    bad.erase("curves");
    refused = identificationResultFromJson(bad, "identification");
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.message().find("curves"), std::string::npos) << refused.message();
    bad = saved;
    bad["fit"]["parameters"] = {1.0, 2.0};
    refused = identificationResultFromJson(bad, "identification");
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.message().find("fit: parameters: [1.0,2.0]: expected a list of 9 values"),
              std::string::npos)
        << refused.message();
}

TEST(SavedIdentification, CurvesThatDoNotMatchTheDataAreRefused) {
    analysis::IdentificationSettings s;
    s.refine = false;
    s.synthetic.slip_count = 10;
    const analysis::IdentificationResult computed =
        analysis::computeIdentification(sandyLoamOnA(), s);
    json saved = savedJson(computed);
    saved["data"]["samples"].erase(0);
    const auto refused = identificationResultFromJson(saved, "identification");
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.message().find("do not match"), std::string::npos) << refused.message();
}

TEST(SavedStream, FramesReadBackToTheSameTable) {
    analysis::StreamingSettings s;
    s.second = io::resolveSoil(kLocations, "clayey-soil").value();
    const analysis::StreamingResult computed = analysis::computeStreaming(sandyLoamOnA(), s);
    ASSERT_GT(computed.frames.size(), 100u);
    SavedStream stream;
    stream.frames = computed.frames;
    stream.sample_count = computed.sample_count;
    stream.true_border = computed.source.true_border;
    stream.description = computed.source.description;
    stream.truth = computed.source.truth;
    stream.stopped = false;
    const json saved = savedJson(stream);
    const Result<SavedStream> read = savedStreamFromJson(json::parse(saved.dump()), "streaming");
    ASSERT_TRUE(read.ok()) << read.message();
    // framesTable (the panel's table and CSV) of the frames read is the computed one's, NaN
    // (no estimate yet) where it was NaN and nowhere else.
    expectSameTable(analysis::framesTable(read->frames), analysis::framesTable(computed.frames));
    EXPECT_EQ(read->sample_count, computed.sample_count);
    EXPECT_EQ(read->true_border, computed.source.true_border);
    ASSERT_EQ(read->truth.size(), computed.source.truth.size());
    EXPECT_EQ(read->truth.back().first, computed.source.truth.back().first);
    std::size_t changes = 0;
    for (const analysis::StreamFrame& f : read->frames) changes += f.estimate.change_detected;
    EXPECT_EQ(changes, computed.changes.size());
    EXPECT_EQ(savedJson(*read), saved);
    // More frames than samples is not a playback.
    json bad = saved;
    bad["sample_count"] = 3;
    EXPECT_FALSE(savedStreamFromJson(bad, "streaming").ok());
    bad = saved;
    bad["frames"][5]["estimate"].erase("cusum");
    const Result<SavedStream> refused = savedStreamFromJson(bad, "streaming");
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.message().find("frames: 5: estimate: cusum"), std::string::npos)
        << refused.message();
}

}  // namespace
}  // namespace terra::project
