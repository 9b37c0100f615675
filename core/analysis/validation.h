#pragma once
/// @file validation.h
/// The model against measured single-wheel tests (docs/validation.md): every measured point is
/// predicted with its load given (θ_f solved from F_z = W, section 2.6.1: the same model as
/// `terrastudio wheel --load`), and each channel's errors are summarised as RMSE, MAE and the
/// largest relative error. Optionally the soil is first calibrated to the test — the global
/// identification from the load (core/identification/identify.h) with the given soil as a
/// Gaussian prior — on all points or on some slips only, the others then held out.
/// `terrastudio validate` and a script's "validation" analysis.

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/common/declared_fields.h"
#include "core/common/range.h"
#include "core/identification/identify.h"
#include "core/io/experiment.h"

namespace terra::analysis {

struct AnalysisType;
struct ReadContext;

/// Noise std of the channels the calibration weights [N, N·m, m] (io::ExperimentChannel order;
/// F_s and F_z are never fitted); 0: estimated from the residuals. The "noise" object.
struct ValidationNoise {
    std::array<double, io::kExperimentChannelCount> sigma{};

    double& operator[](std::size_t channel) { return sigma[channel]; }
    double operator[](std::size_t channel) const { return sigma[channel]; }

    /// Its keys: the fitted channels' names (Fx_N, My_Nm, sinkage_m).
    template <typename Visitor>
    void visitFields(Visitor& v);
};

struct ValidationSettings {
    std::string experiments;  ///< the test: its CSV or its sidecar JSON (io/experiment.h)
    /// The test read already (a script's reader reads it before anything runs); when set,
    /// `experiments` only names it.
    std::optional<io::Experiment> data;
    bool calibrate = false;  ///< fit the soil to the test first
    /// Calibrate on the points at these slips only (each must be a slip of the test); the others
    /// are held out and predicted. Empty: every point.
    std::vector<double> fit_slips;
    /// Noise std of each channel weighting the calibration [N, N·m, m, N, N]
    /// (io::ExperimentChannel order); 0: estimated from the residuals.
    ValidationNoise noise;
    /// Calibration only: fit n₁ of the slip-sinkage exponent N = n + n₁ s too (docs/model.md,
    /// "Slip-sinkage"), by profiling χ² over n₁; false: n₁ = 0, the thesis model.
    bool fit_n1 = false;
    /// Calibration only: fit S of Lyasko's slip sinkage h = h₀ (1 + S s) too (docs/model.md, "Slip
    /// sinkage", Eq. S.1), by profiling χ² over S ∈ [0, 10]; false: S = 0, the thesis model. Not
    /// with fit_n1 (one slip-sinkage model at a time).
    bool fit_slip_sinkage = false;
    /// Compute ValidationRun::curves (the model lines of the validation figures). The studio's
    /// forces panel draws its own sweeps at the test's loads and turns this off. Code only (no
    /// file key).
    bool curves = true;

