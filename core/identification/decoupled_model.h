#pragma once
/// @file decoupled_model.h
/// The linearised, decoupled wheel–soil model of the identification (thesis §4.3, Eqs. 4.1–4.18,
/// with the corrections E5 for B and E6 for F_z of docs/model.md). Each stress is replaced by a
/// "hat" that is zero at θ_r and θ_f and peaks at θ_m (Eq. 4.3), which gives
///   [F_z, F_x, M_y]ᵀ = [[A, B], [−B, A], [0, r C]] [X, Y]ᵀ,  X = r b σ_m,  Y = r b τ_m  (Eq. 4.4)
/// and, eliminating X and Y, three equations that each involve one parameter group:
///   F_x(P_I; F_z, M_y)  Eq. 4.12,   F_z(P_I, P_II; M_y)  Eq. 4.17,   M_y(P_I, P_III; F_z)
///   Eq. 4.18.
/// Templated on the scalar for Ceres' automatic differentiation. Derivation:
/// docs/identification.md.

#include <cmath>

namespace terra::identification {

/// (sin h)/h, with its Taylor series near 0 (exact to double precision below 1e-4).
template <typename T>
T sinc(const T& h) {
    using std::abs;
    using std::sin;
    if (abs(h) < 1e-4) return T(1.0) - h * h / 6.0;
    return sin(h) / h;
}

/// (cos y − cos x)/(y − x) without cancellation: −sin((x + y)/2) · sinc((y − x)/2).
template <typename T>
T cosineSlope(const T& x, const T& y) {
    using std::sin;
    return -sin(0.5 * (x + y)) * sinc(0.5 * (y - x));
}

/// (sin y − sin x)/(y − x) without cancellation: cos((x + y)/2) · sinc((y − x)/2).
template <typename T>
T sineSlope(const T& x, const T& y) {
    using std::cos;
    return cos(0.5 * (x + y)) * sinc(0.5 * (y - x));
}

/// A, B, C of Eqs. 4.5–4.7 and θ_m = (a₀ + a₁ s) θ_f (Eq. 2.18).
template <typename T>
struct HatCoefficients {
    T theta_m;
    T a;  ///< A = ∫ hat cos θ dθ = (cos θ_m − cos θ_r)/(θ_m − θ_r) + (cos θ_m − cos θ_f)/(θ_f −
          ///< θ_m)
    T b;  ///< B = ∫ hat sin θ dθ = (sin θ_m − sin θ_r)/(θ_m − θ_r) + (sin θ_m − sin θ_f)/(θ_f −
          ///< θ_m) (E5)
    T c;  ///< C = ∫ hat dθ = (θ_f − θ_r)/2
};

template <typename T>
HatCoefficients<T> hatCoefficients(const T& a0, const T& a1, double slip, double theta_f,
                                   double theta_r = 0.0) {
    const T theta_m = (a0 + a1 * slip) * theta_f;
    const T tr(theta_r), tf(theta_f);
    return {theta_m, cosineSlope(tr, theta_m) - cosineSlope(theta_m, tf),
            sineSlope(tr, theta_m) - sineSlope(theta_m, tf), T(0.5 * (theta_f - theta_r))};
}

/// |j(θ_m)| / K exponent's argument: the tangential shear deformation at θ_m (Eq. 4.2, driving form
/// with 1 − s as printed; the identification data of chapter 5 are driving).
template <typename T>
T shearAtMaxStress(const T& theta_m, double radius_m, double slip, double theta_f) {
    using std::abs;
    using std::sin;
    return abs(radius_m *
               ((theta_f - theta_m) - (1.0 - slip) * (std::sin(theta_f) - sin(theta_m))));
}

/// F_x from F_z and M_y (Eq. 4.12): (A² + B²)/(r A C) M_y − (B/A) F_z. Depends on P_I only.
template <typename T>
T decoupledDrawbarPull(const HatCoefficients<T>& h, double radius_m, double fz_n, double my_nm) {
    return (h.a * h.a + h.b * h.b) / (radius_m * h.a * h.c) * my_nm - h.b / h.a * fz_n;
}

/// F_z per unit K_s (Eq. 4.17 with E6): r b A r^N (cos θ_m − cos θ_f)^N, N = n₀ + n₁ s, so that
/// F_z = K_s · this + B M_y/(r C). F_z is linear in K_s, which the fit projects out.
/// The hat coefficients may be plain numbers (H = double) when only n₀, n₁ are differentiated.
template <typename T, typename H>
T decoupledPressureTerm(const HatCoefficients<H>& h, double radius_m, double width_m, const T& n0,
                        const T& n1, double slip, double theta_f) {
    using std::cos;
    using std::pow;
    const T exponent = n0 + n1 * slip;
    const H base = cos(h.theta_m) - std::cos(theta_f);
    return base > 0.0 ? T(radius_m * width_m * h.a * pow(radius_m * base, exponent))
                      : T(0.0);  // Eq. 4.1 per unit K_s
}

/// F_z from M_y (Eq. 4.17 with E6): r b A K_s r^N (cos θ_m − cos θ_f)^N + B M_y/(r C),
/// N = n₀ + n₁ s. Depends on P_I and P_II = {K_s, n₀, n₁}.
template <typename T>
T decoupledVerticalForce(const HatCoefficients<T>& h, double radius_m, double width_m,
                         const T& pressure_modulus, const T& n0, const T& n1, double slip,
                         double theta_f, double my_nm) {
    return pressure_modulus * decoupledPressureTerm(h, radius_m, width_m, n0, n1, slip, theta_f) +
           h.b * my_nm / (radius_m * h.c);
}

/// M_y of Eq. 4.18 split as per_cohesion · c + offset: M_y is linear in c for given φ, K (the fit
/// projects c out).
template <typename T>
struct TorqueTerms {
    T per_cohesion;  ///< ∂M_y/∂c [m³]
    T offset;        ///< M_y at c = 0 [N·m]
};

/// The two terms of Eq. 4.18: with D = 1 − exp(−|j(θ_m)|/K) (Eq. 4.15) and
/// den = 1 + B D tan φ/A, M_y = (r² C D b/den) c + r² C D F_z tan φ/(r A den). The hat
/// coefficients may be plain numbers (H = double) when only φ, K are differentiated.
template <typename T, typename H>
TorqueTerms<T> decoupledTorqueTerms(const HatCoefficients<H>& h, double radius_m, double width_m,
                                    const T& friction_angle_rad, const T& shear_modulus_m,
                                    double slip, double theta_f, double fz_n) {
    using std::exp;
    using std::tan;
    const T d = 1.0 - exp(-shearAtMaxStress(h.theta_m, radius_m, slip, theta_f) / shear_modulus_m);
    const T tan_phi = tan(friction_angle_rad);
    const T scale = radius_m * radius_m * h.c * d / (1.0 + h.b * d * tan_phi / h.a);
    return {scale * width_m, T(scale * fz_n * tan_phi / (radius_m * h.a))};
}

/// M_y from F_z (Eq. 4.18): r² C D (b c + F_z tan φ/(r A)) / (1 + B D tan φ/A),
/// D = 1 − exp(−|j(θ_m)|/K) (Eq. 4.15). Depends on P_I and P_III = {c, φ, K}.
template <typename T>
T decoupledTorque(const HatCoefficients<T>& h, double radius_m, double width_m,
                  const T& cohesion_pa, const T& friction_angle_rad, const T& shear_modulus_m,
                  double slip, double theta_f, double fz_n) {
    const TorqueTerms<T> t = decoupledTorqueTerms(h, radius_m, width_m, friction_angle_rad,
                                                  shear_modulus_m, slip, theta_f, fz_n);
    return t.per_cohesion * cohesion_pa + t.offset;
}

}  // namespace terra::identification
