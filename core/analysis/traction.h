#pragma once
/// @file traction.h
/// The best slip for a soil (docs/traction.md): the slip s* that maximises a wheel's drawbar pull
/// F_x or its tractive efficiency η = F_x r (1 − s) / M_y at its load and slip angle, optionally
/// under a sinkage cap; and, from an identified soil's posterior, the band of the objective
/// against slip and a robust s* (the slip that maximises a lower quantile of the objective over
/// the posterior). `terrastudio traction`, a script's "traction" and Python's ts.traction.

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/analysis/soil_posterior.h"
#include "core/common/declared_fields.h"
#include "core/common/range.h"
#include "core/contact/operating_fields.h"
#include "core/scenario/traction_control.h"

namespace terra::analysis {

/// What s* maximises.
enum class TractionObjective {
    kDrawbar,     ///< F_x [N] (Eq. 2.23)
    kEfficiency,  ///< η = F_x r (1 − s) / M_y [-] (output power over input power)
};
const char* objectiveName(TractionObjective objective);

/// The range of the searched slips [-].
inline constexpr Range kTractionSlipRange{0.0, 0.99};

struct TractionSettings {
    double slip_angle_deg = 0.0;  ///< β [deg]
    TractionObjective objective = TractionObjective::kEfficiency;
    std::optional<double> max_sinkage_m;  ///< cap on the sinkage h [m] (compaction.md's concern)
    double slip_min = 0.01;               ///< the search's slips [-]
    double slip_max = 0.9;
    int curve_points = 60;  ///< slips of the curve, evenly from slip_min to slip_max
    std::optional<SoilPosterior> posterior;  ///< the soil's uncertainty
    int posterior_samples = 200;             ///< soils drawn from it
    /// How the posterior is carried through the objective: drawn soils (the default), or the
    /// second-order transform on 2d + 1 sigma points (docs/traction.md §8, "Cost").
    scenario::PosteriorMethod posterior_method = scenario::PosteriorMethod::kSamples;
    std::uint64_t seed = 1;
    double quantile = 0.1;  ///< robust s* maximises this quantile of the objective (0.5: median)
    ModelChoices model;

    /// Its file keys, one line each (core/common/declared_fields.h): the reader, toJson, the
    /// command line's flags and compute's checks are made from them, the model choices included
    /// (ModelChoices' own list).
    template <typename Visitor>
    void visitFields(Visitor& v);
};

/// "posterior" as an object (readPosterior); a file name is left to readTractionSettings, which
/// resolves it against its directory. Problems are reported at `key`.
void readPosteriorObject(io::ObjectReader& r, const char* key, std::optional<SoilPosterior>& out);
/// "posterior" as JSON ({"parameters", "mean", "covariance"}); null when empty.
nlohmann::json posteriorJson(const std::optional<SoilPosterior>& posterior);

template <typename Visitor>
void TractionSettings::visitFields(Visitor& v) {
    const FieldInfo& beta = contact::slipAngleField();
    v(fields::number(beta.key, slip_angle_deg, beta.range, "deg", "slip angle β"));
    v(fields::choice(
        "objective", objective,
        {{"drawbar", TractionObjective::kDrawbar}, {"efficiency", TractionObjective::kEfficiency}},
        "what s* maximises: drawbar pull F_x or tractive efficiency"));
    v(fields::number("max_sinkage_m", max_sinkage_m, {0.0, 1.0, true}, "m",
                     "cap on the sinkage; absent: none"));
    v(fields::number("slip_min", slip_min, kTractionSlipRange, "", "smallest slip searched"));
    v(fields::number("slip_max", slip_max, kTractionSlipRange, "",
                     "largest slip searched (above slip_min)"));
    v(fields::integer("curve_points", curve_points, 5, 10000,
                      "slips of the curve, evenly from slip_min to slip_max"));
    v(fields::integer("posterior_samples", posterior_samples, scenario::kMinPosteriorSamples,
                      scenario::kMaxPosteriorSamples, "posterior: soils drawn from it"));
    v(fields::integer("seed", seed, 0, std::numeric_limits<std::uint64_t>::max(),
                      "posterior: seed of the draws"));
    v(fields::field(scenario::robustQuantileField(), quantile));
    v(fields::choice("posterior_method", posterior_method,
                     {{"samples", scenario::PosteriorMethod::kSamples},
                      {"sigma-points", scenario::PosteriorMethod::kSigmaPoints}},
                     "posterior: drawn soils, or the second-order transform on sigma points"));
    v(fields::custom("posterior", posterior, "object or path",
                     "{parameters, mean, covariance}, or a soil file holding \"posterior\"",
                     "the soil's uncertainty: the band and a robust s*", readPosteriorObject,
                     posteriorJson));
    v(fields::members(model));
}

/// The keys of TractionSettings::visitFields, read strictly (io::readFields), then what a field
/// list cannot say: a "posterior" file (a soil file holding "posterior", relative to
/// `base_dir`) and the rules between keys
/// (tractionRuleIssues).
void readTractionSettings(io::ObjectReader& r, TractionSettings& out,
                          const std::filesystem::path& base_dir = {});
/// The rules a field list cannot say: slip_max above slip_min; the posterior's parameters soil
/// fields, its mean and covariance of their count, the covariance symmetric positive definite.
std::vector<Issue> tractionRuleIssues(const TractionSettings& settings);
/// The settings' file keys (io::fieldsToJson) and the non-default model choices: what
/// readTractionSettings reads back.
nlohmann::json toJson(const TractionSettings& settings);

/// The wheel at one slip.
struct TractionPoint {
    double slip = 0.0;
    double fx_n = 0.0;
    double my_nm = 0.0;
    double efficiency = 0.0;  ///< η; 0 where M_y ≤ 0 (the wheel is driven by the soil)
    double sinkage_m = 0.0;
    bool ok = false;  ///< an equilibrium exists and the sinkage cap holds
};

/// The objective's spread over the posterior at one slip.
struct TractionBand {
    double slip = 0.0;
    double mean = 0.0, p5 = 0.0, p50 = 0.0, p95 = 0.0;
    double quantile = 0.0;  ///< at TractionSettings::quantile
    int samples = 0;        ///< soils with an equilibrium at this slip
};

struct TractionResult {
    TractionObjective objective = TractionObjective::kEfficiency;
    std::optional<double> optimal_slip;  ///< s* of the given soil (the posterior's mean)
    TractionPoint at_optimum;
    std::vector<TractionPoint> curve;
    /// With a posterior: the band on the curve's slips, the robust s* (the quantile's maximum)
    /// and the slip of the largest expected objective.
    std::vector<TractionBand> band;
    std::optional<double> robust_slip;
    double robust_value = 0.0;
    std::optional<double> expected_slip;
    /// The spread of s* over the posterior: the standard deviation of each drawn soil's own s*
    /// (its largest objective on the curve's slips) [-].
    std::optional<double> optimal_slip_std;
    int invalid_samples = 0;  ///< posterior draws outside a field's range (left out)
    std::string message;      ///< non-empty: no slip meets the cap or has an equilibrium
    std::vector<std::string> notes;
    bool cancelled = false;  ///< stopped by the cancel flag: the curve or the band is partial

