#include "core/contact/reference_forces.h"

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <functional>
#include <vector>

namespace terra::contact {

WheelForces<double> computeForcesReference(const ContactParameters<double>& p,
                                           const OperatingPoint<double>& op,
                                           BulldozingModel bulldozing, ReferenceMethod method,
                                           double tolerance) {
    const StressField<double> field(p, op);
    const Kinks kinks = findKinks(detail::shearGeometry(p, field));
    std::vector<double> edges{field.exitAngle(), field.maxStressAngle(), field.entryAngle()};
    edges.insert(edges.end(), kinks.angles.begin(), kinks.angles.begin() + kinks.count);
    // θ = 0 is where the shear direction (1 − κ cos θ, κ tan β) turns fastest when driving: at
    // small β a feature a few 1e-2 rad wide (or narrower) that an adaptive rule in the middle of a
    // long segment can step over. At a segment end tanh-sinh clusters its nodes onto it.
    if (field.exitAngle() < 0.0 && field.entryAngle() > 0.0) edges.push_back(0.0);
    std::sort(edges.begin(), edges.end());

    // Each segment is cut into sub-pieces no longer than kMaxPiece (at least kMinPieces), so that
    // no feature spans less than a few per cent of a piece. Each sub-piece is integrated in the
    // shifted variable x = θ − a on [0, b − a] with b − a < 0.5: Boost's tanh-sinh then evaluates
    // the ends by their complements and never takes the branch whose BOOST_ASSERT(position != a)
    // fires in Debug builds when an abscissa rounds onto an end of a narrow piece far from 0.
    // (Gauss–Kronrod, which has no such assertion, integrates over u = (θ − a)/(b − a) ∈ [0, 1].)
    constexpr double kMaxPiece = 0.1;  // [rad]
    constexpr int kMinPieces = 4;
    std::vector<double> cuts;
    for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
        const double a = edges[i], b = edges[i + 1];
        if (!(b > a)) continue;
        const int n = std::max(kMinPieces, static_cast<int>(std::ceil((b - a) / kMaxPiece)));
        for (int k = 0; k < n; ++k) cuts.push_back(a + (b - a) * k / n);
    }
    cuts.push_back(edges.back());

    // Not const: Boost 1.74 defines tanh_sinh::integrate without the const it declares.
    thread_local boost::math::quadrature::tanh_sinh<double> tanh_sinh(15);
    auto integrate = [&](auto f) {
        double total = 0.0;
        for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
            const double a = cuts[i], width = cuts[i + 1] - a;
            if (!(width > 0.0)) continue;
            if (method == ReferenceMethod::kTanhSinh) {
                auto shifted = [&](double x) { return f(a + x); };
                total += tanh_sinh.integrate(shifted, 0.0, width, tolerance);
            } else {
                // On [0, 1]: Boost 1.74's recursive Gauss–Kronrod compares the unscaled error of
                // a sub-interval with the scaled tolerance, so on a narrow θ-interval with a
                // large integrand its 2·eps error floor never meets the tolerance and all 2^15
                // sub-intervals are evaluated.
                auto unit = [&](double u) { return width * f(a + width * u); };
                total += boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
                    unit, 0.0, 1.0, 15, tolerance);
            }
        }
        return total;
    };
    if (p.lugged()) {
        // The lug model term by term (docs/model.md, "Lugs"), without the ρ weighting of
        // computeForces(): σ on the rim (r b dθ, lever arm r), shear on the cylinder of radius r_s
        // (r_s b dθ, lever arm r_s).
        const double r = p.radius_m, rs = p.shearRadius(), b = p.width_m;
        auto sigma = [&](double t) { return field.at(t).sigma; };
        auto tau_t = [&](double t) { return field.at(t).tau_t; };
        auto tau_l = [&](double t) { return field.at(t).tau_l; };
        WheelForces<double> f;
        f.fx = rs * b * integrate([&](double t) { return tau_t(t) * std::cos(t); }) -
               r * b * integrate([&](double t) { return sigma(t) * std::sin(t); });
        f.fz = r * b * integrate([&](double t) { return sigma(t) * std::cos(t); }) +
               rs * b * integrate([&](double t) { return tau_t(t) * std::sin(t); });
        f.fy = 0.0 - rs * b * integrate(tau_l);
        f.mx = 0.0 - rs * rs * b * integrate([&](double t) { return tau_l(t) * std::cos(t); });
        f.my = rs * rs * b * integrate(tau_t);
        f.mz = 0.0 - rs * rs * b * integrate([&](double t) { return tau_l(t) * std::sin(t); });
        // Bulldozing and the side force as assembleForces() (the rim's submerged segment).
        const WheelForces<double> walls =
            assembleForces(p, op, detail::ForceSums<double>{}, bulldozing);
        f.fb = walls.fb;
        f.fs = f.fy + (walls.fs - walls.fy);
        return f;
    }
    detail::ForceSums<double> sums;
    sums.fx = integrate([&](double t) {
        const auto s = field.at(t);
        return s.tau_t * std::cos(t) - s.sigma * std::sin(t);
    });
    sums.fz = integrate([&](double t) {
        const auto s = field.at(t);
        return s.sigma * std::cos(t) + s.tau_t * std::sin(t);
    });
    sums.fy = integrate([&](double t) { return field.at(t).tau_l; });
    sums.mx = integrate([&](double t) { return field.at(t).tau_l * std::cos(t); });
    sums.my = integrate([&](double t) { return field.at(t).tau_t; });
    sums.mz = integrate([&](double t) { return field.at(t).tau_l * std::sin(t); });
    return assembleForces(p, op, sums, bulldozing);
}

}  // namespace terra::contact
