#pragma once
/// @file forces.h
/// Forces and moments against slip for the project's slip angles (thesis Figs. 2.18–2.26): the
/// studio's forces panel, `terrastudio sweep` and `render`, and a script's "forces" analysis.

#include <optional>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/analysis/sweep.h"

namespace terra::analysis {

struct AnalysisType;

struct ForcesSettings {
    ModelChoices model;
    /// A fixed entry angle θ_f [deg] instead of solving F_z = W at every point.
    std::optional<double> entry_angle_deg;
    /// The slips to sweep; empty: the conditions' grid 0 … slip_max (slip_count points).
    std::vector<double> slips;
    int threads = 0;  ///< worker threads; 0: one per hardware thread
};

/// "entry_angle_deg", "slips" and the model choices (readModelChoices).
void readForcesSettings(io::ObjectReader& r, ForcesSettings& out);

/// The sweep of the inputs' soil and wheel at the conditions' load and slip angles.
using ForcesResult = SweepResult;

/// The sweep specification these settings make of the inputs.
SweepSpec forcesSpec(const Inputs& inputs, const ForcesSettings& settings,
                     const Control& control = {});
/// Runs the sweep; throws std::invalid_argument for invalid inputs or settings.
ForcesResult computeForceSweep(const Inputs& inputs, const ForcesSettings& settings = {},
                               const Control& control = {});
/// Tables: "sweep" (sweepColumns()); notes: the points without equilibrium.
Outcome forcesOutcome(ForcesResult result);

/// The registry's "forces" (figures: one per plotted column, Fx_N … entry_angle_deg).
AnalysisType forcesType();

}  // namespace terra::analysis
