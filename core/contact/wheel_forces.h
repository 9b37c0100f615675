#pragma once
/// @file wheel_forces.h
/// Forces and moments on a rigid wheel from the stresses of the contact (thesis Eqs. 2.23–2.35),
/// by numerical integration that is exact to ~1e-9 relative in a few dozen stress evaluations.
/// Templated on the scalar (double for simulation, ceres::Jet for identification); and, for the
/// identification's projection, the forces as linear forms in (K_s, c, K_s tan φ) in double
/// (computeLinearForces).
///
/// Integration (derivation and accuracy study in docs/model.md, "Integration"):
/// - the contact splits at θ_m into a front region [θ_m, θ_f] and a rear region [θ_r, θ_m];
/// - σ behaves like (θ_f − θ)^N at the front end and like (θ − θ_r)^N at the rear end, whose
///   derivatives are singular for N < 1. Each region is mapped from u ∈ [0, 1] with
///   θ_f − θ = L u^q (front) or θ − θ_r = L u^q (rear): the integrand becomes
///   u^(q(N+1)−1) × smooth, regular enough for Gauss quadrature to converge fast;
/// - the regions are split further at the kinks of kinks.h (j_max, braking sign changes) and at
///   graded points around narrow smooth features (findScaleSplits: the turn of the shear
///   direction near θ = 0 or ±θ* at small β, the rise of 1 − exp(−j/K) behind θ_f);
/// - each piece gets a 15-point Gauss–Kronrod rule; pieces whose Kronrod–Gauss difference exceeds
///   the tolerance are bisected, up to a cap on the pieces that is reported when hit.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "core/common/scalar.h"
#include "core/contact/bulldozing.h"
#include "core/contact/contact_parameters.h"
#include "core/contact/gauss_rule.h"
#include "core/contact/kinks.h"
#include "core/contact/stress_field.h"

namespace terra::contact {

/// Forces and moments that the soil applies to the wheel, in the wheel frame of section 2.2.1
/// (x along travel, z up, y to the left; frame steers with the wheel but does not spin).
template <typename T>
struct WheelForces {
    T fx{};  ///< F_x [N]: drawbar pull (Eq. 2.23)
    T fy{};  ///< F_y [N]: lateral force from the shear stress (Eq. 2.25)
    T fz{};  ///< F_z [N]: vertical force (Eq. 2.31)
    T mx{};  ///< M_x [N·m]: roll moment (Eq. 2.32)
    T my{};  ///< M_y [N·m]: resistance torque (Eq. 2.34)
    T mz{};  ///< M_z [N·m]: yaw moment (Eq. 2.35)
    T fb{};  ///< F_b [N]: bulldozing resistance of one side wall, a magnitude (Eq. 2.30, E1)
    T fs{};  ///< F_s [N]: side force F_y − sign(β) F_b (Eq. 2.24; docs/model.md, "Side force")
};

/// How the contact integrals are evaluated.
struct IntegrationOptions {
    /// Bound on the pieces' summed |Kronrod − Gauss| differences, relative to |F_z| + |F_x| +
    /// |M_y|/r for the in-plane integrals and to |F_y| + |M_x|/r + |M_z|/r for the lateral ones (as
    /// raw integrals; each scale at least 1e-6 of the other), so that F_y is accurate relative to
    /// itself even at tiny slip angles. The difference overestimates the Kronrod result's error by
    /// orders of magnitude (docs/model.md).
    double tolerance = 1e-7;
    /// Cap on the number of pieces (both regions, after splitting and bisection; at most 96).
    /// Hitting it is reported through IntegrationReport.
    int max_pieces = 64;
    /// Exponent q of the end mapping θ_end − θ = L u^q; 0 picks it from the sinkage exponent N
    /// (smallest q ≥ 2 with q(N + 1) − 1 ≥ 3, so the integrand is C³ at the singular end).
    int end_exponent = 0;
    /// Only the 7-point Gauss rule embedded in each piece's Kronrod rule, and no bisection: half
    /// the stress evaluations, without an error estimate. Where the adaptive rule needs no
    /// bisection (the identification's data: 2.4 pieces at a tolerance of 1e-7 as at 1e-4) the
    /// Gauss sums differ from the Kronrod ones by less than the tolerance (docs/model.md,
    /// "Integration"). For searches that a full-accuracy solve finishes (the identification's
    /// screening and descents); the tolerance and the piece cap are then unused.
    bool gauss_only = false;
};

/// How one evaluation of the contact integrals went.
struct IntegrationReport {
    int pieces = 0;         ///< Gauss–Kronrod pieces used
    bool converged = true;  ///< false: the piece cap was hit before the tolerance was met
    /// The pieces' |Kronrod − Gauss| differences relative to the scales of
    /// IntegrationOptions::tolerance, summed: a pessimistic bound on the relative error. NaN with
    /// IntegrationOptions::gauss_only (not estimated).
    double error_estimate = 0.0;
};

/// The end-mapping exponent for sinkage exponent N (see IntegrationOptions::end_exponent).
inline int endExponent(double sinkage_exponent, int requested) {
    if (requested > 0) return requested;
    const double needed = 4.0 / (std::max(sinkage_exponent, 0.05) + 1.0);
    return std::clamp(static_cast<int>(std::ceil(needed - 1e-12)), 2, 8);
}

namespace detail {

template <typename T>
struct ForceSums {
    T fx{}, fy{}, fz{}, mx{}, my{}, mz{};

