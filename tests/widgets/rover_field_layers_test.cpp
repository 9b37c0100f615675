// Issue 23 item 4 in the studio: a field run's maps drawn as layers under the rover panel's top
// view, offscreen on the real panel. The colour map's cells are checked against the run's own
// rasters (FieldMaps) and the field's files at a known cell, the time scrub against the
// passages' times: no rut at t = 0, the final map at the end, ruts appearing in between.
#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QComboBox>
#include <QElapsedTimer>
#include <QLabel>
#include <QSignalSpy>
#include <QSlider>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <set>

#include "core/project/results.h"
#include "core/scenario/scenario_json.h"
#include "widgets/panels/rover_panel.h"
#include "widgets/plots/field_layers.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace field_layers_test {

/// The shipped field scenario cut to `duration_s`, run in the panel (on its worker).
bool runField(RoverPanel& panel, double duration_s) {
    panel.applySettings({{"scenario", "field-slope-wet"}});
    auto json = nlohmann::json::parse(panel.scenarioText().toStdString());
    json["duration_s"] = duration_s;
    QString error;
    if (!panel.setScenarioText(QString::fromStdString(json.dump(2)), &error)) {
        ADD_FAILURE() << error.toStdString();
        return false;
    }
    panel.recompute();
    return test::waitForResult(panel, 120000);
}

QStringList layerKeys(const RoverPanel& panel) {
    QStringList keys;
    for (int i = 0; i < panel.layerChooser()->count(); ++i)
        keys << panel.layerChooser()->itemData(i).toString();
    return keys;
}

/// Centre of the cell with the deepest rut [m].
QPointF deepestRut(const field::Raster& rut) {
    std::size_t best = 0;
    for (std::size_t i = 0; i < rut.values.size(); ++i) {
        if (rut.values[i] > rut.values[best]) best = i;
    }
    const int col = static_cast<int>(best % static_cast<std::size_t>(rut.cols));
    const int row = static_cast<int>(best / static_cast<std::size_t>(rut.cols));
    return {rut.centreX(col), rut.centreY(row)};
}

/// The colour map's value at (x, y) (its cell there).
double drawnAt(const RoverPanel& panel, QPointF at) {
    QCPColorMap* map = topViewLayer(*panel.topView());
    EXPECT_NE(map, nullptr);
    return map ? map->data()->data(at.x(), at.y()) : std::nan("");
}

/// Cells of the drawn layer with a value above 0.
int cellsAboveZero(const RoverPanel& panel) {
    QCPColorMap* map = topViewLayer(*panel.topView());
    if (!map) return -1;
    int n = 0;
    for (int k = 0; k < map->data()->keySize(); ++k) {
        for (int v = 0; v < map->data()->valueSize(); ++v) n += map->data()->cell(k, v) > 0.0;
    }
    return n;
}

int rowAt(const Table& t, double t_s) {
    int row = 0;
    while (row + 1 < static_cast<int>(t.rows.size()) &&
           t.rows[static_cast<std::size_t>(row) + 1][t.column("t_s")] <= t_s)
        ++row;
    return row;
}

