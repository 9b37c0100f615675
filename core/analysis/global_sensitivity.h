#pragma once
/// @file global_sensitivity.h
/// Global sensitivity and uncertainty of the wheel model as analyses of the registry: Sobol'
/// first-order and total indices with bootstrap confidence intervals, or Morris μ*/σ screening
/// ("sensitivity-global"), and Monte Carlo percentile bands of the forces against slip
/// ("uncertainty-bands"), over soil parameters given as ranges, normal distributions or a
/// correlated group (an identification's posterior). `terrastudio gsa` / `terrastudio bands`, a
/// script's analyses of these types and the studio's global sensitivity panel all call the
/// compute functions here; the numerics are core/gsa's (docs/sensitivity.md).

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/analysis/conditions.h"
#include "core/common/declared_fields.h"
#include "core/contact/operating_fields.h"
#include "core/gsa/parameter_space.h"
#include "core/gsa/uncertainty_bands.h"
#include "core/gsa/wheel_studies.h"
#include "core/identification/full_fit.h"
#include "core/identification/soil_conversion.h"

namespace terra::analysis {

struct AnalysisType;

/// One independent uncertain soil parameter: its soil file key ("phi_deg") and its distribution
/// in the file's unit (gsa::Uniform{low, high} or gsa::Normal{mean, sd, low, high}).
struct UncertainParameter {
    std::string key;
    gsa::Marginal distribution;
};

/// Soil parameters varying together, X ~ N(mean, covariance), in the fields' file units (the
/// identification's posterior: correlatedFromIdentification()).
struct CorrelatedParameters {
    std::vector<std::string> keys;
    std::vector<double> mean;
    std::vector<std::vector<double>> covariance;  ///< keys.size() × keys.size(), SPD
};

/// What the uncertain parameters of a study are and where the model is evaluated: shared by the
/// two analyses.
struct StudyDefinition {
    /// Default: the ranges of docs/sensitivity.md's example study.
    std::vector<UncertainParameter> parameters{{"phi_deg", gsa::Uniform{20.0, 35.0}},
                                               {"c_kPa", gsa::Uniform{0.0, 5.0}},
                                               {"K_m", gsa::Uniform{0.005, 0.04}},
                                               {"n", gsa::Uniform{0.5, 1.1}}};
    std::optional<CorrelatedParameters> correlated;  ///< after the independent ones
    std::vector<std::string> outputs{"Fx_N"};        ///< gsa::outputNames()
    std::vector<double> slips{0.1, 0.3, 0.6};        ///< s, each in [−1, 1]
    std::vector<double> slip_angles_deg{0.0};        ///< β [deg]
    /// W [N]; empty: the conditions' load, unless entry_angle_deg is given.
    std::optional<double> load_n;
    std::optional<double> entry_angle_deg;  ///< fixed θ_f [deg] instead of a load
    std::uint64_t seed = 1;                 ///< the same seed gives the same numbers
    double max_failed_fraction = 0.05;      ///< in [0, 1] (gsa::SobolOptions)
    ModelChoices model;
    int threads = 0;  ///< 0: one per hardware thread (the numbers do not depend on it)
    /// Where the compaction outputs (max_sigma_z_kPa, red_to_depth_m, rut_depth_m) are
    /// evaluated: "compaction": {"depth_m", "passes", "concentration", "profile" (an object)}.
    gsa::CompactionStudy compaction;

