#pragma once
/// @file mission.h
/// Missions on a field (issue 23, item 3; docs/field.md, "Missions"): a path — waypoints, or
/// repeated parallel lanes joined by headland turns — followed by a pure-pursuit path controller
/// whose curvature the 4WS geometry turns into each wheel's steering angle and speed (M1–M9).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "core/common/issue.h"
#include "core/common/range.h"
#include "core/dynamics/robot.h"
#include "core/dynamics/rover.h"

namespace terra::scenario {

/// Repeated parallel lanes (docs/field.md, M6): lane k starts `k × spacing` to the side of
/// `start`, runs `length` along the heading (odd lanes back against it), and joins the next
/// through a headland turn of radius R beyond the lane's end: a quarter circle, a straight of
/// spacing − 2R across, a quarter circle.
struct LanesSpec {
    Eigen::Vector2d start_m{0.0, 0.0};  ///< the first lane's start [m]
    double heading_rad = 0.0;           ///< the first lane's direction, from +x [rad]
    double length_m = 10.0;             ///< each lane's length [m]
    double spacing_m = 3.0;             ///< between neighbouring lanes' centre lines [m]
    int count = 2;                      ///< lanes [-]
    double turn_radius_m = 1.5;         ///< the headland turns' radius R [m], ≤ spacing / 2
    bool to_left = true;                ///< later lanes lie to the left of the first's heading
};

/// The scenario's "mission" object.
struct MissionSpec {
    /// The path through these points in order (x, y on the field's map [m]); empty with lanes.
    std::vector<Eigen::Vector2d> waypoints;
    std::optional<LanesSpec> lanes;
    /// The speed of the robot's centre on the path at zero slip, v [m/s]: each wheel's rim runs
    /// at the speed of its hub on the turn (M4); the ground speed is lower by the slip.
    double speed_m_s = 0.3;
    double lookahead_m = 1.0;  ///< L_d: the goal point's distance ahead on the path [m]
    /// The largest steering angle of any wheel [rad]; the curvature is limited to reach it (M5).
    double max_steer_rad = 0.7853981633974483;
    double interval_s = 0.01;  ///< the path controller's period [s] (100 Hz)
    /// α from the direction the robot's centre moves in (its course, the heading plus the crab
    /// angle β; M9) rather than its heading: on a cross slope the robot crabs downhill, and
    /// steering its heading at the goal point leaves an offset of about L_d tan β.
    bool follow_course = true;
};

/// Allowed ranges of the mission's fields (the JSON reader and validate() name them).
struct MissionRanges {
    Range coordinate{-1e6, 1e6};          ///< [m]
    Range speed{0.0, 10.0, true, false};  ///< (0, 10] m/s
    Range lookahead{0.05, 100.0};         ///< [m]
    Range max_steer_deg{1.0, 60.0};       ///< [deg], the scenario's steering range
    Range interval{1e-3, 1.0};            ///< [s]
    Range length{0.1, 1e5};               ///< a lane [m]
    Range spacing{0.05, 1e4};             ///< [m]
    Range turn_radius{0.05, 1e4};         ///< [m]
    int max_count = 1000;                 ///< lanes at most
    std::size_t max_waypoints = 100000;   ///< waypoints at most
};
inline const MissionRanges kMissionRanges{};

/// Every problem of a mission (names under `prefix`, e.g. "mission.lanes.spacing_m"); `robot`
/// for the turns its steering can take.
std::vector<Issue> validate(const MissionSpec& mission, const dynamics::RobotParameters& robot,
                            const std::string& prefix = {});

/// Where a point lies along a path.
struct PathProjection {
    double s_m = 0.0;         ///< arc length of the nearest path point [m] (beyond the end: more)
    double error_m = 0.0;     ///< signed distance to it, positive left of the path [m]
    Eigen::Vector2d point{};  ///< the nearest path point [m]
};

/// A polyline path with its arc length; beyond its ends it continues along its first and last
/// segments (so a goal point ahead of the end and a robot past it are defined).
class Path {
public:
    /// Throws std::invalid_argument for fewer than two distinct points.
    explicit Path(std::vector<Eigen::Vector2d> points);
    /// The path of a mission: its waypoints (repeats dropped) or its lanes (M6).
    static Path ofMission(const MissionSpec& mission);
    /// The lanes and their turns, arcs as chords whose sagitta is at most 0.5 mm.
    static Path ofLanes(const LanesSpec& lanes);

