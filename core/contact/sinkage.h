#pragma once
/// @file sinkage.h
/// Wheel sinkage: static sinkage from the load (Eqs. 2.7, 2.8 with E2 of docs/model.md) and the
/// entry-angle estimator of section 2.6.1 — the θ_f at which F_z(θ_f) = W — solved with a
/// bracketing root finder (Boost's TOMS 748) instead of the thesis's step-until-equal loop.

#include <cmath>
#include <optional>
#include <string>

#include "core/contact/contact_parameters.h"
#include "core/contact/operating_fields.h"
#include "core/contact/wheel_forces.h"

namespace terra::contact {

/// Lyasko's slip-sinkage factor 1 + S s for driving slip s > 0, 1 when towed or braking
/// (Lyasko 2010; docs/model.md, "Slip sinkage", Eq. S.1). Exactly 1 when S = 0.
inline double slipSinkageFactor(double slip, double slip_sinkage_coefficient) {
    if (slip_sinkage_coefficient == 0.0 || !(slip > 0.0)) return 1.0;
    return 1.0 + slip_sinkage_coefficient * slip;
}

/// h [m]: the sinkage of a wheel at entry angle θ_f and slip s. h₀ = r (1 − cos θ_f) (Eq. 2.12) is
/// the load-bearing sinkage; Lyasko's slip sinkage adds the rut the slipping wheel digs below it,
/// h = h₀ (1 + S s) (Eq. S.1, slipSinkageFactor()). S = 0 (the thesis model) returns h₀ exactly.
inline double slipSinkage(double radius_m, double entry_angle_rad, double slip,
                          double slip_sinkage_coefficient) {
    const double h0 = radius_m * (1.0 - std::cos(entry_angle_rad));
    if (slip_sinkage_coefficient == 0.0) return h0;
    return h0 * slipSinkageFactor(slip, slip_sinkage_coefficient);
}

/// Which force model computes F_z.
enum class ContactModel {
    kFull,       ///< numerical integration of the exact stresses (wheel_forces.h)
    kQuadratic,  ///< closed form of the quadratic approximation (quadratic_model.h), as the thesis
};

/// Which part of the static contact Eq. 2.7 integrates over.
enum class StaticContact {
    kSymmetric,  ///< −θ_s..θ_s, as printed in Eq. 2.7
    kFrontHalf,  ///< 0..θ_s, the assumption behind Bekker's formula 2.8 (E2)
};

/// h [m] by Bekker's approximation, Eq. 2.8 corrected (E2):
/// h = [W / (√(2r) b K_s (1 − n/3))]^(1/(n + 1/2)). Valid for moderate sinkage (h ≤ r/3).
double bekkerStaticSinkage(const ContactParameters<double>& p, double load_n);

/// W [N] that holds a towed wheel at static contact angle θ_s (Eq. 2.7):
/// W = r b K_s r^n ∫ (cos θ − cos θ_s)^n cos θ dθ over the chosen contact.
double staticLoad(const ContactParameters<double>& p, double static_angle_rad,
                  StaticContact contact = StaticContact::kSymmetric);

/// Outcome of a sinkage or entry-angle solve.
struct SinkageSolution {
    enum class Status {
        kConverged,      ///< F_z = W to the solver tolerance
        kNoEquilibrium,  ///< even θ_f = 90° (sunk to the axle) does not carry W
        /// The bracket shrank to a few ulps but |F_z − W| > 1e-9 W there: F_z jumps (a tiny
        /// sinkage exponent N with θ_m fixed near θ_f); the message gives both values.
        kLoadNotMatched,
    };
    Status status = Status::kConverged;
    double entry_angle_rad = 0.0;  ///< θ_f (or θ_s for static sinkage) [rad]
    double exit_angle_rad = 0.0;   ///< θ_r [rad]
    /// h [m]: r (1 − cos θ_f) (Eq. 2.12); for an entry-angle solve with slip sinkage on,
    /// slipSinkage() (Eq. S.1)
    double sinkage_m = 0.0;
    double vertical_force_n = 0.0;  ///< F_z at the solution [N]
    int evaluations = 0;            ///< model evaluations spent
    std::string message;            ///< why it failed, for the user

    bool ok() const { return status == Status::kConverged; }
};

/// θ_s and h_s of a towed static wheel from Eq. 2.7. kNoEquilibrium when W > staticLoad(90°).
SinkageSolution solveStaticSinkage(const ContactParameters<double>& p, double load_n,
                                   StaticContact contact = StaticContact::kSymmetric);

/// The exit angle: given directly, or from the rut ratio λ = h_r/h_f (Eq. 2.12).
struct ExitCondition {
    enum class Kind { kAngle, kRutRatio };
    Kind kind = Kind::kAngle;
    double value = 0.0;  ///< θ_r [rad] (≤ 0) or λ ∈ [0, 1]

    double exitAngle(double entry_angle_rad) const;
};

/// The entry-angle problem of section 2.6.1.
struct EntryAngleProblem {
    double load_n = kDefaultLoadN;               ///< W [N]
    double slip = 0.0;                           ///< s [-]
    double slip_angle_rad = 0.0;                 ///< β [rad]
    ExitCondition exit;                          ///< θ_r or λ
    std::optional<double> max_stress_angle_rad;  ///< fixed θ_m; empty: Eq. 2.18
    ContactModel model = ContactModel::kFull;
    IntegrationOptions integration;  ///< for the full model
    /// A nearby solution (the previous point of a sweep): the bracket starts around it.
    std::optional<double> initial_guess_rad;
};

/// The operating point of a problem at entry angle θ_f.
OperatingPoint<double> operatingPoint(const EntryAngleProblem& problem, double entry_angle_rad);

/// F_z [N] of the chosen model at one entry angle.
double verticalForce(const ContactParameters<double>& p, const EntryAngleProblem& problem,
                     double entry_angle_rad);

/// Solves F_z(θ_f) = W on (0, 90°] to |F_z − W| ≤ 1e-9 W (normally ~1e-12). The bracket starts
/// around the guess (Bekker's static angle or `initial_guess_rad`). Where F_z(90°) < W, θ_f is
/// scanned in 2° steps for the first crossing (F_z can peak below 90° under strong braking);
/// without one there is no equilibrium and the result says so (no clamp). When F_z jumps over W
/// between angles a few ulps apart the status is kLoadNotMatched. Throws std::invalid_argument for
/// a non-positive load or an operating point outside the domain.
SinkageSolution solveEntryAngle(const ContactParameters<double>& p,
                                const EntryAngleProblem& problem);

}  // namespace terra::contact
