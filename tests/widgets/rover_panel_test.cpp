// The rover panel's top view, time scrubber and scenario editing, offscreen: the drawn robot sits
// at the time series' pose (geometry of resources/robots/default.json, computed here by hand), an
// invalid edit is refused naming its field, a valid edit changes the run and is kept in the
// project.
#include "widgets/panels/rover_panel.h"

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QSignalSpy>
#include <QSlider>
#include <QTextDocument>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/scenario/scenario_json.h"
#include "widgets/plots/rover_figures.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

constexpr double kPi = 3.14159265358979323846;

QCPCurve* curveNamed(QCustomPlot& plot, const QString& name) {
    for (int i = 0; i < plot.plottableCount(); ++i) {
        auto* curve = qobject_cast<QCPCurve*>(plot.plottable(i));
        if (curve && curve->name() == name) return curve;
    }
    return nullptr;
}

/// Centre and heading of a drawn rectangle (closed: 5 points, the first edge runs backwards
/// along the long side).
struct Drawn {
    double x = 0, y = 0, heading_rad = 0;
};
Drawn drawnRectangle(const QCPCurve& curve) {
    Drawn d;
    const auto& data = *curve.data();
    EXPECT_EQ(data.size(), 5);
    for (int i = 0; i < 4; ++i) {
        d.x += data.at(i)->key / 4.0;
        d.y += data.at(i)->value / 4.0;
    }
    d.heading_rad =
        std::atan2(data.at(0)->value - data.at(1)->value, data.at(0)->key - data.at(1)->key);
    return d;
}

double angleDifference(double a, double b) { return std::remainder(a - b, 2.0 * kPi); }

/// The shipped pulse-steering scenario cut to `duration_s` (the pulse starts at 10 s).
QString pulseText(RoverPanel& panel, double duration_s) {
    auto json = nlohmann::json::parse(panel.scenarioText().toStdString());
    json["duration_s"] = duration_s;
    return QString::fromStdString(json.dump(2));
}

// The results line is the core summary, as `terrastudio simulate` prints it: the same numbers
// at the same decimals, read back from the run's own summary (the final pose, yaw in degrees,
// the distance, each wheel's mean slip, the motor energy).
TEST(RoverPanelSummary, TheResultsLineIsTheCoreSummary) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    QString error;
    auto json = nlohmann::json::parse(panel.scenarioText().toStdString());
    json["duration_s"] = 3.0;
    ASSERT_TRUE(panel.setScenarioText(QString::fromStdString(json.dump(2)), &error))
        << error.toStdString();
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    const scenario::Summary& s = panel.result().summary;
    auto* line = panel.findChild<QLabel*>("rover.summary");
    ASSERT_NE(line, nullptr);
    QTextDocument html;
    html.setHtml(line->text());
    const QString text = html.toPlainText();
    const auto fixed = [](double v, int decimals) { return QString::number(v, 'f', decimals); };
    EXPECT_TRUE(text.startsWith("Completed on sandy loam")) << text.toStdString();
    EXPECT_TRUE(text.contains("3.000 s simulated (3000 steps of 0.001 s)")) << text.toStdString();
    EXPECT_TRUE(text.contains("final x: " + fixed(s.x_m, 4) + " m")) << text.toStdString();
    EXPECT_TRUE(text.contains("final yaw: " + fixed(s.yaw_rad * 180.0 / kPi, 3) + " deg"))
        << text.toStdString();
    EXPECT_TRUE(text.contains("distance: " + fixed(s.distance_m, 4) + " m")) << text.toStdString();
    const char* corners[] = {"FL", "FR", "RL", "RR"};
    for (int i = 0; i < 4; ++i) {
        EXPECT_TRUE(text.contains(QString("mean slip %1: %2")
                                      .arg(corners[i])
                                      .arg(fixed(s.mean_slip[static_cast<std::size_t>(i)], 4))))
            << corners[i] << ": " << text.toStdString();
    }
    EXPECT_TRUE(text.contains("motor energy: " + fixed(s.energy_j, 3) + " J (into the soil " +
                              fixed(s.dissipated_j, 3) + " J)"))
        << text.toStdString();
}

