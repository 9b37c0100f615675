#include "widgets/plots/rover_figures.h"

#include <qcustomplot.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/scenario/map_layers.h"
#include "widgets/plots/figures.h"
#include "widgets/plots/plot_legend.h"
#include "widgets/plots/sweep_plot.h"

namespace terra::ui {
namespace {

constexpr double kPi = 3.14159265358979323846;
const char* const kHeadingItemName = "heading";

const QColor kWheelColors[] = {QColor(31, 119, 180), QColor(214, 39, 40), QColor(44, 160, 44),
                               QColor(255, 127, 14)};
// Four wheels often coincide (straight line, symmetric loads): distinct dashes keep each visible.
const Qt::PenStyle kWheelDashes[] = {Qt::SolidLine, Qt::DashLine, Qt::DotLine, Qt::DashDotLine};

QVector<double> column(const Table& t, const std::string& name, double factor = 1.0) {
    const auto v = t.values(name);
    QVector<double> out(static_cast<qsizetype>(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) out[static_cast<qsizetype>(i)] = v[i] * factor;
    return out;
}

/// Rescales to the data, keeping at least `min_span` on y so that a constant (e.g. a zero yaw or
/// steering angle) is drawn as a flat line in the middle rather than magnified noise.
void finish(QCustomPlot& plot, double min_span, bool include_zero = false) {
    plot.rescaleAxes();
    QCPRange y = plot.yAxis->range();
    if (include_zero) {
        y.expand(0.0);
        plot.yAxis->setRange(y);
    }
    if (y.size() < min_span) {
        plot.yAxis->setRange(y.center() - 0.5 * min_span, y.center() + 0.5 * min_span);
    } else {
        plot.yAxis->scaleRange(1.1, y.center());
    }
    placeLegend(plot);
    plot.replot();
}

/// resetPlot, and undoes what the top view changes beyond it (a plot is reused for every figure
/// in headless runs): the grid's layer.
void resetRoverPlot(QCustomPlot& plot, const QString& title) {
    removeColorScales(plot);  // a field layer's (field_layers.h)
    resetPlot(plot, title);
    plot.xAxis->grid()->setLayer("grid");
    plot.yAxis->grid()->setLayer("grid");
}

struct Line {
    std::string column;
    QString label;
};

/// Clears the plot for a figure against time; false (empty axes drawn) when the series has fewer
/// than two rows.
bool startTimePlot(QCustomPlot& plot, const Table& t, const QString& y_label,
                   const QString& title) {
    resetRoverPlot(plot, title);
    plot.xAxis->setLabel("Time t [s]");
    plot.yAxis->setLabel(y_label);
    if (t.rows.size() >= 2) return true;
    plot.replot();
    return false;
}

void timeLines(QCustomPlot& plot, const Table& t, const std::vector<Line>& lines,
               const QString& y_label, const QString& title, double min_span, double factor = 1.0,
               bool include_zero = false) {
    if (!startTimePlot(plot, t, y_label, title)) return;
    const QVector<double> time = column(t, "t_s");
    int i = 0;
    for (const Line& line : lines) {
        QCPGraph* g = plot.addGraph();
        g->setData(time, column(t, line.column, factor), true);
        g->setName(line.label);
        QPen pen(kWheelColors[i % 4], 1.8);
        pen.setStyle(lines.size() == 4 ? kWheelDashes[i] : Qt::SolidLine);
        g->setPen(pen);
        ++i;
    }
    plot.legend->setVisible(lines.size() > 1);
    finish(plot, min_span, include_zero);
}

std::vector<Line> perWheel(const std::string& suffix) {
    std::vector<Line> out;
    for (const char* w : dynamics::kCornerNames) out.push_back({std::string(w) + "_" + suffix, w});
    return out;
}

void plotPath(QCustomPlot& plot, const Table& t, const QString& title) {
    resetRoverPlot(plot, title);
    plot.xAxis->setLabel("x [m] (initial heading)");
    plot.yAxis->setLabel("y [m] (left)");
    if (t.rows.size() < 2) {
        plot.replot();
        return;
    }
    auto* curve = new QCPCurve(plot.xAxis, plot.yAxis);
    curve->setData(column(t, "x_m"), column(t, "y_m"));
    curve->setPen(QPen(kWheelColors[0], 2.0));
    curve->setName("centre of mass");
    auto* ends = plot.addGraph();
    ends->setData(QVector<double>{t.rows.front()[t.column("x_m")], t.rows.back()[t.column("x_m")]},
                  QVector<double>{t.rows.front()[t.column("y_m")], t.rows.back()[t.column("y_m")]});
    ends->setLineStyle(QCPGraph::lsNone);
    ends->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCircle, Qt::black, Qt::white, 7));
    ends->setName("start, end");
    plot.legend->setVisible(true);
    plot.rescaleAxes();
    plot.xAxis->scaleRange(1.1, plot.xAxis->range().center());
    // Equal scales: a straight run shows as a straight line, a turn with its true radius. The
    // ratio needs the laid-out axis rect (its size in pixels), hence the first replot.
    placeLegend(plot);
    plot.replot();
    plot.yAxis->setScaleRatio(plot.xAxis, 1.0);
    plot.replot();
}

QColor soilColor(int index) {
    // Earthy, light enough for black labels and the robot drawn on top.
    static const QColor colors[] = {QColor(237, 214, 170), QColor(190, 160, 130),
                                    QColor(205, 190, 150), QColor(170, 150, 140),
                                    QColor(220, 200, 120), QColor(180, 185, 160)};
    return colors[index % 6];
}

/// A closed polygon: the rectangle of half-length `a` (along `heading_rad`) and half-width `b`
/// centred at `c`.
void rectangle(QCPCurve& curve, QPointF c, double heading_rad, double a, double b) {
    const double ca = std::cos(heading_rad), sa = std::sin(heading_rad);
    const double corners[5][2] = {{a, b}, {-a, b}, {-a, -b}, {a, -b}, {a, b}};
    QVector<double> xs, ys;
    for (const auto& p : corners) {
        xs.push_back(c.x() + ca * p[0] - sa * p[1]);
        ys.push_back(c.y() + sa * p[0] + ca * p[1]);
    }
    curve.setData(xs, ys);
}

QCPCurve* findCurve(QCustomPlot& plot, const QString& name) {
    for (int i = 0; i < plot.plottableCount(); ++i) {
        auto* curve = qobject_cast<QCPCurve*>(plot.plottable(i));
        if (curve && curve->name() == name) return curve;
    }
    return nullptr;
}

bool hasColumn(const Table& t, const std::string& name) {
    return std::find(t.columns.begin(), t.columns.end(), name) != t.columns.end();
}

/// Σ over the wheels of column `a` × column `b` in one row ("Fx_N" × "vx_m_s": the wheels' output
/// power; "My_Nm" × "omega_rad_s": their input power) [W].
double wheelPower(const Table& t, const std::vector<double>& row, const char* a, const char* b) {
    double sum = 0.0;
    for (const char* w : dynamics::kCornerNames) {
        const std::string p = std::string(w) + "_";
        sum += row[t.column(p + a)] * row[t.column(p + b)];
    }
    return sum;
}

// The slip controller at work (docs/traction.md §5): each wheel's true slip s and, in a
// closed-loop run, the set-point s* its PI tracks (with the optimal controller's dither), the
// same colour dashed. A constant-speed run has no set-point: only s.
void plotSlipControl(QCustomPlot& plot, const Table& t, const QString& title) {
    if (!startTimePlot(plot, t, "Slip ratio s [-]", title)) return;
    const QVector<double> time = column(t, "t_s");
    const bool closed = hasColumn(t, "FL_slip_set");
    for (int i = 0; i < dynamics::kWheelCount; ++i) {
        const std::string w = dynamics::kCornerNames[i];
        QCPGraph* s = plot.addGraph();
        s->setData(time, column(t, w + "_slip"), true);
        s->setName(QString::fromStdString(w + " s"));
        s->setPen(QPen(kWheelColors[i], 1.2));
        if (!closed) continue;
        QCPGraph* set = plot.addGraph();
        set->setData(time, column(t, w + "_slip_set"), true);
        set->setName(QString::fromStdString(w + " s*"));
        QPen pen(kWheelColors[i].darker(130), 2.0);
        pen.setStyle(Qt::DashLine);
        set->setPen(pen);
    }
    plot.legend->setVisible(true);
    finish(plot, 0.02, true);
}

// η = Σ F_x v_x / Σ M_y ω (docs/traction.md §1, §5's mean_efficiency) over a sliding window of
// kWindow_s: the ratio of the wheels' output to input work in it. Rows where the wheels take in
// less than kMinInput_W on average (at rest, braking) draw no point.
void plotEfficiency(QCustomPlot& plot, const Table& t, const QString& title) {
    constexpr double kWindow_s = 1.0, kMinInput_W = 1e-3;
    if (!startTimePlot(plot, t, "Tractive efficiency η [-] (1 s window)", title)) return;
    const std::size_t tc = t.column("t_s");
    std::vector<double> output(t.rows.size()), input(t.rows.size());
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
        output[r] = wheelPower(t, t.rows[r], "Fx_N", "vx_m_s");
        input[r] = wheelPower(t, t.rows[r], "My_Nm", "omega_rad_s");
    }
    // Trapezoidal integrals, then differences over the window.
    std::vector<double> out_work(t.rows.size()), in_work(t.rows.size());
    for (std::size_t r = 1; r < t.rows.size(); ++r) {
        const double dt = t.rows[r][tc] - t.rows[r - 1][tc];
        out_work[r] = out_work[r - 1] + 0.5 * (output[r] + output[r - 1]) * dt;
        in_work[r] = in_work[r - 1] + 0.5 * (input[r] + input[r - 1]) * dt;
    }
    QVector<double> time, eta;
    std::size_t from = 0;
    for (std::size_t r = 1; r < t.rows.size(); ++r) {
        while (t.rows[r][tc] - t.rows[from][tc] > kWindow_s) ++from;
        const double span = t.rows[r][tc] - t.rows[from][tc];
        const double in = in_work[r] - in_work[from];
        if (span < 0.5 * kWindow_s || !(in > kMinInput_W * span)) continue;
        const double value = (out_work[r] - out_work[from]) / in;
        if (!std::isfinite(value)) continue;
        time.push_back(t.rows[r][tc]);
        eta.push_back(value);
    }
    QCPGraph* g = plot.addGraph();
    g->setData(time, eta, true);
    g->setName("η, all wheels");
    g->setPen(QPen(kWheelColors[0], 1.8));
    plot.legend->setVisible(false);
    finish(plot, 0.02, true);
}

