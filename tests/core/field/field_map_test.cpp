#include "core/field/field_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/core/test_support.h"

namespace terra::field {
namespace {

using terra::testing::kExact;

Raster plane(double a, double b, double c) {
    Raster r = makeRaster(40, 30, 0.0, 0.0, 0.5);
    for (int row = 0; row < r.rows; ++row)
        for (int col = 0; col < r.cols; ++col)
            r.value(col, row) = c + a * r.centreX(col) + b * r.centreY(row);
    return r;
}

TEST(FieldMap, FlatWithoutAHeightMap) {
    const FieldMap f;
    EXPECT_EQ(f.heightAt(3.0, -2.0), 0.0);
    EXPECT_EQ(f.normalAt(3.0, -2.0), Eigen::Vector3d(0, 0, 1));
    EXPECT_EQ(f.slopeAt(3.0, -2.0), 0.0);
}

// On the plane z = a x + b y + c: the normal (−a, −b, 1)/√(1 + a² + b²), the steepest slope
// atan √(a² + b²), and under a heading ψ the grade atan(a cos ψ + b sin ψ) and the cross slope
// atan(−a sin ψ + b cos ψ) (docs/field.md, F3).
TEST(FieldMap, SlopesOfAPlane) {
    const double a = 0.1, b = -0.05;
    FieldMap f;
    f.height = plane(a, b, 2.0);
    const double x = 7.3, y = 4.1;
    EXPECT_NEAR(f.heightAt(x, y), 2.0 + a * x + b * y, kExact);
    const Eigen::Vector3d n = f.normalAt(x, y);
    const double norm = std::sqrt(1 + a * a + b * b);
    EXPECT_NEAR(n.x(), -a / norm, kExact);
    EXPECT_NEAR(n.y(), -b / norm, kExact);
    EXPECT_NEAR(n.z(), 1 / norm, kExact);
    EXPECT_NEAR(f.slopeAt(x, y), std::atan(std::hypot(a, b)), kExact);
    for (double psi : {0.0, 0.7, std::numbers::pi / 2, 2.5, -1.2}) {
        const LocalSlope s = f.slopeUnder(x, y, psi);
        EXPECT_NEAR(s.grade_rad, std::atan(a * std::cos(psi) + b * std::sin(psi)), kExact);
        EXPECT_NEAR(s.cross_rad, std::atan(-a * std::sin(psi) + b * std::cos(psi)), kExact);
    }
    // Driving up the x slope (ψ = 0) climbs a = 10 %; the other way descends it.
    EXPECT_GT(f.slopeUnder(x, y, 0.0).grade_rad, 0.0);
    EXPECT_LT(f.slopeUnder(x, y, std::numbers::pi).grade_rad, 0.0);
    // Beyond the map the field continues flat at its edge height.
    EXPECT_NEAR(f.heightAt(-5.0, 4.1), f.heightAt(0.0, 4.1), kExact);
    EXPECT_EQ(f.gradientAt(-5.0, 4.1), Eigen::Vector2d::Zero());
}

TEST(FieldMap, SoilFromClassesAndParameterRasters) {
    FieldMap f;
    f.base.name = "base";
    f.soil_class = makeRaster(2, 1, 0.0, 0.0, 10.0, 1.0);
    f.soil_class->value(1, 0) = 2.0;
    f.legend[1].name = "field";
    f.legend[2].name = "wet patch";
    f.legend[2].cohesion_pa = 4.0e3;
    Raster phi = makeRaster(2, 1, 0.0, 0.0, 10.0, std::nan(""));
    phi.value(1, 0) = 25.0;  // degrees, as the soil file writes φ
    f.parameters.push_back({soil::findSoilField("phi_deg"), phi});

    EXPECT_EQ(f.soilAt(-1.0, 5.0).name, "base");
    EXPECT_EQ(f.soilAt(5.0, 5.0).name, "field");
    const soil::SoilParameters wet = f.soilAt(15.0, 5.0);
    EXPECT_EQ(wet.name, "wet patch");
    EXPECT_DOUBLE_EQ(wet.cohesion_pa, 4.0e3);
    EXPECT_NEAR(wet.friction_angle_rad, 25.0 * std::numbers::pi / 180.0, kExact);
    EXPECT_DOUBLE_EQ(f.soilAt(5.0, 5.0).friction_angle_rad, f.legend[1].friction_angle_rad);
    EXPECT_TRUE(validate(f).empty());
}

TEST(FieldMap, ValidateNamesClassesParametersAndHeights) {
    FieldMap f;
    f.soil_class = makeRaster(3, 1, 0.0, 0.0, 1.0, 1.0);
    f.soil_class->value(1, 0) = 7.0;
    f.soil_class->value(2, 0) = 7.0;
    f.legend[1] = soil::SoilParameters{};
    Raster phi = makeRaster(3, 1, 0.0, 0.0, 1.0, 30.0);
    phi.value(0, 0) = 75.0;
    f.parameters.push_back({soil::findSoilField("phi_deg"), phi});
    f.height = makeRaster(3, 1, 0.0, 0.0, 1.0, 0.0);
    f.height->value(2, 0) = 2.0;  // a 2 m step over 1 m: 63°
    const std::vector<Issue> issues = validate(f);
    ASSERT_EQ(issues.size(), 3u);
    EXPECT_EQ(issues[0].where, "height");
    EXPECT_NE(issues[0].message.find("steeper than 60"), std::string::npos) << issues[0].message;
    EXPECT_EQ(issues[1].where, "soil_classes");
    EXPECT_NE(issues[1].message.find("class 7 (2 cells)"), std::string::npos) << issues[1].message;
    EXPECT_EQ(issues[2].where, "parameters.phi_deg");
    EXPECT_NE(issues[2].message.find("75 deg"), std::string::npos) << issues[2].message;
}

}  // namespace
}  // namespace terra::field
