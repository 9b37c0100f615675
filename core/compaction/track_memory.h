#pragma once
/// @file track_memory.h
/// What a track remembers of the wheels that passed on it (docs/compaction.md, "Repeated
/// passes", R1–R4): the deepest sinkage and the pressure it took, the rut left after the elastic
/// rebound, and the shear deformation already given to the soil. The next wheel meets Wong's
/// unload–reload law: elastic reloading with stiffness k_u = k₀ + A_u z_u up to the earlier
/// largest pressure p_u, then the virgin pressure–sinkage curve (Wong, Theory of Ground
/// Vehicles, 4th ed., §2.4.4; Wong 1978). The track is uniform along its length, so one memory
/// describes every soil column under the wheel's centre line.

#include "core/contact/contact_parameters.h"

namespace terra::compaction {

/// Wong's repetitive-loading parameters: k_u = k₀ + A_u z_u.
struct ReloadLaw {
    /// k₀ [Pa/m] (Wong: kN/m³). Default 5e7 Pa/m: the elastic stiffness K_e of Project Chrono's
    /// SCM terrain (SCMTerrain's default; docs/compaction.md, R1).
    double k0_pa_m = 5.0e7;
    double au_pa_m2 = 0.0;     ///< A_u [Pa/m²] (Wong: kN/m⁴); 0: SCM's constant stiffness
    bool shear_memory = true;  ///< carry the shear deformation of earlier passes (R3)
};

/// The memory of one track.
struct TrackMemory {
    int passes = 0;                ///< wheels that have passed
    double max_sinkage_m = 0.0;    ///< z_u [m]: deepest rim depth below the untouched surface
    double max_pressure_pa = 0.0;  ///< p_u = K_s z_u^N [Pa]: the virgin pressure at z_u
    double rut_depth_m = 0.0;      ///< z_p = z_u − p_u/k_u [m]: the rut after elastic rebound
    double shear_m = 0.0;          ///< j₀ [m]: shear deformation carried by the soil

    bool untouched() const { return passes == 0; }
};

/// The contact parameters of a wheel on this track: `p` (an untouched soil's) with the memory's
/// rut, reload branch and shear offset set. An untouched track returns `p` unchanged.
contact::ContactParameters<double> onTrack(const contact::ContactParameters<double>& p,
                                           const TrackMemory& memory, const ReloadLaw& law);

/// The memory after one more wheel, which sank to `depth_m` below the untouched surface (the
/// rut's bottom plus its own sinkage) with sinkage exponent N = n₀ + n₁ s and left the shear
/// deformation `exit_shear_m` (|j| at θ_r, Eq. 2.15, before any offset) in the soil:
/// - deeper than z_u: the soil yielded; z_u, p_u = K_s z_u^N and the rut z_p = z_u − p_u/k_u
///   (never below 0) are renewed (R2);
/// - not deeper: the wheel stayed on the elastic branch and left no new rut;
/// - j₀ grows by exit_shear_m when the law carries shear, up to j_max (R3).
TrackMemory afterPass(const TrackMemory& memory, const ReloadLaw& law,
                      const contact::ContactParameters<double>& p, double depth_m,
                      double sinkage_exponent, double exit_shear_m);

}  // namespace terra::compaction