TEST(RoverPanelTopView, ScrubbingMovesTheRobotToTheSeriesPoseWithoutRecomputing) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    panel.applySettings({{"scenario", "pulse-steering"}});
    QString error;
    ASSERT_TRUE(panel.setScenarioText(pulseText(panel, 16.0), &error)) << error.toStdString();
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    const Table& t = panel.result().series;
    ASSERT_GT(t.rows.size(), 1500u);
    QCustomPlot& view = *panel.topView();
    QCPCurve* chassis = curveNamed(view, "chassis");
    ASSERT_NE(chassis, nullptr);

    QSignalSpy shown(&panel, &AnalysisPanel::resultShown);
    QSignalSpy busy(&panel, &AnalysisPanel::busyChanged);
    // Default robot: wheelbase 0.5 m, track 0.4 m, centre of mass at mid-wheelbase.
    const double half_l = 0.25, half_t = 0.2;
    const double corner[4][2] = {
        {half_l, half_t}, {half_l, -half_t}, {-half_l, half_t}, {-half_l, -half_t}};
    const char* names[] = {"FL", "FR", "RL", "RR"};
    for (const std::size_t row :
         {std::size_t{0}, std::size_t{500}, std::size_t{1450}, t.rows.size() - 1}) {
        panel.scrubber()->setValue(static_cast<int>(row));  // as the user drags it
        const auto& r = t.rows[row];
        const double x = r[t.column("x_m")], y = r[t.column("y_m")];
        const double yaw = r[t.column("yaw_deg")] * kPi / 180.0;
        EXPECT_TRUE(
            panel.timeLabel().startsWith(QString("t = %1 s").arg(r[t.column("t_s")], 0, 'f', 2)))
            << panel.timeLabel().toStdString();
        const Drawn body = drawnRectangle(*chassis);
        EXPECT_NEAR(body.x, x, 1e-9) << row;  // the chassis centre is the centre of mass here
        EXPECT_NEAR(body.y, y, 1e-9) << row;
        EXPECT_NEAR(angleDifference(body.heading_rad, yaw), 0.0, 1e-9) << row;
        for (int i = 0; i < 4; ++i) {
            QCPCurve* wheel = curveNamed(view, QString("wheel ") + names[i]);
            ASSERT_NE(wheel, nullptr) << names[i];
            const Drawn w = drawnRectangle(*wheel);
            const double hx = x + std::cos(yaw) * corner[i][0] - std::sin(yaw) * corner[i][1];
            const double hy = y + std::sin(yaw) * corner[i][0] + std::cos(yaw) * corner[i][1];
            EXPECT_NEAR(w.x, hx, 1e-9) << names[i] << " row " << row;
            EXPECT_NEAR(w.y, hy, 1e-9) << names[i] << " row " << row;
            const double steer = r[t.column(std::string(names[i]) + "_steer_deg")] * kPi / 180.0;
            EXPECT_NEAR(angleDifference(w.heading_rad, yaw + steer), 0.0, 1e-9)
                << names[i] << " row " << row;
        }
    }
    // Row 1450 (t = 14.5 s) is inside the pulse: the front wheels are drawn steered 10° from the
    // rear.
    panel.scrubber()->setValue(1450);
    const double front = drawnRectangle(*curveNamed(view, "wheel FL")).heading_rad;
    const double rear = drawnRectangle(*curveNamed(view, "wheel RL")).heading_rad;
    EXPECT_NEAR(angleDifference(front, rear), 10.0 * kPi / 180.0, 1e-9);
    EXPECT_EQ(shown.count(), 0);  // scrubbing only redraws
    EXPECT_EQ(busy.count(), 0);
}

QCPAbstractItem* timeCursor(QCustomPlot& plot) {
    for (int i = 0; i < plot.itemCount(); ++i) {
        if (plot.item(i)->objectName() == "time-cursor") return plot.item(i);
    }
    return nullptr;
}

