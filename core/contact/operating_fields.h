#pragma once
/// @file operating_fields.h
/// The field table of the wheel's operating point (core/common/field.h): slip, slip angle, entry,
/// exit and maximum-stress angles, rut ratio and load — keys, units, symbols, tooltips and the
/// model's domain, written once for the validation of the core, the files, the command line and
/// the editors.

#include "core/common/field.h"

namespace terra::contact {

/// W [N]: the thesis's wheel load of 6 kg × 9.81 m/s² (Tables 2.6 and 5.2), the default wherever
/// a load is not given.
inline constexpr double kDefaultLoadN = 58.86;

const FieldInfo& slipField();            ///< "slip": s ∈ [−1, 1] (Eq. 2.1)
const FieldInfo& slipAngleField();       ///< "slip_angle_deg": β ∈ (−90°, 90°) (Eq. 2.2)
const FieldInfo& entryAngleField();      ///< "entry_angle_deg": θ_f ∈ (0°, 90°]
const FieldInfo& exitAngleField();       ///< "exit_angle_deg": θ_r ∈ [−90°, 0°]
const FieldInfo& maxStressAngleField();  ///< "max_stress_angle_deg": θ_m ∈ [−90°, 90°]
const FieldInfo& rutRatioField();        ///< "rut_ratio": λ = h_r/h_f ∈ [0, 1] (Eq. 2.12)
const FieldInfo& loadField();            ///< "load_N": W ∈ (0, 1e5] N

}  // namespace terra::contact
