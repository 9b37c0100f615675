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
const std::array<SoilField, 11> kFields{{
    {"n", "-", "n", {0.1, 2.0}, 1.0, &SoilParameters::sinkage_exponent, true},
    {"c_kPa", "kPa", "c", {0.0, 200.0}, 1e3, &SoilParameters::cohesion_pa, true},
    {"phi_deg",
     "deg",
     "φ",
     {0.0, 60.0, false, true},
     kDeg,
     &SoilParameters::friction_angle_rad,
     true},
    {"kc", "kN/m^(n+1)", "k_c", {-500.0, 5000.0}, 1e3, &SoilParameters::cohesive_modulus, true},
    {"kphi", "kN/m^(n+2)", "k_φ", {0.0, 1e5}, 1e3, &SoilParameters::frictional_modulus, true},
    {"K_m", "m", "K", {0.0, 0.5, true, false}, 1.0, &SoilParameters::shear_modulus_m, true},
    {"gamma_kN_m3",
     "kN/m³",
     "γ",
     {0.0, 30.0, true, false},
     1e3,
     &SoilParameters::unit_weight_n_m3,
     true},
    {"a0", "-", "a₀", {0.0, 1.0}, 1.0, &SoilParameters::max_stress_a0, false},
    {"a1", "-", "a₁", {-1.0, 1.0}, 1.0, &SoilParameters::max_stress_a1, false},
    {"jmax_m",
     "m",
     "j_max",
     {0.0, 1.0, true, false},
     1.0,
     &SoilParameters::max_shear_deformation_m,
     false},
    {"n1", "-", "n₁", {-1.0, 1.0}, 1.0, &SoilParameters::sinkage_exponent_slip, false},
}};

}  // namespace

std::span<const SoilField> soilFields() { return kFields; }

const SoilField* findSoilField(const std::string& key) {
    for (const SoilField& field : kFields) {
        if (key == field.key) return &field;
    }
    return nullptr;
}

double userValue(const SoilParameters& soil, const SoilField& field) {
    // The shortest decimal that converts back to the identical SI double: "29" for a typed 29°
    // (not 29.000000000000004), and an exact round trip for fitted values.
    const double si = soil.*field.member;
    const double raw = si / field.to_si;
    for (int digits = 12; digits <= 17; ++digits) {
        const double candidate = roundSignificant(raw, digits);
        if (candidate * field.to_si == si) return candidate;
    }
    return raw;
}

void setUserValue(SoilParameters& soil, const SoilField& field, double value) {
    soil.*field.member = value * field.to_si;
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
        ok = checkRange(issues, prefix + field.key, value, field.range,
                        std::string(field.unit) == "-" ? "" : field.unit) &&
             ok;
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
