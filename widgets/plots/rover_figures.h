#pragma once
/// @file rover_figures.h
/// Draws a rover run (core/scenario/runner.h) on a QCustomPlot: the thesis's Figs. 3.7–3.15 from
/// the run's time series (columns: docs/dynamics.md, "Outputs"), and a top-down view of the robot
/// on its soil patches at one instant. The same drawing for the rover panel and for `terrastudio
/// run` (app/cli/run_command.cpp). Each plot function replaces what the plot showed.

#include <QPointF>
#include <QString>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "core/common/table.h"
#include "core/dynamics/robot.h"
#include "core/scenario/runner.h"
#include "core/scenario/scenario.h"
#include "widgets/plots/completion.h"

class QCustomPlot;

namespace terra::ui {

/// One time-series figure of a rover run.
struct RoverFigure {
    std::string key;  ///< file-name part and identifier ("path", "slip")
    QString tab;      ///< short label ("Path", "Slip")
    QString thesis;   ///< the thesis figures it corresponds to ("Figs. 3.9, 3.14")
};

/// The figures, in the panel's tab order: path (3.7, 3.11a), yaw (3.11b), velocities (3.8, 3.15),
/// slip (3.9, 3.14), steering (3.10), wheel-vx (3.12), wheel-vy (3.13), drawbar-pull, load,
/// sinkage.
const std::vector<RoverFigure>& roverFigures();

/// Draws figure `key` of roverFigures() from a run's time series. Throws std::invalid_argument
/// for an unknown key; a series with fewer than two rows draws empty axes.
void plotRoverFigure(QCustomPlot& plot, const Table& series, const std::string& key,
                     const QString& title);

/// The time cursor of figure `key` at row `row` of the series (the rover panel's scrubber): a
/// vertical dashed line at t on the time plots, a ring at the centre of mass on the path. Created
/// on the first call (an item named "time-cursor"), moved on the next; no replot. Nothing for a
/// row outside the series.
void setRoverTimeCursor(QCustomPlot& plot, const Table& series, const std::string& key,
                        std::size_t row);

/// How complete a run is (completion.h): cancelled and diverged runs keep their steps.
Completion roverCompletion(scenario::RunResult::Status status);

/// "pulse-steering — completed" (or "CANCELLED (partial)", "DIVERGED (partial)").
QString roverTitle(const std::string& scenario_name, scenario::RunResult::Status status);

/// The robot's pose in one time-series row: centre of mass, yaw and each wheel's steering angle.
struct RoverPose {
    double t_s = 0.0;
    double x_m = 0.0, y_m = 0.0;  ///< centre of mass on the ground
    double yaw_rad = 0.0;
    std::array<double, dynamics::kWheelCount> steer_rad{};
};
RoverPose roverPoseAt(const Table& series, std::size_t row);

/// Wheel centres on the ground at `pose` (FL, FR, RL, RR): the hubs sit at (±L/2, ±T/2) about the
/// middle of the wheelbase, and the centre of mass is chassis_mass · com_forward / total_mass ahead
/// of it (wheels lumped at the hubs, as in core/dynamics/rover.cpp).
std::array<QPointF, dynamics::kWheelCount> hubPositions(const dynamics::RobotParameters& robot,
                                                        const RoverPose& pose);

/// Top-down view: the base soil as the background, each patch as a coloured rectangle labelled with
/// its soil name, the path of the centre of mass, and the robot (chassis outline, four wheels at
/// their steering angles) at row `row` of the series. Equal scales on x and y.
void plotRoverTopView(QCustomPlot& plot, const scenario::Scenario& scenario, const Table& series,
                      std::size_t row, const QString& title);

/// Shows [x0, x1] × [y0, y1] with equal scales on x and y: the axis with room to spare widens
/// around its centre. Replots once to measure the axes; the caller replots after.
void fitEqualScales(QCustomPlot& plot, double x0, double y0, double x1, double y1);

/// Moves the robot of a plot drawn by plotRoverTopView to row `row` and replots; nothing is
/// recomputed. No-op when the plot holds no robot or the row is out of range.
void setRoverTopViewPose(QCustomPlot& plot, const dynamics::RobotParameters& robot,
                         const Table& series, std::size_t row);

/// Names of the top view's robot curves: "chassis" and "wheel FL" … "wheel RR".
inline const char* kChassisCurveName = "chassis";
QString wheelCurveName(int corner);

}  // namespace terra::ui
