#pragma once
/// @file stress_at_depth.h
/// Stress in the soil below a loaded surface: the Söhne/Fröhlich radial-stress solution for point
/// loads on a semi-infinite soil, with the concentration factor ν (ν = 3 is Boussinesq), for
/// vertical and tangential (horizontal) surface forces, superposed over a discretised footprint
/// (docs/compaction.md, "Stress at depth", derivations C1–C4).
///
/// Frame: x along travel, y to the left, z downward (depth below the untouched surface). Forces
/// are those the wheel applies to the soil: a vertical load is +z. Stresses are compressive
/// positive, in Pa. The stress of one point force F at S, at a point P with R = P − S (R_z > 0):
///
///   σ_R = [ν F_z cos^(ν−2)ϑ + ν(ν−2) cos^(ν−3)ϑ (F_h·R̂)] / (2π R²),   cos ϑ = R_z / |R|,
///
/// acting along R̂ only (σ = σ_R R̂ R̂ᵀ). The vertical term is Fröhlich's (Söhne 1958); the
/// tangential term is derived in docs/compaction.md (C2) so that the horizontal force is carried
/// at every depth for every ν, and for ν = 3 it is the radial term of Cerruti's solution (σ_z
/// exactly Cerruti's 3 H x z² / (2π R⁵)).

#include <Eigen/Core>
#include <span>
#include <vector>

namespace terra::compaction {

/// ν when neither the user nor the soil layer gives one: Söhne's "normal" soil.
inline constexpr double kDefaultConcentration = 5.0;

/// A force on the soil at a point of its surface (or of a rut's surface).
struct PointLoad {
    Eigen::Vector3d position;  ///< S [m]: x forward, y left, z depth below the untouched surface
    Eigen::Vector3d force;     ///< F [N] on the soil: z down (a load), x, y tangential
};

/// The stress measures used for compaction at one point, all compressive positive [Pa].
struct StressMeasures {
    double sigma_z = 0.0;  ///< σ_z [Pa]: vertical normal stress
    double sigma_x = 0.0;  ///< σ_x [Pa]: horizontal normal stress along travel
    double sigma_y = 0.0;  ///< σ_y [Pa]: horizontal normal stress across travel
    double mean = 0.0;     ///< p = (σ_x + σ_y + σ_z)/3 [Pa]: mean normal stress
    double major = 0.0;    ///< σ₁ [Pa]: major (largest) principal stress
};

/// The measures of a stress tensor (compressive positive).
StressMeasures measuresOf(const Eigen::Matrix3d& stress);

/// Point loads on a semi-infinite soil with one concentration factor.
class StressPropagation {
public:
    /// Throws std::invalid_argument unless 2 < ν ≤ 12 (ν = 2 carries no horizontal force; the
    /// literature uses 3–6, docs/compaction.md) and every load is finite at depth ≥ 0.
    StressPropagation(std::vector<PointLoad> loads, double concentration);

    double concentration() const { return nu_; }
    std::span<const PointLoad> loads() const { return loads_; }
    /// The deepest load [m]: stresses are defined below it.
    double deepestLoad() const { return deepest_; }

    /// σ [Pa] at P (compressive positive); P must lie below every load (P_z > deepestLoad()).
    /// Loads that P is not strictly below contribute nothing.
    Eigen::Matrix3d stressAt(const Eigen::Vector3d& point) const;
    /// Only σ_z [Pa] at P (a third of the work of stressAt).
    double verticalStressAt(const Eigen::Vector3d& point) const;
    /// The measures at P.
    StressMeasures measuresAt(const Eigen::Vector3d& point) const {
        return measuresOf(stressAt(point));
    }

private:
    /// Calls accumulate(σ_R, R̂) for every load P lies below (C1–C2).
    template <typename Accumulate>
    void forEachRadialStress(const Eigen::Vector3d& point, Accumulate accumulate) const;

    std::vector<PointLoad> loads_;
    double nu_;
    int integer_nu_;  // ν when it is a whole number (the powers become products), else 0
    double deepest_ = 0.0;
};

/// The largest value each measure reaches at a soil point (y, z) while the load passes over it
/// along x: the loads move rigidly, so it is the largest over x of the field at (x, y, z).
struct PassMaxima {
    StressMeasures maxima;   ///< each measure's own largest value [Pa]
    double x_sigma_z = 0.0;  ///< x [m] (relative to the loads) where σ_z peaks
};

/// The largest σ_z, σ_x, σ_y, p and σ₁ over x at (y, z): a scan of `scan_points` positions over
/// the footprint's extent ± 3 z, then Brent's method (Boost.Math) between each measure's best
/// scan point's neighbours (to 2⁻²⁰ in x). Throws std::invalid_argument when z is not below the
/// deepest load.
PassMaxima passMaxima(const StressPropagation& propagation, double y_m, double z_m,
                      int scan_points = 25);

/// Only the largest σ_z over x at (y, z), the same way (a third of passMaxima's work).
double maxVerticalStress(const StressPropagation& propagation, double y_m, double z_m,
                         int scan_points = 25);

/// Where σ_z peaks along x at (y, z) [m, relative to the loads], its value [Pa], and the scan's
/// step [m]: as maxVerticalStress.
struct VerticalStressPeak {
    double x_m = 0.0;
    double sigma_z_pa = 0.0;
    double step_m = 0.0;
};
VerticalStressPeak verticalStressPeak(const StressPropagation& propagation, double y_m, double z_m,
                                      int scan_points = 25);

/// The largest σ_z over x at (y', z) near a known peak at a neighbouring y (the cells across a
/// wheel's width, docs/field.md F13): the vertex of the parabola through the peak's x and x ± a
/// quarter of its scan step; where that does not hold (values not concave, vertex beyond ±d),
/// Brent's method within x ± the step, and the full scan when its maximum is at that bracket's
/// edge.
double maxVerticalStressNear(const StressPropagation& propagation, const VerticalStressPeak& peak,
                             double y_m, double z_m);

/// The same search from a guess of the peak (the last passage's, docs/field.md F16), returning
/// where the peak is, its value and the guess's step; the full scan (verticalStressPeak) when the
/// maximum lies beyond the guess ± its step.
VerticalStressPeak verticalStressPeakNear(const StressPropagation& propagation,
                                          const VerticalStressPeak& guess, double y_m, double z_m);

/// An upper bound of σ_z anywhere on the plane at depth z [Pa]: (ν Σ|F_z| + ν(ν − 2) Σ|F_h|) /
/// (2π (z − z_deepest)²), from C1–C2 with cos ϑ ≤ 1 and R ≥ z − z_deepest. The red-zone search
/// skips depths it proves green.
double verticalStressBound(const StressPropagation& propagation, double z_m);

}  // namespace terra::compaction
