#include "core/contact/quadratic_model.h"

#include <cmath>
#include <stdexcept>

namespace terra::contact {

std::array<ApproximationError, 4> quadraticApproximationErrors(const ContactParameters<double>& p,
                                                               const OperatingPoint<double>& op,
                                                               double step_rad) {
    if (!(step_rad > 0.0)) throw std::invalid_argument("grid step must be > 0");
    const StressField<double> field(p, op);
    const QuadraticStress<double> q = fitQuadraticStress(field);
    std::array<double, 4> squared{}, absolute{};
    const double span = field.entryAngle() - field.exitAngle();
    // Integer steps (not repeated addition), so the last point is θ_f itself when step divides.
    const auto steps = static_cast<long>(std::floor(span / step_rad + 1e-9));
    for (long i = 0; i <= steps; ++i) {
        const double theta = field.exitAngle() + static_cast<double>(i) * step_rad;
        const StressSample<double> exact = field.at(theta);
        const StressSample<double> approx = q.at(theta);
        const std::array<double, 4> diff{exact.sigma - approx.sigma, exact.tau - approx.tau,
                                         exact.tau_t - approx.tau_t, exact.tau_l - approx.tau_l};
        for (int k = 0; k < 4; ++k) {
            squared[k] += diff[k] * diff[k];
            absolute[k] += std::abs(diff[k]);
        }
    }
    const double count = static_cast<double>(steps + 1);
    std::array<ApproximationError, 4> errors;
    for (int k = 0; k < 4; ++k) errors[k] = {std::sqrt(squared[k] / count), absolute[k] / count};
    return errors;
}

}  // namespace terra::contact
