#include "core/scenario/mission.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/common/units.h"

namespace terra::scenario {
namespace {

// The largest sagitta R (1 − cos(Δθ/2)) of an arc's chords [m]: far below a cell and a wheel.
constexpr double kArcSagitta = 5e-4;

// Appends the arc about `centre` of radius r from angle a0 to a1 (counter-clockwise if a1 > a0),
// without its first point (the previous piece's last).
void appendArc(std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& centre, double r,
               double a0, double a1) {
    const double step =
        std::min(units::kPi / 36.0, 2.0 * std::acos(std::max(0.0, 1.0 - kArcSagitta / r)));
    const int n = std::max(1, static_cast<int>(std::ceil(std::abs(a1 - a0) / step)));
    for (int k = 1; k <= n; ++k) {
        const double a = a0 + (a1 - a0) * static_cast<double>(k) / n;
        points.push_back(centre + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
}

// The angle of a direction from +x [rad].
double angleOf(const Eigen::Vector2d& d) { return std::atan2(d.y(), d.x()); }

}  // namespace

std::vector<Issue> validate(const MissionSpec& m, const dynamics::RobotParameters& robot,
                            const std::string& prefix) {
    std::vector<Issue> issues;
    const MissionRanges& r = kMissionRanges;
    checkRange(issues, prefix + "speed_m_s", m.speed_m_s, r.speed, "m/s");
    checkRange(issues, prefix + "lookahead_m", m.lookahead_m, r.lookahead, "m");
    checkRange(issues, prefix + "max_steer_deg", units::radToDeg(m.max_steer_rad), r.max_steer_deg,
               "deg");
    checkRange(issues, prefix + "interval_s", m.interval_s, r.interval, "s");
    if (m.lanes.has_value() == !m.waypoints.empty()) {
        issues.push_back({prefix.empty() ? "mission" : prefix.substr(0, prefix.size() - 1),
                          "give either \"waypoints\" or \"lanes\" (one of them)"});
        return issues;
    }
    if (!m.lanes) {
        for (std::size_t i = 0; i < m.waypoints.size(); ++i) {
            const std::string at = prefix + "waypoints[" + std::to_string(i) + "]";
            checkRange(issues, at + "[0]", m.waypoints[i].x(), r.coordinate, "m");
            checkRange(issues, at + "[1]", m.waypoints[i].y(), r.coordinate, "m");
        }
        double length = 0.0;
        for (std::size_t i = 1; i < m.waypoints.size(); ++i)
            length += (m.waypoints[i] - m.waypoints[i - 1]).norm();
        if (issues.empty() && !(length > 0.0)) {
            issues.push_back({prefix + "waypoints",
                              "needs at least two distinct points (the path has no length)"});
        }
        return issues;
    }
    const LanesSpec& l = *m.lanes;
    const std::string p = prefix + "lanes.";
    checkRange(issues, p + "start[0]", l.start_m.x(), r.coordinate, "m");
    checkRange(issues, p + "start[1]", l.start_m.y(), r.coordinate, "m");
    checkRange(issues, p + "heading_deg", units::radToDeg(l.heading_rad), {-360.0, 360.0}, "deg");
    checkRange(issues, p + "length_m", l.length_m, r.length, "m");
    checkRange(issues, p + "spacing_m", l.spacing_m, r.spacing, "m");
    checkRange(issues, p + "turn_radius_m", l.turn_radius_m, r.turn_radius, "m");
    if (l.count < 1 || l.count > r.max_count) {
        issues.push_back({p + "count", std::to_string(l.count) + " is outside [1, " +
                                           std::to_string(r.max_count) + "]"});
    }
    if (issues.empty() && l.count > 1 && 2.0 * l.turn_radius_m > l.spacing_m * (1.0 + 1e-12)) {
        issues.push_back({p + "turn_radius_m", formatNumber(l.turn_radius_m) +
                                                   " m is more than half the spacing (" +
                                                   formatNumber(l.spacing_m) +
                                                   " m): the turn would overshoot the next lane; "
                                                   "allowed range [0.05, " +
                                                   formatNumber(0.5 * l.spacing_m) + "] m"});
    }
    // A turn the steering cannot take: the robot would leave the path at every headland.
    if (issues.empty() && l.count > 1 &&
        r.max_steer_deg.contains(units::radToDeg(m.max_steer_rad))) {
        const double tightest = 1.0 / maxCurvature(robot, m.max_steer_rad);
        if (l.turn_radius_m < tightest) {
            issues.push_back(
                {p + "turn_radius_m",
                 formatNumber(l.turn_radius_m) +
                     " m is tighter than the robot turns at max_steer_deg = " +
                     formatNumber(roundSignificant(units::radToDeg(m.max_steer_rad), 3)) +
                     " (its smallest radius " + formatNumber(roundSignificant(tightest, 3)) +
                     " m, docs/field.md M5)"});
        }
    }
    return issues;
}

Path::Path(std::vector<Eigen::Vector2d> points) {
    for (const Eigen::Vector2d& p : points) {
        if (!p.allFinite()) throw std::invalid_argument("path: a point is not finite");
        if (!points_.empty() && (p - points_.back()).norm() < 1e-9) continue;
        const double s = points_.empty() ? 0.0 : s_.back() + (p - points_.back()).norm();
        points_.push_back(p);
        s_.push_back(s);
    }
    if (points_.size() < 2) throw std::invalid_argument("path: needs at least two distinct points");
}

Path Path::ofMission(const MissionSpec& mission) {
    return mission.lanes ? ofLanes(*mission.lanes) : Path(mission.waypoints);
}

Path Path::ofLanes(const LanesSpec& l) {
    if (l.count < 1 || !(l.length_m > 0.0) ||
        (l.count > 1 && !(l.spacing_m >= 2.0 * l.turn_radius_m && l.turn_radius_m > 0.0))) {
        throw std::invalid_argument("lanes: count ≥ 1, length > 0 and 0 < 2 R ≤ spacing");
    }
    const Eigen::Vector2d d(std::cos(l.heading_rad), std::sin(l.heading_rad));
    const Eigen::Vector2d side =
        l.to_left ? Eigen::Vector2d(-d.y(), d.x()) : Eigen::Vector2d(d.y(), -d.x());
    const double r = l.turn_radius_m;
    std::vector<Eigen::Vector2d> points;
    for (int k = 0; k < l.count; ++k) {
        const Eigen::Vector2d base = l.start_m + static_cast<double>(k) * l.spacing_m * side;
        const bool forward = k % 2 == 0;
        const Eigen::Vector2d a = forward ? base : Eigen::Vector2d(base + l.length_m * d);
        const Eigen::Vector2d b = forward ? Eigen::Vector2d(base + l.length_m * d) : base;
        if (k == 0) points.push_back(a);
        points.push_back(b);
        if (k + 1 == l.count) break;
        // The headland turn from b (direction u) to the next lane's start b + spacing × side
        // (direction −u): quarter circle about b + R side, the straight across, quarter circle
        // about b + (spacing − R) side.
        const Eigen::Vector2d u = forward ? d : Eigen::Vector2d(-d);
        // Turning towards `side` is counter-clockwise when side is u's left.
        const bool ccw = u.x() * side.y() - u.y() * side.x() > 0.0;
        const double turn = ccw ? units::kPi / 2.0 : -units::kPi / 2.0;
        const Eigen::Vector2d c1 = b + r * side;
        const double a1 = angleOf(b - c1);
        appendArc(points, c1, r, a1, a1 + turn);
        const Eigen::Vector2d c2 = b + (l.spacing_m - r) * side;
        const Eigen::Vector2d from = c2 + r * u;
        if ((from - points.back()).norm() > 1e-9) points.push_back(from);
        const double a2 = angleOf(from - c2);
        appendArc(points, c2, r, a2, a2 + turn);
    }
    return Path(std::move(points));
}

Eigen::Vector2d Path::at(double s_m) const {
    const std::size_t n = points_.size();
    if (s_m <= 0.0) {
        const Eigen::Vector2d u = (points_[1] - points_[0]) / s_[1];
        return points_[0] + s_m * u;
    }
    if (s_m >= s_.back()) {
        const Eigen::Vector2d u = (points_[n - 1] - points_[n - 2]) / (s_[n - 1] - s_[n - 2]);
        return points_[n - 1] + (s_m - s_.back()) * u;
    }
    const std::size_t k =
        static_cast<std::size_t>(std::upper_bound(s_.begin(), s_.end(), s_m) - s_.begin()) - 1;
    const double t = (s_m - s_[k]) / (s_[k + 1] - s_[k]);
    return points_[k] + t * (points_[k + 1] - points_[k]);
}

PathProjection Path::project(const Eigen::Vector2d& p, double s_from, double s_to) const {
    const std::size_t n = points_.size();
    // The segments [k, k + 1] with s_[k + 1] ≥ s_from and s_[k] ≤ s_to.
    std::size_t first =
        static_cast<std::size_t>(std::lower_bound(s_.begin(), s_.end(), s_from) - s_.begin());
    first = first == 0 ? 0 : first - 1;
    first = std::min(first, n - 2);
    PathProjection best;
    double best_distance = std::numeric_limits<double>::infinity();
    for (std::size_t k = first; k + 1 < n && s_[k] <= s_to; ++k) {
        const Eigen::Vector2d a = points_[k];
        const Eigen::Vector2d seg = points_[k + 1] - a;
        const double length = s_[k + 1] - s_[k];
        double t = (p - a).dot(seg) / (length * length);
        // The last segment continues beyond the end; the others are clamped to themselves.
        t = std::max(0.0, k + 2 == n ? t : std::min(1.0, t));
        const Eigen::Vector2d q = a + t * seg;
        const double distance = (p - q).norm();
        if (distance < best_distance) {
            best_distance = distance;
            const Eigen::Vector2d u = seg / length;
            const Eigen::Vector2d off = p - q;
            best.s_m = s_[k] + t * length;
            best.point = q;
            best.error_m = u.x() * off.y() - u.y() * off.x();
        }
    }
    return best;
}

PurePursuit::PurePursuit(Path path, double lookahead_m, double max_curvature_1_m)
    : path_(std::move(path)), lookahead_m_(lookahead_m), max_curvature_(max_curvature_1_m) {
    if (!(lookahead_m > 0.0) || !(max_curvature_1_m > 0.0)) {
        throw std::invalid_argument("pure pursuit: lookahead_m = " + formatNumber(lookahead_m) +
                                    " and max curvature " + formatNumber(max_curvature_1_m) +
                                    " must be > 0");
    }
}

PursuitStep PurePursuit::update(const Eigen::Vector2d& position, double heading_rad) {
    PursuitStep step;
    // Forward only, within L_d: the robot is never taken to a later lane that passes near.
    step.projection = path_.project(position, progress_m_, progress_m_ + lookahead_m_);
    progress_m_ = std::max(progress_m_, step.projection.s_m);
    step.done = progress_m_ >= path_.length();
    step.goal_m = path_.at(progress_m_ + lookahead_m_);
    // M1–M2: G in the robot's frame, α its bearing, κ = 2 sin α / ℓ.
    const Eigen::Vector2d g = step.goal_m - position;
    const double ell = g.norm();
    step.alpha_rad = std::remainder(std::atan2(g.y(), g.x()) - heading_rad, 2.0 * units::kPi);
    const double kappa = ell > 1e-9 ? 2.0 * std::sin(step.alpha_rad) / ell : 0.0;
    step.curvature_1_m = std::clamp(kappa, -max_curvature_, max_curvature_);
    return step;
}

dynamics::Commands fourWheelSteering(const dynamics::RobotParameters& robot, double kappa,
                                     double speed_m_s) {
    const double shear_radius = robot.wheel.radius_m + robot.wheel.lugShearOffset();
    dynamics::Commands commands;
    for (int i = 0; i < dynamics::kWheelCount; ++i) {
        // The hub about the centre between the axles: x forward, y left (the corner order).
        const double x = (i < 2 ? 0.5 : -0.5) * robot.wheelbase_m;
        const double y = (i % 2 == 0 ? 0.5 : -0.5) * robot.track_m;
        // M3: the hub's velocity on the turn about the centre (0, 1/κ) is v (1 − κ y, κ x).
        const double along = 1.0 - kappa * y, across = kappa * x;
        commands[i].steer_angle_rad = std::atan2(across, along);
        commands[i].spin_rate_rad_s = speed_m_s * std::hypot(along, across) / shear_radius;
    }
    return commands;
}

double maxCurvature(const dynamics::RobotParameters& robot, double max_steer_rad) {
    const double t = std::tan(max_steer_rad);
    return t / (0.5 * robot.wheelbase_m + 0.5 * robot.track_m * t);
}

}  // namespace terra::scenario
