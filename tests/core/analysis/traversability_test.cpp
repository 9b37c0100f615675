#include "core/analysis/traversability.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "core/analysis/traction.h"
#include "core/common/units.h"
#include "core/contact/contact_parameters.h"
#include "core/io/parameters_json.h"
#include "core/scenario/map_image.h"
#include "core/scenario/map_layers.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace {

const io::PresetLocations kPresets{{TERRA_RESOURCE_DIR}};
// The map interpolates a 200-point curve at a load binned to 0.25 %: within 2e-3 of the slip
// solved directly at the exact load.
constexpr double kSlipTolerance = 2e-3;

field::FieldMap plane(double grade, const std::string& soil) {
    field::FieldMap f;
    f.base = io::resolveSoil(kPresets, soil).value();
    f.height = field::makeRaster(6, 4, 0.0, 0.0, 1.0);
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 6; ++col)
            f.height->value(col, row) = grade * f.height->centreX(col);
    return f;
}

dynamics::RobotParameters robot() {
    dynamics::RobotParameters r;
    r.wheel = io::resolveWheel(kPresets, "B").value();
    return r;
}

// The slip with F_x(s; W) = pull, by bisection on the wheel model itself at the exact load: an
// independent solution of T2 (no curve, no load bin).
double directSlip(const soil::SoilParameters& soil, const dynamics::RobotParameters& r, double load,
                  double pull) {
    const contact::ContactParameters<double> p = contact::makeContactParameters(soil, r.wheel);
    const TractionSettings ts;
    auto fx = [&](double s) {
        return tractionPoint(p, load, s, ts, contact::ContactModel::kQuadratic).fx_n - pull;
    };
    double lo = 0.01, hi = 0.9;
    EXPECT_LT(fx(lo), 0.0);
    EXPECT_GT(fx(hi), 0.0);
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (fx(mid) < 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

TEST(Traversability, OnLevelGroundEveryHeadingNeedsTheSlipThatCarriesRollingResistance) {
    const field::FieldMap f = plane(0.0, "sandy-loam");
    const dynamics::RobotParameters r = robot();
    const TraversabilityResult out = computeTraversability(f, r);
    const double w = r.totalMass() * units::kGravity / 4;
    const double expected = directSlip(f.base, r, w, 0.0);
    EXPECT_GT(expected, 0.01);
    ASSERT_EQ(out.headings.size(), 8u);
    for (const HeadingMap& m : out.headings) {
        EXPECT_EQ(m.stalled, 0u);
        EXPECT_NEAR(m.slip.value(3, 2), expected, kSlipTolerance);
    }
    EXPECT_EQ(out.curves, 1);
}

// On a 15 % grade along x: uphill (ψ = 0) the wheel carries W cos θ and pulls W sin θ (T1);
// across (ψ = 90°) the grade is zero and the cross slope carries the load reduction.
TEST(Traversability, UphillAcrossAndDownhillOnAGrade) {
    const double a = 0.15;
    const field::FieldMap f = plane(a, "sandy-loam");
    const dynamics::RobotParameters r = robot();
    TraversabilitySettings s;
    s.headings = 4;
    const TraversabilityResult out = computeTraversability(f, r, s);
    const double w = r.totalMass() * units::kGravity / 4, theta = std::atan(a);
    EXPECT_NEAR(out.headings[0].slip.value(2, 1),
                directSlip(f.base, r, w * std::cos(theta), w * std::sin(theta)), kSlipTolerance);
    EXPECT_NEAR(out.headings[1].slip.value(2, 1), directSlip(f.base, r, w * std::cos(theta), 0.0),
                kSlipTolerance);
    EXPECT_GT(out.headings[0].slip.value(2, 1), out.headings[1].slip.value(2, 1));
    // Downhill the slope pulls the robot: the wheels brake (or need less slip than level).
    const double down = out.headings[2].slip.value(2, 1);
    EXPECT_TRUE(std::isnan(down) || down < out.headings[1].slip.value(2, 1));
}

// A 60 % grade of dry sand: no slip gives the pull, uphill stalls on every cell; across the
// slope the robot still holds its speed.
TEST(Traversability, TooSteepStalls) {
    const field::FieldMap f = plane(0.6, "dry-sand");
    TraversabilitySettings s;
    s.headings = 4;
    const TraversabilityResult out = computeTraversability(f, robot(), s);
    // The map's cells are the height map's: every centre has the grade (F1, F2).
    EXPECT_EQ(out.headings[0].stalled, 6u * 4u);
    EXPECT_EQ(out.headings[0].status.value(2, 1), static_cast<double>(TraverseStatus::kStall));
    EXPECT_EQ(out.headings[1].stalled, 0u);
    EXPECT_GT(out.stall_share.value(2, 1), 0.0);
    const nlohmann::json j = toJson(out);
    EXPECT_EQ(j["headings"][0]["stalled"], 24);
    EXPECT_EQ(j["stall_cells"], 24);
}

// The summary `terrastudio field --traversability` prints: every number is the JSON's at the
// pointer its row names (expectSummaryIsTheJson), a heading that stalls everywhere has no
// largest slip ("none"), and the counts are the maps' own (24 stalled cells up the 0.6 grade).
TEST(Traversability, TheSummaryIsTheJson) {
    TraversabilitySettings s;
    s.headings = 4;
    const TraversabilityResult out = computeTraversability(plane(0.6, "dry-sand"), robot(), s);
    const Summary summary = traversabilitySummary(out);
    terra::testing::expectSummaryIsTheJson(summary, toJson(out));
    auto row = [&](const std::string& label) -> const SummaryRow& {
        for (const SummaryRow& r : summary) {
            if (r.label == label) return r;
        }
        ADD_FAILURE() << "no row " << label;
        return summary.front();
    };
    EXPECT_EQ(row("heading 0.0 deg, stalled cells").value, "24");
    EXPECT_EQ(row("heading 0.0 deg, largest slip").value, "none");
    EXPECT_EQ(row("heading 90.0 deg, stalled cells").value, "0");
    EXPECT_EQ(row("heading 90.0 deg, largest slip").json, "/headings/1/max_slip");
    EXPECT_EQ(row("cells where a heading stalls").value, "24");
    EXPECT_EQ(summary.front().emphasis, SummaryRow::Emphasis::kHeading);
    EXPECT_EQ(summary.size(), 4u + 2u * 4u);
}

// Issue 23 item 4: the traversability map as a picture with its legend. Each cell's colour is the
// slip palette's at the cell's largest slip on [0, 1] (scenario::colorAt, computed here); a cell
// where every heading stalls takes slip 1, the darkest.
TEST(Traversability, ThePictureColoursEachCellByItsSlipAndStallsDarkest) {
    const field::FieldMap f = plane(0.6, "dry-sand");
    TraversabilitySettings s;
    s.headings = 4;
    TraversabilityResult out = computeTraversability(f, robot(), s);
    out.worst_slip.value(4, 2) = std::numeric_limits<double>::quiet_NaN();  // as if all stalled
    const io::RgbaImage image = traversabilityImage(out);
    const scenario::MapImageLayout layout = scenario::mapImageLayout(6, 4);
    ASSERT_EQ(image.width, layout.width);
    ASSERT_EQ(image.height, layout.height);
    scenario::MapLayer layer;
    layer.key = "slip";
    scenario::LayerScale unit;  // [0, 1]
    const auto stops = scenario::layerColors(layer, unit);
    for (int row = 0; row < 4; ++row) {
        for (int col = 0; col < 6; ++col) {
            const double slip = col == 4 && row == 2 ? 1.0 : out.worst_slip.value(col, row);
            ASSERT_TRUE(std::isfinite(slip));
            const scenario::Rgb expected = scenario::colorAt(stops, slip);
            const std::uint8_t* px = image.at(col * layout.cell_px + layout.cell_px / 2,
                                              row * layout.cell_px + layout.cell_px / 2);
            EXPECT_EQ(px[0], expected.r) << col << ", " << row;
            EXPECT_EQ(px[1], expected.g) << col << ", " << row;
            EXPECT_EQ(px[2], expected.b) << col << ", " << row;
            EXPECT_EQ(px[3], 255);
        }
    }
    const std::uint8_t* stalled = image.at(4 * layout.cell_px + 1, 2 * layout.cell_px + 1);
    EXPECT_EQ(stalled[0], stops.back().color.r);
    EXPECT_EQ(stalled[2], stops.back().color.b);
}

TEST(Traversability, RefusesBadSettings) {
    TraversabilitySettings s;
    s.headings = 0;
    EXPECT_THROW(computeTraversability(plane(0.0, "sandy-loam"), robot(), s),
                 std::invalid_argument);
    EXPECT_THROW(computeTraversability(field::FieldMap{}, robot()), std::invalid_argument);
}

}  // namespace
}  // namespace terra::analysis