// The drive motors' work ∫ Σ τ ω dt against time (closed-loop runs record it; a constant-speed
// run's ideal servos do not, and its wheels' input work ∫ Σ M_y ω dt stands in, labelled so),
// with the implement's work ∫ F_d v dt when it pulls: the gap is what the drive loses.
void plotEnergy(QCustomPlot& plot, const Table& t, const QString& title) {
    if (!startTimePlot(plot, t, "Cumulative work [J]", title)) return;
    const std::size_t tc = t.column("t_s");
    const QVector<double> time = column(t, "t_s");
    QVector<double> drive(time.size()), drawbar(time.size());
    const bool motors = hasColumn(t, "drive_energy_J");
    const bool pulled = hasColumn(t, "drawbar_N");
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
        const auto& row = t.rows[r];
        const auto q = static_cast<qsizetype>(r);
        const double input = wheelPower(t, row, "My_Nm", "omega_rad_s");
        const double pull_power =
            pulled ? row[t.column("drawbar_N")] * std::max(0.0, row[t.column("forward_m_s")]) : 0.0;
        if (r == 0) {
            drive[q] = motors ? row[t.column("drive_energy_J")] : 0.0;
            continue;
        }
        const double dt = row[tc] - t.rows[r - 1][tc];
        drive[q] = motors ? row[t.column("drive_energy_J")] : drive[q - 1] + input * dt;
        drawbar[q] = drawbar[q - 1] + pull_power * dt;
    }
    QCPGraph* g = plot.addGraph();
    g->setData(time, drive, true);
    g->setName(motors ? "drive motors ∫Στω dt" : "wheels' input ∫ΣM_y ω dt (ideal servos)");
    g->setPen(QPen(kWheelColors[1], 1.8));
    if (pulled) {
        QCPGraph* d = plot.addGraph();
        d->setData(time, drawbar, true);
        d->setName("implement ∫F_d v dt");
        d->setPen(QPen(kWheelColors[2], 1.8));
    }
    plot.legend->setVisible(true);
    finish(plot, 0.1, true);
}

}  // namespace