// While scrubbing, every time plot shows a vertical line at the scrubbed row's time and the path a
// ring at its centre of mass, in figures drawn before and after the scrubber moved.
TEST(RoverPanelTopView, TimePlotsShowACursorAtTheScrubbedTime) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    panel.applySettings({{"scenario", "pulse-steering"}});
    QString error;
    ASSERT_TRUE(panel.setScenarioText(pulseText(panel, 4.0), &error)) << error.toStdString();
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    const Table& t = panel.result().series;
    ASSERT_GT(t.rows.size(), 300u);
    const auto figures = panel.plots();  // draws every figure (as an export does)
    // Right after the run the cursor is at the end.
    const double t_end = t.rows.back()[t.column("t_s")];
    for (const auto& [name, plot] : figures) {
        if (name == "rover-top-view") continue;
        QCPAbstractItem* cursor = timeCursor(*plot);
        ASSERT_NE(cursor, nullptr) << name.toStdString();
        if (name == "rover-path") {
            auto* ring = qobject_cast<QCPItemTracer*>(cursor);
            ASSERT_NE(ring, nullptr);
            EXPECT_DOUBLE_EQ(ring->position->coords().x(), t.rows.back()[t.column("x_m")]);
            EXPECT_DOUBLE_EQ(ring->position->coords().y(), t.rows.back()[t.column("y_m")]);
        } else {
            auto* line = qobject_cast<QCPItemStraightLine*>(cursor);
            ASSERT_NE(line, nullptr) << name.toStdString();
            EXPECT_DOUBLE_EQ(line->point1->coords().x(), t_end) << name.toStdString();
            EXPECT_DOUBLE_EQ(line->point2->coords().x(), t_end) << name.toStdString();
        }
    }
    const std::size_t row = 123;
    panel.scrubber()->setValue(static_cast<int>(row));
    const auto& r = t.rows[row];
    for (const auto& [name, plot] : figures) {
        if (name == "rover-top-view") continue;
        QCPAbstractItem* cursor = timeCursor(*plot);
        ASSERT_NE(cursor, nullptr) << name.toStdString();
        if (auto* ring = qobject_cast<QCPItemTracer*>(cursor)) {
            EXPECT_DOUBLE_EQ(ring->position->coords().x(), r[t.column("x_m")]);
            EXPECT_DOUBLE_EQ(ring->position->coords().y(), r[t.column("y_m")]);
        } else {
            auto* line = qobject_cast<QCPItemStraightLine*>(cursor);
            ASSERT_NE(line, nullptr);
            EXPECT_DOUBLE_EQ(line->point1->coords().x(), r[t.column("t_s")]) << name.toStdString();
        }
        // One cursor per plot, however often it moved.
        int cursors = 0;
        for (int i = 0; i < plot->itemCount(); ++i)
            cursors += plot->item(i)->objectName() == "time-cursor";
        EXPECT_EQ(cursors, 1) << name.toStdString();
    }
}

TEST(RoverPanelEditing, InvalidScenarioIsRefusedNamingTheField) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    panel.applySettings({{"scenario", "straight"}});
    const QString original = panel.scenarioText();
    auto json = nlohmann::json::parse(original.toStdString());

    ScenarioDialog dialog("straight", original, test::resources());
    EXPECT_TRUE(dialog.okEnabled());
    json["duration_s"] = -5;
    dialog.setText(QString::fromStdString(json.dump(2)));
    EXPECT_FALSE(dialog.okEnabled());
    EXPECT_TRUE(dialog.errorText().contains("duration_s")) << dialog.errorText().toStdString();
    dialog.setText("{\"name\": \"straight\",");  // broken JSON
    EXPECT_FALSE(dialog.okEnabled());
    EXPECT_TRUE(dialog.errorText().contains("invalid JSON")) << dialog.errorText().toStdString();
    dialog.setText(original);
    EXPECT_TRUE(dialog.okEnabled());

    // The panel refuses it too, names the field, and keeps the file's scenario.
    json = nlohmann::json::parse(original.toStdString());
    json["wheels"]["all"]["steer_deg"] = 75;
    QString error;
    EXPECT_FALSE(panel.setScenarioText(QString::fromStdString(json.dump()), &error));
    EXPECT_TRUE(error.contains("wheels.all.steer_deg")) << error.toStdString();
    json = nlohmann::json::parse(original.toStdString());
    json["durration_s"] = 3;  // a typo is an unknown key, never silently ignored
    EXPECT_FALSE(panel.setScenarioText(QString::fromStdString(json.dump()), &error));
    EXPECT_TRUE(error.contains("durration_s")) << error.toStdString();
    EXPECT_FALSE(panel.isEdited());
    EXPECT_EQ(panel.scenarioText(), original);
}