    bool ok() const { return optimal_slip.has_value(); }
    /// kCancelled: stopped by the cancel flag (an s* found before it is kept, the band partial);
    /// kFailed: no s* (`message` says why); else kCompleted. Invalid inputs or settings throw
    /// (computeTraction), so never kInvalidInput.
    Outcome::Status status() const {
        return cancelled ? Outcome::Status::kCancelled
               : ok()    ? Outcome::Status::kCompleted
                         : Outcome::Status::kFailed;
    }
};

/// The objective's value at a point (F_x, or η; −∞ where the point is not ok).
double objectiveValue(TractionObjective objective, const TractionPoint& point);

/// The wheel at slip s: θ_f from F_z = W, forces (full or quadratic model), η, sinkage.
/// `failure` (if given) gets the sinkage solver's reason when there is no equilibrium, else "".
TractionPoint tractionPoint(const contact::ContactParameters<double>& params, double load_n,
                            double slip, const TractionSettings& settings,
                            contact::ContactModel model, std::string* failure = nullptr);

/// Throws std::invalid_argument for invalid inputs or settings.
TractionResult computeTraction(const Inputs& inputs, const TractionSettings& settings = {},
                               const Control& control = {});

/// `terrastudio traction --json`: "optimal_slip", "objective", "Fx_N", "My_Nm", "efficiency",
/// "sinkage_m" at s*, "curve": [{"slip", "Fx_N", "My_Nm", "efficiency", "sinkage_m"}, …], and
/// with a posterior "robust_slip", "robust_value", "expected_slip", "optimal_slip_std", "band";
/// always "status" (statusName(result.status())), "notes", and "message" when there is one.
nlohmann::json toJson(const TractionResult& result);
/// The result for a person, as `terrastudio traction` prints it above its curve: a heading
/// with the soil, the wheel, the load W, β, the objective and the sinkage cap; then s*, F_x
/// [N], M_y [N m], η and the sinkage [mm] at s*; with a posterior's robust s*, a heading and
/// the robust s*, the objective's quantile there, the slip of the largest mean and the spread
/// of s*; the notes as warnings. Without an s*: the heading and why (cancelled or failed).
/// Each number's `json` points at it in toJson(result) (the sinkage's `number` in m).
Summary tractionSummary(const Inputs& inputs, const TractionSettings& settings,
                        const TractionResult& result);
/// Tables "curve" (with the band's columns when there is one) and "optimum".
Outcome tractionOutcome(TractionResult result);

struct AnalysisType;
AnalysisType tractionType();

}  // namespace terra::analysis