const std::vector<RoverFigure>& roverFigures() {
    static const std::vector<RoverFigure> figures{
        {"path", "Path", "Figs. 3.7, 3.11a"},
        {"yaw", "Yaw", "Fig. 3.11b"},
        {"velocities", "Velocities", "Figs. 3.8, 3.15"},
        {"slip", "Slip", "Figs. 3.9, 3.14"},
        {"steering", "Steering", "Fig. 3.10"},
        {"wheel-vx", "Wheel v_x", "Fig. 3.12"},
        {"wheel-vy", "Wheel v_y", "Fig. 3.13"},
        {"drawbar-pull", "Drawbar pull", ""},
        {"load", "Load", ""},
        {"sinkage", "Sinkage", ""},
        {"slip-control", "Slip control", ""},
        {"efficiency", "Efficiency", ""},
        {"energy", "Energy", ""},
    };
    return figures;
}

void plotRoverFigure(QCustomPlot& plot, const Table& t, const std::string& key,
                     const QString& title) {
    if (key == "path") {
        plotPath(plot, t, title);
    } else if (key == "yaw") {
        timeLines(plot, t, {{"yaw_deg", "yaw ψ"}}, "Yaw ψ [deg] (positive: left)", title, 1.0);
    } else if (key == "velocities") {
        timeLines(plot, t, {{"forward_m_s", "longitudinal"}, {"lateral_m_s", "lateral (left)"}},
                  "Chassis velocity [mm/s]", title, 1.0, 1e3);
    } else if (key == "slip") {
        timeLines(plot, t, perWheel("slip"), "Slip ratio s [-]", title, 0.02, 1.0, true);
    } else if (key == "steering") {
        timeLines(plot, t, perWheel("steer_deg"), "Steering angle δ [deg] (positive: left)", title,
                  2.0);
    } else if (key == "wheel-vx") {
        timeLines(plot, t, perWheel("vx_m_s"), "Wheel longitudinal velocity v_x [mm/s]", title, 1.0,
                  1e3);
    } else if (key == "wheel-vy") {
        timeLines(plot, t, perWheel("vy_m_s"), "Wheel lateral velocity v_y [mm/s]", title, 1.0,
                  1e3);
    } else if (key == "drawbar-pull") {
        timeLines(plot, t, perWheel("Fx_N"), "Drawbar pull F_x [N]", title, 1.0);
    } else if (key == "load") {
        timeLines(plot, t, perWheel("load_N"), "Wheel load [N]", title, 1.0);
    } else if (key == "sinkage") {
        timeLines(plot, t, perWheel("sinkage_m"), "Sinkage h [mm]", title, 0.5, 1e3, true);
    } else if (key == "slip-control") {
        plotSlipControl(plot, t, title);
    } else if (key == "efficiency") {
        plotEfficiency(plot, t, title);
    } else if (key == "energy") {
        plotEnergy(plot, t, title);
    } else {
        throw std::invalid_argument("unknown rover figure \"" + key + "\"");
    }
}

