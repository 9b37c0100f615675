#pragma once
/// @file wheel_studies.h
/// Global sensitivity of the wheel model: Sobol' indices over a Saltelli design and Morris
/// screening, run locally on threads in chunks of design rows. The same result is obtained from
/// chunks evaluated elsewhere (WheelTarget::evaluate on SaltelliDesign::rows ranges, then
/// concatenate and sobolResult): every chunk is a pure function of its rows.
///
/// Failed evaluations (no equilibrium, F_z jumping over W, a sampled soil outside a field's
/// range) never reach an index: a base sample (Sobol') or trajectory (Morris) is dropped from an
/// operating point when any of its rows failed there, the drops are counted per point and by
/// reason, and the study refuses (kTooManyFailures, no indices) when more than
/// max_failed_fraction of the samples were dropped at some point (docs/sensitivity.md).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/gsa/morris.h"
#include "core/gsa/saltelli_design.h"
#include "core/gsa/sobol_indices.h"
#include "core/gsa/wheel_target.h"

namespace terra::gsa {

/// How a study ended.
enum class StudyStatus {
    kCompleted,
    /// Stopped by the cancel flag: the indices use the samples evaluated before it (if ≥ 2).
    kCancelled,
    /// More than max_failed_fraction of the samples failed at some point: no indices.
    kTooManyFailures,
};

/// Settings of a Sobol' study.
struct SobolOptions {
    std::size_t base_samples = 4096;    ///< N (a power of two keeps the Sobol' points balanced)
    std::uint64_t seed = 1;             ///< digital shift of the Sobol' sequence
    BootstrapOptions bootstrap;         ///< confidence intervals
    double max_failed_fraction = 0.05;  ///< in [0, 1]: the largest share of dropped base samples
    /// Design rows evaluated per chunk (a multiple of d + 2 is used); 0: about 16384 evaluations.
    std::size_t chunk_rows = 0;
};

/// A Sobol' study's indices, one column per output and grid point (column o · points + p).
struct SobolStudyResult {
    StudyStatus status = StudyStatus::kCompleted;
    std::string message;                  ///< why it was refused or cancelled; empty otherwise
    std::vector<std::string> parameters;  ///< the order of the indices' rows
    std::vector<Output> outputs;
    OperatingGrid grid;
    SobolIndices indices;  ///< empty matrices when refused
    /// Per grid point: base samples dropped because one of their rows failed there.
    std::vector<std::size_t> dropped_samples;
    std::vector<FailureCounts> failures;  ///< per grid point: failed evaluations by reason
    std::size_t base_samples = 0;
    std::size_t evaluations = 0;  ///< model evaluations done (rows × points)

    bool usable() const { return status != StudyStatus::kTooManyFailures; }
    /// One output's S_i (parameters × grid points); likewise the others.
    Eigen::MatrixXd firstOrder(std::size_t output) const;
    Eigen::MatrixXd total(std::size_t output) const;
    Eigen::MatrixXd firstOrderConf(std::size_t output) const;
    Eigen::MatrixXd totalConf(std::size_t output) const;
};

/// Throws std::invalid_argument naming the field, value and range.
void requireValid(const SobolOptions& options);

/// The study, locally on control.threads threads. Throws std::invalid_argument for an invalid
/// study or options (before any evaluation).
SobolStudyResult sobolStudy(const WheelStudy& study, const SobolOptions& options,
                            const RunControl& control = {});

/// The study's result from every design row's outputs (`values`: design.rows() rows, e.g. the
/// concatenated chunks of a distributed run). Rows with status kNotEvaluated count as cancelled.
SobolStudyResult sobolResult(const WheelTarget& target, const SaltelliDesign& design,
                             const TargetValues& values, const SobolOptions& options);

/// Settings of a Morris screening.
struct MorrisOptions {
    std::size_t trajectories = 64;  ///< r ≥ 2
    int levels = 4;                 ///< p, even
    std::uint64_t seed = 1;
    BootstrapOptions bootstrap;  ///< confidence interval of μ*
    double max_failed_fraction = 0.05;
};

/// A Morris screening's statistics, one column per output and grid point.
struct MorrisStudyResult {
    StudyStatus status = StudyStatus::kCompleted;
    std::string message;
    std::vector<std::string> parameters;
    std::vector<Output> outputs;
    OperatingGrid grid;
    MorrisIndices indices;
    std::vector<std::size_t> dropped_trajectories;  ///< per grid point
    std::vector<FailureCounts> failures;            ///< per grid point
    std::size_t evaluations = 0;

    bool usable() const { return status != StudyStatus::kTooManyFailures; }
};

/// Throws std::invalid_argument naming the field, value and range.
void requireValid(const MorrisOptions& options);

/// The screening, locally. The parameters must be uniform ranges.
MorrisStudyResult morrisStudy(const WheelStudy& study, const MorrisOptions& options,
                              const RunControl& control = {});

/// The screening's result from every design row's outputs.
MorrisStudyResult morrisResult(const WheelTarget& target, const MorrisDesign& design,
                               const TargetValues& values, const MorrisOptions& options);

}  // namespace terra::gsa
