#pragma once
/// @file wheel_target.h
/// The wheel model as the target of a global study: the parameters of a ParameterSpace are soil
/// fields by their file keys ("phi_deg", "c_kPa", "K_m", "n", …), varied in the file's units and
/// converted to SI through the soil field table; the outputs are chosen forces, moments, sinkage
/// or angles at every point of a grid of slips and slip angles, with the load given (θ_f solved per
/// sample) or θ_f given. One design row is evaluated through evaluateBatch (batch.h), so a row's
/// outputs are a pure function of the row.

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/compaction/passes.h"
#include "core/contact/operating_fields.h"
#include "core/gsa/batch.h"
#include "core/gsa/parameter_space.h"
#include "core/gsa/sobol_indices.h"

namespace terra::gsa {

/// An output of the wheel model, named as the sweep table's columns.
enum class Output {
    kFx,          ///< "Fx_N": drawbar pull F_x [N]
    kFy,          ///< "Fy_N" [N]
    kFz,          ///< "Fz_N" [N] (≡ W when the load is given)
    kMx,          ///< "Mx_Nm" [N·m]
    kMy,          ///< "My_Nm": resistance torque M_y [N·m]
    kMz,          ///< "Mz_Nm" [N·m]
    kFb,          ///< "Fb_N": bulldozing resistance [N]
    kFs,          ///< "Fs_N": side force [N]
    kSinkage,     ///< "sinkage_m": h [m]
    kEntryAngle,  ///< "entry_angle_deg": θ_f [deg]
    kExitAngle,   ///< "exit_angle_deg": θ_r [deg]
    // Compaction (docs/compaction.md; WheelStudy::compaction says where and how many passes):
    kMaxSigmaZ,  ///< "max_sigma_z_kPa": largest σ_z at the study's depth over the passes [kPa]
    kRedDepth,   ///< "red_to_depth_m": depth where the red zone ends (0: none) [m]; needs a profile
    kRutDepth,   ///< "rut_depth_m": the rut after the passes [m]
};

/// Whether an output is one of the compaction outputs (evaluated per sample, not by the batch).
bool isCompactionOutput(Output output);

/// Where and how the compaction outputs are evaluated.
struct CompactionStudy {
    double depth_m = 0.3;  ///< depth of max_sigma_z_kPa [m] below the untouched surface
    int passes = 1;        ///< wheels on the track (rut_depth_m after them; stresses: the largest)
    /// Layers for red_to_depth_m; empty: the base soil's own profile.
    std::optional<soil::SoilProfile> profile;
    std::optional<double> concentration;  ///< ν for every depth; empty: each layer's, else 5
    compaction::ReloadLaw reload;
    compaction::RiskMeasure measure = compaction::RiskMeasure::kVertical;
    /// Depths scanned for the red zone [m] (refined between them by bisection).
    std::vector<double> red_scan_depths{0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4,
                                        0.5, 0.6,  0.7, 0.8,  0.9, 1.0,  1.2};
};

/// The output's column name ("Fx_N"); values of study outputs are in the unit it names.
const char* outputName(Output output);
/// The output with this name; std::nullopt for an unknown one.
std::optional<Output> findOutput(std::string_view name);
/// Every output name, in enum order (for messages and command-line help).
const std::vector<std::string>& outputNames();

/// The operating points: every slip angle × every slip (slip-angle-major, as a sweep).
struct OperatingGrid {
    std::vector<double> slips;                              ///< s values, each in [−1, 1]
    std::vector<double> slip_angles_rad{0.0};               ///< β values [rad]
    std::optional<double> load_n = contact::kDefaultLoadN;  ///< W [N]; set: θ_f solved per sample
    double entry_angle_rad = 0.5236;                        ///< θ_f [rad] when no load is given