void setRoverTimeCursor(QCustomPlot& plot, const Table& t, const std::string& key,
                        std::size_t row) {
    if (row >= t.rows.size()) return;
    QCPAbstractItem* item = nullptr;
    for (int i = 0; i < plot.itemCount() && !item; ++i) {
        if (plot.item(i)->objectName() == "time-cursor") item = plot.item(i);
    }
    const QColor colour(90, 90, 90);
    if (key == "path") {
        auto* ring = qobject_cast<QCPItemTracer*>(item);
        if (!ring) {
            ring = new QCPItemTracer(&plot);  // no graph: its position is set directly
            ring->setObjectName("time-cursor");
            ring->setStyle(QCPItemTracer::tsCircle);
            ring->setSize(11);
            ring->setPen(QPen(colour, 1.8));
            ring->setSelectable(false);
        }
        ring->position->setCoords(t.rows[row][t.column("x_m")], t.rows[row][t.column("y_m")]);
        return;
    }
    auto* line = qobject_cast<QCPItemStraightLine*>(item);
    if (!line) {
        line = new QCPItemStraightLine(&plot);
        line->setObjectName("time-cursor");
        line->setPen(QPen(colour, 1.2, Qt::DashLine));
        line->setSelectable(false);
    }
    const double time = t.rows[row][t.column("t_s")];
    line->point1->setCoords(time, 0.0);
    line->point2->setCoords(time, 1.0);
}

