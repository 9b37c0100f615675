#include "core/identification/parameters.h"

#include <algorithm>
#include <cmath>

#include "core/common/quoted.h"
#include "core/common/range.h"
#include "core/io/csv.h"

namespace terra::identification {

const std::array<ParameterInfo, kFullParameterCount>& parameterInfo() {
    static const std::array<ParameterInfo, kFullParameterCount> table{{
        {"a0", "-", "a₀", 1.0},
        {"a1", "-", "a₁", 1.0},
        {"Ks", "kPa/m^n", "K_s", 1e-3},
        {"n", "-", "n", 1.0},
        {"c_kPa", "kPa", "c", 1e-3},
        {"phi_deg", "deg", "φ", 180.0 / 3.14159265358979323846},
        {"K_m", "m", "K", 1.0},
        {"jmax_m", "m", "j_max", 1.0},
    }};
    return table;
}

std::optional<FullParameter> findParameter(const std::string& name) {
    for (int k = 0; k < kFullParameterCount; ++k) {
        if (name == parameterInfo()[k].name) return static_cast<FullParameter>(k);
    }
    return std::nullopt;
}

ParameterVector toSolver(const ParameterVector& p) {
    const double jmax = std::min(std::log(p[kJmax]), kNoShearLimitSolver);
    return {p[kA0], p[kA1], std::log(p[kKs]), p[kN], p[kC] * 1e-3, p[kPhi], std::log(p[kK]), jmax};
}

ParameterVector physicalPerSolver(const ParameterVector& p) {
    return {1.0, 1.0, p[kKs], 1.0, 1e3, 1.0, p[kK], std::isfinite(p[kJmax]) ? p[kJmax] : 0.0};
}

ParameterVector fromSoil(const soil::SoilParameters& soil, const wheel::WheelParameters& wheel) {
    return {soil.max_stress_a0,
            soil.max_stress_a1,
            soil.cohesive_modulus / wheel.width_m + soil.frictional_modulus,
            soil.sinkage_exponent,
            soil.cohesion_pa,
            soil.friction_angle_rad,
            soil.shear_modulus_m,
            soil.max_shear_deformation_m};
}

Priors priorsFromSoil(const soil::SoilParameters& soil, const wheel::WheelParameters& wheel,
                      const PriorSpreads& spreads) {
    const ParameterVector p = fromSoil(soil, wheel);
    Priors priors;
    priors[kA0] = GaussianPrior{p[kA0], spreads.a0};
    priors[kA1] = GaussianPrior{p[kA1], spreads.a1};
    priors[kKs] = GaussianPrior{p[kKs], spreads.ks_relative * p[kKs]};
    priors[kN] = GaussianPrior{p[kN], spreads.n};
    priors[kC] = GaussianPrior{p[kC], std::max(spreads.c_relative * p[kC], spreads.c_floor_pa)};
    priors[kPhi] = GaussianPrior{p[kPhi], spreads.phi_rad};
    priors[kK] = GaussianPrior{p[kK], spreads.k_relative * p[kK]};
    return priors;
}

std::vector<Issue> parsePriorItem(const std::string& item, Priors& priors) {
    const std::string where = "prior " + quoteText(item);
    const std::size_t equals = item.find('=');
    if (equals == std::string::npos) {
        return {{where, "expected name=mean±std, e.g. phi_deg=30±5 (or 30+-5)"}};
    }
    const std::string name = item.substr(0, equals), value = item.substr(equals + 1);
    const std::optional<FullParameter> k = findParameter(name);
    if (!k) {
        return {{where, "unknown parameter '" + name +
                            "' (allowed: a0, a1, Ks, n, c_kPa, phi_deg, K_m, jmax_m)"}};
    }
    constexpr std::size_t width = 2;  // "±" (two bytes in UTF-8) or "+-"
    std::size_t split = value.find("±");
    if (split == std::string::npos) split = value.find("+-");
    if (split == std::string::npos) return {{where, "expected mean±std after '='"}};
    double mean = 0.0, std = 0.0;
    std::vector<Issue> issues;
    if (!io::parseNumber(value.substr(0, split), mean)) {
        issues.push_back({where, "mean '" + value.substr(0, split) + "' is not a finite number"});
    }
    if (!io::parseNumber(value.substr(split + width), std)) {
        issues.push_back({where, "std '" + value.substr(split + width) + "' is not a number"});
    } else {
        checkRange(issues, where + ": std", std, {0.0, 1e12, true, false},
                   parameterInfo()[*k].unit);
    }
    if (!issues.empty()) return issues;
    const double to_si = 1.0 / parameterInfo()[*k].to_user;
    priors[*k] = GaussianPrior{mean * to_si, std * to_si};
    return {};
}

}  // namespace terra::identification
