#pragma once
/// @file saved_validation.h
/// The calibration to a measured test (core/analysis/validation.h; the studio's "Calibrate to
/// this test" dialog) in a project's results file (core/project/results.h), read back to the
/// same numbers: the points and metrics with the given soil, and the calibration — its report,
/// prior, calibrated soil, n₁ or S with their profiles, the points and metrics with the
/// calibrated soil and on the held-out points — so that a reopened project shows the dialog's
/// tables and can apply the same soil without fitting again.

#include <nlohmann/json.hpp>
#include <string>

#include "core/analysis/validation.h"
#include "core/common/issue.h"

namespace terra::project {

/// The version of the section's form (SavedResult::version).
inline constexpr int kCalibrationVersion = 1;

nlohmann::json savedJson(const analysis::ValidationResult& result);
/// The result savedJson wrote; every problem with its field path under `where`.
Result<analysis::ValidationResult> validationResultFromJson(const nlohmann::json& json,
                                                            const std::string& where);

}  // namespace terra::project
