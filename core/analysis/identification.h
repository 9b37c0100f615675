#pragma once
/// @file identification.h
/// Soil identification from wheel data (thesis chapters 4–5): by default the global
/// identification on the full model (core/identification/identify.h: a space-filling design of
/// starts, screening, descents, refinement; priors, robust loss, held-out error, ambiguity), or
/// the thesis's decoupled three-step fit alone (Eqs. 4.12, 4.17, 4.18), on a CSV data set or on
/// synthetic data made from the inputs' soil (Eq. 5.1). The studio's identification panel,
/// `terrastudio identify --data` and a script's "identification" analysis. The algorithms are
/// core/identification's; this service only chooses the data and the options, and tabulates the
/// result.
///
/// A CSV's fit depends on the data and the settings only, never on the inputs' soil: the global
/// search starts from its design (and the settings' `starts`), j_max is the settings' (none by
/// default). Synthetic data are made from the inputs' soil, so there its j_max is the model's.

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/analysis/conditions.h"
#include "core/analysis/identified_parameters.h"
#include "core/common/declared_fields.h"
#include "core/contact/operating_fields.h"
#include "core/identification/data_set.h"
#include "core/identification/decoupled_fit.h"
#include "core/identification/full_fit.h"
#include "core/identification/identify.h"
#include "core/identification/profile_interval.h"

namespace terra::analysis {

struct AnalysisType;
struct ReadContext;

/// Synthetic data of the identification: slip sweeps of the inputs' soil with Gaussian noise.
struct SyntheticSource {
    double noise_percent = 2.0;   ///< σ of F_x, F_z, M_y as % of each channel's largest value
    std::uint64_t seed = 1;       ///< the same seed gives the same data everywhere
    std::vector<double> loads_n;  ///< W [N], one sweep each; empty: the conditions' load
    int slip_count = 50;          ///< slips 0 … min(conditions' slip_max, max_slip)
    /// Largest slip of the synthetic sweeps: beyond it the entry angle barely changes with
    /// slip and adds nothing to the fit.
    static constexpr double kMaxSlip = 0.9;

    /// Its keys, in the identification's object (core/common/declared_fields.h).
    template <typename Visitor>
    void visitFields(Visitor& v);
};

/// Noise levels weighting the refinement's residuals; 0: estimated from the residuals.
struct NoiseLevels {
    double fx_n = 0.0;   ///< σ of F_x [N]
    double fz_n = 0.0;   ///< σ of F_z [N]
    double my_nm = 0.0;  ///< σ of M_y [N·m]