Completion roverCompletion(scenario::RunResult::Status status) {
    switch (status) {
        case scenario::RunResult::Status::kCompleted:
            return Completion::kComplete;
        case scenario::RunResult::Status::kCancelled:
            return Completion::kCancelled;
        case scenario::RunResult::Status::kDiverged:
            break;
    }
    return Completion::kDiverged;
}

QString roverTitle(const std::string& scenario_name, scenario::RunResult::Status status) {
    const QString name = QString::fromStdString(scenario_name);
    const Completion completion = roverCompletion(status);
    return completion == Completion::kComplete ? name + " — completed"
                                               : markedTitle(name, completion);
}

RoverPose roverPoseAt(const Table& t, std::size_t row) {
    const std::vector<double>& r = t.rows.at(row);
    RoverPose pose;
    pose.t_s = r[t.column("t_s")];
    pose.x_m = r[t.column("x_m")];
    pose.y_m = r[t.column("y_m")];
    pose.yaw_rad = r[t.column("yaw_deg")] * kPi / 180.0;
    for (int i = 0; i < dynamics::kWheelCount; ++i) {
        pose.steer_rad[i] =
            r[t.column(std::string(dynamics::kCornerNames[i]) + "_steer_deg")] * kPi / 180.0;
    }
    return pose;
}

std::array<QPointF, dynamics::kWheelCount> hubPositions(const dynamics::RobotParameters& robot,
                                                        const RoverPose& pose) {
    const double com_forward = robot.com_forward_m * robot.chassis_mass_kg / robot.totalMass();
    const double half_l = 0.5 * robot.wheelbase_m, half_t = 0.5 * robot.track_m;
    const double body[4][2] = {
        {half_l, half_t}, {half_l, -half_t}, {-half_l, half_t}, {-half_l, -half_t}};
    const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
    std::array<QPointF, dynamics::kWheelCount> hubs;
    for (int i = 0; i < dynamics::kWheelCount; ++i) {
        const double bx = body[i][0] - com_forward, by = body[i][1];
        hubs[i] = QPointF(pose.x_m + c * bx - s * by, pose.y_m + s * bx + c * by);
    }
    return hubs;
}