TEST(RoverFieldLayers, AFieldShowsItsSoilMapBeforeItRunsAndTheRunsMapsAfter) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    panel.applySettings({{"scenario", "field-slope-wet"}});
    // Before a run: the field's own maps, the soil classes drawn.
    EXPECT_TRUE(panel.layerChooser()->isVisibleTo(&panel));
    EXPECT_EQ(layerKeys(panel), (QStringList{"none", "height", "soil_classes"}));
    EXPECT_EQ(panel.layerKey(), "soil_classes");
    const scenario::Scenario loaded =
        scenario::resolveScenario(test::resources(), "field-slope-wet").value();
    // The start (27.5, 22) is on class 1 ("field"), the first of the legend: colour index 0;
    // the wet hollow's centre (32, 22) is class 2, index 1 (docs/field.md, "Shipped fields").
    ASSERT_EQ(loaded.field->classAt(27.5, 22.0), 1);
    EXPECT_EQ(drawnAt(panel, {27.5, 22.0}), 0.0);
    // The status names the field's soils by their legend labels (not only the base soil).
    bool said = false;
    for (QLabel* label : panel.findChildren<QLabel*>())
        said = said || label->text().contains("wet hollow: lean clay");
    EXPECT_TRUE(said);

    ASSERT_TRUE(runField(panel, 20.0));
    const scenario::RunResult& run = panel.result();
    ASSERT_TRUE(run.maps);
    EXPECT_EQ(layerKeys(panel),
              (QStringList{"none", "height", "soil_classes", "rut_depth_m", "passes",
                           "compaction_risk", "slip", "energy_per_m_J"}));
    // The run's ruts are what a run's top view shows first.
    EXPECT_EQ(panel.layerKey(), "rut_depth_m");
    const scenario::FieldMaps& maps = *run.maps;
    const QPointF cell = deepestRut(maps.rut_depth_m);
    ASSERT_GT(maps.rut_depth_m.nearest(cell.x(), cell.y()), 1e-3);  // a rut of millimetres
    QCPColorMap* map = topViewLayer(*panel.topView());
    ASSERT_NE(map, nullptr);
    ASSERT_NE(map->colorScale(), nullptr);
    EXPECT_EQ(map->colorScale()->axis()->label(), "rut depth [mm]");
    EXPECT_DOUBLE_EQ(drawnAt(panel, cell), 1e3 * maps.rut_depth_m.nearest(cell.x(), cell.y()));
    // The chooser switches the colour map's data; each at the same cell is that map's value.
    ASSERT_TRUE(panel.chooseLayer("passes"));
    EXPECT_EQ(drawnAt(panel, cell), maps.passes.nearest(cell.x(), cell.y()));
    EXPECT_GE(drawnAt(panel, cell), 1.0);
    EXPECT_EQ(topViewLayer(*panel.topView())->colorScale()->axis()->label(), "wheel passes [-]");
    ASSERT_TRUE(panel.chooseLayer("compaction_risk"));
    EXPECT_DOUBLE_EQ(drawnAt(panel, cell), maps.compaction_risk.nearest(cell.x(), cell.y()));
    ASSERT_TRUE(panel.chooseLayer("height"));
    // The height map's 0.5 m cell under the rut, from the field's file.
    EXPECT_EQ(drawnAt(panel, cell), loaded.field->height->nearest(cell.x(), cell.y()));
    EXPECT_EQ(topViewLayer(*panel.topView())->colorScale()->axis()->label(), "height [m]");
    ASSERT_TRUE(panel.chooseLayer("soil_classes"));
    const int code = *loaded.field->classAt(cell.x(), cell.y());
    EXPECT_EQ(drawnAt(panel, cell), code - 1.0);  // codes 1, 2, 3 are colours 0, 1, 2
    // The classes are named in the legend (no colour scale).
    QStringList names;
    for (int i = 0; i < panel.topView()->legend->itemCount(); ++i) {
        if (auto* item = qobject_cast<QCPPlottableLegendItem*>(panel.topView()->legend->item(i)))
            names << item->plottable()->name();
    }
    EXPECT_TRUE(names.contains("field") && names.contains("wet hollow") &&
                names.contains("headland"))
        << names.join(", ").toStdString();
    EXPECT_EQ(topViewLayer(*panel.topView())->colorScale(), nullptr);
    ASSERT_TRUE(panel.chooseLayer("none"));
    EXPECT_EQ(topViewLayer(*panel.topView()), nullptr);
    EXPECT_FALSE(panel.chooseLayer("moisture"));  // not a map of this run
}

