#pragma once
/// @file identified_parameters.h
/// The field table of the identified soil parameters (core/common/field.h): a₀, a₁, K_s, n₀, n₁,
/// c, φ, K, j_max with their display units (kPa/m^n, kPa, deg). The identification's tables, the
/// command line's output (`identify`, JSON and text), the studio's parameter table and the
/// streaming figures read it. (identification::parameterInfo names the same parameters for the
/// solver, in SI: two tables of one vocabulary, issue 26.)

#include <optional>
#include <span>
#include <string_view>

#include "core/common/field.h"
#include "core/identification/decoupled_fit.h"
#include "core/identification/full_fit.h"
#include "core/identification/soil_conversion.h"
#include "core/soil/soil_parameters.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::analysis {

using IdentifiedField = Field<identification::DecoupledParameters>;

/// a0, a1, Ks_kPa, n0, n1, c_kPa, phi_deg, K_m, jmax_m.
std::span<const IdentifiedField> identifiedFields();
/// The field with this key, or nullptr.
const IdentifiedField* findIdentifiedField(std::string_view key);
/// The field of a parameter of the full-model refinement (its n is n0; n1 is not refined).
const IdentifiedField& fieldOf(identification::FullParameter parameter);
/// The refinement's parameter of a field; empty for n1 (not refined).
std::optional<identification::FullParameter> fullParameterOf(const IdentifiedField& field);

}  // namespace terra::analysis
