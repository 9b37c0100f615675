// Issue 27: the calibration to a measured test saved with a project
// (core/project/saved_validation.h) reads back to the same numbers — checked through the command
// line's JSON writer of the result
// (`validate --json`, another writer of every reported number), the curves cell by cell and the
// calibrated soil field by field; a damaged section is refused with the field it lacks.
#include "core/project/saved_validation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/io/experiment.h"
#include "core/io/parameters_json.h"
#include "tests/core/test_support.h"

namespace terra::project {
namespace {

using nlohmann::json;
using terra::testing::contains;
using terra::testing::kLocations;

analysis::Inputs dingOnHitLss1() {
    analysis::Inputs in;
    in.soil = io::resolveSoil(kLocations, "hit-lss1").value();
    in.wheel = io::resolveWheel(kLocations, "ding2011-smooth").value();
    return in;
}

analysis::ValidationSettings calibrationOf(const std::string& file, std::vector<double> fit_slips) {
    analysis::ValidationSettings s;
    const std::string path = std::string(TERRA_RESOURCE_DIR) + "/experiments/" + file;
    Result<io::Experiment> test = io::readExperiment(path);
    EXPECT_TRUE(test.ok()) << test.message();
    s.experiments = path;
    s.data = test.value();
    s.calibrate = true;
    s.fit_slips = std::move(fit_slips);
    s.noise[io::kExpFx] = 1.0;
    s.noise[io::kExpSinkage] = 1e-3;
    return s;
}

TEST(SavedCalibration, ReadsBackToTheSameCalibrationWithHeldOutPoints) {
    // Calibrated on three slips of the Ding smooth-wheel test, the others held out (the
    // dialog's "Fit on slips"), with the model's curves (the validation figures).
    const analysis::ValidationResult computed = analysis::computeValidation(
        dingOnHitLss1(), calibrationOf("ding2011-smooth-hit-lss1-80N.csv", {0.0, 0.2, 0.6}));
    ASSERT_TRUE(computed.calibration && computed.calibration->report.usable());
    ASSERT_TRUE(computed.calibration->held_out.has_value());
    const Result<analysis::ValidationResult> read =
        validationResultFromJson(json::parse(savedJson(computed).dump()), "forces.calibration");
    ASSERT_TRUE(read.ok()) << read.message();
    EXPECT_EQ(analysis::toJson(*read), analysis::toJson(computed));
    EXPECT_EQ(read->status, analysis::Outcome::Status::kCompleted);
    EXPECT_EQ(read->soil, computed.soil);
    // The summary's heading ("soil on wheel against test") as computed: the wheel is saved.
    EXPECT_FALSE(computed.wheel.empty());
    EXPECT_EQ(analysis::validationSummary(*read).front().value,
              analysis::validationSummary(computed).front().value);
    // What the JSON report leaves out: the model's curves, the points' in-fit marks, the
    // calibrated soil as a whole and the held-out metrics with the given soil.
    const Table& a = read->before.curves;
    const Table& b = computed.before.curves;
    ASSERT_EQ(a.columns, b.columns);
    ASSERT_EQ(a.rows.size(), b.rows.size());
    ASSERT_FALSE(b.rows.empty());
    for (std::size_t r = 0; r < a.rows.size(); ++r) {
        for (std::size_t c = 0; c < a.columns.size(); ++c) {
            EXPECT_EQ(std::isnan(a.rows[r][c]), std::isnan(b.rows[r][c]));
            if (!std::isnan(b.rows[r][c])) {
                EXPECT_EQ(a.rows[r][c], b.rows[r][c]);
            }
        }
    }
    EXPECT_EQ(io::toJson(read->calibration->soil), io::toJson(computed.calibration->soil));
    EXPECT_EQ(read->calibration->soil.max_shear_deformation_m,
              computed.calibration->soil.max_shear_deformation_m);
    const auto& held = *read->calibration->held_out_before;
    const auto& held_computed = *computed.calibration->held_out_before;
    ASSERT_TRUE(held[io::kExpFx] && held_computed[io::kExpFx]);
    EXPECT_EQ(held[io::kExpFx]->rmse, held_computed[io::kExpFx]->rmse);
    EXPECT_EQ(held[io::kExpFx]->count, held_computed[io::kExpFx]->count);
    ASSERT_EQ(read->calibration->after->points.size(), computed.calibration->after->points.size());
    for (std::size_t i = 0; i < read->calibration->after->points.size(); ++i)
        EXPECT_EQ(read->calibration->after->points[i].in_fit,
                  computed.calibration->after->points[i].in_fit);
    EXPECT_EQ(read->calibration->report.uncertainty.std,
              computed.calibration->report.uncertainty.std);
    EXPECT_EQ(read->calibration->report.uncertainty.correlation,
              computed.calibration->report.uncertainty.correlation);
}

TEST(SavedCalibration, AValidationWithoutCalibrationAndADamagedOneAreTold) {
    analysis::ValidationSettings s = calibrationOf("ding2011-smooth-hit-lss1-80N.csv", {});
    s.calibrate = false;
    const analysis::ValidationResult computed = analysis::computeValidation(dingOnHitLss1(), s);
    json saved = savedJson(computed);
    const Result<analysis::ValidationResult> read = validationResultFromJson(saved, "x");
    ASSERT_TRUE(read.ok()) << read.message();
    EXPECT_FALSE(read->calibration.has_value());
    EXPECT_EQ(analysis::toJson(*read), analysis::toJson(computed));
    // A calibration that failed (its noise estimated on two sinkage readings: it interpolates)
    // is reopened failed, with the reason it was computed with (issue 26 item 4).
    analysis::ValidationSettings estimated = calibrationOf("ding2011-smooth-hit-lss1-80N.csv", {});
    estimated.noise = {};
    const analysis::ValidationResult failed =
        analysis::computeValidation(dingOnHitLss1(), estimated);
    ASSERT_EQ(failed.status, analysis::Outcome::Status::kFailed);
    const Result<analysis::ValidationResult> reopened =
        validationResultFromJson(json::parse(savedJson(failed).dump()), "x");
    ASSERT_TRUE(reopened.ok()) << reopened.message();
    EXPECT_EQ(reopened->status, analysis::Outcome::Status::kFailed);
    EXPECT_EQ(reopened->message, failed.message);
    EXPECT_TRUE(contains(reopened->message, "calibration failed: the fit interpolates"))
        << reopened->message;
    saved["before"]["points"][0].erase("slip");
    const Result<analysis::ValidationResult> damaged = validationResultFromJson(saved, "x");
    ASSERT_FALSE(damaged.ok());
    EXPECT_TRUE(contains(damaged.message(), "before")) << damaged.message();
    EXPECT_TRUE(contains(damaged.message(), "slip")) << damaged.message();
}

}  // namespace
}  // namespace terra::project