TEST(RoverPanelEditing, ValidEditChangesTheRunAndIsKeptInTheProject) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    panel.applySettings({{"scenario", "straight"}});
    auto json = nlohmann::json::parse(panel.scenarioText().toStdString());
    QString error;
    json["duration_s"] = 2.0;
    ASSERT_TRUE(panel.setScenarioText(QString::fromStdString(json.dump(2)), &error))
        << error.toStdString();
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    const Table longer = panel.result().series;
    EXPECT_NEAR(panel.result().summary.duration_s, 2.0, 1e-9);

    json["duration_s"] = 1.0;
    ASSERT_TRUE(panel.setScenarioText(QString::fromStdString(json.dump(2)), &error))
        << error.toStdString();
    EXPECT_TRUE(panel.isEdited());
    // Kept in the project (the panel's settings): a new panel on the same settings runs the edit.
    const nlohmann::json stored = document.project().panels.at("rover");
    EXPECT_EQ(stored["edited"]["straight"]["duration_s"], 1.0);
    RoverPanel reopened(&document, test::resources());
    reopened.applySettings(stored);
    EXPECT_TRUE(reopened.isEdited());
    reopened.recompute();
    ASSERT_TRUE(test::waitForResult(reopened, 120000));
    const Table& shorter = reopened.result().series;
    EXPECT_NEAR(reopened.result().summary.duration_s, 1.0, 1e-9);
    // A shorter run of the same deterministic scenario: a prefix of the longer one, half as long.
    ASSERT_LT(shorter.rows.size(), longer.rows.size());
    EXPECT_NEAR(static_cast<double>(shorter.rows.size() - 1),
                0.5 * static_cast<double>(longer.rows.size() - 1), 1.0);
    for (std::size_t i = 0; i < shorter.rows.size(); ++i)
        ASSERT_EQ(shorter.rows[i], longer.rows[i]) << i;

    // Revert: back to the 60 s file.
    reopened.revertScenario();
    EXPECT_FALSE(reopened.isEdited());
    EXPECT_EQ(nlohmann::json::parse(reopened.scenarioText().toStdString())["duration_s"], 60);
}

TEST(RoverPanelEditing, ControllerFieldsEditTheScenarioAndRunIt) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    panel.applySettings({{"scenario", "straight"}});
    auto* controller = panel.findChild<QComboBox*>("rover.controller");
    auto* slip = panel.findChild<QDoubleSpinBox*>("rover.slip");
    auto* limited = panel.findChild<QCheckBox*>("rover.traction_limited");
    ASSERT_NE(controller, nullptr);
    ASSERT_NE(slip, nullptr);
    ASSERT_NE(limited, nullptr);
    // The straight scenario has no controller: constant speed, no set-point to edit.
    EXPECT_EQ(controller->currentText(), "constant-speed");
    EXPECT_FALSE(slip->isEnabled());
    EXPECT_FALSE(limited->isEnabled());
    EXPECT_FALSE(limited->isChecked());
    EXPECT_FALSE(panel.isEdited());

    controller->setCurrentText("fixed-slip");
    slip->setValue(0.3);
    EXPECT_TRUE(panel.isEdited());
    EXPECT_TRUE(slip->isEnabled());
    auto json = nlohmann::json::parse(panel.scenarioText().toStdString());
    EXPECT_EQ(json["controller"]["type"], "fixed-slip");
    EXPECT_EQ(json["controller"]["slip"], 0.3);
    EXPECT_FALSE(json["controller"].contains("traction_limited"));
    EXPECT_TRUE(limited->isEnabled());
    limited->setChecked(true);
    json = nlohmann::json::parse(panel.scenarioText().toStdString());
    EXPECT_EQ(json["controller"]["traction_limited"], true);
    EXPECT_EQ(document.project().panels.at("rover")["edited"]["straight"]["controller"]["slip"],
              0.3);

    // The run holds that set-point (the series has the controller's columns).
    json["duration_s"] = 0.5;
    QString error;
    ASSERT_TRUE(panel.setScenarioText(QString::fromStdString(json.dump(2)), &error))
        << error.toStdString();
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    for (double set : panel.result().series.values("FL_slip_set")) EXPECT_EQ(set, 0.3);

    // Revert: the file again, and the fields show it.
    panel.revertScenario();
    EXPECT_EQ(controller->currentText(), "constant-speed");
    EXPECT_FALSE(slip->isEnabled());
    EXPECT_FALSE(limited->isChecked());
}

