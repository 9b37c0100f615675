// The maps under the studio's top view (core/scenario/map_layers.h): the layers a field and its
// run list, the run's maps as they were at a time t (from the passages the runner recorded),
// and the window and coarsening that keep a 2,500 × 1,000 raster cheap to draw.
#include "core/scenario/map_layers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/scenario/scenario_json.h"
#include "tests/core/test_support.h"

namespace terra::scenario {
namespace {

using terra::testing::kLocations;
constexpr double kEndOfRun = std::numeric_limits<double>::infinity();

Scenario shippedScenario(const std::string& name, double duration_s) {
    Result<Scenario> s = resolveScenario(kLocations, name);
    EXPECT_TRUE(s.ok()) << s.message();
    Scenario out = s.value();
    out.duration_s = duration_s;
    return out;
}

// The shipped field run cut to 20 s: the rear wheels reach the front ruts after ≈ 11 s (0.5 m
// wheelbase at ≈ 0.045 m/s), so cells are passed once and twice.
const RunResult& fieldRun20s() {
    static const RunResult run = runScenario(shippedScenario("field-slope-wet", 20.0));
    return run;
}

CellWindow wholeWindow(const field::Raster& r) { return {0, 0, r.cols, r.rows}; }

bool sameOrBothNan(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

TEST(MapLayers, AFieldListsItsMapsAndItsRunsMapsAPatchScenarioNone) {
    const Scenario field = shippedScenario("field-slope-wet", 20.0);
    std::vector<std::string> keys;
    for (const MapLayer& l : mapLayers(field, nullptr)) keys.push_back(l.key);
    EXPECT_EQ(keys, (std::vector<std::string>{"height", "soil_classes"}));
    const std::vector<MapLayer> all = mapLayers(field, &*fieldRun20s().maps);
    keys.clear();
    for (const MapLayer& l : all) keys.push_back(l.key);
    // The run's maps are those writeResults writes as files, in their order.
    EXPECT_EQ(keys, (std::vector<std::string>{"height", "soil_classes", "rut_depth_m", "passes",
                                              "compaction_risk", "slip", "energy_per_m_J"}));
    ASSERT_EQ(all[1].kind, LayerKind::kClasses);
    // The legend's labels by code (resources/scenarios/field-slope-wet.json).
    EXPECT_EQ(all[1].classes, (std::vector<std::pair<int, std::string>>{
                                  {1, "field"}, {2, "wet hollow"}, {3, "headland"}}));
    EXPECT_FALSE(all[0].timed);
    EXPECT_TRUE(all[2].timed);
    EXPECT_EQ(all[2].unit, "m");
    EXPECT_EQ(all[3].unit, "-");
    EXPECT_NE(all[4].label.find("0.3 m"), std::string::npos) << all[4].label;
    EXPECT_EQ(layerRaster(field, nullptr, "height"), &*field.field->height);
    EXPECT_EQ(layerRaster(field, nullptr, "rut_depth_m"), nullptr);
    EXPECT_TRUE(mapLayers(shippedScenario("straight", 1.0), nullptr).empty());
}

// Issue 23 item 4: the maps also as CSV. maps.csv holds every cell a wheel passed, and only
// those, with each map's value there: checked against the rasters cell by cell.
TEST(MapLayers, TheMapTableHasEveryPassedCellWithEachMapsValue) {
    const FieldMaps& maps = *fieldRun20s().maps;
    const Table table = touchedCells(maps);
    ASSERT_EQ(table.columns,
              (std::vector<std::string>{"x_m", "y_m", "rut_depth_m", "passes", "compaction_risk",
                                        "slip", "energy_per_m_J"}));
    std::size_t passed = 0;
    for (double p : maps.passes.values) passed += p > 0.0 ? 1 : 0;
    ASSERT_GT(passed, 10u);
    ASSERT_EQ(table.rows.size(), passed);
    std::size_t twice = 0;
    for (const auto& row : table.rows) {
        const auto cell = maps.passes.cellAt(row[0], row[1]);
        ASSERT_TRUE(cell.has_value());
        EXPECT_GT(row[3], 0.0);
        twice += row[3] >= 2.0 ? 1 : 0;
        const field::Raster* rasters[] = {&maps.rut_depth_m, &maps.passes, &maps.compaction_risk,
                                          &maps.slip, &maps.energy_per_m_j};
        for (std::size_t i = 0; i < std::size(rasters); ++i) {
            EXPECT_TRUE(sameOrBothNan(row[2 + i], rasters[i]->nearest(row[0], row[1])))
                << table.columns[2 + i] << " at " << row[0] << ", " << row[1];
        }
    }
    EXPECT_GT(twice, 0u) << "the rear wheels in the front ruts: cells passed twice";
    // The file list the CLI writes and cleans ends with it.
    EXPECT_EQ(mapFileNames().back(), "maps.csv");
}

// A map another change adds to FieldMaps (slip, energy) is listed with a label and unit read off
// its key before anyone names it.
TEST(MapLayers, AMapNotKnownByNameTakesItsLabelAndUnitFromItsKey) {
    const FieldMaps maps;
    const MapLayer energy = runMapLayer("energy_J_m", maps);
    EXPECT_EQ(energy.label, "energy");
    EXPECT_EQ(energy.unit, "J/m");
    EXPECT_TRUE(energy.timed);
    EXPECT_EQ(runMapLayer("energy_J_m2", maps).unit, "J/m²");
    EXPECT_EQ(runMapLayer("max_slip", maps).label, "max slip");
    EXPECT_EQ(runMapLayer("max_slip", maps).unit, "-");
    EXPECT_EQ(runMapLayer("rut_depth_m", maps).label, "rut depth");
    EXPECT_EQ(runMapLayer("rut_depth_m", maps).unit, "m");
}

TEST(MapLayers, EveryPassageIsRecordedOnceInTimeOrder) {
    const FieldMaps& maps = *fieldRun20s().maps;
    const MapHistory& h = maps.history;
    ASSERT_GT(h.size(), 20u);
    // Each passage adds one to its cell's count: the passes map (summed from the cell grid) holds
    // as many as the history recorded.
    double passes = 0.0;
    for (double v : maps.passes.values) passes += v;
    EXPECT_EQ(passes, static_cast<double>(h.size()));
    EXPECT_TRUE(std::is_sorted(h.time_s.begin(), h.time_s.end()));
    EXPECT_GT(h.time_s.front(), 0.0);
    EXPECT_LE(h.time_s.back(), 20.0 + 1e-9);
    for (const auto& [key, values] : h.values) EXPECT_EQ(values.size(), h.size()) << key;
    // Some cells were passed twice (rear wheels in the front ruts), not all.
    const auto [lo, hi] = maps.passes.valueRange();
    EXPECT_EQ(lo, 0.0);
    EXPECT_GE(hi, 2.0);
}

TEST(MapLayers, AtTheEndEveryMapIsTheFinalMapAndBeforeAnyPassageUntouched) {
    const FieldMaps& maps = *fieldRun20s().maps;
    const double end = maps.history.time_s.back();
    for (const auto& [key, raster] : mapRasters(maps)) {
        SCOPED_TRACE(key);
        const field::Raster last = mapAt(maps, key, end, wholeWindow(*raster));
        ASSERT_EQ(last.values.size(), raster->values.size());
        long differ = 0;
        for (std::size_t i = 0; i < last.values.size(); ++i)
            differ += sameOrBothNan(last.values[i], raster->values[i]) ? 0 : 1;
        EXPECT_EQ(differ, 0);
        const field::Raster first = mapAt(maps, key, 0.0, wholeWindow(*raster));
        for (std::size_t i = 0; i < first.values.size(); ++i) {
            // Untouched soil: 0, or no data where the final map has none.
            ASSERT_TRUE(std::isnan(raster->values[i]) ? std::isnan(first.values[i])
                                                      : first.values[i] == 0.0)
                << i;
        }
    }
}

TEST(MapLayers, BetweenPassagesACellShowsTheCountAndRutOfThePassagesSoFar) {
    const FieldMaps& maps = *fieldRun20s().maps;
    const MapHistory& h = maps.history;
    // The passages of each cell, by time.
    std::map<std::int32_t, std::vector<std::size_t>> by_cell;
    for (std::size_t i = 0; i < h.size(); ++i) by_cell[h.cell[i]].push_back(i);
    int checked = 0;
    for (const auto& [cell, passages] : by_cell) {
        if (passages.size() < 2) continue;
        const double t_mid = 0.5 * (h.time_s[passages[0]] + h.time_s[passages[1]]);
        if (!(t_mid > h.time_s[passages[0]])) continue;
        const field::Raster& full = maps.passes;
        const CellWindow one{cell % full.cols, cell / full.cols, 1, 1};
        EXPECT_EQ(mapAt(maps, "passes", t_mid, one).values[0], 1.0);
        EXPECT_EQ(mapAt(maps, "passes", kEndOfRun, one).values[0],
                  static_cast<double>(passages.size()));
        // The rut after the first passage: the front wheel's, no deeper than the final one.
        const double rut_mid = mapAt(maps, "rut_depth_m", t_mid, one).values[0];
        EXPECT_GT(rut_mid, 0.0);
        EXPECT_LE(rut_mid, maps.rut_depth_m.values[static_cast<std::size_t>(cell)]);
        ++checked;
    }
    EXPECT_GT(checked, 3);
    // Cells with a rut grow in number as the run goes on.
    auto rutted = [&](double t) {
        const field::Raster r = mapAt(maps, "rut_depth_m", t, wholeWindow(maps.rut_depth_m));
        return std::count_if(r.values.begin(), r.values.end(), [](double v) { return v > 0.0; });
    };
    EXPECT_EQ(rutted(0.0), 0);
    EXPECT_LT(rutted(5.0), rutted(10.0));
    EXPECT_LT(rutted(10.0), rutted(20.0));
}

TEST(MapLayers, CroppedMapsDrawTheSameAsTheWholeOnes) {
    const Scenario field = shippedScenario("field-slope-wet", 20.0);
    const RunResult& run = fieldRun20s();
    const FieldMaps& maps = *run.maps;
    const std::array<double, 4> box = drivenArea(field, run.series);
    const CellWindow window = windowOver(maps.rut_depth_m, box[0], box[1], box[2], box[3]);
    ASSERT_FALSE(window.empty());
    // The driven area is a few metres of the 60 m × 40 m field.
    EXPECT_LT(static_cast<double>(window.cols) * window.rows,
              0.01 * static_cast<double>(maps.rut_depth_m.values.size()));
    const FieldMaps cropped = cropMaps(maps, window);
    // Every passage happened inside the driven area.
    EXPECT_EQ(cropped.history.size(), maps.history.size());
    for (double t : {0.0, 7.5, 13.0, kEndOfRun}) {
        for (const auto& [key, raster] : mapRasters(maps)) {
            const field::Raster a = mapAt(maps, key, t, window);
            const field::Raster b =
                mapAt(cropped, key, t, wholeWindow(*mapRasters(cropped)[0].second));
            ASSERT_EQ(a.values.size(), b.values.size());
            EXPECT_EQ(a.x_min_m, b.x_min_m);
            EXPECT_EQ(a.y_min_m, b.y_min_m);
            for (std::size_t i = 0; i < a.values.size(); ++i)
                ASSERT_TRUE(sameOrBothNan(a.values[i], b.values[i]))
                    << key << " t " << t << " cell " << i;
        }
    }
}

TEST(MapLayers, AWindowHoldsTheCellsOfItsBoxAtTheirPlaces) {
    // 10 × 5 cells of 2 m from (100, 50); value = 10 col + row.
    field::Raster r = field::makeRaster(10, 5, 100.0, 50.0, 2.0);
    for (int row = 0; row < 5; ++row)
        for (int col = 0; col < 10; ++col) r.value(col, row) = 10 * col + row;
    const CellWindow w = windowOver(r, 103.0, 51.0, 108.5, 55.0);
    // x 103 → col 1, 108.5 → col 4 (inclusive); y 55 → row 2 (from the north edge at 60), 51 →
    // row 4.
    EXPECT_EQ(w.col, 1);
    EXPECT_EQ(w.cols, 4);
    EXPECT_EQ(w.row, 2);
    EXPECT_EQ(w.rows, 3);
    const field::Raster c = crop(r, w);
    for (int row = 0; row < c.rows; ++row) {
        for (int col = 0; col < c.cols; ++col)
            EXPECT_EQ(c.value(col, row), r.nearest(c.centreX(col), c.centreY(row)));
    }
    EXPECT_TRUE(windowOver(r, 0.0, 0.0, 10.0, 10.0).empty());       // misses the raster
    EXPECT_TRUE(windowOver(r, 0.0, 0.0, kEndOfRun, 10.0).empty());  // not finite
    const CellWindow all = windowOver(r, -1e6, -1e6, 1e6, 1e6);     // clipped to it
    EXPECT_EQ(all.cols, 10);
    EXPECT_EQ(all.rows, 5);
}

TEST(MapLayers, ALargeRasterIsCoarsenedKeepingAOneCellRut) {
    // 2,500 × 1,000 cells of 2 cm (50 m × 20 m, the field), 0 but for a rut one cell
    // wide along row 333 from col 100 to 2,399 and a few cells without data.
    field::Raster r = field::makeRaster(2500, 1000, 0.0, 0.0, 0.02);
    for (int col = 100; col < 2400; ++col) r.value(col, 333) = 0.004 + 1e-6 * col;
    for (int col = 0; col < 4; ++col)
        for (int row = 996; row < 1000; ++row) r.value(col, row) = std::nan("");
    const field::Raster c = coarsen(r, kMaxViewCells, LayerKind::kContinuous);
    // k = ⌈2500 / 800⌉ = 4: 625 × 250 blocks of 8 cm, the same north-west corner.
    EXPECT_EQ(c.cols, 625);
    EXPECT_EQ(c.rows, 250);
    EXPECT_DOUBLE_EQ(c.cell_m, 0.08);
    EXPECT_EQ(c.x_min_m, 0.0);
    EXPECT_DOUBLE_EQ(c.yMax(), r.yMax());
    // Row 333 lies in block row 83; each block holds the largest of its four columns.
    for (int bcol = 25; bcol < 600; ++bcol)
        EXPECT_DOUBLE_EQ(c.value(bcol, 83), 0.004 + 1e-6 * (4 * bcol + 3)) << bcol;
    EXPECT_EQ(c.value(10, 82), 0.0);
    EXPECT_TRUE(std::isnan(c.value(0, 249)));  // no cell of the block has data
    // Classes: the block's middle cell, never a blend.
    field::Raster classes = field::makeRaster(9, 3, 0.0, 0.0, 1.0, 1.0);
    classes.value(1, 1) = 2.0;
    classes.value(4, 1) = 3.0;
    const field::Raster k = coarsen(classes, 3, LayerKind::kClasses);
    ASSERT_EQ(k.cols, 3);
    ASSERT_EQ(k.rows, 1);
    EXPECT_EQ(k.value(0, 0), 2.0);
    EXPECT_EQ(k.value(1, 0), 3.0);
    EXPECT_EQ(k.value(2, 0), 1.0);
    EXPECT_THROW(coarsen(classes, 0, LayerKind::kClasses), std::invalid_argument);
}

TEST(MapLayers, ALayerViewIsTheBoxOfTheMapAtTimeT) {
    const Scenario field = shippedScenario("field-slope-wet", 20.0);
    const RunResult& run = fieldRun20s();
    const FieldMaps& maps = *run.maps;
    const std::array<double, 4> box = drivenArea(field, run.series);
    for (const MapLayer& layer : mapLayers(field, &maps)) {
        SCOPED_TRACE(layer.key);
        const field::Raster view = layerView(field, &maps, layer, box, 10.0);
        ASSERT_GT(view.cols, 0);
        const field::Raster* raster = layerRaster(field, &maps, layer.key);
        // Cells of the map's own size (the window is small), in the box.
        EXPECT_EQ(view.cell_m, raster->cell_m);
        EXPECT_LE(view.x_min_m, box[0]);
        EXPECT_GE(view.xMax(), box[2]);
        for (int row = 0; row < view.rows; ++row) {
            for (int col = 0; col < view.cols; ++col) {
                const double x = view.centreX(col), y = view.centreY(row);
                const double expected =
                    layer.timed ? mapAt(maps, layer.key, 10.0,
                                        windowOver(*raster, x - 1e-9, y - 1e-9, x + 1e-9, y + 1e-9))
                                      .values[0]
                                : raster->nearest(x, y);
                ASSERT_TRUE(sameOrBothNan(view.value(col, row), expected)) << col << ", " << row;
            }
        }
    }
    const MapLayer height = mapLayers(field, nullptr).front();
    EXPECT_EQ(layerView(field, nullptr, height, {-50.0, -50.0, -40.0, -40.0}).cols, 0);
}

}  // namespace
}  // namespace terra::scenario
