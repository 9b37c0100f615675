#pragma once
/// @file forces.h
/// Forces and moments against slip for the project's slip angles (thesis Figs. 2.18–2.26): the
/// studio's forces panel, `terrastudio sweep` and `render`, and a script's "forces" analysis.

#include <optional>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/analysis/sweep.h"
#include "core/contact/operating_fields.h"

namespace terra::analysis {

struct AnalysisType;

struct ForcesSettings {
    ModelChoices model;
    /// A fixed entry angle θ_f [deg] instead of solving F_z = W at every point.
    std::optional<double> entry_angle_deg;
    /// The slips to sweep; empty: the conditions' grid 0 … slip_max (slip_count points).
    std::vector<double> slips;
    int threads = 0;  ///< worker threads; 0: one per hardware thread (code only, no file key)

    /// Its file keys, one line each (core/common/declared_fields.h): the reader, toJson, the
    /// command line's flags and compute's checks are made from them.
    template <typename Visitor>
    void visitFields(Visitor& v);
};

template <typename Visitor>
void ForcesSettings::visitFields(Visitor& v) {
    v(fields::members(model));
    v(fields::number("entry_angle_deg", entry_angle_deg, contact::entryAngleField().range, "deg",
                     "fixed entry angle θ_f instead of solving F_z = W at every point"));
    v(fields::numbers("slips", slips, contact::slipField().range, "",
                      "the slips to sweep; absent: the conditions' grid 0 … slip_max", 1));
}

/// The keys of ForcesSettings::visitFields, read strictly (io::readFields): "entry_angle_deg",
/// "slips" and the model choices.
void readForcesSettings(io::ObjectReader& r, ForcesSettings& out);
/// The settings' file keys (io::fieldsToJson).
nlohmann::json toJson(const ForcesSettings& settings);

/// The sweep of the inputs' soil and wheel at the conditions' load and slip angles.
using ForcesResult = SweepResult;

/// The sweep specification these settings make of the inputs.
SweepSpec forcesSpec(const Inputs& inputs, const ForcesSettings& settings,
                     const Control& control = {});
/// Runs the sweep; throws std::invalid_argument for invalid inputs or settings (a struct built
/// in code is checked as its reader would read it: io::fieldIssues).
ForcesResult computeForceSweep(const Inputs& inputs, const ForcesSettings& settings = {},
                               const Control& control = {});
/// Tables: "sweep" (sweepColumns()); notes: the points without equilibrium.
Outcome forcesOutcome(ForcesResult result);

/// The registry's "forces" (figures: one per plotted column, Fx_N … entry_angle_deg).
AnalysisType forcesType();

}  // namespace terra::analysis
