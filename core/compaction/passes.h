#pragma once
/// @file passes.h
/// One wheel on a track, solved: the contact on the track's memory (Wong's reload law), its
/// forces, sinkage and the shear it leaves (docs/compaction.md, R1–R3); and the depth where a
/// pass's red zone ends. The compaction analysis (core/analysis/compaction.h) and the global
/// studies' compaction outputs (core/gsa/wheel_target.h) both pass wheels with these.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/compaction/footprint.h"
#include "core/compaction/stress_at_depth.h"
#include "core/compaction/track_memory.h"
#include "core/contact/bulldozing.h"
#include "core/contact/sinkage.h"
#include "core/contact/wheel_forces.h"
#include "core/soil/soil_profile.h"

namespace terra::compaction {

/// The operating conditions of every wheel on the track.
struct PassConditions {
    double load_n = contact::kDefaultLoadN;  ///< W [N]
    double slip = 0.1;                       ///< s [-]
    double slip_angle_rad = 0.0;             ///< β [rad]
    contact::ExitCondition exit;             ///< θ_r or rut ratio λ
    std::optional<double> max_stress_angle_rad;
    contact::BulldozingModel bulldozing = contact::BulldozingModel::kBekker;
    /// The model of an untouched track's wheel; a remembered track is always integrated (the
    /// closed-form quadratic model has no reload branch).
    contact::ContactModel model = contact::ContactModel::kFull;
};

/// A wheel solved on a track.
struct SolvedPass {
    bool ok = false;
    std::string message;                        ///< why not: no equilibrium at this load
    contact::ContactParameters<double> params;  ///< the untouched soil's, with the memory set
    contact::OperatingPoint<double> op{};
    contact::WheelForces<double> forces;
    double sinkage_m = 0.0;     ///< rim depth below the untouched surface: z_p + r(1 − cos θ_f)
    double exit_shear_m = 0.0;  ///< |j| at θ_r (Eq. 2.15), without the memory's offset
    std::string warning;        ///< the force integration hit its piece cap
};

/// Solves F_z = W on the track (Eqs. 2.17–2.31 with the reload law) and the forces there. On an
/// untouched track this is exactly the single-wheel model (`terrastudio wheel`).
SolvedPass solvePass(const contact::ContactParameters<double>& untouched, const TrackMemory& memory,
                     const ReloadLaw& law, const PassConditions& conditions);

/// The track's memory after the solved pass (afterPass with its depth, N and exit shear).
TrackMemory rememberPass(const TrackMemory& memory, const ReloadLaw& law,
                         const contact::ContactParameters<double>& untouched,
                         const PassConditions& conditions, const SolvedPass& pass);

/// Which stress is compared with σ_pc.
enum class RiskMeasure { kVertical, kMajor };

/// Terranimo's traffic light (Stettler et al. 2014, via soilphysics' limits): green when the
/// stress is ≤ 0.5 σ_pc, yellow ≤ 1.1 σ_pc, red above.
enum class Risk { kGreen = 0, kYellow = 1, kRed = 2 };
inline constexpr double kYellowRatio = 0.5;
inline constexpr double kRedRatio = 1.1;
const char* riskName(Risk risk);
Risk riskOf(double stress_pa, double precompression_pa);

/// The largest value of the measure at depth z under the centre line during the pass.
double passStress(const StressPropagation& propagation, double z_m, RiskMeasure measure);

/// Where the red zone (stress > 1.1 σ_pc) ends below the pass, given the layers' current σ_pc
/// and the propagation for each depth (`propagationAt(z)`): scanning `depths` from the deepest,
/// the deepest red depth is refined by bisection toward the next depth (inside its layer) to
/// 1e-5 m. 0 when no depth is red; `deepest_red_is_last` tells when the deepest depth is red.
double redZoneDepth(const std::vector<double>& depths, const std::vector<soil::SoilLayer>& layers,
                    const std::function<const StressPropagation&(double)>& propagation_at,
                    RiskMeasure measure, double deepest_load_m,
                    bool* deepest_red_is_last = nullptr);

/// The layer of `layers` holding depth z, or −1.
int layerIndex(const std::vector<soil::SoilLayer>& layers, double z_m);

}  // namespace terra::compaction
