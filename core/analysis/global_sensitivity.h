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
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/analysis.h"
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
};

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
};

/// The keys of a study's "compaction" object: "depth_m", "passes", "concentration",
/// "risk_stress" and "profile" (an object; readProfile).
void readCompactionStudy(io::ObjectReader& r, gsa::CompactionStudy& out);

/// The keys of a study definition (shared with the bands): "parameters" (an array of {"key",
/// and "range": [low, high] or "normal": [mean, sd] with an optional "bounds": [low, high]}),
/// "correlated" ({"keys", "mean", "covariance"}), "outputs", "slips", "slip_angles_deg",
/// "load_N" or "entry_angle_deg", "seed", "max_failed_fraction" and the model choices. A key
/// outside the soil fields, a range outside its field's or an empty list is reported.
void readStudyDefinition(io::ObjectReader& r, StudyDefinition& out);
/// Those keys and "method" (sobol, morris), "samples", "levels", "resamples", "confidence".
void readGlobalSensitivitySettings(io::ObjectReader& r, GlobalSensitivitySettings& out);

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
};

/// The study definition's keys (slips optional) and "slip_count", "samples", "percentiles".
void readUncertaintyBandSettings(io::ObjectReader& r, UncertaintyBandSettings& out);

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
