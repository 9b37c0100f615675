#pragma once
/// @file identification.h
/// Soil identification from wheel data (thesis chapters 4–5): the decoupled three-step fit
/// (Eqs. 4.12, 4.17, 4.18) and, by default, its refinement through the full model with standard
/// deviations (core/identification/full_fit.h), on a CSV data set or on synthetic data made from
/// the inputs' soil (Eq. 5.1). The studio's identification panel, `terrastudio identify --data`
/// and a script's "identification" analysis. The algorithms are core/identification's; this
/// service only chooses the data, the start and the options, and tabulates the result.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/analysis/identified_parameters.h"
#include "core/analysis/registry.h"
#include "core/identification/data_set.h"
#include "core/identification/decoupled_fit.h"
#include "core/identification/full_fit.h"

namespace terra::analysis {

/// Synthetic data of the identification: slip sweeps of the inputs' soil with Gaussian noise.
struct SyntheticSource {
    double noise_percent = 2.0;   ///< σ of F_x, F_z, M_y as % of each channel's largest value
    std::uint64_t seed = 1;       ///< the same seed gives the same data everywhere
    std::vector<double> loads_n;  ///< W [N], one sweep each; empty: the conditions' load
    int slip_count = 50;          ///< slips 0 … min(conditions' slip_max, max_slip)
    /// Largest slip of the synthetic sweeps: beyond it the entry angle barely changes with
    /// slip and adds nothing to the fit.
    static constexpr double kMaxSlip = 0.9;
};

struct IdentificationSettings {
    std::string csv;             ///< data file (data_set.h columns); empty: synthetic
    bool skip_bad_rows = false;  ///< false: a bad row stops the read, every bad row listed
    /// The data read already (a script's reader reads the CSV before anything runs); when set,
    /// `csv` only names it.
    std::optional<identification::DataSet> data;
    SyntheticSource synthetic;
    identification::DecoupledParameters guess;  ///< start of the fit (the thesis's guesses)
    bool refine = true;  ///< refine through the full model (removes the linearisation bias)
    /// Refinement only: parameters kept at a value, by field key (identified_parameters.h) with
    /// the value in the field's unit.
    std::vector<std::pair<std::string, double>> fixed;
    /// Refinement only: noise levels weighting the residuals [N, N, N·m]; 0: estimated.
    double sigma_fx_n = 0.0, sigma_fz_n = 0.0, sigma_my_nm = 0.0;
    /// The forward model's j_max [m] (a setting, not identified); empty: the inputs' soil's.
    std::optional<double> max_shear_deformation_m;
};

/// "csv" (relative to the context's directory, read at once: a bad file is a problem of the
/// settings), "skip_bad_rows", "noise_percent", "seed", "loads_N", "slip_count", "refine",
/// "fix" ({key: value}), "noise" ({"Fx_N", "Fz_N", "My_Nm"}), "jmax_m".
void readIdentificationSettings(io::ObjectReader& r, const ReadContext& context,
                                IdentificationSettings& out);
nlohmann::json toJson(const IdentificationSettings& settings);

struct IdentificationResult {
    identification::DataSet data;
    std::vector<Issue> skipped;         ///< rows left out (skip_bad_rows)
    std::vector<std::string> warnings;  ///< synthetic points the soil cannot carry
    identification::DecoupledFit fit;
    std::optional<identification::RefineResult> refined;
    identification::DecoupledParameters identified;  ///< the final estimate
    /// slip, entry_angle_deg, Fx_N, Fz_N, My_Nm (data), Fx_fit_N, Fz_fit_N, My_fit_Nm (the full
    /// model with the identified parameters when refined, else the decoupled model) and W_N (the
    /// sample's load, NaN when the data do not say).
    Table curves;
    /// One row: identifiedFields() in their units, and when refined the *_std columns of the
    /// refined parameters.
    Table parameters;
    double fit_time_ms = 0.0;
    std::string message;             ///< non-empty: there was nothing to fit (see data_issues)
    std::vector<Issue> data_issues;  ///< why the data could not be read

    /// Every step's report: the three decoupled steps, then the refinement's.
    std::vector<identification::StepReport> steps() const;
    /// The fit and its refinement converged to usable solutions.
    bool usable() const;
};

/// Throws std::invalid_argument for invalid inputs or settings (a fixed key that is not a
/// refined parameter); data that cannot be read come back in `data_issues`.
IdentificationResult computeIdentification(const Inputs& inputs,
                                           const IdentificationSettings& settings = {},
                                           const Control& control = {});
/// Tables "parameters" (main) and "curves"; notes: each step's termination and Σr².
Outcome identificationOutcome(IdentificationResult result);

AnalysisType identificationType();

}  // namespace terra::analysis
