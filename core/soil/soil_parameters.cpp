#include "core/soil/soil_parameters.h"

#include <array>
#include <cmath>
#include <stdexcept>

#include "core/common/units.h"

namespace terra::soil {
namespace {

constexpr double kDeg = units::kPi / 180.0;

// Ranges are physical bounds wide enough for every soil in Wong's tables, narrow enough to catch
// a unit mistake (a friction angle in radians, a cohesion in Pa where kPa is expected).
SoilField make(FieldInfo info, double SoilParameters::*member, bool required = true) {
    SoilField field{info};
    field.member = member;
    field.required = required;
    return field;
}

const std::array<SoilField, 12> kFields{{
    make({"n",
          "-",
          "n",
          "sinkage exponent",
          "Sinkage exponent n of Bekker's law σ = (k_c/b + k_φ) h^n (Eq. 2.3); with n₁ ≠ 0 it is "
          "n₀ of N = n₀ + n₁ s. Dimensionless.",
          {0.1, 2.0}},
         &SoilParameters::sinkage_exponent),
    make({"c_kPa",
          "kPa",
          "c",
          "cohesion",
          "Cohesion c of the Mohr–Coulomb shear strength τ_max = c + σ tan φ (Eqs. 2.20, 2.21), "
          "in kPa.",
          {0.0, 200.0},
          1e3},
         &SoilParameters::cohesion_pa),
    make({"phi_deg",
          "deg",
          "φ",
          "friction angle",
          "Internal friction angle φ of the Mohr–Coulomb shear strength τ_max = c + σ tan φ "
          "(Eq. 2.21), in degrees.",
          {0.0, 60.0, false, true},
          kDeg},
         &SoilParameters::friction_angle_rad),
    make({"kc",
          "kN/m^(n+1)",
          "k_c",
          "cohesive modulus",
          "Cohesive modulus k_c of Bekker's law σ = (k_c/b + k_φ) h^n (Eq. 2.3), in kN/m^(n+1); "
          "may be negative when k_φ outweighs it.",
          {-500.0, 5000.0},
          1e3},
         &SoilParameters::cohesive_modulus),
    make({"kphi",
          "kN/m^(n+2)",
          "k_φ",
          "frictional modulus",
          "Frictional modulus k_φ of Bekker's law σ = (k_c/b + k_φ) h^n (Eq. 2.3), in "
          "kN/m^(n+2).",
          {0.0, 1e5},
          1e3},
         &SoilParameters::frictional_modulus),
    make({"K_m",
          "m",
          "K",
          "shear deformation modulus",
          "Shear deformation modulus K of Janosi–Hanamoto's τ = τ_max (1 − e^(−j/K)) (Eq. 2.20), "
          "in metres.",
          {1e-4, 0.5}},
         &SoilParameters::shear_modulus_m),
    make({"gamma_kN_m3",
          "kN/m³",
          "γ",
          "specific weight",
          "Specific weight γ of the soil, used by the bulldozing resistance (Eq. 2.27), in "
          "kN/m³.",
          {0.5, 30.0},
          1e3},
         &SoilParameters::unit_weight_n_m3),
    make({"a0",
          "-",
          "a₀",
          "maximum-stress coefficient a₀",
          "a₀ of the angle of maximum stress θ_m = (a₀ + a₁ s) θ_f (Eq. 2.18). Dimensionless.",
          {0.0, 1.0}},
         &SoilParameters::max_stress_a0, false),
    make({"a1",
          "-",
          "a₁",
          "maximum-stress coefficient a₁",
          "a₁ of the angle of maximum stress θ_m = (a₀ + a₁ s) θ_f (Eq. 2.18). Dimensionless.",
          {-1.0, 1.0}},
         &SoilParameters::max_stress_a1, false),
    make({"jmax_m",
          "m",
          "j_max",
          "shear deformation limit",
          "Largest shear deformation j_max a smooth wheel builds up (Eq. 2.16), in metres; "
          "absent: no limit.",
          {1e-4, 1.0}},
         &SoilParameters::max_shear_deformation_m, false),
    make({"n1",
          "-",
          "n₁",
          "slip dependence of n",
          "n₁ of the slip-dependent sinkage exponent N = n₀ + n₁ s (Ding; the thesis's Eqs. 4.1, "
          "4.17); 0 keeps n constant. Dimensionless.",
          {-1.0, 1.0}},
         &SoilParameters::sinkage_exponent_slip, false),
    make({"slip_sinkage",
          "-",
          "S",
          "slip-sinkage coefficient",
          "S of Lyasko's slip sinkage h = h₀ (1 + S s) at driving slip s, h₀ the sinkage of Eq. "
          "2.12 (docs/model.md, Eq. S.1): the wheel digs itself in below h₀. Changes the sinkage "
          "only, not the forces; 0 (absent) is the thesis model. Dimensionless.",
          {0.0, 10.0}},
         &SoilParameters::slip_sinkage_coefficient, false),
}};

}  // namespace

std::span<const SoilField> soilFields() { return kFields; }

const SoilField* findSoilField(const std::string& key) { return findField(soilFields(), key); }

double userValue(const SoilParameters& soil, const SoilField& field) {
    return field.userValue(soil);
}

void setUserValue(SoilParameters& soil, const SoilField& field, double value) {
    field.setUserValue(soil, value);
}

std::vector<Issue> validate(const SoilParameters& soil, const std::string& prefix) {
    std::vector<Issue> issues;
    bool ok = true;
    for (const SoilField& field : kFields) {
        const double value = userValue(soil, field);
        // An optional limit left at +inf means "no limit" (j_max), not an error.
        if (!field.required && std::isinf(value) && value > 0 &&
            field.member == &SoilParameters::max_shear_deformation_m) {
            continue;
        }
        ok = checkRange(issues, prefix + field.key, value, field.range, field.displayUnit()) && ok;
    }
    // N = n0 + n1 s is linear in s, so it stays in n's range over the whole slip range s ∈ [−1, 1]
    // (braking included) when it does at both ends, n0 − n1 and n0 + n1. Checked only when n0 and
    // n1 themselves are valid, so one mistake gives one message.
    // Rounded like the user's numbers: n = 0.6, n1 = 0.5 gives N = 0.1, not 0.09999999999999998.
    const double n_braking = roundSignificant(soil.sinkage_exponent - soil.sinkage_exponent_slip);
    const double n_driving = roundSignificant(soil.sinkage_exponent + soil.sinkage_exponent_slip);
    const Range& n_range = kFields[0].range;
    if (ok && (!n_range.contains(n_braking) || !n_range.contains(n_driving))) {
        issues.push_back(
            {prefix + "n1",
             "N = n + n1·s must stay in the allowed range " + n_range.describe() +
                 " for every slip s in [-1, 1], but n - n1 = " + formatNumber(n_braking) +
                 " (s → -1) and n + n1 = " + formatNumber(n_driving) + " (s → 1)"});
    }
    return issues;
}

void requireValid(const SoilParameters& soil) {
    const std::vector<Issue> issues = validate(soil, "soil.");
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
}

}  // namespace terra::soil