    ForceSums& operator+=(const ForceSums& o) {
        fx += o.fx, fy += o.fy, fz += o.fz, mx += o.mx, my += o.my, mz += o.mz;
        return *this;
    }
};

// One region [θ_lo, θ_hi] mapped from u ∈ [0, 1]; u = 0 is the σ-singular end (θ_f for the front
// region, θ_r for the rear one).
template <typename T>
struct Region {
    T theta_lo, theta_hi, length;
    bool singular_at_hi;
    int q;

    T theta(double u, double& jacobian) const {
        double uq1 = 1.0;  // u^(q−1)
        for (int e = 1; e < q; ++e) uq1 *= u;
        jacobian = q * uq1;
        const T offset = length * (uq1 * u);
        return singular_at_hi ? T(theta_hi - offset) : T(theta_lo + offset);
    }
};

// A piece [u0, u1] of a region with its Kronrod sums and error estimates.
template <typename T, typename Sums = ForceSums<T>>
struct Piece {
    int region;
    double u0, u1;
    Sums sums;
    double error;          // max |Kronrod − Gauss| of ∫F_x, ∫F_z, ∫M_y
    double lateral_error;  // max |Kronrod − Gauss| of ∫F_y, ∫M_x, ∫M_z
};

// The stresses at node u of a region (sin θ, cos θ and dθ/du·du with them), the shear ones weighted
// for the lug model: the shear acts on the cylinder of radius r_s = ρ r (docs/model.md, "Lugs"):
// its area element is r_s b dθ, so the shear integrands carry ρ here and the moments' lever arm
// r_s the other ρ (assembleForces).
template <typename T>
struct NodeStress {
    StressSample<T> st;
    T s, c, dtheta;
};

template <typename T>
NodeStress<T> nodeStress(const StressField<T>& field, const Region<T>& region, double u,
                         double du) {
    using std::cos;
    using std::sin;
    double jacobian = 0.0;
    const T theta = region.theta(u, jacobian);
    NodeStress<T> n{{}, sin(theta), cos(theta), T(region.length * (jacobian * du))};
    n.st = field.at(theta, n.s, n.c);
    if (field.lugged()) {
        n.st.tau_t *= field.shearRadiusRatio();
        n.st.tau_l *= field.shearRadiusRatio();
    }
    return n;
}

// Integrates the six integrands over one piece with the 15-point Kronrod rule; the error is the
// largest difference to the embedded 7-point Gauss rule (on the plain values). `GaussOnly`: the
// sums of the Gauss rule alone, errors 0 (a template argument: a run-time test in this loop cost
// the default rule ~5 % of an evaluation).
template <typename T, bool GaussOnly = false>
void evaluatePiece(const StressField<T>& field, const Region<T>& region, const KronrodRule& rule,
                   Piece<T>& piece) {
    ForceSums<T> k;
    double g[6] = {0, 0, 0, 0, 0, 0};
    const double du = piece.u1 - piece.u0;
    for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
        if constexpr (GaussOnly) {
            if (rule.gauss_weights[i] == 0.0) continue;
        }
        const NodeStress<T> n = nodeStress(field, region, piece.u0 + du * rule.nodes[i], du);
        const StressSample<T>& st = n.st;
        const T& s = n.s;
        const T& c = n.c;
        const T& dtheta = n.dtheta;
        const T fx = st.tau_t * c - st.sigma * s;
        const T fz = st.sigma * c + st.tau_t * s;
        const T mx = st.tau_l * c;
        const T mz = st.tau_l * s;
        const T w = dtheta * (GaussOnly ? rule.gauss_weights[i] : rule.weights[i]);
        k.fx += w * fx, k.fz += w * fz, k.fy += w * st.tau_l;
        k.mx += w * mx, k.my += w * st.tau_t, k.mz += w * mz;
        if (!GaussOnly && rule.gauss_weights[i] != 0.0) {
            const double wg = scalarValue(dtheta) * rule.gauss_weights[i];
            g[0] += wg * scalarValue(fx), g[1] += wg * scalarValue(fz);
            g[2] += wg * scalarValue(st.tau_l), g[3] += wg * scalarValue(mx);
            g[4] += wg * scalarValue(st.tau_t), g[5] += wg * scalarValue(mz);
        }
    }
    if constexpr (GaussOnly) {
        piece.error = piece.lateral_error = 0.0;
    } else {
        piece.error =
            std::max({std::abs(scalarValue(k.fx) - g[0]), std::abs(scalarValue(k.fz) - g[1]),
                      std::abs(scalarValue(k.my) - g[4])});
        piece.lateral_error =
            std::max({std::abs(scalarValue(k.fy) - g[2]), std::abs(scalarValue(k.mx) - g[3]),
                      std::abs(scalarValue(k.mz) - g[5])});
    }
    piece.sums = k;
}

// The contact integrals as linear forms in α = (K_s, c, K_s tan φ), in which the stresses are
// linear (Eqs. 2.17, 2.20: σ = K_s σ₁, τ = (c + σ tan φ) e with σ₁ and e free of α): the sums per
// unit K_s of σ alone (`modulus`), per unit c (`cohesion`) and per unit K_s tan φ (`friction`),
// so that ForceSums = K_s modulus + c cohesion + K_s tan φ friction. docs/identification.md §9,
// "eighth pass".
struct LinearSums {
    ForceSums<double> modulus, cohesion, friction;

