#pragma once
/// @file saved_analyses.h
/// The quick panels' results in a project's results file (core/project/results.h): the forces
/// panel's sweep, soil curves and comparison with the project's measured test ("forces"), the
/// stresses ("stresses"), the compaction study ("compaction") and the local sensitivity study
/// ("sensitivity"), each read back to the same numbers (NaN, as a point without equilibrium
/// gives, and the infinities included: result_json.h's `number`). Each struct is written and
/// read by one key list (saved::Fields, result_json.h).

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/compaction.h"
#include "core/analysis/forces.h"
#include "core/analysis/sensitivity.h"
#include "core/analysis/soil_curves.h"
#include "core/analysis/stresses.h"
#include "core/analysis/validation.h"
#include "core/common/issue.h"

namespace terra::project {

/// Versions of the sections' forms (SavedResult::version).
inline constexpr int kForcesVersion = 1;
inline constexpr int kStressesVersion = 1;
inline constexpr int kCompactionVersion = 1;
inline constexpr int kSensitivityVersion = 1;

/// The model swept at one of a measured test's loads (over the test's slip angles).
struct SavedTestSweep {
    double load_n = 0.0;  ///< W [N]
    Table table;          ///< sweepColumns()
};

/// What the forces panel shows of the project (its comparison soil is session state: not saved).
struct SavedForces {
    analysis::ForcesResult sweep;
    analysis::SoilCurves soil;
    /// The project's measured test predicted (with a test in the project).
    std::optional<analysis::ValidationResult> validation;
    std::vector<SavedTestSweep> test_sweeps;
};

nlohmann::json savedJson(const SavedForces& forces);
nlohmann::json savedJson(const analysis::StressResult& result);
nlohmann::json savedJson(const analysis::CompactionResult& result);
nlohmann::json savedJson(const analysis::SensitivityResult& result);

/// The results savedJson wrote; every problem with its key path under `where`
/// ("compaction: passes: 2: forces: fx: \"x\" is not a number").
Result<SavedForces> savedForcesFromJson(const nlohmann::json& json, const std::string& where);
Result<analysis::StressResult> stressResultFromJson(const nlohmann::json& json,
                                                    const std::string& where);
Result<analysis::CompactionResult> compactionResultFromJson(const nlohmann::json& json,
                                                            const std::string& where);
Result<analysis::SensitivityResult> sensitivityResultFromJson(const nlohmann::json& json,
                                                              const std::string& where);

}  // namespace terra::project