    double length() const { return s_.back(); }
    const std::vector<Eigen::Vector2d>& points() const { return points_; }
    /// The arc length of each point [m].
    const std::vector<double>& arcLengths() const { return s_; }
    /// The point at arc length s (continued straight before 0 and after length()).
    Eigen::Vector2d at(double s_m) const;
    /// The nearest point among the segments that reach into [s_from, s_to] (the last segment
    /// continued beyond the end): a window, so that a lane never jumps to its neighbour.
    PathProjection project(const Eigen::Vector2d& p, double s_from, double s_to) const;

private:
    std::vector<Eigen::Vector2d> points_;
    std::vector<double> s_;
};

/// What the path controller decides at one tick.
struct PursuitStep {
    double curvature_1_m = 0.0;  ///< κ (M2), limited to ±κ_max (M5) [1/m], positive left
    double alpha_rad = 0.0;      ///< α: the goal point's bearing from the heading [rad]
    Eigen::Vector2d goal_m{};    ///< the goal point [m]
    PathProjection projection;   ///< the robot's place along the path
    bool done = false;           ///< the robot has passed the path's end
};

/// Pure pursuit (Coulter 1992; docs/field.md M1–M2): the goal point G lies L_d ahead of the
/// robot's projection on the path (arc length); the circle through the robot's centre P, tangent
/// to its heading, through G has κ = 2 sin α / ℓ, ℓ = |G − P|, α the bearing of G from the
/// heading. The projection only moves forward, searched within L_d ahead.
class PurePursuit {
public:
    /// Throws std::invalid_argument for lookahead_m ≤ 0 or max_curvature ≤ 0.
    PurePursuit(Path path, double lookahead_m, double max_curvature_1_m);
    /// The step for the robot's centre `position` [m] heading `heading_rad` (from +x).
    PursuitStep update(const Eigen::Vector2d& position, double heading_rad);
    const Path& path() const { return path_; }
    double progress() const { return progress_m_; }

private:
    Path path_;
    double lookahead_m_;
    double max_curvature_;
    double progress_m_ = 0.0;
};

/// M3–M4: each wheel's steering angle and rim speed for the robot's centre (midway between the
/// axles) on a circle of curvature κ at speed v: δ_i = atan2(κ x_i, 1 − κ y_i),
/// v_i = v √((1 − κ y_i)² + (κ x_i)²), ω_i = v_i / r_s (r_s the shear radius, Eq. 2.1 at s = 0).
dynamics::Commands fourWheelSteering(const dynamics::RobotParameters& robot, double curvature_1_m,
                                     double speed_m_s);
/// M5: the largest |κ| at which no wheel steers beyond `max_steer_rad` (< 90°) [1/m].
double maxCurvature(const dynamics::RobotParameters& robot, double max_steer_rad);

/// A run's mission outcome (summary.json).
struct MissionOutcome {
    bool completed = false;        ///< the robot passed the path's end before the duration ran out
    double path_length_m = 0.0;    ///< [m]
    double progress_m = 0.0;       ///< arc length reached (≤ the length) [m]
    double error_rms_m = 0.0;      ///< RMS of the signed distance to the path over the ticks [m]
    double error_max_m = 0.0;      ///< its largest magnitude [m]
    std::optional<double> time_s;  ///< when the end was passed [s]
};

}  // namespace terra::scenario