    LinearSums& operator+=(const LinearSums& o) {
        modulus += o.modulus, cohesion += o.cohesion, friction += o.friction;
        return *this;
    }
};

// The stress field of unit coefficients (K_s = 1, c = 1, φ = 0: σ = σ₁, τ = e) and the α at which
// the adaptive rule judges its pieces (computeLinearForces' `nominal`).
struct LinearField : StressField<double> {
    LinearField(const ContactParameters<double>& unit, const OperatingPoint<double>& op,
                const std::array<double, 3>& nominal_alpha)
        : StressField<double>(unit, op), nominal(nominal_alpha) {}
    std::array<double, 3> nominal;

    ForceSums<double> combine(const LinearSums& s) const {
        const auto one = [this](double m, double c, double f) {
            return nominal[0] * m + nominal[1] * c + nominal[2] * f;
        };
        return {one(s.modulus.fx, s.cohesion.fx, s.friction.fx),
                one(s.modulus.fy, s.cohesion.fy, s.friction.fy),
                one(s.modulus.fz, s.cohesion.fz, s.friction.fz),
                one(s.modulus.mx, s.cohesion.mx, s.friction.mx),
                one(s.modulus.my, s.cohesion.my, s.friction.my),
                one(s.modulus.mz, s.cohesion.mz, s.friction.mz)};
    }
};

// The plain values of a piece's or a total's sums: the sums' own for ForceSums, the nominal α's
// combination for LinearSums (the adaptive rule's error scale).
template <typename T>
ForceSums<double> plainSums(const StressField<T>&, const ForceSums<T>& s) {
    return {scalarValue(s.fx), scalarValue(s.fy), scalarValue(s.fz),
            scalarValue(s.mx), scalarValue(s.my), scalarValue(s.mz)};
}
inline ForceSums<double> plainSums(const LinearField& field, const LinearSums& s) {
    return field.combine(s);
}

// evaluatePiece for the linear forms: one double stress evaluation per node gives σ₁ and e (with
// the shear's direction), and the three forms follow by products; the error is that of the
// nominal α's combination, as the Jet of the same α would have it. The nodes' stresses come from
// nodeStress, as the generic evaluatePiece's. (T is double: the parameter only lets
// integrateContact's call evaluatePiece<T, true> name this overload too.)
template <typename T = double, bool GaussOnly = false>
void evaluatePiece(const LinearField& field, const Region<double>& region, const KronrodRule& rule,
                   Piece<double, LinearSums>& piece) {
    static_assert(std::is_same_v<T, double>);
    LinearSums k;
    ForceSums<double> gauss;
    const double du = piece.u1 - piece.u0;
    for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
        if constexpr (GaussOnly) {
            if (rule.gauss_weights[i] == 0.0) continue;
        }
        // σ = σ₁, τ = e (unit coefficients).
        const NodeStress<double> n = nodeStress(field, region, piece.u0 + du * rule.nodes[i], du);
        const StressSample<double>& st = n.st;
        const double s = n.s, c = n.c, dtheta = n.dtheta;
        const double w = dtheta * (GaussOnly ? rule.gauss_weights[i] : rule.weights[i]);
        const double sigma = st.sigma;
        // Per unit c: σ = 0, τ = e; per unit K_s tan φ: σ = 0, τ = σ₁ e; per unit K_s: σ₁, τ = 0.
        const double ct = w * st.tau_t, cl = w * st.tau_l;
        k.modulus.fx += -w * sigma * s, k.modulus.fz += w * sigma * c;
        k.cohesion.fx += ct * c, k.cohesion.fz += ct * s, k.cohesion.fy += cl;
        k.cohesion.mx += cl * c, k.cohesion.my += ct, k.cohesion.mz += cl * s;
        const double ft = ct * sigma, fl = cl * sigma;
        k.friction.fx += ft * c, k.friction.fz += ft * s, k.friction.fy += fl;
        k.friction.mx += fl * c, k.friction.my += ft, k.friction.mz += fl * s;
        if (!GaussOnly && rule.gauss_weights[i] != 0.0) {
            // The nominal α's integrands on the Gauss weights, as the generic evaluatePiece.
            const double wg = dtheta * rule.gauss_weights[i];
            const double sigma0 = field.nominal[0] * sigma;                     // K_s σ₁
            const double shear0 = field.nominal[1] + field.nominal[2] * sigma;  // c + σ tan φ
            const double tt = wg * shear0 * st.tau_t, tl = wg * shear0 * st.tau_l;
            gauss.fx += tt * c - wg * sigma0 * s, gauss.fz += wg * sigma0 * c + tt * s;
            gauss.fy += tl, gauss.mx += tl * c, gauss.my += tt, gauss.mz += tl * s;
        }
    }
    if constexpr (GaussOnly) {
        piece.error = piece.lateral_error = 0.0;
    } else {
        const ForceSums<double> v = field.combine(k);
        piece.error = std::max(
            {std::abs(v.fx - gauss.fx), std::abs(v.fz - gauss.fz), std::abs(v.my - gauss.my)});
        piece.lateral_error = std::max(
            {std::abs(v.fy - gauss.fy), std::abs(v.mx - gauss.mx), std::abs(v.mz - gauss.mz)});
    }
    piece.sums = k;
}

