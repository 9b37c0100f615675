// The rover on a field (docs/field.md, "The rover on a field"): a flat field is today's patch
// terrain bit for bit; a straight pass leaves the single-wheel pass model's rut and the rear wheel
// in the front rut is its two-pass case (core/compaction, solved on its own); on a uniform slope
// the robot's steady slip is where the wheel model's pull carries the slope (an independent
// bisection); a slope steeper than the soil can carry stalls the robot; runs repeat bit for bit.
#include "core/dynamics/field_terrain.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "core/compaction/footprint.h"
#include "core/compaction/passes.h"
#include "core/compaction/stress_at_depth.h"
#include "core/io/parameters_json.h"
#include "core/scenario/runner.h"
#include "core/scenario/scenario_json.h"
#include "tests/core/test_support.h"

namespace terra::dynamics {
namespace {

using terra::testing::kLocations;
using terra::testing::messageOf;

scenario::Scenario shipped(const std::string& name, double duration_s) {
    Result<scenario::Scenario> s = scenario::resolveScenario(kLocations, name);
    EXPECT_TRUE(s.ok()) << s.message();
    scenario::Scenario out = s.value();
    out.duration_s = duration_s;
    return out;
}

// A flat field of one soil everywhere (no rasters): the field's form of a patch terrain.
std::shared_ptr<const field::FieldMap> uniformField(const soil::SoilParameters& soil) {
    auto map = std::make_shared<field::FieldMap>();
    map->base = soil;
    return map;
}

// A field whose class raster puts `patch` at x ≥ x_border (cells 0.5 m wide, edges on x_border)
// and `base` elsewhere: the soil-border scenario as a map.
std::shared_ptr<const field::FieldMap> borderField(const soil::SoilParameters& base,
                                                   const soil::SoilParameters& patch,
                                                   double x_border) {
    auto map = std::make_shared<field::FieldMap>();
    map->base = base;
    map->soil_class = field::makeRaster(80, 40, x_border - 10.0, -10.0, 0.5);
    for (int row = 0; row < map->soil_class->rows; ++row)
        for (int col = 0; col < map->soil_class->cols; ++col)
            map->soil_class->value(col, row) = map->soil_class->centreX(col) < x_border ? 1 : 2;
    map->legend[1] = base;
    map->legend[2] = patch;
    return map;
}

// A plane rising along x at tan α (and along y at tan β), 1 m cells over [−20, 60] × [−20, 20].
std::shared_ptr<const field::FieldMap> slopedField(const soil::SoilParameters& soil,
                                                   double alpha_rad, double beta_rad = 0.0) {
    auto map = std::make_shared<field::FieldMap>();
    map->base = soil;
    map->height = field::makeRaster(80, 40, -20.0, -20.0, 1.0);
    for (int row = 0; row < map->height->rows; ++row)
        for (int col = 0; col < map->height->cols; ++col)
            map->height->value(col, row) = std::tan(alpha_rad) * map->height->centreX(col) +
                                           std::tan(beta_rad) * map->height->centreY(row);
    return map;
}

void expectSameSeries(const scenario::RunResult& a, const scenario::RunResult& b,
                      bool skip_soil_index) {
    ASSERT_EQ(a.series.columns, b.series.columns);
    ASSERT_EQ(a.series.rows.size(), b.series.rows.size());
    for (std::size_t c = 0; c < a.series.columns.size(); ++c) {
        const std::string& name = a.series.columns[c];
        if (skip_soil_index && name.size() > 5 && name.substr(name.size() - 5) == "_soil") continue;
        for (std::size_t r = 0; r < a.series.rows.size(); ++r) {
            ASSERT_EQ(a.series.rows[r][c], b.series.rows[r][c]) << name << " row " << r;
        }
    }
}

double last(const scenario::RunResult& r, const std::string& column) {
    return r.series.rows.back()[r.series.column(column)];
}

// (a) of the brief: the patch scenarios on a flat grid with the memory off are today's runs, bit
// for bit (the local frame reduces exactly to the flat one: n = up, D = hub z).
TEST(FieldRover, FlatFieldIsThePatchTerrainBitForBit) {
    for (const char* name : {"straight", "pulse-steering"}) {
        scenario::Scenario patch = shipped(name, 6.0);
        scenario::Scenario field = patch;
        field.field = uniformField(patch.terrain.base);
        field.field_options.repeated_passes = false;
        const scenario::RunResult a = scenario::runScenario(patch);
        const scenario::RunResult b = scenario::runScenario(field);
        SCOPED_TRACE(name);
        expectSameSeries(a, b, false);
        EXPECT_EQ(a.summary.energy_j, b.summary.energy_j);
        EXPECT_FALSE(a.maps);
        ASSERT_TRUE(b.maps);
        EXPECT_GT(*b.summary.cells_touched, 0);
    }
    // The border as a class map: the same physics, only the soil's index differs (0/1 on the
    // patches, 1/2 for the legend's classes).
    scenario::Scenario patch = shipped("soil-border", 50.0);
    patch.streaming.reset();
    ASSERT_EQ(patch.terrain.patches.size(), 1u);
    scenario::Scenario field = patch;
    field.field = borderField(patch.terrain.base, patch.terrain.patches[0].soil,
                              patch.terrain.patches[0].x_min_m);
    field.field_options.repeated_passes = false;
    const scenario::RunResult a = scenario::runScenario(patch);
    const scenario::RunResult b = scenario::runScenario(field);
    ASSERT_GT(a.summary.x_m, 1.0);  // every wheel crossed the border
    expectSameSeries(a, b, true);
    EXPECT_EQ(last(a, "FL_soil"), 1.0);
    EXPECT_EQ(last(b, "FL_soil"), 2.0);
}

// The cell of a wheel's track at x: the wheels' centre lines (y = ±track/2) lie on cell edges, so
// of the two cells beside y the one the wheel passed (or nullptr).
const field::CellState* cellAt(const FieldTerrain& t, double x, double y) {
    const double h = t.cells().cellSize();
    const field::CellState* best = nullptr;
    for (double dy : {-0.3 * h, 0.3 * h}) {
        const field::CellState* c = t.cells().find(x, y + dy);
        if (c != nullptr && (best == nullptr || c->track.passes > best->track.passes)) best = c;
    }
    return best;
}

// One straight run on a flat uniform field with the memory on, driven by hand so the terrain's
// cells can be read afterwards.
struct StraightOnField {
    scenario::Scenario s;
    std::unique_ptr<FieldTerrain> terrain;
    RoverState end;
};

// The shipped straight run, its wheels at 1.5 rad/s (0.14 m/s) so that the front wheels' track
// is longer than the wheelbase within seconds.
StraightOnField driveStraight(double duration_s, double cell_m, bool across_width = true) {
    StraightOnField out;
    out.s = shipped("straight", duration_s);
    for (auto& w : out.s.wheels) w.spin_rate_rad_s = scenario::Signal::constant(1.5);
    out.s.options.contact.model = contact::ContactModel::kFull;
    FieldTerrainOptions options;
    options.cell_m = cell_m;
    options.across_width = across_width;
    out.terrain =
        std::make_unique<FieldTerrain>(uniformField(out.s.terrain.base), out.s.robot, options);
    Rover rover(out.s.robot, *out.terrain, out.s.options, out.s.initial, out.s.commandsAt(0.0));
    const long steps = std::lround(duration_s / out.s.time_step_s);
    for (long k = 0; k < steps; ++k) rover.step(out.s.time_step_s, out.s.commandsAt(0.0));
    out.end = rover.evaluate(out.s.commandsAt(0.0));
    out.terrain->finish();
    return out;
}

// The wheel's instant as a pass of core/compaction: the load is the model's own F_z (the rover's
// load adds the vertical damper's force, which is not the soil's).
compaction::PassConditions conditionsOf(const WheelState& w) {
    compaction::PassConditions c;
    c.load_n = w.contact.forces.fz;
    c.slip = w.contact.slip;
    c.exit = {contact::ExitCondition::Kind::kAngle, 0.0};
    c.model = contact::ContactModel::kFull;
    return c;
}

// A straight pass leaves the single-wheel pass model's rut, and the rear wheel, in the front
// wheel's rut, meets the two-pass case: core/compaction solves both on their own from the loads
// and slips the run ended with.
TEST(FieldRover, StraightPassLeavesTheSingleWheelRutAndTheRearWheelIsPassTwo) {
    const StraightOnField run = driveStraight(14.0, 0.02);
    const WheelState& front = run.end.wheels[kFrontLeft];
    const WheelState& rear = run.end.wheels[kRearLeft];
    const auto params = contact::makeContactParameters(run.s.terrain.base, run.s.robot.wheel);
    const compaction::ReloadLaw law = run.terrain->reloadLaw();
    ASSERT_FALSE(law.shear_memory);  // the rover's default (docs/field.md, F11)
    const compaction::PassConditions front_c = conditionsOf(front);
    const compaction::SolvedPass pass1 =
        compaction::solvePass(params, compaction::TrackMemory{}, law, front_c);
    ASSERT_TRUE(pass1.ok) << pass1.message;
    const compaction::TrackMemory after1 =
        compaction::rememberPass({}, law, params, front_c, pass1);

    // The front wheel's cells between the two axles at the end: passed once.
    const double y = 0.5 * run.s.robot.track_m;
    const double x_front = run.end.position_m[0] + 0.5 * run.s.robot.wheelbase_m;
    const double x_rear = run.end.position_m[0] - 0.5 * run.s.robot.wheelbase_m;
    ASSERT_GT(x_rear, 0.7);  // the rear wheels are past the front wheels' start and transient
    int checked = 0;
    for (double x = x_rear + 0.1; x < x_front - 0.1; x += 0.02) {
        const field::CellState* c = cellAt(*run.terrain, x, y);
        ASSERT_NE(c, nullptr);
        EXPECT_EQ(c->track.passes, 1) << x;
        EXPECT_NEAR(c->track.rut_depth_m, after1.rut_depth_m, 0.01 * after1.rut_depth_m) << x;
        EXPECT_NEAR(c->track.max_sinkage_m, after1.max_sinkage_m, 0.01 * after1.max_sinkage_m);
        ++checked;
    }
    EXPECT_GE(checked, 10);
    // The largest σ_z at the risk depth (0.3 m) under the front wheel's centre line: the
    // footprint of the solved pass, propagated with ν = 5 (no profile gives one), within 2 %.
    ASSERT_EQ(run.terrain->cells().stressDepths(), std::vector<double>{0.3});
    const double nu = run.s.terrain.base.profile ? 0.0 : compaction::kDefaultConcentration;
    if (nu > 0.0) {
        const compaction::StressPropagation propagation(
            compaction::wheelFootprint(pass1.params, pass1.op), nu);
        const double sigma = compaction::maxVerticalStress(propagation, 0.0, 0.3);
        const field::CellState* c = cellAt(*run.terrain, 0.5 * (x_rear + x_front), y);
        ASSERT_NE(c, nullptr);
        EXPECT_NEAR(c->max_stress_pa[0], sigma, 0.02 * sigma);
    }

    // The rear wheel on pass two: its sinkage below the untouched surface and its forces.
    ASSERT_EQ(rear.passes_before, 1);
    const compaction::PassConditions rear_c = conditionsOf(rear);
    const compaction::SolvedPass pass2 = compaction::solvePass(params, after1, law, rear_c);
    ASSERT_TRUE(pass2.ok) << pass2.message;
    EXPECT_NEAR(rear.contact.sinkage_m, pass2.sinkage_m, 0.01 * pass2.sinkage_m);
    EXPECT_NEAR(rear.contact.forces.fx, pass2.forces.fx, 0.02 * std::abs(pass1.forces.fx) + 0.05);
    EXPECT_NEAR(rear.contact.forces.my, pass2.forces.my, 0.02 * std::abs(pass2.forces.my));
    // Pass two sinks less into the rut than pass one did into untouched soil (R2).
    EXPECT_LT(rear.contact.sinkage_m - after1.rut_depth_m, pass1.sinkage_m);

    // Behind the rear wheel: two passes, and the rut the second one leaves.
    const compaction::TrackMemory after2 =
        compaction::rememberPass(after1, law, params, rear_c, pass2);
    const field::CellState* behind = cellAt(*run.terrain, x_rear - 0.3, y);
    ASSERT_NE(behind, nullptr);
    EXPECT_EQ(behind->track.passes, 2);
    EXPECT_NEAR(behind->track.rut_depth_m, after2.rut_depth_m, 0.01 * after2.rut_depth_m);
}

// Passes are counted once per wheel and cell, not per step: along a straight 2 cm track every
// cell the four wheels crossed has two passes (front, then rear), whatever the cell size.
TEST(FieldRover, EachWheelCountsOnePassPerCell) {
    for (double cell : {0.02, 0.05}) {
        const StraightOnField run = driveStraight(12.0, cell);
        const double y = 0.5 * run.s.robot.track_m;
        const double x_rear = run.end.position_m[0] - 0.5 * run.s.robot.wheelbase_m;
        ASSERT_GT(x_rear, 0.5);
        // From the front wheels' start (x = L/2) to the rear wheels' contact at the end.
        for (double x = 0.5 * run.s.robot.wheelbase_m + 0.5 * cell; x < x_rear - 0.05; x += cell) {
            const field::CellState* c = cellAt(*run.terrain, x, y);
            ASSERT_NE(c, nullptr);
            EXPECT_EQ(c->track.passes, 2) << "cell " << cell << " x " << x;
            EXPECT_GT(c->max_slip, 0.0f);
            EXPECT_GT(c->energy_j, 0.0f);
            EXPECT_GT(c->max_stress_pa[0], 0.0f);
        }
        // Off the tracks nothing was touched.
        const field::CellState* between = cellAt(*run.terrain, x_rear - 0.1, 0.0);
        EXPECT_TRUE(between == nullptr || between->track.passes == 0);
    }
}

// F13: a passage is written to every cell under the wheel's width. On a straight run along the
// grid the wheels read the same cells as with the centre line alone (the run is the same bit for
// bit); across a track, the cells whose centres lie within b/2 of the wheel's centre line hold
// the centre cell's passes and rut, those beyond b/2 + h nothing; the energy and distance are
// shared, so their sums over the field are the centre-line run's and a cell's energy per metre is
// the passage's; σ_z at depth falls off across the width (at the nearest point of each cell).
TEST(FieldRover, APassageIsWrittenToEveryCellUnderTheWheelsWidth) {
    const double h = 0.02;
    const StraightOnField wide = driveStraight(10.0, h, true);
    const StraightOnField line = driveStraight(10.0, h, false);
    EXPECT_EQ(wide.end.position_m, line.end.position_m);
    for (int i = 0; i < kWheelCount; ++i) {
        EXPECT_EQ(wide.end.wheels[i].contact.sinkage_m, line.end.wheels[i].contact.sinkage_m);
    }
    const double b = wide.s.robot.wheel.width_m;
    const double y_track = 0.5 * wide.s.robot.track_m;
    const double x_rear = wide.end.position_m[0] - 0.5 * wide.s.robot.wheelbase_m;
    ASSERT_GT(x_rear, 0.5);
    int columns = 0;
    for (double x = 0.5 * wide.s.robot.wheelbase_m + 0.5 * h; x < x_rear - 0.05; x += h) {
        const field::CellState* centre = cellAt(*wide.terrain, x, y_track);
        ASSERT_NE(centre, nullptr);
        ASSERT_EQ(centre->track.passes, 2) << x;
        int across = 0;
        float last_sigma = centre->max_stress_pa[0];
        // Outwards from the centre line (on a cell edge), cell by cell, on the outer side.
        for (int k = 0; k < 6; ++k) {
            const double dy = (k + 0.5) * h;  // the cell centre's distance from the line
            const field::CellState* c = wide.terrain->cells().find(x, y_track + dy);
            if (dy < 0.5 * b - 0.25 * h) {
                ASSERT_NE(c, nullptr) << x << " " << dy;
                EXPECT_EQ(c->track.passes, 2) << x << " " << dy;
                EXPECT_FLOAT_EQ(c->track.rut_depth_m, centre->track.rut_depth_m);
                EXPECT_NEAR(c->energy_j / c->travel_m, centre->energy_j / centre->travel_m,
                            0.02 * centre->energy_j / centre->travel_m);
                EXPECT_LE(c->max_stress_pa[0], last_sigma * (1.0f + 1e-6f)) << x << " " << dy;
                last_sigma = c->max_stress_pa[0];
                ++across;
            } else if (dy > 0.5 * b + h) {
                EXPECT_TRUE(c == nullptr || c->track.passes == 0) << x << " " << dy;
            }
        }
        EXPECT_GE(across, 2);  // 0.107 m over 2 cm cells: 2 centres within b/2 − h/4 per side
        ++columns;
    }
    EXPECT_GE(columns, 10);
    // The centre-line run's cell under the line holds the same σ_z (both at the line).
    const double x_mid = 0.5 * (0.5 * wide.s.robot.wheelbase_m + x_rear);
    EXPECT_EQ(cellAt(*wide.terrain, x_mid, y_track)->max_stress_pa[0],
              cellAt(*line.terrain, x_mid, y_track)->max_stress_pa[0]);
    // The width's cells share the energy and the distance: the sums are the centre line's.
    auto sums = [](const FieldTerrain& t) {
        double energy = 0.0, travel = 0.0;
        long cells = 0;
        t.cells().forEachCell([&](field::CellKey, const field::CellState& c) {
            energy += c.energy_j, travel += c.travel_m;
            cells += c.track.passes > 0;
        });
        return std::array<double, 3>{energy, travel, static_cast<double>(cells)};
    };
    const std::array<double, 3> w = sums(*wide.terrain), l = sums(*line.terrain);
    EXPECT_NEAR(w[0], l[0], 1e-4 * std::abs(l[0]));
    EXPECT_NEAR(w[1], l[1], 1e-4 * l[1]);
    // Cells passed: about b/h times the centre line's (5.35 here; 2 cm cells hold 5 or 6 centres).
    EXPECT_GT(w[2], 4.5 * l[2]);
    EXPECT_LT(w[2], 6.5 * l[2]);
    EXPECT_EQ(wide.terrain->cellsTouched(), static_cast<long>(w[2]));
}

// F16: the peak of σ_z under a wheel's centre line, searched from the wheel's last passage's
// peak (a full scan every 16 passages), is the full scan's at every passage, within 10⁻⁵: on a
// run that turns (the front wheels at 8°) across a soil border into a softer soil (the loads and
// the footprints change) at a shallow and a deep depth. The stress at depth is an output only:
// the run's memory is the same bit for bit.
TEST(FieldRover, TheStressPeakFromTheLastPassageIsTheFullScans) {
    scenario::Scenario s = shipped("straight", 12.0);
    for (auto& w : s.wheels) w.spin_rate_rad_s = scenario::Signal::constant(1.5);
    for (int i = 0; i < 2; ++i)
        s.wheels[i].steer_angle_rad = scenario::Signal::constant(8.0 * M_PI / 180.0);
    soil::SoilParameters softer = s.terrain.base;
    softer.frictional_modulus *= 0.5;
    softer.cohesion_pa *= 0.5;
    auto run = [&](int full_scan_every) {
        FieldTerrainOptions options;
        options.cell_m = 0.02;
        options.stress_depths_m = {0.05, 0.3};
        options.full_scan_every = full_scan_every;
        auto terrain = std::make_unique<FieldTerrain>(borderField(s.terrain.base, softer, 0.8),
                                                      s.robot, options);
        Rover rover(s.robot, *terrain, s.options, s.initial, s.commandsAt(0.0));
        const long steps = std::lround(s.duration_s / s.time_step_s);
        for (long k = 0; k < steps; ++k) rover.step(s.time_step_s, s.commandsAt(0.0));
        terrain->finish();
        return terrain;
    };
    const auto warm = run(16), full = run(1);
    long cells = 0;
    full->cells().forEachCell([&](field::CellKey key, const field::CellState& c) {
        const field::CellState* w = warm->cells().find(key);
        ASSERT_NE(w, nullptr);
        EXPECT_EQ(w->track.passes, c.track.passes);
        EXPECT_EQ(w->track.rut_depth_m, c.track.rut_depth_m);
        for (std::size_t k = 0; k < 2; ++k) {
            EXPECT_NEAR(w->max_stress_pa[k], c.max_stress_pa[k], 1e-5f * c.max_stress_pa[k]) << k;
        }
        cells += c.track.passes > 0 && c.max_stress_pa[1] > 0.0f;
    });
    EXPECT_GT(cells, 700);  // 1.7 m driven, 4 wheels, 5–6 cells across each
    EXPECT_EQ(warm->cellsTouched(), full->cellsTouched());
    // The search did start from the last passage's peak: one passage in 16 (and each wheel's
    // first) scanned, per depth.
    EXPECT_GT(full->fullScans(), 200);
    EXPECT_LT(warm->fullScans(), full->fullScans() / 8);
}

// A field memory of cells h wide, with σ_z kept at `depths` (none: no stress at depth).
FieldTerrainOptions cellsOf(double h, std::vector<double> depths = {}) {
    FieldTerrainOptions options;
    options.cell_m = h;
    options.stress_depths_m = std::move(depths);
    return options;
}

// F13 off the grid: one wheel driven by hand along a line at 30° to the grid and around an arc
// of 0.5 m radius (less than half a turn) passes every cell of its band once — consecutive
// passages tile the band, also where the wheel leaves a cell sideways — and never meets its own
// pass; the cells passed are the band's area over h² (1.5 m × 0.107 m on 2 cm cells: ≈ 401),
// within 10 % (its two ends).
TEST(FieldRover, OneWheelOffTheGridPassesEachCellOfItsBandOnce) {
    const scenario::Scenario s = shipped("straight", 1.0);
    const FieldTerrainOptions options = cellsOf(0.02);
    const auto params = contact::makeContactParameters(s.terrain.base, s.robot.wheel);
    const double step = 1e-4, length = 1.5, radius = 0.5;
    for (const bool arc : {false, true}) {
        FieldTerrain t(uniformField(s.terrain.base), s.robot, options);
        const long steps = std::lround(length / step);
        int own = 0;
        for (long k = 0; k <= steps; ++k) {
            const double travelled = static_cast<double>(k) * step;
            double x = 0.31 + travelled * std::cos(M_PI / 6.0);
            double y = 0.17 + travelled * std::sin(M_PI / 6.0);
            double heading = M_PI / 6.0;
            if (arc) {
                const double angle = travelled / radius;
                x = radius * std::cos(angle), y = radius * std::sin(angle);
                heading = angle + 0.5 * M_PI;
            }
            // Nor across its width (F15): every band it samples is untouched.
            if (t.memoryUnder(0, x, y) != nullptr || !t.memoriesAcross(0).empty()) ++own;
            WheelImprint imprint;
            imprint.in_contact = true;
            imprint.depth_m = 0.01;
            imprint.power_w = 1.0;
            imprint.params = params;
            imprint.op = {0.2, 0.0, 0.3, 0.0, std::nullopt};
            imprint.axle = {-std::sin(heading), std::cos(heading)};
            t.imprint(0, imprint);
            t.advanced(1e-3);
        }
        t.finish();
        EXPECT_EQ(own, 0) << (arc ? "arc" : "line") << ": the wheel met its own pass";
        long passed = 0, twice = 0;
        t.cells().forEachCell([&](field::CellKey, const field::CellState& c) {
            passed += c.track.passes > 0;
            twice += c.track.passes > 1;
        });
        EXPECT_EQ(twice, 0) << (arc ? "arc" : "line");
        const double expected = length * s.robot.wheel.width_m / (0.02 * 0.02);
        EXPECT_NEAR(static_cast<double>(passed), expected, 0.1 * expected)
            << (arc ? "arc" : "line");
    }
}

// The wheel model on its own: drawbar pull F_x at slip s and load W (the quadratic model, as
// the run below), solved for its sinkage.
double pull(const scenario::Scenario& s, double load_n, double slip) {
    const auto params = contact::makeContactParameters(s.terrain.base, s.robot.wheel);
    compaction::PassConditions c;
    c.load_n = load_n;
    c.slip = slip;
    c.exit = {contact::ExitCondition::Kind::kAngle, 0.0};
    c.model = s.options.contact.model;
    const compaction::SolvedPass p = compaction::solvePass(params, {}, {}, c);
    EXPECT_TRUE(p.ok) << p.message;
    return p.forces.fx;
}

// F15 at the terrain. `drive` runs one wheel along a line (through (0.003 + x, y) at `angle` to
// the grid) on a fresh pass of `each` per evaluation, with a 1 cm imprint.
template <class Each>
void driveLine(FieldTerrain& t, const contact::ContactParameters<double>& params, int wheel,
               double y, double angle, double footprint_scale, Each&& each) {
    const double c = std::cos(angle), s = std::sin(angle);
    for (double u = 0.003; u < 1.0; u += 1e-3) {
        const double x = u * c, yy = y + u * s;
        const compaction::TrackMemory* centre = t.memoryUnder(wheel, x, yy);
        each(u, centre, t.memoriesAcross(wheel));
        WheelImprint imprint;
        imprint.in_contact = true;
        imprint.depth_m = 0.01;
        imprint.params = params;
        imprint.op = {0.2, 0.0, 0.3, 0.0, std::nullopt};
        imprint.axle = {-s, c};
        imprint.footprint_scale = footprint_scale;
        t.imprint(wheel, imprint);
        t.advanced(1e-3);
    }
    t.finish();
}

// A wheel driven beside a band another wheel wrote meets the band's memory over the share of its
// width that overlaps it. Wheel 0 runs along y = y₀ on 2 cm cells and writes the cells whose
// centres lie within b/2 of its line (F13); their extent across is the band, computed here from
// the cell centres. Wheel 1 runs along y = y₀ + d. The share of its width in the band is the
// overlap of [d − b/2, d + b/2] with the band over b, within the width one sample stands for
// (the outer ones: half a cell beyond the span, plus half a step of at most h/4).
TEST(FieldRover, AWheelBesideABandMeetsItOverTheShareOfItsWidthThatOverlapsIt) {
    const scenario::Scenario s = shipped("straight", 1.0);
    const FieldTerrainOptions options = cellsOf(0.02);
    const auto params = contact::makeContactParameters(s.terrain.base, s.robot.wheel);
    const double b = s.robot.wheel.width_m, h = 0.02;
    const double tolerance = (0.5 * h + 0.125 * h) / b;
    for (const double y0 : {0.0, 0.0037, 0.01}) {
        // The written band: the cells whose centres (k + ½) h lie within b/2 of y₀.
        double lo = 1e9, hi = -1e9;
        for (int k = -10; k < 10; ++k) {
            const double centre = (k + 0.5) * h;
            if (std::abs(centre - y0) <= 0.5 * b) {
                lo = std::min(lo, centre - 0.5 * h), hi = std::max(hi, centre + 0.5 * h);
            }
        }
        for (const double d : {0.0, 0.02, 0.04, 0.06, 0.08, 0.1, 0.12, 0.2}) {
            FieldTerrain t(uniformField(s.terrain.base), s.robot, options);
            ASSERT_EQ(t.bandSamples({0.0, 1.0}), 19);  // (b − h)/(h/4) = 17.4 gaps: 18, 19 points
            driveLine(t, params, 0, y0, 0.0, 1.0, [](auto...) {});
            const double y = y0 + d;
            const double overlap =
                std::max(0.0, std::min(y + 0.5 * b, hi) - std::max(y - 0.5 * b, lo)) / b;
            int checked = 0;
            driveLine(t, params, 1, y, 0.0, 1.0,
                      [&](double x, const compaction::TrackMemory* centre,
                          std::span<const BandShare> band) {
                          if (x < 0.2 || x > 0.8) return;  // away from the band's two ends
                          double share = 0.0;
                          if (band.empty()) {
                              share = centre != nullptr ? 1.0 : 0.0;
                          } else {
                              double total = 0.0;
                              for (const BandShare& part : band) {
                                  total += part.share;
                                  if (part.memory != nullptr) share += part.share;
                                  EXPECT_GT(part.share, 0.0);
                              }
                              EXPECT_NEAR(total, 1.0, 1e-12);
                          }
                          EXPECT_NEAR(share, overlap, tolerance)
                              << "y0 = " << y0 << ", d = " << d << ", x = " << x;
                          ++checked;
                      });
            EXPECT_GT(checked, 500) << d;
        }
    }
}

// A wheel in the exact track of the one before it meets that wheel's band across its whole width,
// wherever the track lies on the grid (a review found the outer points of the first sampling in
// unwritten cells at about half the offsets): lines along the grid and at 30° to it, at ten
// offsets within a cell, on 2 cm and 10 cm cells; never a band of parts, always the rut.
TEST(FieldRover, AWheelInTheExactTrackOfAnotherMeetsItsBandAcrossItsWidth) {
    const scenario::Scenario s = shipped("straight", 1.0);
    const auto params = contact::makeContactParameters(s.terrain.base, s.robot.wheel);
    for (const double h : {0.02, 0.1}) {
        const FieldTerrainOptions options = cellsOf(h);
        for (const double angle : {0.0, M_PI / 6.0}) {
            for (int k = 0; k < 10; ++k) {
                const double y0 = 0.1 * k * h + 1e-4;
                FieldTerrain t(uniformField(s.terrain.base), s.robot, options);
                driveLine(t, params, 0, y0, angle, 1.0, [](auto...) {});
                int parted = 0, untouched = 0, checked = 0;
                driveLine(t, params, 1, y0, angle, 1.0,
                          [&](double u, const compaction::TrackMemory* centre,
                              std::span<const BandShare> band) {
                              if (u < 0.2 || u > 0.8) return;
                              parted += !band.empty();
                              untouched += centre == nullptr;
                              ++checked;
                          });
                EXPECT_GT(checked, 500);
                EXPECT_EQ(parted, 0) << "h = " << h << ", angle " << angle << ", y0 = " << y0;
                // On cells about as wide as the wheel (b = 0.107 m, h = 0.1 m) F13 may leave the
                // contact point's own cell unwritten off the grid's axes (its centre more than
                // b/2 from the line), which the follower then meets untouched (F10): on 2 cm
                // cells never.
                if (h < 0.05) {
                    EXPECT_EQ(untouched, 0)
                        << "h = " << h << ", angle " << angle << ", y0 = " << y0;
                }
            }
        }
    }
}

// F15's footprint scale: σ_z at depth is linear in the footprint's loads (Boussinesq–Fröhlich,
// docs/compaction.md C1), so a passage imprinted with footprint_scale 2 leaves every cell of its
// band exactly twice the largest σ_z of the same passage at scale 1.
TEST(FieldRover, TheFootprintScaleScalesTheStressAtDepth) {
    const scenario::Scenario s = shipped("straight", 1.0);
    FieldTerrainOptions options = cellsOf(0.02, {0.2});
    options.concentration = 5.0;
    const auto params = contact::makeContactParameters(s.terrain.base, s.robot.wheel);
    FieldTerrain once(uniformField(s.terrain.base), s.robot, options);
    FieldTerrain twice(uniformField(s.terrain.base), s.robot, options);
    driveLine(once, params, 0, 0.0, 0.0, 1.0, [](auto...) {});
    driveLine(twice, params, 0, 0.0, 0.0, 2.0, [](auto...) {});
    int cells = 0;
    once.cells().forEachCell([&](field::CellKey key, const field::CellState& c) {
        if (c.track.passes == 0) return;  // a tile's cells beside the band
        const field::CellState* other = twice.cells().find(key);
        ASSERT_NE(other, nullptr);
        ASSERT_GT(c.max_stress_pa[0], 0.0f);
        EXPECT_NEAR(other->max_stress_pa[0], 2.0f * c.max_stress_pa[0], 1e-6f * c.max_stress_pa[0]);
        ++cells;
    });
    EXPECT_GT(cells, 200);
}

// F15 in the rover: crab steering (every wheel at δ) puts the rear wheels' tracks L sin δ beside
// the front wheels' (L = 0.5 m), from in the front rut (δ = 0) to clear of it (18.7°: 0.16 m,
// more than b + the band's cell). Between the two, a rear wheel meets the rut over the share of
// its width that overlaps it: its sinkage below the untouched surface falls and its resistance
// torque grows steadily with the offset, strictly between the two limits (read across the width
// off, the contact point's cell decides for the whole width: at 3.07° the wheel is still all in
// the rut, and the torque is not monotone). The limits themselves are the same runs bit for bit.
TEST(FieldRover, ARearWheelOnTheFrontRutsEdgeSinksBetweenInTheRutAndBesideIt) {
    auto run = [](double steer_deg, bool across) {
        const nlohmann::json j = {
            {"robot", "default"},
            {"duration_s", 12},
            {"time_step_s", 0.001},
            {"output_interval_s", 0.01},
            {"model", "quadratic"},
            {"initial", {{"x_m", 0.01}, {"y_m", 0.0137}}},
            {"terrain", "sandy-loam"},
            {"wheels", {{"all", {{"omega_rad_s", 2.0}, {"steer_deg", steer_deg}}}}}};
        Result<scenario::Scenario> s = scenario::scenarioFromJson(j, "crab", kLocations);
        EXPECT_TRUE(s.ok()) << s.message();
        scenario::Scenario sc = s.value();
        sc.field = uniformField(sc.terrain.base);
        sc.field_options.cell_m = 0.02;
        sc.field_options.stress_depths_m.clear();
        sc.field_options.read_across_width = across;
        return scenario::runScenario(sc);
    };
    // The rear-left wheel's mean sinkage [mm] and resistance torque [N·m] once it runs in (or
    // beside) the front-left wheel's track (t ≥ 7 s: the robot has moved more than 0.5 m).
    auto rear = [](const scenario::RunResult& r) {
        const std::size_t t = r.series.column("t_s"), h = r.series.column("RL_sinkage_m"),
                          my = r.series.column("RL_My_Nm");
        double sum_h = 0.0, sum_my = 0.0;
        int n = 0;
        for (const auto& row : r.series.rows) {
            if (row[t] < 7.0) continue;
            sum_h += row[h], sum_my += row[my], ++n;
        }
        return std::array<double, 2>{1e3 * sum_h / n, sum_my / n};
    };
    const double angles[] = {0.0, 3.07, 6.15, 9.26, 18.7};
    std::vector<std::array<double, 2>> band, centre;
    std::vector<scenario::RunResult> ends;
    for (const double steer : angles) {
        const scenario::RunResult a = run(steer, true), b = run(steer, false);
        band.push_back(rear(a));
        centre.push_back(rear(b));
        if (steer == angles[0] || steer == angles[4]) {
            SCOPED_TRACE(steer);
            expectSameSeries(a, b, false);
        }
    }
    const double in_rut = band.front()[0], beside = band.back()[0];
    ASSERT_GT(in_rut - beside, 0.5);  // mm: the rut lowers the rear wheel (measured 5.20 − 4.16)
    for (std::size_t k = 1; k < band.size(); ++k) {
        SCOPED_TRACE(angles[k]);
        EXPECT_LT(band[k][0], band[k - 1][0] - 0.1 * (in_rut - beside) / 4);
        EXPECT_GT(band[k][1], band[k - 1][1]);
        if (k + 1 < band.size()) {
            EXPECT_GT(band[k][0], beside + 0.1 * (in_rut - beside));
            EXPECT_LT(band[k][0], in_rut - 0.1 * (in_rut - beside));
        }
    }
    // The contact point's cell alone: at 3.07° (0.027 m beside, the contact point still in the
    // band) the wheel sinks as in the rut, within 2 % of the gap.
    EXPECT_NEAR(centre[1][0], in_rut, 0.02 * (in_rut - beside));
}

// On a uniform slope α uphill the four wheels carry m g cos α along the normal and pull
// m g sin α along the slope; the robot's steady slip is where the wheel model, at the loads the
// run found, pulls that much (an independent bisection on the model).
TEST(FieldRover, SteadySlipUpASlopeIsWhereThePullCarriesTheSlope) {
    scenario::Scenario s = shipped("straight", 25.0);
    const double alpha = 4.0 * M_PI / 180.0;
    s.field = slopedField(s.terrain.base, alpha);
    s.field_options.repeated_passes = false;
    const scenario::RunResult r = scenario::runScenario(s);
    ASSERT_EQ(r.status, scenario::RunResult::Status::kCompleted) << r.message;
    const double weight = s.robot.totalMass() * s.options.gravity_m_s2;
    double normal = 0.0;
    std::array<double, kWheelCount> loads{};
    for (int i = 0; i < kWheelCount; ++i) {
        loads[i] = last(r, std::string(kCornerNames[i]) + "_load_N");
        normal += loads[i];
    }
    EXPECT_NEAR(normal, weight * std::cos(alpha), 2e-3 * weight);
    // The pitch follows the slope, and the robot climbed: z rose by x tan α.
    // The pitch follows the slope, to the rear wheels' deeper sinkage under the load moved to them
    // (≈ 1 mm over the 0.5 m wheelbase).
    EXPECT_NEAR(last(r, "pitch_deg"), -4.0, 0.15);
    EXPECT_NEAR(r.summary.potential_change_j / (weight * r.summary.x_m), std::tan(alpha), 2e-3);

    // Bisection: Σ F_x(s, W_i) = m g sin α.
    auto excess = [&](double slip) {
        double sum = 0.0;
        for (double w : loads) sum += pull(s, w, slip);
        return sum - weight * std::sin(alpha);
    };
    double lo = 0.0, hi = 0.95;
    ASSERT_LT(excess(lo), 0.0);
    ASSERT_GT(excess(hi), 0.0);
    for (int k = 0; k < 40; ++k) {
        const double mid = 0.5 * (lo + hi);
        (excess(mid) > 0.0 ? hi : lo) = mid;
    }
    const double slip = 0.5 * (lo + hi);
    for (const char* w : kCornerNames) EXPECT_NEAR(last(r, std::string(w) + "_slip"), slip, 3e-3);
    // The mean wheel of the issue (m g sin α / 4 at m g cos α / 4) is near too: the load moves
    // to the rear axle on the slope, the pulls about balance.
    const double quarter = 0.25 * weight;
    double mlo = 0.0, mhi = 0.95;
    for (int k = 0; k < 40; ++k) {
        const double mid = 0.5 * (mlo + mhi);
        (pull(s, quarter * std::cos(alpha), mid) > quarter * std::sin(alpha) ? mhi : mlo) = mid;
    }
    EXPECT_NEAR(last(r, "FL_slip"), 0.5 * (mlo + mhi), 0.01);
}

// A slope steeper than the soil can carry: the largest pull of the wheel model (over slip, at
// the robot's load along the normal) is below m g sin α; the robot stalls, its wheels spin.
TEST(FieldRover, ASlopeSteeperThanTheSoilCarriesStallsTheRobot) {
    scenario::Scenario s = shipped("straight", 12.0);
    const double weight = s.robot.totalMass() * s.options.gravity_m_s2;
    // The steepest slope the model carries: tan α* = max_s F_x(s, W cos α*) / (W cos α*) per
    // wheel, found by fixed point (the pull's ratio barely depends on the load).
    double alpha_max = 0.0;
    for (int it = 0; it < 5; ++it) {
        const double w = 0.25 * weight * std::cos(alpha_max);
        double best = 0.0;
        for (double slip = 0.05; slip <= 0.951; slip += 0.05)
            best = std::max(best, pull(s, w, slip));
        alpha_max = std::atan(best / w);
    }
    ASSERT_GT(alpha_max, 0.02);
    for (const double factor : {0.6, 1.4}) {
        scenario::Scenario on = s;
        on.field = slopedField(s.terrain.base, factor * alpha_max);
        on.field_options.repeated_passes = false;
        const scenario::RunResult r = scenario::runScenario(on);
        SCOPED_TRACE(factor);
        ASSERT_NE(r.status, scenario::RunResult::Status::kDiverged) << r.message;
        const double commanded = s.robot.wheel.radius_m * 0.4 * on.duration_s;
        if (factor < 1.0) {
            EXPECT_GT(r.summary.x_m, 0.2 * commanded);
        } else {
            // Stalled or sliding back, the wheels spinning on the spot.
            EXPECT_LT(r.summary.x_m, 0.05 * commanded);
            EXPECT_GT(last(r, "FL_slip"), 0.9);
        }
    }
}

// The shipped field scenario, twice: the same maps bit for bit (and the same series).
TEST(FieldRover, FieldRunsRepeatBitForBit) {
    const scenario::Scenario s = shipped("field-slope-wet", 8.0);
    ASSERT_TRUE(s.field);
    const scenario::RunResult a = scenario::runScenario(s);
    const scenario::RunResult b = scenario::runScenario(s);
    ASSERT_EQ(a.status, scenario::RunResult::Status::kCompleted) << a.message;
    ASSERT_TRUE(a.maps && b.maps);
    expectSameSeries(a, b, false);
    for (const auto& [x, y] : {std::pair{&a.maps->rut_depth_m, &b.maps->rut_depth_m},
                               std::pair{&a.maps->passes, &b.maps->passes},
                               std::pair{&a.maps->compaction_risk, &b.maps->compaction_risk},
                               std::pair{&a.maps->slip, &b.maps->slip},
                               std::pair{&a.maps->energy_per_m_j, &b.maps->energy_per_m_j}}) {
        ASSERT_EQ(x->values.size(), y->values.size());
        EXPECT_EQ(
            std::memcmp(x->values.data(), y->values.data(), x->values.size() * sizeof(double)), 0);
    }
    EXPECT_EQ(*a.summary.cells_touched, *b.summary.cells_touched);
    // The maps span the field's extent on the memory's 0.1 m cells.
    EXPECT_EQ(a.maps->passes.cols, 600);
    EXPECT_EQ(a.maps->passes.rows, 400);
    EXPECT_DOUBLE_EQ(a.maps->passes.cell_m, 0.1);
    EXPECT_GT(a.maps->rut_depth_m.valueRange().second, 0.0);
}

// The two forms of a field terrain read the same maps: {"field": FILE} and the scenario's own
// "height", "soils", "legend"; giving both is an error naming the keys.
TEST(FieldRover, ScenarioReadsAFieldFileOrItsOwnRasters) {
    const std::string fields = std::string(TERRA_RESOURCE_DIR) + "/fields/sloped-wet/";
    auto scenarioWith = [](const nlohmann::json& terrain) {
        return nlohmann::json{{"name", "t"},
                              {"robot", "default"},
                              {"duration_s", 1},
                              {"time_step_s", 0.001},
                              {"initial", {{"x_m", 10}, {"y_m", 10}}},
                              {"terrain", terrain},
                              {"wheels", {{"all", {{"omega_rad_s", 0.4}}}}}};
    };
    const Result<scenario::Scenario> by_file = scenario::scenarioFromJson(
        scenarioWith({{"field", fields + "field.json"}}), "by-file", kLocations);
    ASSERT_TRUE(by_file.ok()) << by_file.message();
    const Result<scenario::Scenario> inline_maps = scenario::scenarioFromJson(
        scenarioWith(
            {{"height", fields + "height.asc"},
             {"soils", fields + "soil-classes.asc"},
             {"legend", {{"1", "sandy-loam"}, {"2", "lean-clay-wet"}, {"3", "sandy-loam"}}},
             {"cell_m", 0.05},
             {"repeated_passes", false},
             {"read_across_width", false}}),
        "inline", kLocations);
    ASSERT_TRUE(inline_maps.ok()) << inline_maps.message();
    for (const scenario::Scenario* s : {&by_file.value(), &inline_maps.value()}) {
        ASSERT_TRUE(s->field);
        EXPECT_EQ(s->soilCount(), 4);  // the base soil, then classes 1, 2, 3
        EXPECT_EQ(s->soil(2).name, s->field->legend.at(2).name);
        EXPECT_EQ(s->field->height->values, by_file.value().field->height->values);
    }
    EXPECT_EQ(inline_maps.value().field_options.cell_m, 0.05);
    EXPECT_FALSE(inline_maps.value().field_options.repeated_passes);
    EXPECT_FALSE(inline_maps.value().field_options.read_across_width);
    EXPECT_TRUE(by_file.value().field_options.read_across_width);
    // Without "soil" the base soil is the lowest class's.
    EXPECT_EQ(inline_maps.value().terrain.base.name, inline_maps.value().soil(1).name);

    const Result<scenario::Scenario> both = scenario::scenarioFromJson(
        scenarioWith({{"field", fields + "field.json"}, {"height", fields + "height.asc"}}), "both",
        kLocations);
    ASSERT_FALSE(both.ok());
    EXPECT_NE(both.message().find("terrain.height"), std::string::npos) << both.message();
    const Result<scenario::Scenario> bad_cell = scenario::scenarioFromJson(
        scenarioWith({{"field", fields + "field.json"}, {"cell_m", 0}}), "bad", kLocations);
    ASSERT_FALSE(bad_cell.ok());
    EXPECT_NE(bad_cell.message().find("terrain.cell_m"), std::string::npos) << bad_cell.message();
}

// F14: a parameter raster is the soil it gives. The soil-border scenario with its patch given
// by parameter rasters over a uniform class (each soil value where the patch differs from the
// base, no data elsewhere) drives bit for bit as the patch terrain, the oracle controller
// included (it plans on the soil of each index), and only the soil's index differs.
TEST(FieldRover, ParameterRastersAreTheSoilTheyGive) {
    scenario::Scenario patch = shipped("traction-border", 40.0);
    patch.streaming.reset();
    patch.controller.type = scenario::ControllerType::kOracle;
    ASSERT_EQ(patch.terrain.patches.size(), 1u);
    const soil::SoilParameters& base = patch.terrain.base;
    const soil::SoilParameters& other = patch.terrain.patches[0].soil;
    const double x_border = patch.terrain.patches[0].x_min_m;
    auto map = std::make_shared<field::FieldMap>();
    map->base = base;
    for (const soil::SoilField& f : soil::soilFields()) {
        const double v = soil::userValue(other, f);
        if (v == soil::userValue(base, f) || !std::isfinite(v)) continue;
        field::ParameterRaster p{&f, field::makeRaster(60, 20, x_border - 10.0, -5.0, 0.5)};
        for (int row = 0; row < p.raster.rows; ++row)
            for (int col = 0; col < p.raster.cols; ++col)
                p.raster.value(col, row) =
                    p.raster.centreX(col) < x_border ? std::numeric_limits<double>::quiet_NaN() : v;
        map->parameters.push_back(std::move(p));
    }
    ASSERT_GE(map->parameters.size(), 3u);  // clayey soil differs from sandy loam in most values
    scenario::Scenario field = patch;
    field.field = map;
    field.field_options.repeated_passes = false;
    // A planner of the soil's values (not its name, which the rasters keep as the base's).
    scenario::RunOptions options;
    options.slip_planner = [](const scenario::SlipPlanRequest& request) {
        return std::optional<scenario::SlipPlan>(
            scenario::SlipPlan{0.3 + 0.1 * std::tan(request.soil.friction_angle_rad) +
                                   0.05 * request.soil.sinkage_exponent,
                               std::nullopt});
    };
    const scenario::RunResult a = scenario::runScenario(patch, options);
    const scenario::RunResult b = scenario::runScenario(field, options);
    ASSERT_EQ(a.status, scenario::RunResult::Status::kCompleted) << a.message;
    // The front wheels crossed the border (the rear ones stay on the base soil: 0.7 m in 40 s).
    ASSERT_GT(a.summary.x_m + 0.5 * patch.robot.wheelbase_m, x_border + 0.1);
    expectSameSeries(a, b, true);
    EXPECT_EQ(last(a, "FL_soil"), 1.0);
    EXPECT_EQ(last(b, "FL_soil"), 1.0);  // base 0, then the one soil the rasters make
    EXPECT_EQ(last(b, "RL_soil"), 0.0);
}

// F14: the rover's soil at a point is the map's (FieldMap::soilAt, read on its own) wherever the
// class raster and two parameter rasters of other cells and offsets overlap, and it has as many
// soils as a fine scan of the map finds distinct (class and values); too many distinct soils are
// refused by name.
TEST(FieldRover, TheRoversSoilsAreTheMapsEverywhere) {
    const soil::SoilParameters sandy = io::resolveSoil(kLocations, "sandy-loam").value();
    const soil::SoilParameters clay = io::resolveSoil(kLocations, "clayey-soil").value();
    auto map = std::make_shared<field::FieldMap>();
    map->base = sandy;
    map->legend[1] = sandy;
    map->legend[2] = clay;
    map->soil_class = field::makeRaster(4, 4, 0.0, 0.0, 1.0);
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) map->soil_class->value(col, row) = col < 2 ? 1 : 2;
    field::ParameterRaster phi{soil::findSoilField("phi_deg"),
                               field::makeRaster(5, 3, 0.25, 0.5, 0.7)};
    field::ParameterRaster c{soil::findSoilField("c_kPa"), field::makeRaster(3, 6, -0.4, 0.3, 0.6)};
    for (int row = 0; row < phi.raster.rows; ++row)
        for (int col = 0; col < phi.raster.cols; ++col)
            phi.raster.value(col, row) =
                (col + row) % 3 == 0 ? std::numeric_limits<double>::quiet_NaN() : 20.0 + col;
    for (int row = 0; row < c.raster.rows; ++row)
        for (int col = 0; col < c.raster.cols; ++col)
            c.raster.value(col, row) = 1.0 + 0.5 * (row % 2);
    map->parameters = {phi, c};
    const FieldTerrain terrain(map, RobotParameters{});
    std::set<std::vector<double>> seen;
    int points = 0;
    for (double y = -1.0; y < 5.0; y += 0.013) {
        for (double x = -1.0; x < 5.0; x += 0.017) {
            const soil::SoilParameters want = map->soilAt(x, y);
            const soil::SoilParameters& got = terrain.soil(terrain.soilIndexAt(x, y));
            // A soil is its class (the base soil and class 1 are both sandy loam) and its values.
            std::vector<double> values{static_cast<double>(map->classAt(x, y).value_or(-1))};
            for (const soil::SoilField& f : soil::soilFields()) {
                ASSERT_EQ(soil::userValue(got, f), soil::userValue(want, f))
                    << f.key << " at (" << x << ", " << y << ")";
                values.push_back(soil::userValue(want, f));
            }
            seen.insert(values);
            ++points;
        }
    }
    ASSERT_GT(points, 100000);
    EXPECT_EQ(static_cast<std::size_t>(terrain.soilCount()), seen.size());

