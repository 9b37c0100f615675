#pragma once
/// @file sobol_indices.h
/// Variance-based sensitivity indices from the outputs of a Saltelli design: first-order indices
/// by Saltelli et al. (2010), total indices by Jansen (1999), with bootstrap confidence intervals
/// that resample the base samples (docs/sensitivity.md gives the formulas).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/gsa/saltelli_design.h"

namespace terra::gsa {

/// Which evaluations succeeded: rows × columns, true = usable. An empty mask means all usable.
using Mask = Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic>;

/// Bootstrap confidence intervals.
struct BootstrapOptions {
    int resamples = 1000;            ///< B ∈ [0, 10⁶]; 0: no intervals (conf = 0)
    double confidence_level = 0.95;  ///< in (0, 1)
    std::uint64_t seed = 1;          ///< seed of the resamples' generator (SplitMix64)
    int threads = 0;  ///< columns estimated in parallel; 0: one per hardware thread (same result)
};

/// Throws std::invalid_argument naming the field, the value and the range.
void requireValid(const BootstrapOptions& options);

/// Indices of every parameter for every output column (one output at one operating point, or
/// one output of a test function). Matrices are parameters × columns.
struct SobolIndices {
    Eigen::MatrixXd first_order;            ///< S_i = V[E(Y|X_i)] / V(Y)
    Eigen::MatrixXd total;                  ///< S_Ti = E[V(Y|X_~i)] / V(Y)
    Eigen::MatrixXd first_order_conf;       ///< half-width of S_i's confidence interval
    Eigen::MatrixXd total_conf;             ///< half-width of S_Ti's confidence interval
    Eigen::VectorXd mean;                   ///< E(Y) over the A and B rows used, per column
    Eigen::VectorXd variance;               ///< V(Y) over the A and B rows used, per column
    std::vector<std::size_t> samples_used;  ///< base samples whose d + 2 rows all succeeded
    /// sd(Y) ≤ 1e-9 |E(Y)| (F_z when the load is given): no variance to share out, indices and
    /// intervals are 0.
    std::vector<bool> constant;
};

/// The indices from the design's outputs `values` (rows() × columns, rows in design order).
/// A base sample is used for a column only when all its d + 2 rows succeeded there (`ok`);
/// columns with fewer than 2 such samples have indices 0 and samples_used < 2 tells so. Throws
/// std::invalid_argument for mismatched sizes, a non-finite usable value or invalid options.
SobolIndices estimateSobol(const SaltelliDesign& design, const Eigen::MatrixXd& values,
                           const Mask& ok, const BootstrapOptions& options);

}  // namespace terra::gsa