template <typename T>
ShearGeometry shearGeometry(const ContactParameters<T>& p, const StressField<T>& field) {
    // j (and so its kinks) is computed on the shearing radius r_s (r for a smooth wheel).
    // With a shear offset j₀ from earlier passes, j_max is reached where the local j = j_max − j₀.
    const double max_shear = field.shearOffset() > 0.0
                                 ? std::max(p.max_shear_deformation_m - field.shearOffset(), 0.0)
                                 : p.max_shear_deformation_m;
    return {scalarValue(field.shearRadius()),     scalarValue(field.entryAngle()),
            scalarValue(field.exitAngle()),       scalarValue(field.velocityRatio()),
            scalarValue(field.lateralVelocity()), max_shear,
            scalarValue(p.shear_modulus_m),       scalarValue(field.slipAngleTangent())};
}

// The angles where σ has the reload law's kink (both regions), NaN where there is none.
template <typename T>
std::array<double, 2> reloadKinks(const StressField<T>& field) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double r = scalarValue(field.radiusValue());
    const double entry = scalarValue(field.entryAngle());
    const double cos_kink = std::cos(entry) + field.reloadDepth() / r;
    if (!(field.reloadDepth() > 0.0) || !(cos_kink < 1.0)) return {nan, nan};
    const double front = std::acos(cos_kink);
    const double theta_m = scalarValue(field.maxStressAngle());
    const double theta_r = scalarValue(field.exitAngle());
    // θ_e(θ) = θ_f − (θ − θ_r)(θ_f − θ_m)/(θ_m − θ_r) = front, solved for θ behind θ_m.
    const double rear = entry > theta_m && theta_m > theta_r
                            ? theta_r + (entry - front) * (theta_m - theta_r) / (entry - theta_m)
                            : nan;
    return {front >= theta_m ? front : nan, rear};
}

