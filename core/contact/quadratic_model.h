#pragma once
/// @file quadratic_model.h
/// The quadratic stress approximation and its closed-form forces (thesis section 2.5,
/// Eqs. 2.36–2.46, with the corrections E3, E3b, E3c, E4 of docs/model.md). Each stress p ∈
/// {σ, τ, τ_t, τ_l} is replaced on each region by the parabola through its values at θ_m, at the
/// region's mid angle (Eq. 2.36) and at the region's end (θ_f or θ_r): an exact 3-point
/// interpolation (E4). The polynomials are written in x = θ − θ_m, which is better conditioned than
/// the thesis's powers of θ and gives the same parabola; the antiderivatives of x^k sin θ and
/// x^k cos θ are derived in docs/model.md.

#include <array>
#include <cmath>

#include "core/contact/bulldozing.h"
#include "core/contact/stress_field.h"
#include "core/contact/wheel_forces.h"

namespace terra::contact {

/// p(θ) = a x² + b x + c with x = θ − θ_m.
template <typename T>
struct Parabola {
    T a{}, b{}, c{};
    T operator()(const T& x) const { return (a * x + b) * x + c; }
};

/// The parabolas of the four stresses over one region (front [θ_m, θ_f] or rear [θ_r, θ_m]).
template <typename T>
struct QuadraticRegion {
    T lower;  ///< ˡθ_i [rad]
    T upper;  ///< ᵘθ_i [rad]
    Parabola<T> sigma, tau, tau_t, tau_l;
    /// sin and cos of the bounds and of the origin of x, as the fit computed them for its stress
    /// samples (the forces' integrals need them again); absent, they are computed.
    bool has_trig = false;
    T sin_lower{}, cos_lower{}, sin_upper{}, cos_upper{}, sin_origin{}, cos_origin{};
};

/// The quadratic approximation of the whole contact.
template <typename T>
struct QuadraticStress {
    T max_stress_angle;  ///< θ_m [rad], the origin of x
    QuadraticRegion<T> front;
    QuadraticRegion<T> rear;

