#pragma once
/// @file field.h
/// Field tables: every user-facing number of a parameter struct described once — its file key,
/// unit, symbol, label, tooltip, allowed range and SI conversion. The JSON readers and writers,
/// the command line's tables and overrides, the studio's editors and its undo labels all read
/// the same table, so a key, a unit or a range is written in one place (soil_parameters.h,
/// wheel_parameters.h, robot.h, analysis/conditions.h, analysis/identified_parameters.h).
///
/// Ranges are kept in the user's unit: what is checked is the number the user typed (29° typed
/// is 29° checked, never 29.000000000000004°); `siRange()` gives them in SI.

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "core/common/range.h"

namespace terra {

/// The description of one numeric field.
struct FieldInfo {
    const char* key;          ///< file/JSON key, unit-suffixed where it has a unit ("phi_deg")
    const char* unit;         ///< unit shown to the user ("deg"); "-" for a pure number
    const char* symbol;       ///< literature symbol ("φ")
    const char* label;        ///< short label for editors and tables ("friction angle")
    const char* description;  ///< tooltip: meaning, equation and unit
    Range range;              ///< allowed values in the user's unit
    double to_si = 1.0;       ///< SI value = user value × to_si

    /// The unit for messages and axis labels: empty for a pure number.
    std::string displayUnit() const;
    /// "φ [deg]" (or "n" for a pure number).
    std::string symbolWithUnit() const;
    /// The allowed range in SI.
    Range siRange() const;
    /// A user value in SI.
    double toSi(double user_value) const { return user_value * to_si; }
    /// An SI value in the user's unit: the shortest decimal that converts back to the identical
    /// double, so that 29° typed reads back as 29 and fitted values round-trip exactly.
    double toUser(double si) const;
};

/// A field of struct S stored in one double member (in SI).
template <typename S>
struct Field : FieldInfo {
    double S::*member = nullptr;
    bool required = true;  ///< false: optional key, the struct's default kept when absent

    double userValue(const S& s) const { return toUser(s.*member); }
    void setUserValue(S& s, double user_value) const { s.*member = toSi(user_value); }
};

/// The field with this key in a table, or nullptr.
template <typename F>
const F* findField(std::span<const F> table, std::string_view key) {
    for (const F& field : table) {
        if (key == field.key) return &field;
    }
    return nullptr;
}

}  // namespace terra
