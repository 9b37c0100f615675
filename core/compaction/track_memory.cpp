#include "core/compaction/track_memory.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace terra::compaction {

contact::ContactParameters<double> onTrack(const contact::ContactParameters<double>& p,
                                           const TrackMemory& memory, const ReloadLaw& law) {
    contact::ContactParameters<double> out = p;
    if (memory.untouched()) return out;
    const double k_u = law.k0_pa_m + law.au_pa_m2 * memory.max_sinkage_m;
    out.rut_depth_m = memory.rut_depth_m;
    out.reload_depth_m = memory.max_sinkage_m - memory.rut_depth_m;
    out.reload_modulus_pa_m = k_u;
    out.shear_offset_m = law.shear_memory ? memory.shear_m : 0.0;
    return out;
}

TrackMemory afterPass(const TrackMemory& memory, const ReloadLaw& law,
                      const contact::ContactParameters<double>& p, double depth_m,
                      double sinkage_exponent, double exit_shear_m) {
    if (!(depth_m >= 0.0) || !std::isfinite(depth_m) || !(exit_shear_m >= 0.0)) {
        throw std::invalid_argument("afterPass: depth and exit shear must be finite and >= 0");
    }
    TrackMemory out = memory;
    ++out.passes;
    if (depth_m > memory.max_sinkage_m) {
        out.max_sinkage_m = depth_m;
        out.max_pressure_pa = p.pressure_modulus * std::pow(depth_m, sinkage_exponent);
        const double k_u = law.k0_pa_m + law.au_pa_m2 * depth_m;
        // R2: the elastic rebound p_u/k_u, never more than the sinkage itself (k_u → 0).
        const double rebound = k_u > 0.0 ? std::min(out.max_pressure_pa / k_u, depth_m) : depth_m;
        out.rut_depth_m = depth_m - rebound;
    }
    if (law.shear_memory) {
        out.shear_m = std::min(memory.shear_m + exit_shear_m, p.max_shear_deformation_m);
    }
    return out;
}

}  // namespace terra::compaction
