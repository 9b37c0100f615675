#pragma once
/// @file parameters.h
/// The parameters that the full-model identification estimates, θ = (a₀, a₁, K_s, n, c, φ, K)
/// (thesis Eqs. 2.9, 2.17, 2.18, 2.20, 2.21) and the shear limit j_max (Eq. 2.16; held at a value,
/// +inf for none, unless identified), their names and user units — the one field table of the
/// identified parameters (issue 26: one key, unit, symbol and factor each, the old keys read as
/// deprecated aliases) — bounds, the solver's coordinates, and Gaussian priors.

#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/field.h"
#include "core/common/issue.h"
#include "core/identification/decoupled_fit.h"
#include "core/identification/parameter_text.h"
#include "core/soil/soil_parameters.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::identification {

/// The parameters, in this order everywhere (arrays of kFullParameterCount).
enum FullParameter { kA0, kA1, kKs, kN, kC, kPhi, kK, kJmax, kFullParameterCount };

/// The parameters the model differentiates exactly (ceres::Jet): all but j_max, whose column is
/// a central difference (the contact model takes j_max as a plain double: it moves where the
/// integrand has a kink, contact_parameters.h).
constexpr int kJetParameterCount = kJmax;

/// Parameter values in SI: a₀ [-], a₁ [-], K_s [Pa/m^n], n [-], c [Pa], φ [rad], K [m],
/// j_max [m] (+inf: no limit).
using ParameterVector = std::array<double, kFullParameterCount>;

/// One identified parameter as it is shown and entered (files, flags, screen, JSON): its key
/// with the unit in it ("Ks_kPa"), unit, symbol, label, tooltip, range in the user's unit and the
/// factor to SI, stored in its member of DecoupledParameters (SI).
using ParameterField = Field<DecoupledParameters>;

/// THE table of the identified parameters, written once (parameters.cpp): a0, a1, Ks_kPa, n0,
/// n1, c_kPa, phi_deg, K_m, jmax_m — the decoupled model's eight (n = n₀ + n₁ s) and j_max. The
/// identification's tables and JSON, the command line's `--prior`/`--fix`, the settings readers,
/// the studio's tables and figures, the solver's messages (parameterInfo) all read it.
std::span<const ParameterField> parameterFields();

/// A key that named a parameter before issue 26 (identification's first table: "Ks" for K_s in
/// kPa/m^n, "n" for the constant exponent) and the key that replaces it. Still read everywhere a
/// parameter is named, with a deprecation note naming the new key.
struct DeprecatedParameterKey {
    const char* old_key;  ///< "Ks"
    const char* key;      ///< "Ks_kPa"
};
/// The deprecated keys: Ks → Ks_kPa, n → n0.
std::span<const DeprecatedParameterKey> deprecatedParameterKeys();

/// A parameter named by a key (the table's or a deprecated one).
struct ParameterLookup {
    const ParameterField* field = nullptr;  ///< nullptr: no parameter has this key
    bool deprecated = false;                ///< the key is an old one (deprecationNote says so)
    explicit operator bool() const { return field != nullptr; }
};
/// The key a field had before issue 26 ("Ks" for Ks_kPa, "n" for n0; the field's key for the
/// others): the keys of outputs that scripts read and that keep them (`validate --json`'s
/// "calibration.parameters" and its parameters table).
const char* oldKeyOf(const ParameterField& field);
/// The parameter of a key, the old keys included.
ParameterLookup lookupParameter(std::string_view key);
/// The field with this key (the table's keys only), or nullptr.
const ParameterField* findParameterField(std::string_view key);
/// "parameter key 'Ks' is deprecated: use 'Ks_kPa'" for an old key.
std::string deprecationNote(std::string_view old_key);
/// "unknown parameter 'Kss' (did you mean 'Ks_kPa'?); allowed: a0, a1, …" over the keys of
/// `allowed` (the table's keys; the old keys are tried for the suggestion too).
std::string unknownParameterMessage(std::string_view key, const std::vector<std::string>& allowed);
/// The keys of the refined parameters (FullParameter order): a0, a1, Ks_kPa, n0, c_kPa, phi_deg,
/// K_m, jmax_m.
std::vector<std::string> fullParameterKeys();

/// The field of a parameter of the full model (its n is n0; n1 is not refined).
const ParameterField& fieldOf(FullParameter parameter);
/// The full model's parameter of a field; empty for n1 (not refined).
std::optional<FullParameter> fullParameterOf(const ParameterField& field);
/// The field of a member of DecoupledParameters (&DecoupledParameters::n1 → n1's).
const ParameterField& fieldOf(double DecoupledParameters::*member);

/// The soil file key of the field that carries a parameter in a soil made from it (soilOf, with
/// k_c = 0): "kphi" for K_s, "n" for n₀; every other parameter's key is the soil's own.
const char* soilKeyOf(const ParameterField& field);
/// The parameter a soil file key carries (soilKeyOf's inverse), or nullptr.
const ParameterField* parameterOfSoilKey(std::string_view soil_key);

/// "{Ks_kPa}": how a ParameterText (parameter_text.h) names a parameter, worded as its key or
/// symbol by the renderer.
std::string reference(FullParameter parameter);
std::string reference(double DecoupledParameters::*member);

/// How the solver names a parameter in its messages and converts it: a view of parameterFields()
/// in FullParameter order (name = the field's key, to_user = 1 / to_si).
struct ParameterInfo {
    const char* name;    ///< the field's key: "a0", "a1", "Ks_kPa", "n0", "c_kPa", "phi_deg", …
    const char* unit;    ///< user unit: "-", "-", "kPa/m^n", "-", "kPa", "deg", "m", "m"
    const char* symbol;  ///< "a₀", "a₁", "K_s", "n₀", "c", "φ", "K", "j_max"
    double to_user;      ///< user value = SI value × to_user
};