QString wheelCurveName(int corner) { return QString("wheel ") + dynamics::kCornerNames[corner]; }

void plotRoverTopView(QCustomPlot& plot, const scenario::Scenario& scenario, const Table& t,
                      std::size_t row, const QString& title) {
    resetRoverPlot(plot, title);
    plot.xAxis->setLabel("x [m]");
    plot.yAxis->setLabel("y [m]");
    const dynamics::RobotParameters& robot = scenario.robot;
    // The view: the path (or the start) with a margin of the robot's size.
    const auto [x0, y0, x1, y1] = scenario::drivenArea(scenario, t);

    // Soils: the base soil is a rectangle under everything (not the axis rect's background, which
    // the plot theme owns), patches are rectangles on it; infinite sides are clipped to a large
    // box.
    const double far = 1e3 + std::max({std::abs(x0), std::abs(x1), std::abs(y0), std::abs(y1)});
    auto clip = [far](double v) { return std::clamp(v, -far, far); };
    auto* base = new QCPItemRect(&plot);
    base->topLeft->setCoords(-far, far);
    base->bottomRight->setCoords(far, -far);
    base->setBrush(QBrush(soilColor(0)));
    base->setPen(Qt::NoPen);
    base->setLayer("background");
    auto* base_label = new QCPItemText(&plot);
    base_label->setPositionAlignment(Qt::AlignLeft | Qt::AlignTop);
    base_label->position->setType(QCPItemPosition::ptAxisRectRatio);
    base_label->position->setCoords(0.01, 0.01);
    // A field's soils vary across it (its soil layer shows them): its name, not the base soil's.
    base_label->setText(
        QString::fromStdString(scenario.field ? scenario.field->name : scenario.terrain.base.name));
    base_label->setFont(QFont("sans", 10, QFont::Bold));
    base_label->setClipToAxisRect(true);
    for (std::size_t i = 0; i < scenario.terrain.patches.size(); ++i) {
        const dynamics::SoilPatch& p = scenario.terrain.patches[i];
        auto* rect = new QCPItemRect(&plot);
        rect->topLeft->setCoords(clip(p.x_min_m), clip(p.y_max_m));
        rect->bottomRight->setCoords(clip(p.x_max_m), clip(p.y_min_m));
        rect->setBrush(QBrush(soilColor(static_cast<int>(i) + 1)));
        rect->setPen(QPen(QColor(90, 70, 50), 1.0, Qt::DashLine));
        rect->setLayer("background");
        auto* label = new QCPItemText(&plot);
        label->setText(QString::fromStdString(p.soil.name));
        label->setFont(QFont("sans", 10, QFont::Bold));
        // At the patch's visible top-left corner.
        label->position->setCoords(std::clamp(p.x_min_m, x0, x1), std::clamp(p.y_max_m, y0, y1));
        label->setPositionAlignment(Qt::AlignLeft | Qt::AlignTop);
        label->setPadding(QMargins(4, 4, 4, 4));
    }
    plot.xAxis->grid()->setLayer("background");
    plot.yAxis->grid()->setLayer("background");

    if (!t.rows.empty()) {
        auto* path = new QCPCurve(plot.xAxis, plot.yAxis);
        path->setData(column(t, "x_m"), column(t, "y_m"));
        // Solid: a dashed pen over thousands of points is slow to paint (GUI-thread time).
        path->setPen(QPen(QColor(40, 40, 40), 1.5));
        path->setName("path of the centre of mass");
        auto* chassis = new QCPCurve(plot.xAxis, plot.yAxis);
        chassis->setName(kChassisCurveName);
        chassis->setPen(QPen(QColor(50, 50, 60), 2.0));
        chassis->setBrush(QBrush(QColor(120, 130, 150, 120)));
        for (int i = 0; i < dynamics::kWheelCount; ++i) {
            auto* wheel = new QCPCurve(plot.xAxis, plot.yAxis);
            wheel->setName(wheelCurveName(i));
            wheel->setPen(QPen(kWheelColors[i], 2.0));
            wheel->setBrush(QBrush(kWheelColors[i].lighter(130)));
            wheel->removeFromLegend();
        }
        chassis->removeFromLegend();
        auto* heading = new QCPItemLine(&plot);  // from the chassis centre to its front edge
        heading->setObjectName(kHeadingItemName);
        heading->setHead(QCPLineEnding(QCPLineEnding::esSpikeArrow, 10, 12));
        heading->setPen(QPen(QColor(30, 30, 30), 1.6));
        plot.legend->setVisible(true);
    }
    if (t.rows.empty()) {
        // Before a run: where the robot starts.
        QCPGraph* start = plot.addGraph();
        start->setData(QVector<double>{scenario.initial.x_m},
                       QVector<double>{scenario.initial.y_m});
        start->setLineStyle(QCPGraph::lsNone);
        start->setScatterStyle(
            QCPScatterStyle(QCPScatterStyle::ssCrossCircle, QColor(30, 30, 30), 14));
        start->setName("start of the centre of mass");
        plot.legend->setVisible(true);
    }
    fitEqualScales(plot, x0, y0, x1, y1);
    if (!t.rows.empty()) {
        setRoverTopViewPose(plot, robot, t, std::min(row, t.rows.size() - 1));
    } else {
        plot.replot();
    }
}