// The contact integrals ∫(τ_t cos θ − σ sin θ), ∫(σ cos θ + τ_t sin θ), ∫τ_l, ∫τ_l cos θ,
// ∫τ_t, ∫τ_l sin θ over [θ_r, θ_f]: both regions, split at the kinks and the scale splits, then
// adaptive bisection of the piece with the largest relative error estimate until every estimate
// is below the tolerance or the piece cap is reached.
template <typename T, typename Field = StressField<T>, typename Sums = ForceSums<T>>
Sums integrateContact(const ContactParameters<T>& p, const Field& field,
                      const IntegrationOptions& options, IntegrationReport* report = nullptr) {
    constexpr int kCapacity = 96;
    // Below this fraction of the other group's scale the in-plane or lateral integrals need only
    // absolute accuracy (F_x, F_z ~ 1e-9 F_y when σ ≡ 0 and β = 89°; F_y ~ 1e-7 F_z at β = 1e-5°).
    constexpr double kFloor = 1e-6;
    const ShearGeometry geometry = shearGeometry(p, field);
    const Kinks kinks = findKinks(geometry);
    const Kinks splits = findScaleSplits(geometry);
    const KronrodRule& rule = kronrodRule();
    const int q = endExponent(scalarValue(field.sinkageExponent()), options.end_exponent);
    const Region<T> regions[2] = {{field.maxStressAngle(), field.entryAngle(),
                                   field.entryAngle() - field.maxStressAngle(), true, q},
                                  {field.exitAngle(), field.maxStressAngle(),
                                   field.maxStressAngle() - field.exitAngle(), false, q}};
    // Uninitialised storage: value-initialising 96 pieces (8 kB for double, 17 kB for the linear
    // forms) on every call cost ~5 % of a whole evaluation. Pieces are created in order and
    // destroyed on return.
    struct Storage {
        alignas(Piece<T, Sums>) unsigned char bytes[sizeof(Piece<T, Sums>) * kCapacity];
        int count = 0;
        Piece<T, Sums>& operator[](int i) {
            return *std::launder(reinterpret_cast<Piece<T, Sums>*>(bytes) + i);
        }
        Piece<T, Sums>& add() {
            return *::new (bytes + sizeof(Piece<T, Sums>) * count++) Piece<T, Sums>();
        }
        ~Storage() { std::destroy_n(&(*this)[0], count); }
    } pieces;
    int& count = pieces.count;
    for (int r = 0; r < 2; ++r) {
        const Region<T>& region = regions[r];
        const double lo = scalarValue(region.theta_lo), hi = scalarValue(region.theta_hi);
        if (!(hi > lo)) continue;
        // Kinks and splits inside the region, as break points in u (ascending).
        std::array<double, 2 * kMaxKinks + 2> breaks{};
        int n = 0;
        breaks[n++] = 0.0;
        for (const Kinks* set : {&kinks, &splits}) {
            for (int k = 0; k < set->count; ++k) {
                const double theta = set->angles[k];
                if (theta <= lo || theta >= hi) continue;
                const double distance = region.singular_at_hi ? hi - theta : theta - lo;
                breaks[n++] = std::pow(distance / (hi - lo), 1.0 / q);
            }
        }
        if (field.remembers()) {
            // The reload law's kink (elastic k_u d meets the virgin curve at d = δ): on the front
            // where r (cos θ − cos θ_f) = δ, and behind θ_m at its equivalent angle (Eq. 2.19).
            for (const double theta : reloadKinks(field)) {
                if (!(theta > lo && theta < hi)) continue;  // NaN: no kink
                const double distance = region.singular_at_hi ? hi - theta : theta - lo;
                breaks[n++] = std::pow(distance / (hi - lo), 1.0 / q);
            }
        }
        breaks[n++] = 1.0;
        std::sort(breaks.begin() + 1, breaks.begin() + n - 1);
        for (int b = 0; b + 1 < n && count < kCapacity; ++b) {
            if (!(breaks[b + 1] > breaks[b])) continue;
            Piece<T, Sums>& piece = pieces.add();
            piece.region = r;
            piece.u0 = breaks[b];
            piece.u1 = breaks[b + 1];
            if (options.gauss_only) {
                evaluatePiece<T, true>(field, region, rule, piece);
            } else {
                evaluatePiece(field, region, rule, piece);
            }
        }
    }
    if (options.gauss_only) {
        Sums total;
        for (int i = 0; i < count; ++i) total += pieces[i].sums;
        if (report) *report = {count, true, std::numeric_limits<double>::quiet_NaN()};
        return total;
    }
    const int limit = std::clamp(options.max_pieces, count, kCapacity);
    while (count > 0) {
        Sums total;
        for (int i = 0; i < count; ++i) total += pieces[i].sums;
        const ForceSums<double> plain = plainSums(field, total);
        const double in_plane = std::abs(plain.fz) + std::abs(plain.fx) + std::abs(plain.my);
        const double lateral = std::abs(plain.fy) + std::abs(plain.mx) + std::abs(plain.mz);
        const double scale = std::max(in_plane, kFloor * lateral);
        const double lateral_scale = std::max(lateral, kFloor * in_plane);
        // Error relative to the allowed one; 0/0 (no lateral motion) is 0.
        auto relative = [](double error, double allowed) {
            return error == 0.0 ? 0.0 : error / allowed;
        };
        int worst = 0;
        double worst_ratio = -1.0, sum_ratio = 0.0;
        for (int i = 0; i < count; ++i) {
            const double ratio =
                std::max(relative(pieces[i].error, options.tolerance * scale),
                         relative(pieces[i].lateral_error, options.tolerance * lateral_scale));
            sum_ratio += ratio;
            if (ratio > worst_ratio) worst = i, worst_ratio = ratio;
        }
        const bool converged = sum_ratio <= 1.0;
        if (converged || count >= limit) {
            if (report) *report = {count, converged, sum_ratio * options.tolerance};
            return total;
        }
        // Bisect the worst piece in u.
        Piece<T, Sums>& left = pieces[worst];
        Piece<T, Sums>& right = pieces.add();
        const double middle = 0.5 * (left.u0 + left.u1);
        right.region = left.region;
        right.u0 = middle;
        right.u1 = left.u1;
        left.u1 = middle;
        evaluatePiece(field, regions[left.region], rule, left);
        evaluatePiece(field, regions[right.region], rule, right);
    }
    if (report) *report = {};
    return {};
}

}  // namespace detail

