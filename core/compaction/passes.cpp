#include "core/compaction/passes.h"

#include <cmath>

#include "core/common/range.h"
#include "core/contact/contact_angles.h"
#include "core/contact/quadratic_model.h"
#include "core/contact/stress_field.h"

namespace terra::compaction {

const char* riskName(Risk risk) {
    switch (risk) {
        case Risk::kGreen:
            return "green";
        case Risk::kYellow:
            return "yellow";
        case Risk::kRed:
            return "red";
    }
    return "?";
}

Risk riskOf(double stress_pa, double precompression_pa) {
    if (stress_pa > kRedRatio * precompression_pa) return Risk::kRed;
    if (stress_pa > kYellowRatio * precompression_pa) return Risk::kYellow;
    return Risk::kGreen;
}

SolvedPass solvePass(const contact::ContactParameters<double>& untouched, const TrackMemory& memory,
                     const ReloadLaw& law, const PassConditions& c) {
    SolvedPass out;
    out.params = onTrack(untouched, memory, law);
    const contact::ContactParameters<double>& p = out.params;
    contact::EntryAngleProblem problem;
    problem.load_n = c.load_n;
    problem.slip = c.slip;
    problem.slip_angle_rad = c.slip_angle_rad;
    problem.exit = c.exit;
    problem.max_stress_angle_rad = c.max_stress_angle_rad;
    problem.model = memory.untouched() ? c.model : contact::ContactModel::kFull;
    const contact::SinkageSolution solution = contact::solveEntryAngle(p, problem);
    if (!solution.ok()) {
        out.message = solution.message;
        return out;
    }
    const double theta_f = solution.entry_angle_rad;
    // As analysis::evaluatePoint (the `wheel` command): θ_r kept ≥ −θ_f.
    out.op = {c.slip, c.slip_angle_rad, theta_f,
              contact::clampedExitAngle(c.exit.exitAngle(theta_f), theta_f),
              c.max_stress_angle_rad};
    if (problem.model == contact::ContactModel::kFull) {
        contact::IntegrationReport report;
        out.forces = contact::computeForces(p, out.op, c.bulldozing, {}, &report);
        if (!report.converged) {
            out.warning = "the force integration stopped at its cap of " +
                          std::to_string(report.pieces) + " pieces";
        }
    } else {
        out.forces = contact::computeQuadraticForces(p, out.op, c.bulldozing);
    }
    out.sinkage_m = memory.rut_depth_m + p.radius_m * (1.0 - std::cos(theta_f));
    // The shear the soil under the centre line received: |j| at θ_r without the offset.
    contact::ContactParameters<double> plain = p;
    plain.shear_offset_m = 0.0;
    const contact::StressField<double> field(plain, out.op);
    out.exit_shear_m = field.locked() ? 0.0 : field.at(field.exitAngle()).shear;
    out.ok = true;
    return out;
}

TrackMemory rememberPass(const TrackMemory& memory, const ReloadLaw& law,
                         const contact::ContactParameters<double>& untouched,
                         const PassConditions& c, const SolvedPass& pass) {
    const double n = untouched.sinkage_exponent + untouched.sinkage_exponent_slip * c.slip;
    return afterPass(memory, law, untouched, pass.sinkage_m, n, pass.exit_shear_m);
}

double passStress(const StressPropagation& propagation, double z_m, RiskMeasure measure) {
    if (measure == RiskMeasure::kVertical) return maxVerticalStress(propagation, 0.0, z_m);
    return passMaxima(propagation, 0.0, z_m).maxima.major;
}

int layerIndex(const std::vector<soil::SoilLayer>& layers, double z) {
    for (std::size_t i = 0; i < layers.size(); ++i)
        if (z >= layers[i].top_m && z <= layers[i].bottom_m) return static_cast<int>(i);
    return -1;
}

double redZoneDepth(const std::vector<double>& depths, const std::vector<soil::SoilLayer>& layers,
                    const std::function<const StressPropagation&(double)>& propagation_at,
                    RiskMeasure measure, double deepest_load_m, bool* deepest_red_is_last) {
    if (deepest_red_is_last) *deepest_red_is_last = false;
    auto redAt = [&](double z, int layer) {
        const double sigma_pc = *layers[static_cast<std::size_t>(layer)].precompression_pa;
        const StressPropagation& propagation = propagation_at(z);
        // The bound proves most deep depths green without a search (σ_z only).
        if (measure == RiskMeasure::kVertical &&
            !(verticalStressBound(propagation, z) > kRedRatio * sigma_pc))
            return false;
        return riskOf(passStress(propagation, z, measure), sigma_pc) == Risk::kRed;
    };
    // From the deepest depth up: the first red one is the deepest red depth.
    for (std::size_t i = depths.size(); i-- > 0;) {
        const double z = depths[i];
        if (!(z > deepest_load_m + 1e-3)) break;
        const int layer = layerIndex(layers, z);
        if (layer < 0 || !redAt(z, layer)) continue;
        if (i + 1 == depths.size()) {
            if (deepest_red_is_last) *deepest_red_is_last = true;
            return z;
        }
        // Bisection toward the next depth, inside this layer (σ_pc is constant there and the
        // stress falls with depth).
        double lo = z,
               hi = std::min(depths[i + 1], layers[static_cast<std::size_t>(layer)].bottom_m);
        if (!(hi > lo)) return z;
        for (int k = 0; k < 40 && hi - lo > 1e-5; ++k) {
            const double mid = 0.5 * (lo + hi);
            (redAt(mid, layer) ? lo : hi) = mid;
        }
        return 0.5 * (lo + hi);
    }
    return 0.0;
}

}  // namespace terra::compaction