    /// Its file keys, one line each (core/common/declared_fields.h): the reader, toJson, the
    /// command line's flags and compute's checks are made from them. The test read (`data`) and
    /// `curves` are not file keys.
    template <typename Visitor>
    void visitFields(Visitor& v);
};

/// The range of a noise level given (σ > 0; absent, 0 in the member: estimated).
inline constexpr Range kValidationNoiseRange{0.0, 1e6, true, false};

template <typename Visitor>
void ValidationNoise::visitFields(Visitor& v) {
    for (const std::size_t c : {io::kExpFx, io::kExpMy, io::kExpSinkage}) {
        const io::ExperimentColumn& column = io::experimentChannels()[c];
        v(fields::number(column.name, sigma[c], kValidationNoiseRange, column.unit,
                         "calibration: noise σ of the channel; absent: estimated", 0.0));
    }
}

template <typename Visitor>
void ValidationSettings::visitFields(Visitor& v) {
    v(fields::path("experiments", experiments,
                   "the test: its CSV or its sidecar JSON (required; read at once)"));
    v(fields::flag("calibrate", calibrate, "fit the soil to the test first"));
    v(fields::numbers("fit_slips", fit_slips, {-1.0, 1.0}, "",
                      "calibration: fit on the points at these slips of the test only; the others "
                      "are held out",
                      1));
    v(fields::object("noise", noise, "calibration: noise levels weighting the channels"));
    v(fields::flag("fit_n1", fit_n1,
                   "calibration: fit n1 of the slip-sinkage exponent N = n + n1 s too"));
    v(fields::flag("fit_slip_sinkage", fit_slip_sinkage,
                   "calibration: fit S of Lyasko's slip sinkage h = h0 (1 + S s) too (not with "
                   "fit_n1)"));
}

/// The keys of ValidationSettings::visitFields, read strictly (io::readFields), then what a field
/// list cannot say: "experiments" is required and read at once (relative to the context's
/// directory; a bad test is a problem of the settings; a test the caller has read already, in
/// `out.data`, is not read again), every fit slip must be a slip of the test, and the rules
/// between keys (validationRuleIssues).
void readValidationSettings(io::ObjectReader& r, const ReadContext& context,
                            ValidationSettings& out);
/// The rules between keys: "fit_slips", "fit_n1" and "fit_slip_sinkage" belong to the
/// calibration; "fit_n1" or "fit_slip_sinkage", not both.
std::vector<Issue> validationRuleIssues(const ValidationSettings& settings);
/// The fit slips that are no slip of `experiment`, at "fit_slips[i]".
std::vector<Issue> fitSlipIssues(const std::vector<double>& fit_slips,
                                 const io::Experiment& experiment);
/// The settings' file keys (io::fieldsToJson): what readValidationSettings reads back.
nlohmann::json toJson(const ValidationSettings& settings);

/// The errors of one channel over the points that measure it and have a prediction.
struct ChannelMetrics {
    std::size_t count = 0;  ///< points compared
    double rmse = 0.0;      ///< √(mean (predicted − measured)²)
    double mae = 0.0;       ///< mean |predicted − measured|
    /// max |predicted − measured| / |measured| over the points with measured ≠ 0 (NaN if none)
    double max_rel_error = std::numeric_limits<double>::quiet_NaN();
};

/// Per channel; empty where no point measures it (or none could be predicted).
using ValidationMetrics = std::array<std::optional<ChannelMetrics>, io::kExperimentChannelCount>;

/// One measured point and the model's prediction of it.
struct PointComparison {
    io::ExperimentPoint point;
    bool predicted = false;  ///< false: no equilibrium at this load (see failure)
    std::string failure;     ///< why there is no prediction
    double entry_angle_deg = std::numeric_limits<double>::quiet_NaN();
    /// F_x, M_y, sinkage r (1 − cos θ_f), side force F_s (Eq. 2.24), F_z [N, N·m, m, N, N]
    std::array<double, io::kExperimentChannelCount> values{};
    bool in_fit = true;  ///< among the points the calibration used
};

/// The points of a test predicted with one soil, and their metrics.
struct ValidationRun {
    soil::SoilParameters soil;
    std::vector<PointComparison> points;
    ValidationMetrics metrics;
    /// The model against slip through the test, for plots: for each (load, slip angle) of its
    /// points, kValidationCurveSlips slips evenly from min(0, the lowest slip) to the highest
    /// (at least 0.05 wide); columns load_N, slip_angle_deg, slip, then the channels Fx_N, My_Nm,
    /// sinkage_m, Fy_N, Fz_N as predicted (NaN where there is no equilibrium).
    Table curves;
};

inline constexpr int kValidationCurveSlips = 61;

/// The calibration of the soil to the test.
struct Calibration {
    identification::IdentificationReport report;
    identification::ParameterVector prior{};  ///< the given soil's parameters on this wheel (SI)
    std::vector<std::string> channels;        ///< the channels fitted ("Fx_N", "sinkage_m")
    soil::SoilParameters soil;                ///< the calibrated soil (usable report only)
    /// With fit_n1: n₁ at the minimum of the profile χ²(n₁) (the report is the fit at it), its
    /// std from the profile's curvature (Δχ² = 1), and the profile (n₁, χ²) evaluated.
    std::optional<double> n1, n1_std;
    std::vector<std::pair<double, double>> n1_profile;
    /// With fit_slip_sinkage: S at the minimum of the profile χ²(S), its std (Δχ² = 1) and the
    /// profile (S, χ²), as for n₁.
    std::optional<double> slip_sinkage, slip_sinkage_std;
    std::vector<std::pair<double, double>> slip_sinkage_profile;
    std::optional<ValidationRun> after;  ///< every point with the calibrated soil
    /// Held-out points only (when fit_slips leaves some out): with the given and the calibrated
    /// soil.
    std::optional<ValidationMetrics> held_out_before, held_out;
};

struct ValidationResult {
    /// kCompleted; kCancelled: stopped by the cancel flag (the given soil's predictions are
    /// kept, a calibration stopped halfway is dropped); kFailed: no result, `message` says why
    /// (validationFailure); kInvalidInput: the test named by the settings could not be read
    /// (`issues`). Callers test this, never the message's words.
    Outcome::Status status = Outcome::Status::kCompleted;
    std::string message;
    std::vector<Issue> issues;  ///< kInvalidInput: every problem of the test
    std::string source;         ///< the test's file
    std::string soil, wheel;    ///< the given soil's and the wheel's names
    ValidationRun before;
    std::optional<Calibration> calibration;
    std::vector<std::string> notes;
};

/// The errors of the points (those with in_fit == `in_fit` when given).
ValidationMetrics computeMetrics(const std::vector<PointComparison>& points,
                                 std::optional<bool> in_fit = std::nullopt);

/// Predicts every point of `experiment` with the soil and wheel of `inputs` (and, with `curves`,
/// the model against slip through them).
ValidationRun predictExperiment(const Inputs& inputs, const io::Experiment& experiment,
                                bool curves = true);

/// The soil whose parameters on `wheel` are `p` (identify.h's θ): a₀, a₁, n, c, φ, K taken over,
/// n₁ as given (the identification's model), and k_c, k_φ both scaled by K_s(p)/K_s(prior) so that
/// K_s = k_c/b + k_φ is p's on this wheel width (only K_s is seen by a test at one width), S of
/// the slip sinkage (Eq. S.1) as given. The rest (γ, j_max) as `prior`'s.
soil::SoilParameters soilFromParameters(const soil::SoilParameters& prior,
                                        const wheel::WheelParameters& wheel,
                                        const identification::ParameterVector& p, double n1 = 0.0,
                                        double slip_sinkage = 0.0);

/// Throws std::invalid_argument for invalid inputs or settings that the reader refuses (a struct
/// built in code: a value out of its range, a fit slip that is not in the test; a programmer's
/// error, in the reader's words); a test named by `settings.experiments` that cannot be read
/// (no `data`) gives status kInvalidInput with its issues.
ValidationResult computeValidation(const Inputs& inputs, const ValidationSettings& settings,
                                   const Control& control = {});

/// The result as JSON: {"points": [{"load_N", "slip", "slip_angle_deg", CHANNEL: {"measured",
/// "predicted"}, …}], "metrics": {CHANNEL: {"rmse", "mae", "max_rel_error", "count"}}, and with a
/// calibration "calibration": {…} (docs/cli.md, `validate`).
nlohmann::json toJson(const ValidationResult& result);

/// Why the validation is no result, or "" (also for a cancelled one): the calibration failed (its
/// solver found no usable or no converged fit), the calibrated soil predicts none of the points,
/// or, without a calibration, the given soil predicts none (every point without equilibrium: no
/// metric).
std::string validationFailure(const ValidationResult& result);

/// The result for a person, as `terrastudio validate` prints it: the title, the metrics of the
/// given soil, the calibration (its parameters ± std with their priors, its flags; or FAILED
/// and why), the calibrated soil's metrics, the held-out points' metrics, the notes. A metrics
/// row per channel shows its RMSE (the MAE, largest relative error and count in its detail).
/// Forces and torques in N, N·m, the sinkage in mm, the largest relative error in %; each
/// number's `json` points at it in toJson(result).
/// The parameter rows, labelled by symbol (K_s, n₀, φ, …; the JSON keeps the keys), give each
/// value to the decimal place its std supports (formatAtStd) and
/// the prior in the detail ("prior 31.9", then ", ended at its bound" when it did); the
/// calibration's heading says the solver's outcome in a user's words
/// (identification::solverOutcome).
Summary validationSummary(const ValidationResult& result);

/// The validation's metrics as one table for a person (the studio's calibration dialog shows
/// it): a row per measured channel and metric — RMSE, MAE, largest relative error — and a column
/// per set of points: the given soil, the calibrated soil (a usable calibration), and, when the
/// calibration held points out, those points with the given and with the calibrated soil. Each
/// cell is the number formatted as validationSummary formats it (the same function: "5.656" "N",
/// "84.0" "%", the sinkage in mm; value "" where the column has none for that channel), its
/// `json` pointing at it in toJson(result).
struct MetricsTable {
    /// "given soil", "calibrated", "held out, given soil", "held out, calibrated" (those present).
    std::vector<std::string> columns;
    struct Row {
        std::string label;              ///< "F_x RMSE", "h MAE", "M_y max relative error"
        std::vector<SummaryRow> cells;  ///< one per column
    };
    std::vector<Row> rows;
};
MetricsTable validationMetricsTable(const ValidationResult& result);

/// A cell's text: its value and unit ("5.656 N"), or "" for none.
std::string cellText(const SummaryRow& cell);

/// Tables "metrics" (main: one row, CHANNEL_rmse, CHANNEL_mae, CHANNEL_max_rel_error,
/// CHANNEL_count per measured channel), "points", "curves" (ValidationRun::curves) and,
/// calibrated, "calibrated_metrics", "calibrated_points", "calibrated_curves", "held_out_metrics",
/// "parameters"; the JSON as "-validation.json". Failed (with validationFailure's reason) when
/// validationFailure says so. Figures "Fx", "sinkage", "My", "Fy": the
/// measured points on the model's curves (widgets/plots/figures.h, plotValidation).
Outcome validationOutcome(ValidationResult result);

AnalysisType validationType();

}  // namespace terra::analysis