    // On the cells' edges too, where floating rounding decides: rasters at projected coordinates
    // whose edges coincide in exact arithmetic (0.3 m and 0.1 m cells offset by whole cells),
    // probed on every computed edge and one double either side.
    auto utm = std::make_shared<field::FieldMap>();
    utm->base = sandy;
    field::ParameterRaster a{soil::findSoilField("phi_deg"),
                             field::makeRaster(12, 8, 500123.37, 5200456.11, 0.3)};
    field::ParameterRaster b{soil::findSoilField("c_kPa"),
                             field::makeRaster(30, 20, 500123.37 + 0.9, 5200456.11 + 0.6, 0.1)};
    for (std::size_t i = 0; i < a.raster.values.size(); ++i)
        a.raster.values[i] = 20.0 + 0.01 * static_cast<double>(i);
    for (std::size_t i = 0; i < b.raster.values.size(); ++i)
        b.raster.values[i] = 1.0 + 0.001 * static_cast<double>(i);
    utm->parameters = {a, b};
    const FieldTerrain on_edges(utm, RobotParameters{});
    std::vector<double> xs, ys;
    for (const field::ParameterRaster* r : {&a, &b}) {
        for (int k = 0; k <= r->raster.cols; ++k)
            xs.push_back(r->raster.x_min_m + k * r->raster.cell_m);
        for (int k = 0; k <= r->raster.rows; ++k)
            ys.push_back(r->raster.y_min_m + k * r->raster.cell_m);
        for (int k = 0; k <= r->raster.rows; ++k)
            ys.push_back(r->raster.yMax() - k * r->raster.cell_m);
    }
    int probes = 0;
    for (double x0 : xs) {
        for (double y0 : ys) {
            for (double x : {std::nextafter(x0, -HUGE_VAL), x0, std::nextafter(x0, HUGE_VAL)}) {
                for (double y : {std::nextafter(y0, -HUGE_VAL), y0, std::nextafter(y0, HUGE_VAL)}) {
                    const soil::SoilParameters want = utm->soilAt(x, y);
                    const soil::SoilParameters& got = on_edges.soil(on_edges.soilIndexAt(x, y));
                    ASSERT_EQ(got.friction_angle_rad, want.friction_angle_rad) << x << ", " << y;
                    ASSERT_EQ(got.cohesion_pa, want.cohesion_pa) << x << ", " << y;
                    ++probes;
                }
            }
        }
    }
    EXPECT_GT(probes, 20000);

