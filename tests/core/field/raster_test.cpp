#include "core/field/raster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/core/test_support.h"

namespace terra::field {
namespace {

using terra::testing::kExact;

// A raster of f at the cell centres.
template <typename F>
Raster sampled(int cols, int rows, double x0, double y0, double cell, F f) {
    Raster r = makeRaster(cols, rows, x0, y0, cell);
    for (int row = 0; row < rows; ++row)
        for (int col = 0; col < cols; ++col) r.value(col, row) = f(r.centreX(col), r.centreY(row));
    return r;
}

TEST(Raster, RowZeroIsTheNorthernRow) {
    const Raster r = sampled(3, 2, 10.0, 20.0, 0.5, [](double, double y) { return y; });
    EXPECT_DOUBLE_EQ(r.value(0, 0), 20.75);  // north row centre: y_min + 1.5 cells
    EXPECT_DOUBLE_EQ(r.value(0, 1), 20.25);
    const auto c = r.cellAt(10.0, 20.0);  // the south-west corner belongs to the last row
    ASSERT_TRUE(c);
    EXPECT_EQ(c->col, 0);
    EXPECT_EQ(c->row, 1);
    EXPECT_FALSE(r.cellAt(11.5, 20.2));  // the east edge is outside
    EXPECT_FALSE(r.cellAt(10.2, 21.0));  // the north edge too
    EXPECT_TRUE(std::isnan(r.nearest(9.99, 20.5)));
}

// A plane is reproduced exactly by the bilinear surface (F1) and its gradient is the plane's
// (F2), at any point between the outermost centres.
TEST(Raster, BilinearReproducesAPlaneAndItsGradient) {
    const double a = 0.02, b = -0.05, c = 0.3;
    const Raster r =
        sampled(20, 15, -3.0, 4.0, 0.25, [&](double x, double y) { return c + a * x + b * y; });
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> ux(r.centreX(0), r.centreX(r.cols - 1));
    std::uniform_real_distribution<double> uy(r.centreY(r.rows - 1), r.centreY(0));
    for (int k = 0; k < 200; ++k) {
        const double x = ux(rng), y = uy(rng);
        EXPECT_NEAR(r.bilinear(x, y), c + a * x + b * y, kExact);
        const Eigen::Vector2d g = r.gradient(x, y);
        EXPECT_NEAR(g.x(), a, kExact);
        EXPECT_NEAR(g.y(), b, kExact);
    }
}

// Linear interpolation of f = x² between nodes h apart errs by at most h²/8 · max|f''| = h²/4
// (the classic interpolation error bound), and exactly that at mid-cell.
TEST(Raster, BilinearErrorOfAParabolaMeetsTheInterpolationBound) {
    const double h = 0.4;
    const Raster r = sampled(30, 3, 0.0, 0.0, h, [](double x, double) { return x * x; });
    double worst = 0.0;
    for (double x = r.centreX(0); x <= r.centreX(r.cols - 1); x += h / 16) {
        worst = std::max(worst, std::abs(r.bilinear(x, 0.6) - x * x));
    }
    EXPECT_NEAR(worst, h * h / 4.0, 1e-12);
    // The slope of the chord: (f(x₁) − f(x₀))/h = x₀ + x₁ at any point of the cell.
    const double x0 = r.centreX(5), x1 = r.centreX(6);
    EXPECT_NEAR(r.gradient(0.5 * (x0 + x1) + 0.01, 0.6).x(), x0 + x1, 1e-12);
}

TEST(Raster, EdgeCellsAreExtendedFlatToTheEdge) {
    const Raster r = sampled(4, 4, 0.0, 0.0, 1.0, [](double x, double y) { return x + 10 * y; });
    // Between the west edge and the first centre (x < 0.5) the value is the first column's.
    EXPECT_NEAR(r.bilinear(0.1, 2.0), r.bilinear(0.5, 2.0), kExact);
    EXPECT_EQ(r.gradient(0.1, 2.0).x(), 0.0);
    EXPECT_NEAR(r.gradient(0.1, 2.0).y(), 10.0, kExact);
    EXPECT_TRUE(std::isnan(r.bilinear(4.01, 2.0)));
    EXPECT_TRUE(std::isnan(r.gradient(-0.01, 2.0).x()));
}

TEST(Raster, ACellWithoutDataMakesItsNeighbourhoodNaN) {
    Raster r = sampled(4, 4, 0.0, 0.0, 1.0, [](double, double) { return 1.0; });
    r.value(1, 1) = std::nan("");
    EXPECT_TRUE(std::isnan(r.bilinear(1.2, 2.3)));  // between centres of cols 0–1, rows 1–2
    EXPECT_DOUBLE_EQ(r.bilinear(3.2, 0.7), 1.0);    // far from it
    EXPECT_EQ(r.cellsWithData(), 15u);
    const auto [lo, hi] = r.valueRange();
    EXPECT_EQ(lo, 1.0);
    EXPECT_EQ(hi, 1.0);
}

TEST(Raster, ValidateNamesTheBadDimension) {
    Raster r = makeRaster(2, 2, 0.0, 0.0, 1.0);
    EXPECT_TRUE(validate(r, "h").empty());
    r.cell_m = -1.0;
    const std::vector<Issue> issues = validate(r, "h");
    ASSERT_EQ(issues.size(), 1u);
    EXPECT_NE(issues[0].message.find("cellsize = -1"), std::string::npos) << issues[0].message;
    r.cell_m = 1.0;
    r.values.pop_back();
    ASSERT_EQ(validate(r, "h").size(), 1u);
    EXPECT_NE(validate(r, "h")[0].message.find("3 values"), std::string::npos);
}

}  // namespace
}  // namespace terra::field