/// Applies the integral prefactors (r b, r² b and the signs of Eqs. 2.23–2.35) and bulldozing.
/// With the lug model (p.lugged()) the sums hold the shear stresses weighted by ρ = r_s/r, and the
/// moments, pure shear integrals, take the lever arm r_s: r r_s b instead of r² b (docs/model.md,
/// "Lugs": M_y = r_s² b ∫τ_t dθ).
template <typename T>
WheelForces<T> assembleForces(const ContactParameters<T>& p, const OperatingPoint<T>& op,
                              const detail::ForceSums<T>& sums, BulldozingModel bulldozing) {
    const T rb = p.radius_m * p.width_m;
    const T r2b = p.lugged() ? T(rb * p.shearRadius()) : T(rb * p.radius_m);
    WheelForces<T> f;
    // 0 − x rather than −x: no lateral motion gives F_y = M_x = M_z = +0, never "-0" on output.
    f.fx = rb * sums.fx;
    f.fy = 0.0 - rb * sums.fy;
    f.fz = rb * sums.fz;
    f.mx = 0.0 - r2b * sums.mx;
    f.my = r2b * sums.my;
    f.mz = 0.0 - r2b * sums.mz;
    f.fb = bulldozingForce(p, op.entry_angle_rad, bulldozing);
    if (op.slip_angle_rad > 0.0) {
        f.fs = f.fy - f.fb;
    } else if (op.slip_angle_rad < 0.0) {
        f.fs = f.fy + f.fb;
    } else {
        f.fs = f.fy;  // no lateral motion, no bulldozing (docs/model.md, "Side force")
    }
    return f;
}

