#pragma once
/// @file experiment_overlay.h
/// A measured single-wheel test (core/io/experiment.h) drawn over a forces-versus-slip plot
/// (sweep_plot.h): the measured points of the plot's channel as markers with their own legend
/// entries ("measured, W = 80 N, β = 0°"), and the model at the test's conditions as a dashed
/// curve ("model, W = 80 N, β = 0°") wherever the plot's own curves are at other conditions.

#include <optional>
#include <string>
#include <vector>

#include "core/analysis/conditions.h"
#include "core/common/table.h"
#include "core/io/experiment.h"
#include "widgets/plots/sweep_plot.h"

class QCustomPlot;

namespace terra::ui {

/// The model swept at one load of a test, over the test's slip angles at that load.
struct TestSweep {
    double load_n = 0.0;  ///< W [N]
    Table table;          ///< sweepColumns() (core/analysis/sweep.h)
};

/// The test channel a sweep column shows: Fx_N → F_x, Fs_N → the side force (the test's Fy_N,
/// compared with F_s as core/analysis/validation.h does), Fz_N, My_Nm, sinkage_m; nullopt for the
/// others.
std::optional<io::ExperimentChannel> measuredChannel(const std::string& column);

/// A channel as the studio labels it, symbol and display unit: "F_x [N]", "M_y [N·m]",
/// "h [mm]", "F_s [N]" (the side force), "F_z [N]".
QString channelLabel(io::ExperimentChannel channel);
/// A value of the channel (SI) in its display unit with the unit, 4 significant digits:
/// "5.656 N", "6.021 mm"; "0 mm" for rounding noise next to values of size `scale_si` (an error
/// of 4.945e-15 mm beside one of 2 mm: number_format.h).
QString channelValue(io::ExperimentChannel channel, double value_si, double scale_si = 0.0);
/// A relative error in percent, one decimal ("84.0 %"); "–" for NaN (no measured value ≠ 0).
QString relativeError(double fraction);

/// Adds the test to a plot drawn by plotSweep for `quantity`: the model curves of `sweeps` whose
/// load and slip angle the plot does not already show (`shown`: the project's conditions), then
/// the measured points of the quantity's channel; refits the axes (fitSweepAxes). A quantity that
/// no channel measures, or a test that does not measure it, adds nothing. Measured graphs are
/// named "measured, …" and have the object name "measured".
void overlayExperiment(QCustomPlot& plot, const SweepQuantity& quantity,
                       const io::Experiment& experiment, const std::vector<TestSweep>& sweeps,
                       const analysis::OperatingConditions& shown);

/// The data behind a plot with a test overlaid (its CSV export and "Copy data"): the project's
/// sweep rows, the rows of the model at the test's conditions, then one row per measured point
/// with the measured values in their columns (the test's Fy_N under Fs_N, as plotted) and NaN
/// elsewhere; the columns of the sweep plus "load_N" and "measured" (1 for measured rows).
Table tableWithTest(const Table& sweep, double project_load_n, const io::Experiment& experiment,
                    const std::vector<TestSweep>& sweeps);

}  // namespace terra::ui
