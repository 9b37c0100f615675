#pragma once
/// @file soil_parameters.h
/// Soil parameters of the wheel–soil model, in SI units (thesis Table 2.1 gives them in kPa, deg,
/// kN/m^(n+1), kN/m^(n+2), kN/m³; the conversion happens in the field table below, at the edge).

#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/common/field.h"
#include "core/common/issue.h"
#include "core/common/range.h"
#include "core/soil/soil_profile.h"

namespace terra::soil {

/// Parameters of a homogeneous deformable soil (Bekker pressure–sinkage, Janosi–Hanamoto shear).
struct SoilParameters {
    std::string name;    ///< human-readable name ("sandy loam")
    std::string source;  ///< where the values come from (paper, table)
    /// n [-]: sinkage exponent of Bekker's law σ = (k_c/b + k_φ) h^n (Eq. 2.3). When
    /// `sinkage_exponent_slip` is non-zero this is n₀ of Ding's N = n₀ + n₁ s.
    double sinkage_exponent = 0.7;
    double sinkage_exponent_slip = 0.0;  ///< n₁ [-] of N = n₀ + n₁ s (Ding [5]); 0: constant n
    double cohesion_pa = 1.7e3;          ///< c [Pa]: cohesion (Eqs. 2.20, 2.21)
    double friction_angle_rad = 0.5061;   ///< φ [rad]: internal friction angle (Eq. 2.21)
    double cohesive_modulus = 5.3e3;      ///< k_c [N/m^(n+1)] (Eq. 2.3)
    double frictional_modulus = 1.515e6;  ///< k_φ [N/m^(n+2)] (Eq. 2.3)
    double shear_modulus_m = 0.025;       ///< K [m]: shear deformation modulus (Eq. 2.20)
    double unit_weight_n_m3 = 15.2e3;     ///< γ [N/m³]: specific weight (Eq. 2.27)
    double max_stress_a0 = 0.2;           ///< a₀ [-] of θ_m = (a₀ + a₁ s) θ_f (Eq. 2.18)
    double max_stress_a1 = 0.3;           ///< a₁ [-] of Eq. 2.18
    /// j_max [m]: shear deformation limit of a smooth wheel (Eq. 2.16); +inf = no limit.
    double max_shear_deformation_m = std::numeric_limits<double>::infinity();
    /// S [-]: slip-sinkage coefficient of Lyasko's h = h₀ (1 + S s) (Lyasko 2010; docs/model.md,
    /// "Slip sinkage", Eq. S.1): the rut the slipping wheel digs below its load-bearing sinkage
    /// h₀ = r (1 − cos θ_f). It changes the reported sinkage only, never θ_f or a force. 0: off.
    double slip_sinkage_coefficient = 0.0;
    /// The layers below the surface, for compaction (soil_profile.h); empty: none given.
    std::optional<SoilProfile> profile;

    bool hasShearLimit() const {
        return max_shear_deformation_m < std::numeric_limits<double>::infinity();
    }
};

/// One user-facing field of the soil (core/common/field.h): file key, unit, symbol, label,
/// tooltip, allowed range, SI conversion. This table drives the JSON reader and writer, the
/// validation, the command-line overrides (--set) and the studio's soil editor.
using SoilField = Field<SoilParameters>;

/// The field table (n, c, φ, k_c, k_φ, K, γ, a₀, a₁, j_max, n₁, S).
std::span<const SoilField> soilFields();

/// The field of the table with this key, or nullptr.
const SoilField* findSoilField(const std::string& key);

/// The value of a field in the user's unit.
double userValue(const SoilParameters& soil, const SoilField& field);

/// Sets a field from a value in the user's unit.
void setUserValue(SoilParameters& soil, const SoilField& field, double value);

/// Every out-of-range or non-finite field, each naming the field, the value and the range.
std::vector<Issue> validate(const SoilParameters& soil, const std::string& prefix = {});

/// Throws std::invalid_argument listing every problem when `soil` is not valid (API misuse).
void requireValid(const SoilParameters& soil);

}  // namespace terra::soil
