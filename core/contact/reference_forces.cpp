#include "core/contact/reference_forces.h"

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
    std::sort(edges.begin(), edges.end());

    // Not const: Boost 1.74 defines tanh_sinh::integrate without the const it declares.
    thread_local boost::math::quadrature::tanh_sinh<double> tanh_sinh(15);
    auto integrate = [&](auto f) {
        double total = 0.0;
        for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
            if (!(edges[i + 1] > edges[i])) continue;
            if (method == ReferenceMethod::kTanhSinh) {
                total += tanh_sinh.integrate(f, edges[i], edges[i + 1], tolerance);
            } else {
                total += boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
                    f, edges[i], edges[i + 1], 15, tolerance);
            }
        }
        return total;
    };
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
