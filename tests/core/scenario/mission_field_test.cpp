// Missions and the maps of a field run (docs/field.md, "Missions" and "Maps of a drive"): the
// shipped controlled-traffic mission leaves the beds untouched; lanes give one pass per wheel
// across each lane and none between them; the slip and energy-per-metre maps (F11–F12) against
// the wheels' own slip and power over speed in the time series; mission runs repeat bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/io/parameters_json.h"
#include "core/scenario/mission.h"
#include "core/scenario/runner.h"
#include "core/scenario/scenario_json.h"
#include "tests/core/test_support.h"

namespace terra::scenario {
namespace {

using terra::testing::kLocations;

Scenario shipped(const std::string& name) {
    Result<Scenario> s = resolveScenario(kLocations, name);
    EXPECT_TRUE(s.ok()) << s.message();
    return s.value();
}

// A flat field of one soil everywhere (no rasters).
std::shared_ptr<const field::FieldMap> uniformField(const soil::SoilParameters& soil) {
    auto map = std::make_shared<field::FieldMap>();
    map->base = soil;
    return map;
}

// The value of a map at (x, y), or NaN outside it.
double at(const field::Raster& r, double x, double y) {
    const std::optional<field::CellIndex> c = r.cellAt(x, y);
    return c ? r.value(c->col, c->row) : std::nan("");
}

TEST(MissionField, ControlledTrafficMissionLeavesTheBedsUntouched) {
    const Scenario s = shipped("mission-controlled-traffic");
    ASSERT_TRUE(s.field && s.mission);
    const RunResult r = runScenario(s);
    ASSERT_EQ(r.status, RunResult::Status::kCompleted) << r.message;
    ASSERT_TRUE(r.summary.mission && r.maps);
    EXPECT_TRUE(r.summary.mission->completed);
    const field::Raster& passes = r.maps->passes;
    long lane_cells = 0, bed_cells = 0;
    std::array<long, 2> per_lane{};
    for (int row = 0; row < passes.rows; ++row) {
        for (int col = 0; col < passes.cols; ++col) {
            if (passes.value(col, row) == 0.0) continue;
            const double x = passes.centreX(col), y = passes.centreY(row);
            // The field's own class map (2: traffic lane), not y mod 3.
            if (s.field->classAt(x, y) == 2) {
                ++lane_cells;
                if (y < 3.0) ++per_lane[0];
                if (y > 3.0) ++per_lane[1];
            } else {
                ++bed_cells;
                ADD_FAILURE() << "a bed cell at (" << x << ", " << y << ") was passed "
                              << passes.value(col, row) << " times";
            }
        }
    }
    EXPECT_EQ(bed_cells, 0);
    // 14 m of both lanes in the field (x 26 to 40), two wheel tracks each, 0.1 m cells.
    EXPECT_GT(per_lane[0], 2 * 130);
    EXPECT_GT(per_lane[1], 2 * 130);
    EXPECT_LT(r.summary.mission->error_max_m, 0.1);  // the lanes' margin for a 0.4 m track
    // The slip and energy maps have data exactly where wheels passed.
    for (std::size_t k = 0; k < passes.values.size(); ++k) {
        EXPECT_EQ(passes.values[k] > 0.0, std::isfinite(r.maps->slip.values[k])) << k;
        EXPECT_EQ(passes.values[k] > 0.0, std::isfinite(r.maps->energy_per_m_j.values[k])) << k;
    }
}

// Three lanes 1.6 m apart on a uniform field: across the middle of each lane the four wheels
// pass once each (F10: one passage per wheel and cell) over the cells under their width (F13: a
// 0.107 m wheel covers the centres of 2 or 3 cells of 5 cm), in two tracks a track width apart;
// no wheel passes between the lanes. Repeated, the run's maps are the same bit for bit.
TEST(MissionField, LanesGiveOnePassPerWheelAcrossEachLane) {
    Scenario s = shipped("straight");
    s.field = uniformField(s.terrain.base);
    s.field_options.cell_m = 0.05;
    s.options.contact.model = contact::ContactModel::kQuadratic;
    s.duration_s = 60.0;
    MissionSpec m;
    m.lanes = LanesSpec{};
    m.lanes->length_m = 4.0;
    m.lanes->spacing_m = 1.6;
    m.lanes->count = 3;
    m.lanes->turn_radius_m = 0.8;
    m.speed_m_s = 0.8;
    m.lookahead_m = 0.6;
    s.mission = m;
    const RunResult r = runScenario(s);
    ASSERT_EQ(r.status, RunResult::Status::kCompleted) << r.message;
    ASSERT_TRUE(r.summary.mission->completed);
    const field::Raster& passes = r.maps->passes;
    const std::optional<field::CellIndex> mid = passes.cellAt(2.0, 0.0);
    ASSERT_TRUE(mid);
    std::array<double, 3> in_lane{};
    double between = 0.0;
    const double half_width = 0.5 * s.robot.wheel.width_m, h = passes.cell_m;
    for (int row = 0; row < passes.rows; ++row) {
        const double y = passes.centreY(row), n = passes.value(mid->col, row);
        const int lane = static_cast<int>(std::lround(y / 1.6));
        if (lane >= 0 && lane < 3 && std::abs(y - 1.6 * lane) < 0.4) {
            in_lane[lane] += n;
            // The tracks lie half the 0.4 m track beside the lane's line, a wheel's width wide;
            // a cell is passed by the front and the rear wheel of its side, or by one of them
            // where the two tracks' edges differ.
            if (n > 0.0) {
                EXPECT_NEAR(std::abs(y - 1.6 * lane), 0.2, half_width + 0.5 * h) << "lane " << lane;
                EXPECT_TRUE(n == 1.0 || n == 2.0) << "lane " << lane << " y " << y << ": " << n;
            }
        } else {
            between += n;
        }
    }
    // Each of the four wheels covers 2 or 3 cell centres across its 0.107 m on 5 cm cells.
    ASSERT_NEAR(s.robot.wheel.width_m, 0.107, 1e-9);
    for (int lane = 0; lane < 3; ++lane) {
        EXPECT_GE(in_lane[lane], 4 * 2.0) << "lane " << lane;
        EXPECT_LE(in_lane[lane], 4 * 3.0) << "lane " << lane;
    }
    EXPECT_EQ(between, 0.0);

    const RunResult again = runScenario(s);
    ASSERT_TRUE(again.maps);
    for (const auto& [a, b] : {std::pair{&r.maps->passes, &again.maps->passes},
                               std::pair{&r.maps->slip, &again.maps->slip},
                               std::pair{&r.maps->energy_per_m_j, &again.maps->energy_per_m_j},
                               std::pair{&r.maps->rut_depth_m, &again.maps->rut_depth_m}}) {
        ASSERT_EQ(a->values.size(), b->values.size());
        EXPECT_EQ(
            std::memcmp(a->values.data(), b->values.data(), a->values.size() * sizeof(double)), 0);
    }
    ASSERT_EQ(r.series.rows.size(), again.series.rows.size());
    EXPECT_EQ(r.series.rows.back(), again.series.rows.back());
    EXPECT_EQ(r.summary.mission->error_rms_m, again.summary.mission->error_rms_m);
}

// F11–F12 on a straight steady run: a cell of the left wheels' track holds the larger |s| of the
// front and rear wheel, and E/d = the mean over the two wheels of the power they lose into the
// soil over their speed, (M_y ω − F_x v_x) / v_x (the soil's power on a wheel rolling straight,
// no side force, no vertical motion), read from the time series when each crossed the cell.
TEST(MissionField, SlipAndEnergyMapsAreTheWheelsOwn) {
    Scenario s = shipped("straight");
    for (auto& w : s.wheels) w.spin_rate_rad_s = Signal::constant(3.0);
    s.field = uniformField(s.terrain.base);
    s.field_options.cell_m = 0.03;  // the track at y = 0.2 m lies inside a cell, not on an edge
    s.options.contact.model = contact::ContactModel::kQuadratic;
    s.duration_s = 8.0;
    const RunResult r = runScenario(s);
    ASSERT_EQ(r.status, RunResult::Status::kCompleted) << r.message;
    ASSERT_TRUE(r.maps);
    const double x_cell = 0.6 * r.summary.x_m;  // passed by both left wheels at a steady speed
    const double track_y = 0.5 * s.robot.track_m;
    const std::vector<double> t = r.series.values("t_s"), x = r.series.values("x_m");
    // The row at which wheel `w`'s hub (x ± wheelbase/2 from the centre) is over the cell.
    auto crossing = [&](int w) {
        const double offset = (w < 2 ? 0.5 : -0.5) * s.robot.wheelbase_m;
        std::size_t k = 0;
        while (k + 1 < x.size() && x[k] + offset < x_cell) ++k;
        return k;
    };
    double expected_slip = 0.0, expected_e = 0.0;
    for (int w : {dynamics::kFrontLeft, dynamics::kRearLeft}) {
        const std::size_t k = crossing(w);
        const std::vector<double>& row = r.series.rows[k];
        const std::string p = std::string(dynamics::kCornerNames[w]) + "_";
        auto v = [&](const std::string& c) { return row[r.series.column(p + c)]; };
        expected_slip = std::max(expected_slip, std::abs(v("slip")));
        const double power = v("My_Nm") * v("omega_rad_s") - v("Fx_N") * v("vx_m_s");
        expected_e += 0.5 * power / v("vx_m_s");
        EXPECT_GT(t[k], 2.0);  // steady by then
    }
    const double slip = at(r.maps->slip, x_cell, track_y);
    const double energy = at(r.maps->energy_per_m_j, x_cell, track_y);
    EXPECT_EQ(at(r.maps->passes, x_cell, track_y), 2.0);
    EXPECT_NEAR(slip, expected_slip, 2e-3);
    EXPECT_NEAR(energy, expected_e, 0.02 * expected_e);
    EXPECT_GT(energy, 0.0);
    // No data beside the tracks.
    EXPECT_TRUE(std::isnan(at(r.maps->slip, x_cell, 0.0)));
    EXPECT_TRUE(std::isnan(at(r.maps->energy_per_m_j, x_cell, 0.0)));
}

// M9 on an 8 % cross slope (a plane rising along x; the path runs along +y, on the contour): the
// robot crabs downhill at β. Steered by its heading it settles where the goal point lies straight
// ahead of the heading, L_d tan β beside the path (within 30 % of that, from the run's own β);
// steered by its course it stays on the path (its offset below a quarter of the heading's).
TEST(MissionField, OnACrossSlopeTheCourseKeepsThePath) {
    auto map = std::make_shared<field::FieldMap>();
    Scenario s = shipped("straight");
    map->base = s.terrain.base;
    map->height = field::makeRaster(40, 40, -20.0, -10.0, 1.0);
    for (int row = 0; row < 40; ++row)
        for (int col = 0; col < 40; ++col)
            map->height->value(col, row) = 0.08 * map->height->centreX(col);
    s.field = map;
    s.options.contact.model = contact::ContactModel::kQuadratic;
    s.initial.yaw_rad = 0.5 * M_PI;
    s.duration_s = 60.0;
    MissionSpec m;
    m.waypoints = {{0.0, 0.0}, {0.0, 7.0}};
    m.speed_m_s = 0.6;
    m.lookahead_m = 1.0;
    // The largest |e| and the mean crab angle over the path's last 3 m.
    auto steady = [&](bool course) {
        m.follow_course = course;
        s.mission = m;
        const RunResult r = runScenario(s);
        EXPECT_EQ(r.status, RunResult::Status::kCompleted) << r.message;
        EXPECT_TRUE(r.summary.mission && r.summary.mission->completed);
        const std::vector<double> p = r.series.values("path_s_m"),
                                  e = r.series.values("path_error_m"),
                                  v = r.series.values("forward_m_s"),
                                  w = r.series.values("lateral_m_s");
        double worst = 0.0, beta = 0.0;
        int n = 0;
        for (std::size_t k = 0; k < p.size(); ++k) {
            if (p[k] < 4.0) continue;
            worst = std::max(worst, std::abs(e[k]));
            beta += std::atan2(w[k], v[k]);
            ++n;
        }
        return std::pair{worst, beta / std::max(1, n)};
    };
    const auto [by_heading, beta] = steady(false);
    const auto [by_course, beta_course] = steady(true);
    (void)beta_course;
    EXPECT_GT(std::abs(beta), 0.05);  // a real crab (rad)
    EXPECT_NEAR(by_heading, m.lookahead_m * std::tan(std::abs(beta)), 0.3 * by_heading);
    EXPECT_LT(by_course, 0.25 * by_heading);
}

}  // namespace
}  // namespace terra::scenario