    // Over 64 soils the explicit step's bound is taken at the corners of the rasters' box: with
    // k_phi and n varying over 100 cells each, it is no larger than the least of the soils' own
    // bounds (each soil on its own, a second computation).
    auto stiff = std::make_shared<field::FieldMap>();
    stiff->base = sandy;
    field::ParameterRaster kphi{soil::findSoilField("kphi"), field::makeRaster(10, 10, 0, 0, 1.0)};
    field::ParameterRaster n{soil::findSoilField("n"), field::makeRaster(10, 10, 0, 0, 1.0)};
    for (std::size_t i = 0; i < 100; ++i) {
        kphi.raster.values[i] = 500.0 + 40.0 * static_cast<double>((i * 37) % 100);
        n.raster.values[i] = 0.6 + 0.004 * static_cast<double>((i * 53) % 100);
    }
    stiff->parameters = {kphi, n};
    const FieldTerrain varied(stiff, RobotParameters{});
    ASSERT_GT(varied.soilCount(), 64);
    EXPECT_EQ(varied.stepLimitSoils().size(), 1u + 4u);  // the base soil and its 4 corners
    const RoverOptions options;
    double least = HUGE_VAL;
    for (int i = 0; i < varied.soilCount(); ++i) {
        Terrain one;
        one.base = varied.soil(i);
        least = std::min(least, largestStableStep(RobotParameters{}, one, options).max_step_s);
    }
    ASSERT_TRUE(std::isfinite(least));
    EXPECT_LE(largestStableStep(RobotParameters{}, varied, options).max_step_s,
              least * (1 + 1e-12));