/// F_x, F_y, F_z, M_x, M_y, M_z, F_b and F_s of the full model at one operating point.
/// Preconditions (checked by requireValid in the double API of sinkage.h / the CLI): valid
/// parameters and operating point.
/// `report`, when given, receives the number of pieces and whether the tolerance was met before
/// the piece cap (IntegrationOptions::max_pieces).
template <typename T>
WheelForces<T> computeForces(const ContactParameters<T>& p, const OperatingPoint<T>& op,
                             BulldozingModel bulldozing = BulldozingModel::kBekker,
                             const IntegrationOptions& options = {},
                             IntegrationReport* report = nullptr) {
    const StressField<T> field(p, op);
    const detail::ForceSums<T> sums = detail::integrateContact(p, field, options, report);
    return assembleForces(p, op, sums, bulldozing);
}

/// Whether computeForces at `op` is the same for every j_max ≥ `limit` as without a limit, to
/// the last bit: the shear deformation with j₀ stays below `limit` (by a margin of 1e-9 of it)
/// over the whole contact, so neither the integrand (Eq. 2.16) nor its pieces (the j_max kink,
/// the rise's splits: kinks.h) use j_max. Known for a driven wheel (κ ≤ 1: the shear is largest
/// at θ_r, peakShearDeformation); false when braking or locked. `p`'s own j_max is not used.
inline bool shearLimitUnreached(const ContactParameters<double>& p,
                                const OperatingPoint<double>& op, double limit) {
    const StressField<double> field(p, op);
    if (field.locked() || !field.driving()) return false;
    const double peak = peakShearDeformation(detail::shearGeometry(p, field));
    return peak + field.shearOffset() < limit * (1.0 - 1e-9);
}

/// F_x, F_z and M_y of the full model per unit coefficient of α = (K_s, c, K_s tan φ), in which
/// they are linear: F = K_s P + c Q + K_s tan φ R (computeLinearForces).
struct LinearForces {
    std::array<double, 3> fx{}, fz{}, my{};  ///< [P, Q, R] of each
};

/// The linear forms of LinearForces (Eqs. 2.17, 2.20, 2.23, 2.31, 2.34; the bulldozing of Eq.
/// 2.30 is not in them): one stress evaluation in double per node instead of a Jet's
/// (docs/identification.md §9, "eighth pass"). `nominal` is the α at which the adaptive rule
/// judges its pieces (the pieces of computeForces at that α; on the Gauss rule they do not
/// depend on α); `p`'s own K_s, c and φ are not used. Throws std::invalid_argument when the track
/// reloads (reload_depth_m > 0: k_u d is not linear in K_s); a rut alone is linear.
inline LinearForces computeLinearForces(ContactParameters<double> p,
                                        const OperatingPoint<double>& op,
                                        const std::array<double, 3>& nominal,
                                        const IntegrationOptions& options = {},
                                        IntegrationReport* report = nullptr) {
    if (p.reload_depth_m > 0.0) {
        throw std::invalid_argument(
            "computeLinearForces: reload_depth_m = " + std::to_string(p.reload_depth_m) +
            " m > 0: the track reloads elastically (k_u d), not linearly in K_s; allowed: 0");
    }
    p.pressure_modulus = 1.0;
    p.cohesion_pa = 1.0;
    p.friction_angle_rad = 0.0;
    const detail::LinearField field(p, op, nominal);
    const detail::LinearSums sums =
        detail::integrateContact<double, detail::LinearField, detail::LinearSums>(p, field, options,
                                                                                  report);
    const double rb = p.radius_m * p.width_m;
    const double r2b = rb * (p.lugged() ? p.shearRadius() : p.radius_m);
    LinearForces out;
    const detail::ForceSums<double>* forms[3] = {&sums.modulus, &sums.cohesion, &sums.friction};
    for (int k = 0; k < 3; ++k) {
        out.fx[k] = rb * forms[k]->fx;
        out.fz[k] = rb * forms[k]->fz;
        out.my[k] = r2b * forms[k]->my;
    }
    return out;
}

}  // namespace terra::contact