TEST(RoverPanelEditing, RobustAndEstimatorFieldsEditTheOptimalController) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    panel.applySettings({{"scenario", "straight"}});
    auto* controller = panel.findChild<QComboBox*>("rover.controller");
    auto* robust = panel.findChild<QComboBox*>("rover.robust");
    auto* quantile = panel.findChild<QDoubleSpinBox*>("rover.quantile");
    auto* identifier = panel.findChild<QComboBox*>("rover.identifier");
    ASSERT_NE(controller, nullptr);
    ASSERT_NE(robust, nullptr);
    ASSERT_NE(quantile, nullptr);
    ASSERT_NE(identifier, nullptr);
    // The scenario's defaults, and only the optimal controller has them to edit.
    const scenario::ControllerSpec defaults;
    EXPECT_EQ(robust->currentText().toStdString(), scenario::robustSlipName(defaults.robust));
    EXPECT_EQ(quantile->value(), defaults.quantile);
    EXPECT_EQ(identifier->currentText().toStdString(),
              scenario::soilIdentifierName(defaults.identifier));
    EXPECT_FALSE(robust->isEnabled());
    EXPECT_FALSE(identifier->isEnabled());
    // The quantile's range is the declared field's, as the reader's.
    EXPECT_EQ(quantile->minimum(), scenario::robustQuantileField().range.low);
    EXPECT_EQ(quantile->maximum(), scenario::robustQuantileField().range.high);

    controller->setCurrentText("optimal");
    EXPECT_TRUE(robust->isEnabled());
    EXPECT_TRUE(identifier->isEnabled());
    EXPECT_FALSE(quantile->isEnabled());  // only for the quantile set-point
    robust->setCurrentText("quantile");
    EXPECT_TRUE(quantile->isEnabled());
    quantile->setValue(0.25);
    identifier->setCurrentText("full");
    auto json = nlohmann::json::parse(panel.scenarioText().toStdString());
    EXPECT_EQ(json["controller"]["type"], "optimal");
    EXPECT_EQ(json["controller"]["robust"], "quantile");
    EXPECT_EQ(json["controller"]["quantile"], 0.25);
    EXPECT_EQ(json["controller"]["identifier"], "full");
    // The edited scenario reads back with those keys (the reader the run uses).
    const Result<scenario::Scenario> read =
        scenario::scenarioFromJson(json, "edited.json", test::resources());
    ASSERT_TRUE(read.ok()) << read.message();
    EXPECT_EQ(read->controller.robust, scenario::RobustSlip::kQuantile);
    EXPECT_EQ(read->controller.quantile, 0.25);
    EXPECT_EQ(read->controller.identifier, scenario::SoilIdentifier::kFull);

    // Revert: the file's (none) again.
    panel.revertScenario();
    EXPECT_EQ(robust->currentText().toStdString(), scenario::robustSlipName(defaults.robust));
    EXPECT_FALSE(robust->isEnabled());
}

}  // namespace
}  // namespace terra::ui