    // A long east–west strip crossing a long north–south one: 10¹⁰ pieces, refused by name
    // before any is walked.
    auto strips = std::make_shared<field::FieldMap>();
    strips->base = sandy;
    field::ParameterRaster east{soil::findSoilField("c_kPa"),
                                field::makeRaster(100000, 1, 0, 0, 0.01)};
    field::ParameterRaster north{soil::findSoilField("phi_deg"),
                                 field::makeRaster(1, 100000, 0, 0, 0.01)};
    std::fill(east.raster.values.begin(), east.raster.values.end(), 1.0);
    std::fill(north.raster.values.begin(), north.raster.values.end(), 30.0);
    strips->parameters = {east, north};
    EXPECT_NE(messageOf([&] { FieldTerrain refused(strips, RobotParameters{}); }).find("pieces"),
              std::string::npos);

    // 300 × 300 distinct cohesions: more soils than the rover takes.
    auto wide = std::make_shared<field::FieldMap>();
    wide->base = sandy;
    field::ParameterRaster many{soil::findSoilField("c_kPa"),
                                field::makeRaster(300, 300, 0, 0, 0.1)};
    for (std::size_t i = 0; i < many.raster.values.size(); ++i)
        many.raster.values[i] = 0.5 + 1e-5 * static_cast<double>(i);
    wide->parameters.push_back(std::move(many));
    try {
        const FieldTerrain refused(wide, RobotParameters{});
        ADD_FAILURE() << "90000 soils were taken";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("65536"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("parameter rasters"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace terra::dynamics