    /// The approximated stresses at θ (σ, τ, τ_t, τ_l set; shear deformations left at zero).
    StressSample<T> at(const T& theta) const {
        const QuadraticRegion<T>& region = theta >= max_stress_angle ? front : rear;
        const T x = theta - max_stress_angle;
        return {region.sigma(x), region.tau(x), region.tau_t(x), region.tau_l(x), T(0), T(0), T(0)};
    }
};

namespace detail {

// The parabola through (0, p0), (h/2, p_mid), (h, p_end); h = 0 gives the constant p0.
template <typename T>
Parabola<T> interpolate(const T& h, const T& p0, const T& p_mid, const T& p_end) {
    if (h == 0.0) return {T(0), T(0), p0};
    const T a = 2.0 * (p_end - 2.0 * p_mid + p0) / (h * h);
    const T b = (4.0 * p_mid - 3.0 * p0 - p_end) / h;
    return {a, b, p0};
}

// A contact angle with its sine, cosine and stresses (computed once for the fit and the
// integrals).
template <typename T>
struct Node {
    T theta, sin, cos;
    StressSample<T> stress;
};

template <typename T>
Node<T> nodeAt(const StressField<T>& field, const T& theta) {
    using std::cos;
    using std::sin;
    Node<T> node{theta, sin(theta), cos(theta), {}};
    node.stress = field.at(theta, node.sin, node.cos);  // = field.at(θ)
    return node;
}

// The region from `start` (the origin of x: θ_m, or a kink) to θ_end; the node at θ_end is also
// given to `at_end` when asked (the next region's start).
template <typename T>
QuadraticRegion<T> fitRegion(const StressField<T>& field, const Node<T>& start, const T& theta_end,
                             Node<T>* at_end = nullptr) {
    const T h = theta_end - start.theta;
    const StressSample<T> mid = field.at(start.theta + 0.5 * h);  // θ_fm or θ_rm, Eq. 2.36
    const Node<T> end = nodeAt(field, theta_end);
    if (at_end) *at_end = end;
    const Node<T>& lower = h >= 0.0 ? start : end;
    const Node<T>& upper = h >= 0.0 ? end : start;
    QuadraticRegion<T> region;
    region.lower = lower.theta;
    region.upper = upper.theta;
    region.has_trig = true;
    region.sin_lower = lower.sin, region.cos_lower = lower.cos;
    region.sin_upper = upper.sin, region.cos_upper = upper.cos;
    region.sin_origin = start.sin, region.cos_origin = start.cos;
    const StressSample<T>& a = start.stress;
    const StressSample<T>& e = end.stress;
    region.sigma = interpolate(h, a.sigma, mid.sigma, e.sigma);
    region.tau = interpolate(h, a.tau, mid.tau, e.tau);
    region.tau_t = interpolate(h, a.tau_t, mid.tau_t, e.tau_t);
    region.tau_l = interpolate(h, a.tau_l, mid.tau_l, e.tau_l);
    return region;
}

// Antiderivatives at x (θ = θ_m + x, with sin θ, cos θ given):
//   ∫ p cos θ dx = (p − 2a) sin θ + (2a x + b) cos θ
//   ∫ p sin θ dx = −(p − 2a) cos θ + (2a x + b) sin θ
//   ∫ p dx       = a x³/3 + b x²/2 + c x
template <typename T>
T integralCos(const Parabola<T>& p, const T& x, const T& s, const T& c) {
    return (p(x) - 2.0 * p.a) * s + (2.0 * p.a * x + p.b) * c;
}
template <typename T>
T integralSin(const Parabola<T>& p, const T& x, const T& s, const T& c) {
    return -(p(x) - 2.0 * p.a) * c + (2.0 * p.a * x + p.b) * s;
}
template <typename T>
T integralOne(const Parabola<T>& p, const T& x) {
    return ((p.a / 3.0 * x + p.b / 2.0) * x + p.c) * x;
}

// ∫_0^t x^k cos x dx and ∫_0^t x^k sin x dx for k = 0, 1, 2, by their Taylor series
//   Σ_j (−1)^j t^(2j+k+1) / ((2j)! (2j+k+1)),   Σ_j (−1)^j t^(2j+k+2) / ((2j+1)! (2j+k+2)),
// for |t| ≤ kSeriesBelow: 8 terms leave < 1e-20 relative, and the terms fall so fast that the sum
// does not cancel.
template <typename T>
struct TrigMoments {
    T cos_moment[3];
    T sin_moment[3];
};

inline constexpr double kSeriesBelow = 0.3;  // [rad]

template <typename T>
TrigMoments<T> trigMoments(const T& t) {
    constexpr int kTerms = 8;
    TrigMoments<T> m{};
    for (int k = 0; k < 3; ++k) m.cos_moment[k] = m.sin_moment[k] = T(0.0);
    if (t == 0.0) return m;  // the θ_m end of every region
    const T t2 = t * t;
    T power = t;                // t^(2j+1)
    double even_factorial = 1;  // (2j)!
    for (int j = 0; j < kTerms; ++j) {
        const double odd_factorial = even_factorial * (2 * j + 1);  // (2j+1)!
        const double sign = j % 2 == 0 ? 1.0 : -1.0;
        T tk = power;  // t^(2j+1+k)
        for (int k = 0; k < 3; ++k) {
            m.cos_moment[k] += tk * (sign / (even_factorial * (2 * j + k + 1)));
            m.sin_moment[k] += tk * t * (sign / (odd_factorial * (2 * j + k + 2)));
            tk *= t;
        }
        power *= t2;
        even_factorial = odd_factorial * (2 * j + 2);
    }
    return m;
}

// Adds ∫ over [x0, x1] of one region (upper minus lower: E3); θ_m is the region's origin of x.
template <typename T>
void addRegion(const QuadraticRegion<T>& q, const T& theta_m, ForceSums<T>& sums) {
    using std::cos;
    using std::sin;
    if (!(q.upper > q.lower)) return;
    const T x0 = q.lower - theta_m;
    const T x1 = q.upper - theta_m;
    sums.fy += integralOne(q.tau_l, x1) - integralOne(q.tau_l, x0);  // Eq. 2.42 (E3b)
    sums.my += integralOne(q.tau_t, x1) - integralOne(q.tau_t, x0);  // Eq. 2.45 (E3c)
    if (q.upper - q.lower < kSeriesBelow) {
        // Narrow region: the antiderivatives below hold terms of size a ~ Δ²p/h² that cancel to
        // O(a h³), losing ~eps/h² relative (1e-4 at h = 1e-6 rad). With θ = θ_m + x,
        // ∫ p cos θ = cos θ_m Σ p_k C_k − sin θ_m Σ p_k S_k and ∫ p sin θ = sin θ_m Σ p_k C_k +
        // cos θ_m Σ p_k S_k, where C_k, S_k are the moments ∫ x^k cos x, ∫ x^k sin x over [x0, x1]
        // (one end is x = 0), whose series have no cancellation.
        const TrigMoments<T> m1 = trigMoments(x1), m0 = trigMoments(x0);
        const T sm = q.has_trig ? q.sin_origin : T(sin(theta_m));
        const T cm = q.has_trig ? q.cos_origin : T(cos(theta_m));
        auto moments = [&](const Parabola<T>& p, T& with_cos, T& with_sin) {
            const T coefficient[3] = {p.c, p.b, p.a};
            T c_sum(0.0), s_sum(0.0);
            for (int k = 0; k < 3; ++k) {
                c_sum += coefficient[k] * (m1.cos_moment[k] - m0.cos_moment[k]);
                s_sum += coefficient[k] * (m1.sin_moment[k] - m0.sin_moment[k]);
            }
            with_cos = cm * c_sum - sm * s_sum;  // ∫ p cos θ dx
            with_sin = sm * c_sum + cm * s_sum;  // ∫ p sin θ dx
        };
        T sigma_cos, sigma_sin, tau_t_cos, tau_t_sin, tau_l_cos, tau_l_sin;
        moments(q.sigma, sigma_cos, sigma_sin);
        moments(q.tau_t, tau_t_cos, tau_t_sin);
        moments(q.tau_l, tau_l_cos, tau_l_sin);
        sums.fx += tau_t_cos - sigma_sin;
        sums.fz += sigma_cos + tau_t_sin;
        sums.mx += tau_l_cos;
        sums.mz += tau_l_sin;
        return;
    }
    const T s0 = q.has_trig ? q.sin_lower : T(sin(q.lower));
    const T c0 = q.has_trig ? q.cos_lower : T(cos(q.lower));
    const T s1 = q.has_trig ? q.sin_upper : T(sin(q.upper));
    const T c1 = q.has_trig ? q.cos_upper : T(cos(q.upper));
    auto cosInt = [&](const Parabola<T>& p) {
        return integralCos(p, x1, s1, c1) - integralCos(p, x0, s0, c0);
    };
    auto sinInt = [&](const Parabola<T>& p) {
        return integralSin(p, x1, s1, c1) - integralSin(p, x0, s0, c0);
    };
    sums.fx += cosInt(q.tau_t) - sinInt(q.sigma);  // Eq. 2.41 (E3)
    sums.fz += cosInt(q.sigma) + sinInt(q.tau_t);  // Eq. 2.43 (E3)
    sums.mx += cosInt(q.tau_l);                    // Eq. 2.44 (E3)
    sums.mz += sinInt(q.tau_l);                    // Eq. 2.46 (E3)
}

}  // namespace detail

/// Fits the parabolas of Eq. 2.37 by exact interpolation (Eq. 2.38, E4): five stress evaluations.
template <typename T>
QuadraticStress<T> fitQuadraticStress(const StressField<T>& field) {
    const detail::Node<T> m = detail::nodeAt(field, field.maxStressAngle());
    return {m.theta, detail::fitRegion(field, m, field.entryAngle()),
            detail::fitRegion(field, m, field.exitAngle())};
}

namespace detail {

// The lug model weights the shear stresses with ρ = r_s/r as the full model does (wheel_forces.h,
// evaluatePiece); the parabolas are linear in their coefficients.
template <typename T>
void weightShear(const StressField<T>& field, QuadraticRegion<T>& region) {
    const T& rho = field.shearRadiusRatio();
    for (Parabola<T>* parabola : {&region.tau_t, &region.tau_l}) {
        parabola->a *= rho, parabola->b *= rho, parabola->c *= rho;
    }
}

// One region from θ_m to its end, on a remembered track split at the reload law's kink θ_k
// (docs/model.md, "The quadratic reload branch", Q1–Q3): the parabola through θ_m, the middle
// and θ_k, then the one through θ_k, the middle and the end, each in x measured from its own start.
template <typename T>
void addRememberedRegion(const StressField<T>& field, const Node<T>& m, const T& end, double kink,
                         ForceSums<T>& sums) {
    const bool split = std::isfinite(kink) && (kink - m.theta) * (end - kink) > 0.0;
    const T k = split ? T(kink) : end;
    Node<T> at_k;  // θ_k, where the far parabola starts
    QuadraticRegion<T> near = fitRegion(field, m, k, split ? &at_k : nullptr);
    if (field.lugged()) weightShear(field, near);
    addRegion(near, m.theta, sums);
    if (!split) return;
    QuadraticRegion<T> far = fitRegion(field, at_k, end);
    if (field.lugged()) weightShear(field, far);
    addRegion(far, at_k.theta, sums);
}

}  // namespace detail

/// F̃_x, F̃_y, F̃_z, M̃_x, M̃_y, M̃_z (Eqs. 2.41–2.46 corrected) plus F_b and F_s, without numerical
/// integration. On a remembered track (ContactParameters::remembers()) σ has the reload law's kink
/// where the elastic reload meets the virgin curve (docs/compaction.md, R1): each region is then
/// split there and fitted piece by piece (docs/model.md, "The quadratic reload branch"), two
/// stress evaluations more per split region.
template <typename T>
WheelForces<T> computeQuadraticForces(const ContactParameters<T>& p, const OperatingPoint<T>& op,
                                      BulldozingModel bulldozing = BulldozingModel::kBekker) {
    const StressField<T> field(p, op);
    detail::ForceSums<T> sums;
    if (field.remembers()) {
        const detail::Node<T> m = detail::nodeAt(field, field.maxStressAngle());
        const std::array<double, 2> kinks = detail::reloadKinks(field);
        detail::addRememberedRegion(field, m, field.entryAngle(), kinks[0], sums);
        detail::addRememberedRegion(field, m, field.exitAngle(), kinks[1], sums);
        return assembleForces(p, op, sums, bulldozing);
    }
    QuadraticStress<T> q = fitQuadraticStress(field);
    if (field.lugged()) {
        detail::weightShear(field, q.front);
        detail::weightShear(field, q.rear);
    }
    detail::addRegion(q.front, q.max_stress_angle, sums);
    detail::addRegion(q.rear, q.max_stress_angle, sums);
    return assembleForces(p, op, sums, bulldozing);
}

/// RMSE and MAE of one approximated stress against the exact one (Eqs. 2.39, 2.40).
struct ApproximationError {
    double rmse = 0.0;  ///< [Pa]
    double mae = 0.0;   ///< [Pa]
};

/// Errors of σ, τ, τ_t, τ_l (in this order), over a uniform grid θ_r, θ_r + step, …, ≤ θ_f.
/// Tables 2.4–2.5 are reproduced with a 0.01° step (docs/model.md, "Tables 2.4–2.5").
std::array<ApproximationError, 4> quadraticApproximationErrors(const ContactParameters<double>& p,
                                                               const OperatingPoint<double>& op,
                                                               double step_rad);

}  // namespace terra::contact