    std::size_t size() const { return slips.size() * slip_angles_rad.size(); }
    double slip(std::size_t point) const { return slips[point % slips.size()]; }
    double slipAngle(std::size_t point) const { return slip_angles_rad[point / slips.size()]; }
};

/// Everything a wheel study needs but its sample size and seed.
struct WheelStudy {
    soil::SoilParameters soil;  ///< the base soil (fields not in `parameters` stay at it)
    wheel::WheelParameters wheel;
    ModelOptions model;
    OperatingGrid grid;
    std::vector<Output> outputs{Output::kFx};
    ParameterSpace parameters;   ///< names: soil file keys; values in the file's units
    CompactionStudy compaction;  ///< for the compaction outputs
};

/// Throws std::invalid_argument listing every problem, each naming the field, the value and the
/// allowed range: a parameter that is not a soil field, a uniform range or a finite truncation
/// bound outside the field's allowed range (an unbounded normal or a correlated group may sample
/// outside it: those samples are flagged kInvalidSoil), an invalid base soil or wheel, slips or
/// slip angles, load or entry angle, no outputs or a repeated one.
void requireValid(const WheelStudy& study);

/// What a status matrix records per row and point (values of SampleStatus).
using StatusMatrix = Eigen::Matrix<std::uint8_t, Eigen::Dynamic, Eigen::Dynamic>;

/// Outputs of some design rows: values rows × columns (column o · points + p for output o at
/// grid point p), status rows × points.
struct TargetValues {
    Eigen::MatrixXd values;
    StatusMatrix status;
    bool cancelled = false;  ///< some rows were not evaluated (status kNotEvaluated)
};

/// Rows of several chunks stacked in order (the chunks of a distributed run, gathered).
TargetValues concatenate(const std::vector<TargetValues>& chunks);

/// Evaluations that failed, by reason.
struct FailureCounts {
    std::size_t no_equilibrium = 0;
    std::size_t load_not_matched = 0;
    std::size_t invalid_soil = 0;
    std::size_t non_finite = 0;

    std::size_t total() const {
        return no_equilibrium + load_not_matched + invalid_soil + non_finite;
    }
};

/// The wheel model as a function of a design row.
class WheelTarget {
public:
    /// Validates the study (requireValid).
    explicit WheelTarget(WheelStudy study);

    const WheelStudy& study() const { return study_; }
    std::size_t parameters() const { return study_.parameters.dimension(); }
    std::size_t points() const { return study_.grid.size(); }
    std::size_t columns() const { return study_.outputs.size() * points(); }
    std::size_t column(std::size_t output, std::size_t point) const {
        return output * points() + point;
    }

    /// Evaluates design rows (rows × parameters, values in the fields' file units) at every grid
    /// point, through one evaluateBatch call with InvalidSoil::kFlag. Failed evaluations have 0 in
    /// `values` and their status in `status`.
    TargetValues evaluate(const Eigen::MatrixXd& rows, const RunControl& control = {}) const;

    /// true where an evaluation succeeded, rows × columns (the estimators' mask).
    Mask successMask(const TargetValues& values) const;
    /// Failures per grid point, over the given rows.
    std::vector<FailureCounts> failures(const TargetValues& values) const;

private:
    /// Fills the compaction outputs' buffers of the samples the batch evaluated (status kOk);
    /// a sample whose later pass finds no equilibrium becomes kNoEquilibrium.
    void evaluateCompactionOutputs(const BatchInput& input,
                                   std::vector<std::vector<double>>& buffers,
                                   std::vector<SampleStatus>& status,
                                   const RunControl& control) const;

    WheelStudy study_;
};

/// Model evaluations per chunk of the studies (Sobol', Morris, bands) when the caller sets none:
/// large enough to keep every thread busy, small enough for the memory of a 10⁷-evaluation study
/// to stay that of one chunk plus the outputs.
inline constexpr std::size_t kChunkEvaluations = 16384;

/// Evaluates design rows [0, rows) through `target` in chunks of about `chunk_rows` rows (rounded
/// to a multiple of `row_multiple`), with overall progress and the cancel flag: after a cancel
/// the remaining rows are marked kNotEvaluated. `rows_of(begin, end)` returns the design's rows.
TargetValues evaluateInChunks(
    const WheelTarget& target, std::size_t rows, std::size_t chunk_rows, std::size_t row_multiple,
    const std::function<Eigen::MatrixXd(std::size_t, std::size_t)>& rows_of,
    const RunControl& control);

}  // namespace terra::gsa
