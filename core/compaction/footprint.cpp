#include "core/compaction/footprint.h"

#include <cmath>
#include <stdexcept>

#include "core/contact/gauss_rule.h"
#include "core/contact/stress_field.h"
#include "core/contact/wheel_forces.h"

namespace terra::compaction {

const char* widthProfileName(WidthProfile profile) {
    return profile == WidthProfile::kParabolic ? "parabolic" : "uniform";
}

WidthProfile widthProfileNamed(const std::string& name) {
    if (name == "uniform") return WidthProfile::kUniform;
    if (name == "parabolic") return WidthProfile::kParabolic;
    throw std::invalid_argument("width profile \"" + name + "\" is not one of uniform, parabolic");
}

std::vector<PointLoad> wheelFootprint(const contact::ContactParameters<double>& p,
                                      const contact::OperatingPoint<double>& op,
                                      const FootprintOptions& options) {
    const contact::StressField<double> field(p, op);
    const contact::GaussRule& along = contact::gaussRule(options.nodes_along);
    const contact::GaussRule& across = contact::gaussRule(options.nodes_across);
    const double r = p.radius_m, b = p.width_m;
    const double shear_ratio = field.lugged() ? field.shearRadiusRatio() : 1.0;
    const double cos_entry = std::cos(field.entryAngle());
    const int q = contact::endExponent(field.sinkageExponent(), 0);
    // Width weights (fractions of b summing to 1) and positions.
    std::vector<double> ys, width_weights;
    for (std::size_t j = 0; j < across.nodes.size(); ++j) {
        const double y = (across.nodes[j] - 0.5) * b;
        double weight = across.weights[j];
        if (options.width == WidthProfile::kParabolic) {
            const double u = 2.0 * y / b;
            weight *= 1.5 * (1.0 - u * u);  // ∫₋₁¹ (3/4)(1 − u²) du = 1 over the width
        }
        ys.push_back(y);
        width_weights.push_back(weight);
    }
    std::vector<PointLoad> loads;
    loads.reserve(2 * along.nodes.size() * ys.size());
    // Front [θ_m, θ_f] from its θ_f end, rear [θ_r, θ_m] from its θ_r end: θ_end ∓ L u^q.
    const double theta_f = field.entryAngle(), theta_m = field.maxStressAngle();
    const double theta_r = field.exitAngle();
    struct Region {
        double end, length, sign;
    };
    const Region regions[2] = {{theta_f, theta_f - theta_m, -1.0},
                               {theta_r, theta_m - theta_r, +1.0}};
    for (const Region& region : regions) {
        if (!(region.length > 0.0)) continue;
        for (std::size_t i = 0; i < along.nodes.size(); ++i) {
            const double u = along.nodes[i];
            const double uq1 = std::pow(u, q - 1);
            const double theta = region.end + region.sign * region.length * uq1 * u;
            const double dtheta = region.length * q * uq1 * along.weights[i];
            const double s = std::sin(theta), c = std::cos(theta);
            const contact::StressSample<double> st = field.at(theta, s, c);
            const double tau_t = st.tau_t * shear_ratio, tau_l = st.tau_l * shear_ratio;
            const Eigen::Vector3d per_width{-(tau_t * c - st.sigma * s), tau_l,
                                            st.sigma * c + tau_t * s};
            const double depth = p.rut_depth_m + std::max(r * (c - cos_entry), 0.0);
            for (std::size_t j = 0; j < ys.size(); ++j) {
                loads.push_back(
                    {{r * s, ys[j], depth}, per_width * (r * b * dtheta * width_weights[j])});
            }
        }
    }
    return loads;
}

}  // namespace terra::compaction