    template <typename Visitor>
    void visitFields(Visitor& v);
};

struct IdentificationSettings {
    std::string csv;             ///< data file (data_set.h columns); empty: synthetic
    bool skip_bad_rows = false;  ///< false: a bad row stops the read, every bad row listed
    /// The data read already (a script's reader reads the CSV before anything runs); when set,
    /// `csv` only names it.
    std::optional<identification::DataSet> data;
    /// The columns of `csv` that the reader does not use ("FILE:1: column 'x' is not read …"),
    /// passed on to the result's warnings.
    std::vector<std::string> data_warnings;
    /// Deprecated parameter keys the reader read ("Ks" for "Ks_kPa", issue 26), each where it
    /// was and the note naming the new key; passed on to the result's warnings (the command line
    /// prints them with its flags' names and clears them).
    std::vector<Issue> key_warnings;
    SyntheticSource synthetic;
    identification::DecoupledParameters guess;  ///< start of the decoupled fit (thesis's guesses)
    /// true: the global identification on the full model (identify.h; removes the decoupled
    /// model's linearisation bias and does not depend on a start); false: the decoupled fit alone.
    bool refine = true;
    /// Full model: starts besides the space-filling design (a user's guess); none is needed.
    std::vector<identification::Start> starts;
    /// Full model: points of the space-filling design (`--starts`).
    int design_points = identification::IdentifyOptions{}.design_points;
    /// Full model: Gaussian priors centred on a soil (PriorSpreads of parameters.h) and named
    /// ("sandy-loam"), then items in user units ("phi_deg=30±5", parsePriorItem) on top.
    std::optional<soil::SoilParameters> prior_soil;
    std::string prior_soil_name;
    std::vector<std::string> prior_items;
    identification::Loss loss = identification::Loss::kSquared;
    /// Full model: held-out validation, a fraction in (0, 1) or k ≥ 2 folds (0: none).
    double holdout_fraction = 0.0;
    int folds = 0;
    /// Full model: W [N] of every sample without a W_N cell (data without an entry angle).
    std::optional<double> load_n;
    /// Refinement only: parameters kept at a value, by field key (identified_parameters.h) with
    /// the value in the field's unit.
    std::vector<std::pair<std::string, double>> fixed;
    /// Refinement only: noise levels weighting the residuals; 0: estimated.
    NoiseLevels noise;
    /// The forward model's j_max [m] (held); empty: the inputs' soil's (synthetic data) or none;
    /// +inf (code only, never written): none, whatever the data.
    std::optional<double> max_shear_deformation_m;
    /// Full model: identify j_max as an eighth parameter (`--jmax fit`, "fit_jmax": true; with a
    /// prior when the data do not determine it, IdentifyOptions::fit_max_shear_deformation).
    bool fit_max_shear_deformation = false;
    /// Full model: profile-likelihood intervals (Δχ² = 9, profile_interval.h) of the parameters
    /// in a flagged trade-off or at a bound (`--profile`; costs up to 10 refinements per side).
    bool profile = false;

