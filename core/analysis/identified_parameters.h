#pragma once
/// @file identified_parameters.h
/// The identified soil parameters as the analyses name them: the one field table of
/// identification/parameters.h (a₀, a₁, K_s, n₀, n₁, c, φ, K, j_max with their display units,
/// kPa/m^n, kPa, deg), under the names the analysis layer has used since it was written. The
/// identification's tables, the command line's output (`identify`, JSON and text), the studio's
/// parameter table and the streaming figures read it; the solver reads the same table through
/// identification::parameterInfo (issue 26: one vocabulary, the old keys "Ks" and "n" read as
/// deprecated aliases by lookupParameter).

#include <optional>
#include <span>
#include <string_view>

#include "core/common/field.h"
#include "core/identification/decoupled_fit.h"
#include "core/identification/full_fit.h"
#include "core/identification/parameters.h"
#include "core/identification/soil_conversion.h"
#include "core/soil/soil_parameters.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::analysis {

using IdentifiedField = identification::ParameterField;

/// a0, a1, Ks_kPa, n0, n1, c_kPa, phi_deg, K_m, jmax_m (identification::parameterFields).
inline std::span<const IdentifiedField> identifiedFields() {
    return identification::parameterFields();
}
/// The field with this key (the table's keys; lookupParameter also reads the old ones), or
/// nullptr.
inline const IdentifiedField* findIdentifiedField(std::string_view key) {
    return identification::findParameterField(key);
}
/// The field of a parameter of the full-model refinement (its n is n0; n1 is not refined).
using identification::fieldOf;
/// The refinement's parameter of a field; empty for n1 (not refined).
using identification::fullParameterOf;

}  // namespace terra::analysis