void fitEqualScales(QCustomPlot& plot, double x0, double y0, double x1, double y1) {
    plot.xAxis->setRange(x0, x1);
    plot.yAxis->setRange(y0, y1);
    layOutLegend(plot);  // under the axes before they are measured
    plot.replot();       // lays out the axis rect: the scale ratio needs its size in pixels
    if ((x1 - x0) / std::max(plot.axisRect()->width(), 1) >=
        (y1 - y0) / std::max(plot.axisRect()->height(), 1)) {
        plot.yAxis->setScaleRatio(plot.xAxis, 1.0);
    } else {
        plot.xAxis->setScaleRatio(plot.yAxis, 1.0);
    }
}

void setRoverTopViewPose(QCustomPlot& plot, const dynamics::RobotParameters& robot, const Table& t,
                         std::size_t row) {
    QCPCurve* chassis = findCurve(plot, kChassisCurveName);
    if (!chassis || row >= t.rows.size()) return;
    const RoverPose pose = roverPoseAt(t, row);
    const auto hubs = hubPositions(robot, pose);
    // Chassis: the rectangle between the hubs, inset by half a wheel width on each side, its
    // centre the middle of the four hubs.
    const QPointF middle = (hubs[0] + hubs[1] + hubs[2] + hubs[3]) / 4.0;
    const double half_width =
        std::max(0.5 * robot.track_m - 0.5 * robot.wheel.width_m - 0.01, 0.25 * robot.track_m);
    rectangle(*chassis, middle, pose.yaw_rad, 0.5 * robot.wheelbase_m, half_width);
    for (int i = 0; i < plot.itemCount(); ++i) {
        if (auto* heading = qobject_cast<QCPItemLine*>(plot.item(i));
            heading && heading->objectName() == kHeadingItemName) {
            const double reach = 0.5 * robot.wheelbase_m;
            heading->start->setCoords(middle);
            heading->end->setCoords(middle.x() + reach * std::cos(pose.yaw_rad),
                                    middle.y() + reach * std::sin(pose.yaw_rad));
        }
    }
    for (int i = 0; i < dynamics::kWheelCount; ++i) {
        if (QCPCurve* wheel = findCurve(plot, wheelCurveName(i))) {
            rectangle(*wheel, hubs[i], pose.yaw_rad + pose.steer_rad[i], robot.wheel.radius_m,
                      0.5 * robot.wheel.width_m);
        }
    }
    plot.replot();
}

}  // namespace terra::ui