    /// Its file keys, one line each (core/common/declared_fields.h): what the reader, toJson,
    /// the command line's flags and the panel's saved state are made from. The data, the
    /// resolved prior soil, the decoupled fit's guess and extra starts are not file keys.
    template <typename Visitor>
    void visitFields(Visitor& v);
};

/// Reads "fix" ({key: value}, the refined parameters' keys of identified_parameters.h in their
/// units; a deprecated key, "Ks" or "n", is read as its new one), reporting an unknown key with
/// the nearest one and a value outside its field's range. The pairs are stored under the
/// table's keys.
void readFixedParameters(io::ObjectReader& r, const char* key,
                         std::vector<std::pair<std::string, double>>& out);
/// The deprecated parameter keys (issue 26) of a settings object just read: each prior item with
/// an old key ("Ks=1500±500") rewritten with its new one, and noted in `out.key_warnings`, where
/// `priors_key` was (the command line names its flag there), as each old key of "fix" (read as its
/// new one by readFixedParameters). The identification's reader and the identification panel's
/// saved settings (core/project/panels.h) note them so.
void noteDeprecatedParameterKeys(io::ObjectReader& r, IdentificationSettings& out,
                                 const char* priors_key = "priors");
/// The prior items of `s` with an old key: {"priors", "prior 'Ks=1500±500': parameter key 'Ks'
/// is deprecated: use 'Ks_kPa'"} each (computeIdentification notes those of settings built in
/// code among its warnings).
std::vector<Issue> deprecatedPriorItems(const IdentificationSettings& s);

/// "fix" as JSON; null when empty.
nlohmann::json fixedParametersJson(const std::vector<std::pair<std::string, double>>& fixed);

/// The σ ranges of the noise levels [N, N, N·m] and of the synthetic noise [%].
inline constexpr Range kNoiseLevelRange{0.0, 1e6};
inline constexpr Range kNoisePercentRange{0.0, 100.0};

template <typename Visitor>
void SyntheticSource::visitFields(Visitor& v) {
    const FieldInfo& load = contact::loadField();
    v(fields::number("noise_percent", noise_percent, kNoisePercentRange, "%",
                     "synthetic data: noise σ of F_x, F_z, M_y as % of each channel's largest "
                     "value (Eq. 5.1)"));
    v(fields::integer("seed", seed, 0, std::numeric_limits<std::uint64_t>::max(),
                      "synthetic data: the random seed"));
    v(fields::numbers("loads_N", loads_n, load.range, "N",
                      "synthetic data: W [N], one slip sweep each; absent: the conditions' load",
                      1));
    v(fields::integer("slip_count", slip_count, static_cast<int>(slipCountField().range.low),
                      static_cast<int>(slipCountField().range.high),
                      "synthetic data: slips 0 … min(slip_max, 0.9) of each sweep"));
}

template <typename Visitor>
void NoiseLevels::visitFields(Visitor& v) {
    v(fields::number("Fx_N", fx_n, kNoiseLevelRange, "N", "σ of F_x; 0: estimated"));
    v(fields::number("Fz_N", fz_n, kNoiseLevelRange, "N", "σ of F_z; 0: estimated"));
    v(fields::number("My_Nm", my_nm, kNoiseLevelRange, "N·m", "σ of M_y; 0: estimated"));
}

template <typename Visitor>
void IdentificationSettings::visitFields(Visitor& v) {
    using identification::Loss;
    v(fields::path("csv", csv,
                   "data set CSV (data_set.h columns), read at once; empty: synthetic data from "
                   "the inputs' soil"));
    v(fields::flag("skip_bad_rows", skip_bad_rows,
                   "true: bad rows of the CSV are skipped (listed); false: they stop the read"));
    v(fields::members(synthetic));
    v(fields::flag("refine", refine,
                   "true: the global identification on the full model; false: the decoupled "
                   "three-step fit alone"));
    v(fields::custom("fix", fixed, "object", "{refined parameter key: value in its unit}",
                     "refinement: parameters kept at a value", readFixedParameters,
                     fixedParametersJson));
    v(fields::object("noise", noise, "refinement: noise levels weighting the residuals"));
    v(fields::field(*soil::findSoilField("jmax_m"), max_shear_deformation_m,
                    std::numeric_limits<double>::infinity()));
    v(fields::flag("fit_jmax", fit_max_shear_deformation,
                   "full model: identify j_max as an eighth parameter (not with jmax_m)"));
    v(fields::texts("priors", prior_items,
                    "full model: Gaussian priors NAME=MEAN±STD in the parameters' units"));
    v(fields::text("prior_soil", prior_soil_name,
                   "full model: priors centred on this soil (preset or JSON file)"));
    v(fields::choice("loss", loss,
                     {{"l2", Loss::kSquared},
                      {"huber", Loss::kHuber},
                      {"cauchy", Loss::kCauchy},
                      {"squared", Loss::kSquared, true}},
                     "full model: the loss (huber, cauchy: robust to outliers)"));
    v(fields::number("holdout", holdout_fraction, {0.0, 1.0, true, true}, "",
                     "full model: held-out error, this fraction of the samples predicted from a "
                     "fit without them",
                     0.0));
    v(fields::integer("folds", folds, 2, 1000,
                      "full model: held-out error by k-fold cross-validation", 0));
    v(fields::integer("starts", design_points, 0, 100000,
                      "full model: points of the space-filling design of starts"));
    v(fields::field(contact::loadField(), load_n));
    v(fields::flag("profile", profile,
                   "full model: profile-likelihood intervals of the flagged parameters"));
}

/// The keys of IdentificationSettings::visitFields, read strictly (io::readFields), then what a
/// field list cannot say: "csv" is read at once (relative to the context's directory; a bad
/// file is a problem of the settings, read as the full model or the decoupled fit reads it),
/// "priors" items are parsed, "prior_soil" is resolved (a preset, or a file relative to the
/// context's directory), and the pairs that exclude each other (identificationRuleIssues).
void readIdentificationSettings(io::ObjectReader& r, const ReadContext& context,
                                IdentificationSettings& out);
/// The rules between keys: "jmax_m" or "fit_jmax", "holdout" or "folds", not both.
std::vector<Issue> identificationRuleIssues(const IdentificationSettings& settings);
/// The settings' file keys (io::fieldsToJson): a default value is written, an empty optional or
/// list is left out.
nlohmann::json toJson(const IdentificationSettings& settings);

struct IdentificationResult {
    identification::DataSet data;
    std::vector<Issue> skipped;  ///< rows left out (skip_bad_rows)
    /// Synthetic points the soil cannot carry; columns of the CSV that are not read.
    std::vector<std::string> warnings;
    identification::DecoupledFit fit;
    /// The global identification's report (refine = true).
    std::optional<identification::IdentificationReport> report;
    identification::DecoupledParameters identified;  ///< the final estimate
    /// slip, entry_angle_deg, Fx_N, Fz_N, My_Nm (data; NaN where not measured), Fx_fit_N,
    /// Fz_fit_N, My_fit_Nm (the full model with the identified parameters when refined, else the
    /// decoupled model), W_N (the sample's load, NaN when the data do not say), then
    /// entry_angle_fit_deg (the model's θ_f: measured, or solved from the load), sinkage_m and
    /// sinkage_fit_m.
    Table curves;
    /// One row: identifiedFields() in their units, and when refined the *_std columns of the
    /// refined parameters.
    Table parameters;
    double fit_time_ms = 0.0;
    /// Profile-likelihood intervals (settings.profile; `computed` false for the others).
    std::array<identification::ProfileInterval, identification::kFullParameterCount> profile{};
    double profile_time_ms = 0.0;
    std::string wheel;  ///< the wheel's name
    /// kCompleted: fitted (usable() says whether it converged; a fit that did not is still a
    /// result, its tables kept); kInvalidInput: nothing to fit, `message` says why and the issues
    /// are in `data_issues` (the CSV could not be read) or the report's `issues` (data or options
    /// the identification cannot use); kCancelled: stopped by the cancel flag before a result.
    /// Callers test this, never the message's words. (Never kFailed.)
    Outcome::Status status = Outcome::Status::kCompleted;
    std::string message;  ///< non-empty: there was nothing to fit (see data_issues)
    /// status == kCancelled (kept for the panels that test it).
    bool cancelled = false;
    std::vector<Issue> data_issues;  ///< why the data could not be read