    /// Its file keys, one line each (core/common/declared_fields.h), shared by the two analyses'
    /// lists, the model choices among them. `threads` is not a file key.
    template <typename Visitor>
    void visitFields(Visitor& v);
};

/// "parameters": an array of {"key", and "range": [low, high] or "normal": [mean, sd] with an
/// optional "bounds": [low, high]} (each key checked against the soil fields with the rules,
/// studyRuleIssues). The writer gives a normal's bounds when both are finite.
void readUncertainParameters(io::ObjectReader& r, const char* key,
                             std::vector<UncertainParameter>& out);
nlohmann::json writeUncertainParameters(const std::vector<UncertainParameter>& parameters);
/// "correlated": {"keys", "mean", "covariance"} (absent: none).
void readCorrelatedParameters(io::ObjectReader& r, const char* key,
                              std::optional<CorrelatedParameters>& out);
nlohmann::json writeCorrelatedParameters(const std::optional<CorrelatedParameters>& group);
/// "samples": a whole number in [2, 2^24] (read as an int: its range in the reader's words).
void readSampleCount(io::ObjectReader& r, const char* key, std::size_t& out);
nlohmann::json writeSampleCount(const std::size_t& samples);
/// "compaction": the object readCompactionStudy reads.
void readCompactionStudyKey(io::ObjectReader& r, const char* key, gsa::CompactionStudy& out);
nlohmann::json writeCompactionStudy(const gsa::CompactionStudy& study);

template <typename Visitor>
void StudyDefinition::visitFields(Visitor& v) {
    v(fields::custom("parameters", parameters, "list of objects",
                     "{\"key\", \"range\": [low, high]} or {\"key\", \"normal\": [mean, sd], "
                     "\"bounds\": [low, high]}",
                     "the independent uncertain soil parameters, in the soil file's units",
                     readUncertainParameters, writeUncertainParameters));
    v(fields::custom("correlated", correlated, "object", "{\"keys\", \"mean\", \"covariance\"}",
                     "soil parameters varying together, X ~ N(mean, covariance)",
                     readCorrelatedParameters, writeCorrelatedParameters));
    v(fields::texts("outputs", outputs, "the outputs studied (gsa::outputNames())"));
    v(fields::numbers("slips", slips, contact::slipField().range, "", "the slips s", 1));
    v(fields::numbers("slip_angles_deg", slip_angles_deg, contact::slipAngleField().range, "deg",
                      "the slip angles beta", 1));
    v(fields::number("load_N", load_n, contact::loadField().range, "N",
                     "wheel load W; absent: the conditions' (unless entry_angle_deg)"));
    v(fields::number("entry_angle_deg", entry_angle_deg, contact::entryAngleField().range, "deg",
                     "a fixed entry angle instead of a load"));
    v(fields::integer("seed", seed, 0, std::numeric_limits<std::uint64_t>::max(),
                      "the same seed gives the same numbers"));
    v(fields::number("max_failed_fraction", max_failed_fraction, {0.0, 1.0}, "",
                     "largest share of samples without equilibrium at a point"));
    v(fields::custom("compaction", compaction, "object",
                     "depth_m, passes, concentration, risk_stress, profile",
                     "where the compaction outputs are evaluated", readCompactionStudyKey,
                     writeCompactionStudy));
    v(fields::members(model));
}

/// The gsa study these settings make of the inputs: the inputs' soil as the base soil (fields
/// not varied keep its values), the conditions' contact model. Throws std::invalid_argument
/// naming every problem (gsa::requireValid(WheelStudy) and the settings').
gsa::WheelStudy wheelStudyOf(const Inputs& inputs, const StudyDefinition& definition);

/// Global sensitivity method.
enum class GsaMethod { kSobol, kMorris };

struct GlobalSensitivitySettings {
    StudyDefinition study;
    GsaMethod method = GsaMethod::kSobol;
    std::size_t samples = 4096;  ///< Sobol': base samples N; Morris: trajectories r
    int levels = 4;              ///< Morris grid levels p (even)
    int resamples = 1000;        ///< bootstrap resamples of the confidence intervals
    double confidence_level = 0.95;

    /// Its file keys: the study's and the method's (core/common/declared_fields.h).
    template <typename Visitor>
    void visitFields(Visitor& v) {
        v(fields::members(study));
        v(fields::choice("method", method,
                         {{"sobol", GsaMethod::kSobol}, {"morris", GsaMethod::kMorris}},
                         "Sobol' indices or Morris screening"));
        v(fields::custom("samples", samples, "whole number", "[2, 16777216]",
                         "Sobol': base samples N; Morris: trajectories r", readSampleCount,
                         writeSampleCount));
        v(fields::integer("levels", levels, 2, 1000, "Morris grid levels p (even)"));
        v(fields::integer("resamples", resamples, 0, 1000000,
                          "bootstrap resamples of the confidence intervals"));
        v(fields::number("confidence", confidence_level, {0.0, 1.0, true, true}, "",
                         "confidence level of the intervals"));
    }
};

/// The keys of a study's "compaction" object: "depth_m", "passes", "concentration",
/// "risk_stress" and "profile" (an object; readProfile).
void readCompactionStudy(io::ObjectReader& r, gsa::CompactionStudy& out);

/// What a study's field list cannot say: a parameter key outside the soil fields or varied
/// twice, a range or bounds outside its field's or empty, sd <= 0, a correlated group of the
/// wrong shape or not positive definite, an unknown output, no slips (`slips_needed`) or slip
/// angles, load_N and entry_angle_deg both given.
std::vector<Issue> studyRuleIssues(const StudyDefinition& definition, bool slips_needed = true);

/// The keys of StudyDefinition::visitFields read strictly (io::readFields), then the model
/// choices and studyRuleIssues.
void readStudyDefinition(io::ObjectReader& r, StudyDefinition& out);
/// The keys of GlobalSensitivitySettings::visitFields (the study's and "method", "samples",
/// "levels", "resamples", "confidence"; the model choices among them), then
/// globalSensitivityRuleIssues.
void readGlobalSensitivitySettings(io::ObjectReader& r, GlobalSensitivitySettings& out);
/// studyRuleIssues and the method's: even levels, Morris screening on ranges only.
std::vector<Issue> globalSensitivityRuleIssues(const GlobalSensitivitySettings& settings);
/// The settings' file keys (io::fieldsToJson), the model choices among them.
nlohmann::json toJson(const GlobalSensitivitySettings& settings);

struct GlobalSensitivityResult {
    GsaMethod method = GsaMethod::kSobol;
    std::optional<gsa::SobolStudyResult> sobol;
    std::optional<gsa::MorrisStudyResult> morris;

