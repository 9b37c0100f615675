#include "core/analysis/identified_parameters.h"

#include <array>

#include "core/common/units.h"

namespace terra::analysis {
namespace {

using identification::DecoupledParameters;

IdentifiedField make(FieldInfo info, double DecoupledParameters::*member) {
    IdentifiedField field{info};
    field.member = member;
    return field;
}

// Ranges: the widest the identification can return (the bounds of the decoupled fit and the
// refinement, decoupled_fit.h and full_fit.cpp).
const std::array<IdentifiedField, 9> kFields{{
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
    make({"Ks_kPa",
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
          "n₁ of N = n₀ + n₁ s, identified from F_z (step II, Eq. 4.17); 0 after the refinement.",
          {-1.0, 1.0}},
         &DecoupledParameters::n1),
    make({"c_kPa",
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
          "Friction angle φ of τ_max = c + σ tan φ, identified from M_y (step III, Eq. 4.18), in "
          "degrees.",
          {0.0, 60.0},
          units::kPi / 180.0},
         &DecoupledParameters::friction_angle_rad),
    make({"K_m",
          "m",
          "K",
          "shear deformation modulus",
          "K of τ = τ_max (1 − e^(−j/K)) (Eq. 2.20), identified from M_y (step III, Eq. 4.18), in "
          "metres.",
          {0.0, 0.5}},
         &DecoupledParameters::shear_modulus_m),
    make({"jmax_m",
          "m",
          "j_max",
          "shear deformation limit",
          "j_max of j = min(j, j_max) (Eq. 2.16), in metres: identified by `--jmax fit`, else the "
          "value the model held (+inf, null in JSON: no limit).",
          {1e-4, 1.0}},
         &DecoupledParameters::max_shear_deformation_m),
}};

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

}  // namespace

std::span<const IdentifiedField> identifiedFields() { return kFields; }

const IdentifiedField* findIdentifiedField(std::string_view key) {
    return findField(identifiedFields(), key);
}

const IdentifiedField& fieldOf(identification::FullParameter parameter) {
    for (const auto& [full, index] : kFull) {
        if (full == parameter) return kFields[static_cast<std::size_t>(index)];
    }
    return kFields[0];
}

std::optional<identification::FullParameter> fullParameterOf(const IdentifiedField& field) {
    for (const auto& [full, index] : kFull) {
        if (&kFields[static_cast<std::size_t>(index)] == &field) return full;
    }
    return std::nullopt;
}

}  // namespace terra::analysis