    /// What the fit started from, for a person: "global search (64 design points)", "+ guess …",
    /// "prior: …", or "decoupled fit from the thesis's guesses".
    std::string start_description;

    /// Every step's report: the three decoupled steps, or the global identification's phases
    /// (screening, descent, refinement, and held-out when computed).
    std::vector<identification::StepReport> steps() const;
    /// The fit and its refinement converged to usable solutions.
    bool usable() const;
};

/// The identified parameters as JSON: identifiedFields()' keys in their units.
nlohmann::json identifiedJson(const identification::DecoupledParameters& parameters);
/// The seven parameters of the full model (SI) as JSON in their fields' keys and units.
nlohmann::json fullParametersJson(const identification::ParameterVector& si);

/// The Gauss–Newton covariance of the identified parameters (IdentificationReport::uncertainty:
/// Σ_ij = σ_i σ_j ρ_ij) in the identification's keys and display units, each parameter's
/// std scaled by its field's unit (Σ_ij / (to_si_i to_si_j)): {"parameters": [keys of the free
/// parameters, fieldOf order], "mean": [the estimate], "covariance": [[…]]}; null when the
/// covariance was not computed (rank deficient). Its diagonal's square roots are the "std" of
/// toJson.
nlohmann::json covarianceJson(const identification::IdentificationReport& report);

/// The result as `terrastudio identify --json` prints it and Python's ts.identify returns it
/// (docs/cli.md, "identify"): the parameters (identifiedFields() keys), and when refined "std",
/// "flags", "covariance", "prior", "holdout", "ambiguity", "ambiguity_delta_chi2",
/// "gradient_norm", "newton_decrement", "chi2", "start", "source", "noise",
/// "noise_estimated", "profile_interval"; always "steps" and "samples". For a result with a
/// `message` (nothing fitted) only "steps" and "samples" mean anything.
nlohmann::json toJson(const IdentificationResult& result);

/// The result for a person, as `terrastudio identify` prints it and the identification panel
/// shows it (widgets/panels/identification_report.h): the kind of fit and its wheel, the
/// samples, the identified parameters (with a std: the value to the place its std supports,
/// formatAtStd; j_max "held" or identified), each step's Σr², and after the global
/// identification where it started, χ², the gradient norm, what one more step would gain (the
/// Newton decrement, "at a minimum" below 0.1), the priors against the posterior, the held-out
/// errors (or "not computed"), the adequacy test, the profile intervals, the other minima (or
/// "ambiguity: none") and the flags. Each number's `json` points at it in toJson(result). A
/// cancelled result or one without data: the title and why.
Summary identificationSummary(const IdentificationResult& result);
/// Decimals of an identified parameter for a person (K_s in kPa/m^n is in the thousands: 1).
int displayDecimals(const IdentifiedField& field);

/// The soil an identification found, as `identify --save-soil` writes it: `base` (its γ, which
/// the wheel data do not see) with a₀, a₁, n, n₁, c, φ, K identified, k_c = 0 and k_φ = K_s (so
/// that K_s = k_c/b + k_φ is the identified one on any width: a test at one width sees only
/// K_s), and j_max the global identification's (identified, or the value it held), else (the
/// decoupled fit) `max_shear_deformation_m` (+inf: none). Issues name the identified values
/// that are outside a soil field's range (soil::validate).
Result<soil::SoilParameters> identifiedSoilFile(const IdentificationResult& result,
                                                const soil::SoilParameters& base,
                                                const wheel::WheelParameters& wheel,
                                                double max_shear_deformation_m);

/// The identification's posterior in the soil file's keys and units, the form `traction
/// --posterior`, `bands --posterior` and a study's "correlated" group read: {"parameters":
/// ["a0", "a1", "kphi", "n", "c_kPa", "phi_deg", "K_m", "jmax_m"] (the free ones), "mean": [the
/// values of `soil`, identifiedSoilFile's], "covariance": [[…]]}. K_s is carried by k_φ (k_c = 0 in
/// that soil, so Var k_φ = Var K_s), n₀ by n; the units are the identification's (kPa/m^n is
/// kN/m^(n+2)), so the numbers equal covarianceJson's. A parameter that ended at a bound of the
/// fit is held there (left out; the others' covariance is conditional on it, the Schur
/// complement Σ_ff − Σ_fb Σ_bb⁻¹ Σ_bf). Null when the covariance was not computed (rank
/// deficient, or the decoupled fit).
nlohmann::json soilPosteriorJson(const IdentificationResult& result,
                                 const soil::SoilParameters& soil,
                                 const wheel::WheelParameters& wheel);

/// Throws std::invalid_argument for invalid inputs or settings (a fixed key that is not a
/// refined parameter, a holdout fraction outside (0, 1)); data that cannot be read come back in
/// `data_issues`, data the identification cannot use (no load and no entry angle) in `message`.
IdentificationResult computeIdentification(const Inputs& inputs,
                                           const IdentificationSettings& settings = {},
                                           const Control& control = {});
/// Tables "parameters" (main) and "curves"; notes: each step's termination and Σr².
Outcome identificationOutcome(IdentificationResult result);

/// The identification options of the settings (the full model's) on this wheel, for
/// `identify()`. Throws std::invalid_argument for a bad prior item.
identification::IdentifyOptions identifyOptions(const IdentificationSettings& settings,
                                                const wheel::WheelParameters& wheel,
                                                double max_shear_deformation_m);
/// The priors of the settings on this wheel, and what they come from ("sandy-loam preset +
/// phi_deg=30±5"; empty: none). Throws std::invalid_argument for a bad item.
identification::Priors priorsOf(const IdentificationSettings& settings,
                                const wheel::WheelParameters& wheel, std::string* source = nullptr);

/// Reads a loss name: "l2" (or "squared"), "huber", "cauchy"; nullopt for another.
std::optional<identification::Loss> lossFromName(const std::string& name);
const char* lossName(identification::Loss loss);

AnalysisType identificationType();

}  // namespace terra::analysis
