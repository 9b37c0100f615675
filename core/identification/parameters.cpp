#include "core/identification/parameters.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/common/quoted.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/identification/soil_conversion.h"
#include "core/io/csv.h"

namespace terra::identification {

namespace {

ParameterField make(FieldInfo info, double DecoupledParameters::*member) {
    ParameterField field{info};
    field.member = member;
    return field;
}

// Ranges: the widest the identification can return (the bounds of the decoupled fit and the
// refinement, decoupled_fit.h and full_fit.cpp). A function's static: built on first use, so
// that another file's static initialiser may read it.
const std::array<ParameterField, 9>& parameterTable() {
    static const std::array<ParameterField, 9> fields{{
        make({"a0",
              "-",
              "a₀",
              "maximum-stress coefficient a₀",
              "a₀ of θ_m = (a₀ + a₁ s) θ_f (Eq. 2.18), identified from F_x (step I, Eq. 4.12).",
              {0.0, 1.0}},
             &DecoupledParameters::a0),
        make({"a1",
              "-",
              "a₁",
              "maximum-stress coefficient a₁",
              "a₁ of θ_m = (a₀ + a₁ s) θ_f (Eq. 2.18), identified from F_x (step I, Eq. 4.12).",
              {-1.0, 1.0}},
             &DecoupledParameters::a1),
        make(
            {"Ks_kPa",
             "kPa/m^n",
             "K_s",
             "pressure modulus",
             "K_s = k_c/b + k_φ of σ = K_s h^N (Eq. 2.9), identified from F_z (step II, Eq. 4.17), "
             "in kPa/m^n (= kN/m^(n+2)).",
             {0.0, 1e6},
             1e3},
            &DecoupledParameters::pressure_modulus),
        make({"n0",
              "-",
              "n₀",
              "sinkage exponent n₀",
              "n₀ of N = n₀ + n₁ s, identified from F_z (step II, Eq. 4.17); the refinement's "
              "constant n.",
              {0.0, 2.0}},
             &DecoupledParameters::n0),
        make({"n1",
              "-",
              "n₁",
              "slip dependence n₁",
              "n₁ of N = n₀ + n₁ s, identified from F_z (step II, Eq. 4.17); 0 after the "
              "refinement.",
              {-1.0, 1.0}},
             &DecoupledParameters::n1),
        make(
            {"c_kPa",
             "kPa",
             "c",
             "cohesion",
             "Cohesion c of τ_max = c + σ tan φ, identified from M_y (step III, Eq. 4.18), in kPa.",
             {0.0, 200.0},
             1e3},
            &DecoupledParameters::cohesion_pa),
        make({"phi_deg",
              "deg",
              "φ",
              "friction angle",
              "Friction angle φ of τ_max = c + σ tan φ, identified from M_y (step III, Eq. 4.18), "
              "in "
              "degrees.",
              {0.0, 60.0},
              units::kPi / 180.0},
             &DecoupledParameters::friction_angle_rad),
        make({"K_m",
              "m",
              "K",
              "shear deformation modulus",
              "K of τ = τ_max (1 − e^(−j/K)) (Eq. 2.20), identified from M_y (step III, Eq. 4.18), "
              "in "
              "metres.",
              {0.0, 0.5}},
             &DecoupledParameters::shear_modulus_m),
        make({"jmax_m",
              "m",
              "j_max",
              "shear deformation limit",
              "j_max of j = min(j, j_max) (Eq. 2.16), in metres: identified by `--jmax fit`, else "
              "the "
              "value the model held (+inf, null in JSON: no limit).",
              {1e-4, 1.0}},
             &DecoupledParameters::max_shear_deformation_m),
    }};
    return fields;
}

// The refinement's parameters (full_fit.h order) and their fields.
constexpr std::array<std::pair<identification::FullParameter, int>, 8> kFull{{
    {identification::kA0, 0},
    {identification::kA1, 1},
    {identification::kKs, 2},
    {identification::kN, 3},
    {identification::kC, 5},
    {identification::kPhi, 6},
    {identification::kK, 7},
    {identification::kJmax, 8},
}};

constexpr std::array<DeprecatedParameterKey, 2> kDeprecated{{{"Ks", "Ks_kPa"}, {"n", "n0"}}};

}  // namespace

std::span<const ParameterField> parameterFields() { return parameterTable(); }

std::span<const DeprecatedParameterKey> deprecatedParameterKeys() { return kDeprecated; }

const ParameterField* findParameterField(std::string_view key) {
    return findField(parameterFields(), key);
}

ParameterLookup lookupParameter(std::string_view key) {
    if (const ParameterField* field = findParameterField(key)) return {field, false};
    for (const DeprecatedParameterKey& old : kDeprecated) {
        if (key == old.old_key) return {findParameterField(old.key), true};
    }
    return {};
}

const char* oldKeyOf(const ParameterField& field) {
    for (const DeprecatedParameterKey& old : kDeprecated) {
        if (std::string_view(old.key) == field.key) return old.old_key;
    }
    return field.key;
}

std::string deprecationNote(std::string_view old_key) {
    const ParameterLookup found = lookupParameter(old_key);
    return "parameter key '" + std::string(old_key) + "' is deprecated: use '" +
           (found ? found.field->key : "?") + "'";
}

std::string unknownParameterMessage(std::string_view key, const std::vector<std::string>& allowed) {
    std::string near = nearestName(key, allowed);
    if (near.empty()) {
        // A near miss of an old key ("KS", "Ks_kpa") suggests its replacement.
        std::vector<std::string> old_keys;
        for (const DeprecatedParameterKey& old : kDeprecated) old_keys.emplace_back(old.old_key);
        const std::string near_old = nearestName(key, old_keys);
        if (!near_old.empty()) near = lookupParameter(near_old).field->key;
    }
    std::string list;
    for (const std::string& name : allowed) list += (list.empty() ? "" : ", ") + name;
    return "unknown parameter '" + std::string(key) + "'" +
           (near.empty() ? "" : " (did you mean '" + near + "'?)") + "; allowed: " + list;
}

const ParameterField& fieldOf(FullParameter parameter) {
    for (const auto& [full, index] : kFull) {
        if (full == parameter) return parameterTable()[static_cast<std::size_t>(index)];
    }
    return parameterTable()[0];
}

std::optional<FullParameter> fullParameterOf(const ParameterField& field) {
    for (const auto& [full, index] : kFull) {
        if (&parameterTable()[static_cast<std::size_t>(index)] == &field) return full;
    }
    return std::nullopt;
}

const ParameterField& fieldOf(double DecoupledParameters::*member) {
    for (const ParameterField& field : parameterTable()) {
        if (field.member == member) return field;
    }
    throw std::invalid_argument("fieldOf: not a member of the parameter table");
}

const char* soilKeyOf(const ParameterField& field) {
    if (field.member == &DecoupledParameters::pressure_modulus) return "kphi";
    if (field.member == &DecoupledParameters::n0) return "n";
    return field.key;
}

const ParameterField* parameterOfSoilKey(std::string_view soil_key) {
    for (const ParameterField& field : parameterTable()) {
        if (soil_key == soilKeyOf(field)) return &field;
    }
    return nullptr;
}

std::string reference(FullParameter parameter) {
    return ParameterText::reference(fieldOf(parameter).key);
}

std::string reference(double DecoupledParameters::*member) {
    return ParameterText::reference(fieldOf(member).key);
}

std::vector<std::string> fullParameterKeys() {
    std::vector<std::string> keys;
    for (int k = 0; k < kFullParameterCount; ++k)
        keys.emplace_back(fieldOf(static_cast<FullParameter>(k)).key);
    return keys;
}

const std::array<ParameterInfo, kFullParameterCount>& parameterInfo() {
    static const std::array<ParameterInfo, kFullParameterCount> table = [] {
        std::array<ParameterInfo, kFullParameterCount> out{};
        for (int k = 0; k < kFullParameterCount; ++k) {
            const ParameterField& field = fieldOf(static_cast<FullParameter>(k));
            out[static_cast<std::size_t>(k)] = {field.key, field.unit, field.symbol,
                                                1.0 / field.to_si};
        }
        return out;
    }();
    return table;
}

std::optional<FullParameter> findParameter(const std::string& name) {
    const ParameterLookup found = lookupParameter(name);
    return found ? fullParameterOf(*found.field) : std::nullopt;
}

ParameterVector toSolver(const ParameterVector& p) {
    const double jmax = std::min(std::log(p[kJmax]), kNoShearLimitSolver);
    return {p[kA0], p[kA1], std::log(p[kKs]), p[kN], p[kC] * 1e-3, p[kPhi], std::log(p[kK]), jmax};
}

ParameterVector physicalPerSolver(const ParameterVector& p) {
    return {1.0, 1.0, p[kKs], 1.0, 1e3, 1.0, p[kK], std::isfinite(p[kJmax]) ? p[kJmax] : 0.0};
}

ParameterVector fromSoil(const soil::SoilParameters& soil, const wheel::WheelParameters& wheel) {
    return vectorOf(decoupledOf(soil, wheel));
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

std::vector<Issue> parsePriorItem(const std::string& item, Priors& priors,
                                  std::vector<std::string>* warnings) {
    const std::string where = "prior " + quoteText(item);
    const std::size_t equals = item.find('=');
    if (equals == std::string::npos) {
        return {{where, "expected name=mean±std, e.g. phi_deg=30±5 (or 30+-5)"}};
    }
    const std::string name = item.substr(0, equals), value = item.substr(equals + 1);
    const ParameterLookup found = lookupParameter(name);
    const std::optional<FullParameter> k = found ? fullParameterOf(*found.field) : std::nullopt;
    if (!k) return {{where, unknownParameterMessage(name, fullParameterKeys())}};
    if (found.deprecated && warnings != nullptr)
        warnings->push_back(where + ": " + deprecationNote(name));
    const ParameterField& field = *found.field;
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
        checkRange(issues, where + ": std", std, {0.0, 1e12, true, false}, field.unit);
    }
    if (!issues.empty()) return issues;
    // Divided by to_user rather than multiplied by to_si: the numbers read before issue 26.
    const double to_si = 1.0 / parameterInfo()[*k].to_user;
    priors[*k] = GaussianPrior{mean * to_si, std * to_si};
    return {};
}

std::string canonicalPriorItem(const std::string& item) {
    const std::size_t equals = item.find('=');
    if (equals == std::string::npos) return item;
    const ParameterLookup found = lookupParameter(item.substr(0, equals));
    if (!found || !found.deprecated) return item;
    return found.field->key + item.substr(equals);
}

}  // namespace terra::identification