    gsa::StudyStatus status() const;
    const std::string& message() const;
    const std::vector<std::string>& parameters() const;
    const std::vector<gsa::Output>& outputs() const;
    const gsa::OperatingGrid& grid() const;

    /// One row per grid point (slip-angle-major): slip_angle_deg, slip, then per output O and
    /// parameter P: Sobol' "O_S1_P", "O_S1_P_conf", "O_ST_P", "O_ST_P_conf" and "O_samples" (base
    /// samples used); Morris "O_mu_star_P", "O_mu_star_P_conf", "O_mu_P", "O_sigma_P" and
    /// "O_trajectories". No rows when the study was refused.
    Table table() const;
    /// {"method", "status", "message", "parameters", "outputs", "slips", "slip_angles_deg",
    /// "evaluations"} and per index ("S1", "ST", "S1_conf", "ST_conf" or "mu_star", "mu",
    /// "sigma", "mu_star_conf") an object output → [parameter][grid point].
    nlohmann::json toJson() const;
};

/// Runs the study with progress and cancel from `control` (a cancelled study keeps the indices
/// of the samples evaluated). Throws std::invalid_argument for invalid inputs or settings.
GlobalSensitivityResult computeGlobalSensitivity(const Inputs& inputs,
                                                 const GlobalSensitivitySettings& settings,
                                                 const Control& control = {});
/// Table "indices" (main; file suffix ""), document "-indices.json"; a refused study fails
/// with its message, a cancelled one is marked.
Outcome globalSensitivityOutcome(GlobalSensitivityResult result);
AnalysisType globalSensitivityType();

/// The bands' study defaults: F_x and F_s, no slips (the conditions' grid is used).
StudyDefinition bandStudyDefaults();

struct UncertaintyBandSettings {
    /// Empty slips: 0 … the conditions' slip_max in `slip_count` points.
    StudyDefinition study = bandStudyDefaults();
    int slip_count = 20;
    std::size_t samples = 512;                         ///< Monte Carlo samples M
    std::vector<double> percentiles{5.0, 50.0, 95.0};  ///< each in [0, 100]

    /// Its file keys: the study's and the bands' (core/common/declared_fields.h).
    template <typename Visitor>
    void visitFields(Visitor& v) {
        v(fields::members(study));
        const FieldInfo& count = slipCountField();
        v(fields::integer(count.key, slip_count, static_cast<int>(count.range.low),
                          static_cast<int>(count.range.high),
                          "slips 0 ... slip_max of the grid when no slips are given"));
        v(fields::custom("samples", samples, "whole number", "[2, 16777216]",
                         "Monte Carlo samples M", readSampleCount, writeSampleCount));
        v(fields::numbers("percentiles", percentiles, {0.0, 100.0}, "%", "the percentiles drawn", 1,
                          100));
    }
};

/// The keys of UncertaintyBandSettings::visitFields (the study's, slips optional, and
/// "slip_count", "samples", "percentiles"; the model choices among them), then
/// studyRuleIssues.
void readUncertaintyBandSettings(io::ObjectReader& r, UncertaintyBandSettings& out);
/// The settings' file keys (io::fieldsToJson), the model choices among them.
nlohmann::json toJson(const UncertaintyBandSettings& settings);

struct UncertaintyBandResult {
    gsa::BandResult bands;
    /// outputs × grid points: the outputs of the inputs' soil itself (NaN where it has no
    /// equilibrium), the curve the bands are drawn around.
    Eigen::MatrixXd nominal;
    /// bands.table() with one "O_nominal" column per output at the end.
    Table table() const;
};

UncertaintyBandResult computeUncertaintyBands(const Inputs& inputs,
                                              const UncertaintyBandSettings& settings,
                                              const Control& control = {});
/// Table "bands" (main).
Outcome uncertaintyBandOutcome(UncertaintyBandResult result);
AnalysisType uncertaintyBandType();

/// The identification's posterior as a correlated group in soil file units: the parameters with
/// a standard deviation (not fixed), K_s carried by k_φ (k_c fixed, so Var k_φ = Var K_s), with
/// mean the identified value and covariance σ_i σ_j ρ_ij. Throws std::invalid_argument when
/// the uncertainty was not computed or no parameter has one.
CorrelatedParameters correlatedFromIdentification(
    const identification::DecoupledParameters& identified,
    const identification::Uncertainty& uncertainty, const soil::SoilParameters& base,
    const wheel::WheelParameters& wheel);

}  // namespace terra::analysis
