#pragma once
/// @file adequacy.h
/// Model adequacy of a fit: whether its residuals are noise or a pattern. A model that lacks
/// something the data have (a shear limit j_max, slip-sinkage) leaves a smooth misfit along slip
/// that the fit spreads into biased parameters with small std (the README tour without j_max:
/// φ = 25.6 ± 0.29° for a 29° soil). The misfit per sample may be below the noise, but it is
/// coherent over a sweep: the residuals' projection on a cubic in slip, per sweep, holds far more
/// than noise would.
///
/// The test: in each sweep g (the samples of one load and slip angle) the residuals e_g are
/// regressed on 1, s, s², s³ (Q_g an orthonormal basis of those columns at the sweep's slips);
/// SS_trend = Σ_g ‖Q_gᵀ e_g‖², with k = Σ_g rank(Q_g) degrees of freedom, SS_rest = Σ e² −
/// SS_trend with n − k, and F = (SS_trend / k) / (SS_rest / (n − k)). For independent normal
/// noise of any level F follows Fisher's F(k, n − k) (the projections on orthogonal subspaces are
/// independent χ²): p = P(F(k, n − k) ≥ F) (the lack-of-fit F test, e.g. Draper & Smith,
/// Applied Regression Analysis, 3rd ed., §2.1, with the cubic trend as the richer model).
/// The fit's own seven parameters absorb part of any trend, which makes p larger (conservative).

#include <limits>
#include <vector>

namespace terra::identification {

/// One residual and where it lies: its sweep (the samples of one load and slip angle) and slip.
struct OrderedResidual {
    double load_n = 0.0;      ///< W of the sweep [N] (0 when the data do not say)
    double slip_angle = 0.0;  ///< β of the sweep [rad]
    double slip = 0.0;        ///< s [-]
    double value = 0.0;       ///< predicted − measured, any unit
};

/// The lack-of-fit test of a channel's residuals against a cubic trend in slip per sweep.
struct TrendTest {
    int values = 0;            ///< n: residuals tested
    int sweeps = 0;            ///< sweeps with a trend fitted
    int trend_dof = 0;         ///< k = Σ rank of the sweeps' cubic bases
    double f = 0.0;            ///< F = (SS_trend / k) / (SS_rest / (n − k))
    double trend_share = 0.0;  ///< SS_trend / Σ e²: the part of the residuals a trend explains
    /// P(F(k, n − k) ≥ F): small when the residuals follow slip. NaN when not tested (fewer
    /// than kTrendTestMinValues residuals, or n − k < kTrendTestMinValues / 2).
    double p = std::numeric_limits<double>::quiet_NaN();
    bool tested() const { return p == p; }
};

/// Residuals below this count are not tested; a sweep needs 8 (twice the cubic's terms) for a
/// trend, fewer are pooled with the rest (they count in SS_rest).
inline constexpr int kTrendTestMinValues = 10;
inline constexpr int kTrendTestMinSweep = 8;

/// The test of `residuals` (any order). Sweeps are the distinct (load, slip angle) pairs; when
/// those hold too few samples for a trend (a load that varies from row to row), all residuals
/// are one sweep.
TrendTest trendTest(const std::vector<OrderedResidual>& residuals);

}  // namespace terra::identification