/// The eight refined parameters, in FullParameter order, generated from parameterFields().
const std::array<ParameterInfo, kFullParameterCount>& parameterInfo();

/// The index of the parameter with this key ("phi_deg"; an old key too), or nullopt.
std::optional<FullParameter> findParameter(const std::string& name);

/// Box bounds of the estimate, SI. The defaults are wide enough for every preset in resources/soils
/// (K_s 0.10–6.2 MPa/m^n, n 0.11–1.6, c 1–69 kPa, φ 6–34°, K 6–30 mm) and keep the model inside
/// its domain (n > 0, K > 0, θ_m = (a₀ + a₁ s) θ_f inside the contact). j_max, when identified,
/// lies in 1 mm … 1 m: beyond the largest shear deformation of a wheel test (r (θ_f − θ_r) plus
/// the slip's share, well under 1 m) a limit changes nothing.
struct ParameterBounds {
    ParameterVector lower{0.0, -1.0, 1e4, 0.05, 0.0, 0.0, 1e-4, 1e-3};
    ParameterVector upper{1.0, 1.0, 5e7, 2.0, 2e5, 1.047, 0.5, 1.0};
};

/// The solver coordinate ln j_max that stands for "no limit" (j_max = +inf): ln(1e6 m), a limit
/// no wheel reaches, so that a held j_max = +inf is a finite coordinate (Ceres refuses non-finite
/// parameter values); toPhysical maps it (and above) back to +inf exactly.
constexpr double kNoShearLimitSolver = 13.815510557964274;

/// The solver's coordinates u: K_s, K and j_max are fitted as ln K_s, ln K, ln j_max (they span
/// decades, and σ ∝ K_s, τ depends on j/K: their valleys are straight in the logarithms), c in
/// kPa, the rest as they are. ln j_max ≥ kNoShearLimitSolver is j_max = +inf.
template <typename T>
std::array<T, kFullParameterCount> toPhysical(const T* u) {
    using std::exp;
    const T jmax = u[kJmax] >= T(kNoShearLimitSolver) ? T(std::numeric_limits<double>::infinity())
                                                      : T(exp(u[kJmax]));
    return {u[kA0], u[kA1], exp(u[kKs]), u[kN], u[kC] * 1e3, u[kPhi], exp(u[kK]), jmax};
}

/// The inverse of toPhysical.
ParameterVector toSolver(const ParameterVector& physical);

/// d(physical)/d(u) of each parameter (toPhysical is diagonal).
ParameterVector physicalPerSolver(const ParameterVector& physical);

/// The parameters of a soil on a wheel: K_s = k_c/b + k_φ (Eq. 2.9), n = n₀ (n₁ is not estimated),
/// its j_max (+inf: none) — vectorOf(decoupledOf(soil, wheel)) of soil_conversion.h.
ParameterVector fromSoil(const soil::SoilParameters& soil, const wheel::WheelParameters& wheel);

/// A Gaussian prior on one parameter, SI: the estimate is penalised by ((θ − mean)/std)².
struct GaussianPrior {
    double mean = 0.0;
    double std = 0.0;  ///< > 0
};

/// One optional prior per parameter.
using Priors = std::array<std::optional<GaussianPrior>, kFullParameterCount>;

/// The spreads of a prior built from a soil preset, each justified in docs/identification.md
/// ("Priors"): how far soils of one class differ from the preset that names the class.
struct PriorSpreads {
    double a0 = 0.1;             ///< [-] (Table 5.3–5.4 fits scatter 0.24–0.29 about 0.2)
    double a1 = 0.1;             ///< [-]
    double ks_relative = 0.5;    ///< K_s: ±50 %
    double n = 0.2;              ///< [-]
    double c_relative = 0.5;     ///< c: ±50 % of the preset's value, at least `c_floor_pa`
    double c_floor_pa = 1e3;     ///< [Pa]
    double phi_rad = 0.0872665;  ///< φ: ±5°
    double k_relative = 0.5;     ///< K: ±50 %
};

/// The prior of j_max when it is identified and the data do not determine it: 20 ± 20 mm (the
/// presets of resources/soils have 9–20 mm; the spread keeps a limit anywhere from a few mm to a
/// few cm plausible).
constexpr GaussianPrior kDefaultShearLimitPrior{0.02, 0.02};

/// Priors centred on a soil preset on this wheel with the given spreads (none on j_max).
Priors priorsFromSoil(const soil::SoilParameters& soil, const wheel::WheelParameters& wheel,
                      const PriorSpreads& spreads = {});

/// Parses one prior item in user units, "phi_deg=30±5" or "phi_deg=30+-5" (also
/// "Ks_kPa=1500±500", "c_kPa=2±1"), into `priors`. Returns the problems (unknown name with the
/// nearest key, bad number, std ≤ 0). An old key ("Ks=1500±500") is read as its new one, with
/// deprecationNote in `warnings` when given.
std::vector<Issue> parsePriorItem(const std::string& item, Priors& priors,
                                  std::vector<std::string>* warnings = nullptr);
/// The item with its key written as the table's ("Ks=1500±500" → "Ks_kPa=1500±500"); the item
/// itself when its key is current or unknown.
std::string canonicalPriorItem(const std::string& item);

}  // namespace terra::identification