TEST(RoverFieldLayers, ScrubbingShowsTheRutsAsTheyWereAtThatTime) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    ASSERT_TRUE(runField(panel, 20.0));
    const scenario::RunResult& run = panel.result();
    const scenario::FieldMaps& maps = *run.maps;
    const Table& t = run.series;
    QSignalSpy shown(&panel, &AnalysisPanel::resultShown);
    QSignalSpy busy(&panel, &AnalysisPanel::busyChanged);
    ASSERT_EQ(panel.layerKey(), "rut_depth_m");

    // t = 0: no wheel has left a cell yet, no rut.
    panel.scrubber()->setValue(0);
    EXPECT_EQ(cellsAboveZero(panel), 0);
    // The end: every drawn cell is the final map's (0, untouched, is left clear).
    panel.scrubber()->setValue(panel.scrubber()->maximum());
    QCPColorMap* map = topViewLayer(*panel.topView());
    ASSERT_NE(map, nullptr);
    QCPColorMapData* data = map->data();
    int rutted_end = 0, compared = 0;
    for (int k = 0; k < data->keySize(); ++k) {
        for (int v = 0; v < data->valueSize(); ++v) {
            double x = 0, y = 0;
            data->cellToCoord(k, v, &x, &y);
            const double final_rut = maps.rut_depth_m.nearest(x, y);
            const double drawn = data->cell(k, v);
            if (final_rut == 0.0) {
                EXPECT_TRUE(std::isnan(drawn)) << x << ", " << y;
            } else {
                EXPECT_DOUBLE_EQ(drawn, 1e3 * final_rut) << x << ", " << y;
                ++rutted_end;
            }
            ++compared;
        }
    }
    EXPECT_GT(compared, 300);  // the driven area: ≈ 2.5 m × 1.7 m of 0.1 m cells
    EXPECT_GT(rutted_end, 20);
    // Half-way the ruts drawn are those of the passages written by then: as many as the run's
    // history holds up to that time (one per cell, counted here from its times and cells).
    const int mid = rowAt(t, 10.0);
    panel.scrubber()->setValue(mid);
    const double t_mid = t.rows[static_cast<std::size_t>(mid)][t.column("t_s")];
    std::set<std::int32_t> cells_by_then;
    for (std::size_t i = 0; i < maps.history.size(); ++i) {
        if (maps.history.time_s[i] <= t_mid && maps.history.values.at("rut_depth_m")[i] > 0.0)
            cells_by_then.insert(maps.history.cell[i]);
    }
    EXPECT_EQ(cellsAboveZero(panel), static_cast<int>(cells_by_then.size()));
    EXPECT_GT(cellsAboveZero(panel), 0);
    EXPECT_LT(cellsAboveZero(panel), rutted_end);
    // Passes at the same time: no cell holds two yet where it ends with two (the rear wheels
    // reach the front ruts later).
    ASSERT_TRUE(panel.chooseLayer("passes"));
    panel.scrubber()->setValue(rowAt(t, 5.0));
    map = topViewLayer(*panel.topView());
    int twice = 0;
    for (int k = 0; k < map->data()->keySize(); ++k) {
        for (int v = 0; v < map->data()->valueSize(); ++v) twice += map->data()->cell(k, v) >= 2.0;
    }
    EXPECT_EQ(twice, 0);
    // Scrubbing only redraws. Instrumented, not timed (docs/performance.md, "Field layers in
    // the studio"): the GUI thread's time per scrub step and per layer switch, a 1 s freeze guard.
    QElapsedTimer clock;
    double scrub_max_ms = 0.0, switch_max_ms = 0.0;
    ASSERT_TRUE(panel.chooseLayer("rut_depth_m"));
    for (int row = 0; row <= panel.scrubber()->maximum(); row += 40) {
        clock.start();
        panel.scrubber()->setValue(row);
        scrub_max_ms = std::max(scrub_max_ms, clock.nsecsElapsed() * 1e-6);
    }
    for (const char* key : {"height", "soil_classes", "passes", "compaction_risk", "rut_depth_m"}) {
        clock.start();
        ASSERT_TRUE(panel.chooseLayer(key));
        switch_max_ms = std::max(switch_max_ms, clock.nsecsElapsed() * 1e-6);
    }
    RecordProperty("scrub_step_max_ms", QString::number(scrub_max_ms, 'f', 2).toStdString());
    RecordProperty("layer_switch_max_ms", QString::number(switch_max_ms, 'f', 2).toStdString());
    std::printf("[ gui time ] scrub step max %.2f ms, layer switch max %.2f ms\n", scrub_max_ms,
                switch_max_ms);
    EXPECT_LT(scrub_max_ms, 1000.0);
    EXPECT_LT(switch_max_ms, 1000.0);
    EXPECT_EQ(shown.count(), 0);
    EXPECT_EQ(busy.count(), 0);
}

TEST(RoverFieldLayers, ASavedFieldRunShowsItsLayersAgainWithoutRunning) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    ASSERT_TRUE(runField(panel, 14.0));
    const scenario::FieldMaps& maps = *panel.result().maps;
    const QPointF cell = deepestRut(maps.rut_depth_m);
    const double rut_mm = 1e3 * maps.rut_depth_m.nearest(cell.x(), cell.y());
    const auto saved = panel.savedResults();
    ASSERT_EQ(saved.size(), 1u);
    project::SavedResult section = saved.begin()->second;
    section.result = nlohmann::json::parse(section.result.dump());  // as read from the file

    RoverPanel reopened(&document, test::resources());
    reopened.applySettings(panel.settings());
    QSignalSpy busy(&reopened, &AnalysisPanel::busyChanged);
    ASSERT_TRUE(reopened.restoreResult(saved.begin()->first, section).shown());
    EXPECT_EQ(busy.count(), 0);  // nothing ran
    ASSERT_TRUE(reopened.result().maps);
    EXPECT_EQ(layerKeys(reopened), layerKeys(panel));
    EXPECT_EQ(reopened.layerKey(), "rut_depth_m");
    EXPECT_DOUBLE_EQ(drawnAt(reopened, cell), rut_mm);
    // Kept over the driven area only: a few metres of the 60 m field.
    EXPECT_LT(reopened.result().maps->rut_depth_m.values.size(),
              maps.rut_depth_m.values.size() / 100);
    reopened.scrubber()->setValue(0);
    EXPECT_EQ(cellsAboveZero(reopened), 0);
    reopened.scrubber()->setValue(reopened.scrubber()->maximum());
    EXPECT_EQ(cellsAboveZero(reopened), cellsAboveZero(panel));
}

TEST(RoverFieldLayers, APatchScenarioHasNoLayers) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    panel.applySettings({{"scenario", "straight"}});
    EXPECT_FALSE(panel.layerChooser()->isVisibleTo(&panel));
    EXPECT_EQ(layerKeys(panel), QStringList{"none"});
    EXPECT_EQ(topViewLayer(*panel.topView()), nullptr);
}

}  // namespace field_layers_test
}  // namespace terra::ui
