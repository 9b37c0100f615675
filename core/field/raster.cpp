#include "core/field/raster.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/common/range.h"

namespace terra::field {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The four cells around (x, y) and the weights of the bilinear surface (docs/field.md, F1).
struct Stencil {
    int c0 = 0, c1 = 0, r0 = 0, r1 = 0;
    double u = 0.0, v = 0.0;  // fractions towards c1 (east) and r1 (south)
    bool x_inside = true;     // between the outermost centres in x (else the value is extended)
    bool y_inside = true;
};

// One axis: a continuous index f (cell centres at 0, 1, …, n − 1) to the lower cell and the
// fraction, extended flat beyond the outermost centres.
void axis(double f, int n, int& i0, int& i1, double& t, bool& inside) {
    if (n == 1) {
        i0 = i1 = 0;
        t = 0.0;
        inside = false;
        return;
    }
    inside = f >= 0.0 && f <= n - 1;
    f = std::clamp(f, 0.0, static_cast<double>(n - 1));
    i0 = std::min(static_cast<int>(std::floor(f)), n - 2);
    i1 = i0 + 1;
    t = f - i0;
}

std::optional<Stencil> stencil(const Raster& r, double x_m, double y_m) {
    if (!(x_m >= r.x_min_m && x_m <= r.xMax() && y_m >= r.y_min_m && y_m <= r.yMax()))
        return std::nullopt;
    Stencil s;
    axis((x_m - r.x_min_m) / r.cell_m - 0.5, r.cols, s.c0, s.c1, s.u, s.x_inside);
    axis((r.yMax() - y_m) / r.cell_m - 0.5, r.rows, s.r0, s.r1, s.v, s.y_inside);
    return s;
}

}  // namespace

std::optional<CellIndex> Raster::cellAt(double x_m, double y_m) const {
    if (!(x_m >= x_min_m && x_m < xMax() && y_m >= y_min_m && y_m < yMax())) return std::nullopt;
    CellIndex c;
    c.col = std::min(static_cast<int>(std::floor((x_m - x_min_m) / cell_m)), cols - 1);
    // y just above y_min can round to row == rows (x near x_max likewise): the clamps keep the
    // point on the raster.
    c.row = std::min(static_cast<int>(std::floor((yMax() - y_m) / cell_m)), rows - 1);
    return c;
}

double Raster::nearest(double x_m, double y_m) const {
    const std::optional<CellIndex> c = cellAt(x_m, y_m);
    return c ? value(c->col, c->row) : kNaN;
}

double Raster::bilinear(double x_m, double y_m) const {
    const std::optional<Stencil> s = stencil(*this, x_m, y_m);
    if (!s) return kNaN;
    const double z00 = value(s->c0, s->r0), z10 = value(s->c1, s->r0);
    const double z01 = value(s->c0, s->r1), z11 = value(s->c1, s->r1);
    return (1.0 - s->u) * (1.0 - s->v) * z00 + s->u * (1.0 - s->v) * z10 +
           (1.0 - s->u) * s->v * z01 + s->u * s->v * z11;
}

Eigen::Vector2d Raster::gradient(double x_m, double y_m) const {
    const std::optional<Stencil> s = stencil(*this, x_m, y_m);
    if (!s) return {kNaN, kNaN};
    const double z00 = value(s->c0, s->r0), z10 = value(s->c1, s->r0);
    const double z01 = value(s->c0, s->r1), z11 = value(s->c1, s->r1);
    const double dz_du = (1.0 - s->v) * (z10 - z00) + s->v * (z11 - z01);
    const double dz_dv = (1.0 - s->u) * (z01 - z00) + s->u * (z11 - z10);
    if (std::isnan(dz_du) || std::isnan(dz_dv)) return {kNaN, kNaN};
    // v grows southwards (rows from the north), so ∂/∂y = −∂/∂v / cell.
    return {s->x_inside ? dz_du / cell_m : 0.0, s->y_inside ? -dz_dv / cell_m : 0.0};
}

std::pair<double, double> Raster::valueRange() const {
    double lo = kNaN, hi = kNaN;
    for (double v : values) {
        if (std::isnan(v)) continue;
        if (std::isnan(lo) || v < lo) lo = v;
        if (std::isnan(hi) || v > hi) hi = v;
    }
    return {lo, hi};
}

std::size_t Raster::cellsWithData() const {
    return static_cast<std::size_t>(
        std::count_if(values.begin(), values.end(), [](double v) { return !std::isnan(v); }));
}

std::vector<Issue> validate(const Raster& raster, const std::string& where) {
    std::vector<Issue> issues;
    constexpr int kMaxSide = 100000;
    constexpr double kMaxCells = 1e9;
    constexpr double kMaxCell = 1e4;
    if (raster.cols < 1 || raster.cols > kMaxSide)
        issues.push_back({where, "ncols = " + std::to_string(raster.cols) + " must be in [1, " +
                                     std::to_string(kMaxSide) + "]"});
    if (raster.rows < 1 || raster.rows > kMaxSide)
        issues.push_back({where, "nrows = " + std::to_string(raster.rows) + " must be in [1, " +
                                     std::to_string(kMaxSide) + "]"});
    if (static_cast<double>(raster.cols) * raster.rows > kMaxCells)
        issues.push_back({where, "ncols × nrows = " +
                                     formatNumber(static_cast<double>(raster.cols) * raster.rows) +
                                     " cells is above the limit of 1e9"});
    if (!(raster.cell_m > 0.0 && raster.cell_m <= kMaxCell))
        issues.push_back(
            {where, "cellsize = " + formatNumber(raster.cell_m) + " m must be in (0, 10000] m"});
    if (!std::isfinite(raster.x_min_m) || !std::isfinite(raster.y_min_m))
        issues.push_back({where, "the lower-left corner must be finite"});
    if (issues.empty() &&
        raster.values.size() != static_cast<std::size_t>(raster.cols) * raster.rows)
        issues.push_back(
            {where, "holds " + std::to_string(raster.values.size()) +
                        " values for ncols × nrows = " +
                        std::to_string(static_cast<std::size_t>(raster.cols) * raster.rows)});
    return issues;
}

Raster makeRaster(int cols, int rows, double x_min_m, double y_min_m, double cell_m, double fill) {
    Raster r;
    r.cols = cols;
    r.rows = rows;
    r.x_min_m = x_min_m;
    r.y_min_m = y_min_m;
    r.cell_m = cell_m;
    r.values.assign(static_cast<std::size_t>(cols) * rows, fill);
    return r;
}

}  // namespace terra::field
