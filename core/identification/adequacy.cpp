#include "core/identification/adequacy.h"

#include <Eigen/QR>
#include <algorithm>
#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>
#include <map>
#include <utility>

namespace terra::identification {
namespace {

// ‖Qᵀe‖² of the cubic basis at the sweep's slips (scaled to [−1, 1] for the conditioning), and
// its rank (fewer distinct slips than four give fewer terms).
std::pair<double, int> trendEnergy(const std::vector<const OrderedResidual*>& sweep) {
    const auto n = static_cast<Eigen::Index>(sweep.size());
    double low = sweep.front()->slip, high = low;
    for (const OrderedResidual* r : sweep) {
        low = std::min(low, r->slip);
        high = std::max(high, r->slip);
    }
    const double middle = 0.5 * (low + high), half = std::max(0.5 * (high - low), 1e-12);
    Eigen::MatrixXd basis(n, 4);
    Eigen::VectorXd e(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const double x = (sweep[static_cast<std::size_t>(i)]->slip - middle) / half;
        basis.row(i) << 1.0, x, x * x, x * x * x;
        e(i) = sweep[static_cast<std::size_t>(i)]->value;
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(basis);
    const Eigen::Index rank = qr.rank();
    if (rank == 0) return {0.0, 0};
    const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(n, rank);
    return {(q.transpose() * e).squaredNorm(), static_cast<int>(rank)};
}

}  // namespace

TrendTest trendTest(const std::vector<OrderedResidual>& residuals) {
    TrendTest out;
    out.values = static_cast<int>(residuals.size());
    if (out.values < kTrendTestMinValues) return out;
    std::map<std::pair<double, double>, std::vector<const OrderedResidual*>> sweeps;
    for (const OrderedResidual& r : residuals) sweeps[{r.load_n, r.slip_angle}].push_back(&r);
    std::size_t in_trends = 0;
    for (const auto& [key, sweep] : sweeps)
        in_trends += sweep.size() >= kTrendTestMinSweep ? sweep.size() : 0;
    // A load that varies from row to row leaves sweeps of one sample: test all as one.
    if (2 * in_trends < residuals.size()) {
        std::vector<const OrderedResidual*> all;
        for (const OrderedResidual& r : residuals) all.push_back(&r);
        sweeps = {{{0.0, 0.0}, all}};
    }
    double total = 0.0, trend = 0.0;
    for (const OrderedResidual& r : residuals) total += r.value * r.value;
    for (const auto& [key, sweep] : sweeps) {
        if (sweep.size() < kTrendTestMinSweep) continue;
        const auto [energy, rank] = trendEnergy(sweep);
        trend += energy;
        out.trend_dof += rank;
        ++out.sweeps;
    }
    const int rest_dof = out.values - out.trend_dof;
    if (out.trend_dof == 0 || rest_dof < kTrendTestMinValues / 2 || !(total > 0.0)) return out;
    const double rest = std::max(total - trend, 0.0);
    out.trend_share = trend / total;
    out.f = rest > 0.0 ? (trend / out.trend_dof) / (rest / rest_dof)
                       : std::numeric_limits<double>::infinity();
    out.p = std::isinf(out.f) ? 0.0
                              : boost::math::cdf(boost::math::complement(
                                    boost::math::fisher_f(out.trend_dof, rest_dof), out.f));
    return out;
}

}  // namespace terra::identification
