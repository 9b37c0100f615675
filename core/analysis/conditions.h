#pragma once
/// @file conditions.h
/// The operating conditions every analysis of a project shares (thesis Table 2.6): the wheel load,
/// the slip angles of the sweeps, the slip grid and the contact model, with their field table
/// (core/common/field.h) and their JSON form ("conditions" of a .terra file or a run script).

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "core/common/field.h"
#include "core/common/issue.h"
#include "core/contact/operating_fields.h"
#include "core/contact/sinkage.h"
#include "core/io/json_reader.h"

namespace terra::analysis {

/// Operating conditions shared by the analyses; the defaults are Table 2.6's.
struct OperatingConditions {
    double load_n = contact::kDefaultLoadN;                      ///< W [N] (6 kg)
    std::vector<double> slip_angles_deg{5, 10, 15, 20, 25, 30};  ///< β of the sweeps [deg]
    int slip_count = 100;                                        ///< slips 0 … slip_max
    double slip_max = 0.99;                                      ///< largest slip [-]
    bool quadratic = false;  ///< closed-form model (Eqs. 2.36–2.38) instead of the full one

    contact::ContactModel model() const {
        return quadratic ? contact::ContactModel::kQuadratic : contact::ContactModel::kFull;
    }
    /// The slip grid: slip_count values from 0 to slip_max.
    std::vector<double> slips() const;
    bool operator==(const OperatingConditions&) const = default;
};

/// "slip_angles_deg": each slip angle of the sweeps (contact::slipAngleField()'s range).
const FieldInfo& slipAnglesField();
/// "slip_max": the largest slip of the sweeps, in (0, 1).
const FieldInfo& slipMaxField();
/// "slip_count": points of the slip grid, a whole number in [2, 10000].
const FieldInfo& slipCountField();
/// Every field of the conditions, in file order: load_N, slip_angles_deg (each value),
/// slip_count, slip_max (model is a choice: full or quadratic).
std::span<const FieldInfo* const> conditionsFields();

/// Reads the keys present in `r` over `out` (absent keys keep their value), each checked.
void readConditions(io::ObjectReader& r, OperatingConditions& out);
/// The JSON form: load_N, slip_angles_deg, slip_count, slip_max, model.
nlohmann::json toJson(const OperatingConditions& conditions);
/// Every out-of-range value ("conditions.load_N"), for conditions built in code.
std::vector<Issue> validate(const OperatingConditions& conditions,
                            const std::string& prefix = "conditions.");

}  // namespace terra::analysis
