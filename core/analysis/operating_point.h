#pragma once
/// @file operating_point.h
/// Forces and moments of the wheel at one operating point (thesis section 2.4): the entry angle
/// given, or solved so that F_z = W (section 2.6.1). `terrastudio wheel`, one point or a CSV of
/// points.

#include <optional>
#include <string>

#include "core/analysis/analysis.h"
#include "core/contact/wheel_forces.h"

namespace terra::analysis {

struct PointSpec {
    double slip = 0.0;                      ///< s [-]
    double slip_angle_deg = 0.0;            ///< β [deg]
    std::optional<double> entry_angle_deg;  ///< θ_f given [deg] …
    std::optional<double> load_n;           ///< … or W [N] to solve θ_f from
    ModelChoices model;
    contact::ContactModel contact_model = contact::ContactModel::kFull;
};

struct PointResult {
    contact::WheelForces<double> forces;
    double entry_angle_deg = 0.0;  ///< θ_f used
    double exit_angle_deg = 0.0;   ///< θ_r used (≥ −θ_f)
    double sinkage_m = 0.0;  ///< h = r (1 − cos θ_f), × (1 + S s) with slip sinkage (Eq. S.1)
    bool solved_from_load = false;
    std::string failure;        ///< non-empty: no equilibrium, or F_z = W not reproducible
    std::string status = "ok";  ///< ok, no-equilibrium, load-not-matched
    std::string warning;        ///< non-empty: the integration hit its piece cap
};

/// Throws std::invalid_argument naming the field, value and range for a point outside the
/// model's domain, or when neither θ_f nor W is given.
PointResult evaluatePoint(const contact::ContactParameters<double>& params, const PointSpec& spec);

}  // namespace terra::analysis
