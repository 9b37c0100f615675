#pragma once
/// @file soil_curves.h
/// The forces panel's two curves of the soil alone (no slip): bulldozing resistance against
/// sinkage (thesis Fig. 2.15; Eqs. 2.26–2.30 as corrected in MODEL-NOTES E1) and static sinkage
/// against load (Fig. 2.6; Eq. 2.7 and Bekker's Eq. 2.8 as corrected in E2). Plain functions of
/// plain inputs like analyses.h: they run off the GUI thread and return tables to plot and export.

#include <atomic>

#include "core/common/table.h"
#include "widgets/analyses/analyses.h"

namespace terra::ui {

struct SoilCurvesSettings {
    int points = 61;  ///< grid size of each curve
    /// Largest sinkage of the bulldozing curve as a fraction of r (0.5: θ_f = 60°).
    double max_sinkage_fraction_of_radius = 0.5;
    /// Largest load of the static-sinkage curve as a multiple of the project's W.
    double max_load_factor = 2.0;
};

struct SoilCurves {
    /// sinkage_mm, entry_angle_deg, Fb_bekker_N, Fb_hegedus_N: F_b of one side wall over the
    /// submerged segment at θ_f = acos(1 − h/r), with the Bekker and the Hegedus coefficients
    /// (Eq. 2.27). The forces panel's F_s uses Bekker's.
    Table bulldozing;
    /// load_N, h_bekker_mm (Eq. 2.8, E2), h_eq27_mm (Eq. 2.7 over −θ_s..θ_s, as printed),
    /// h_eq27_front_mm (Eq. 2.7 over 0..θ_s, Bekker's assumption). NaN where Eq. 2.7 has no
    /// equilibrium (the wheel would sink to its axle).
    Table static_sinkage;
    double load_n = 0.0;  ///< the project's W [N], marked on the static-sinkage plot
};

/// Both curves for the project's soil and wheel. Returns early (partial tables) when `cancel` is
/// set.
SoilCurves computeSoilCurves(const AnalysisInputs& in, const SoilCurvesSettings& settings = {},
                             const std::atomic<bool>* cancel = nullptr);

}  // namespace terra::ui
