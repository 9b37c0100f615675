#pragma once
/// @file scalar.h
/// Helpers that let the wheel–soil model be written once for a generic scalar: `double` for the
/// CLI, the GUI and the rover, and automatic-differentiation types (ceres::Jet) for identification.
/// A scalar type T must provide the usual arithmetic, comparisons and the math functions found by
/// argument-dependent lookup (sin, cos, pow, exp, expm1, sqrt, acos, tan); ceres::Jet does.

#include <cmath>
#include <limits>
#include <type_traits>

namespace terra {

/// The plain value of a scalar: the number itself for arithmetic types.
inline double scalarValue(double x) { return x; }

/// The plain value of an automatic-differentiation scalar (the `a` part of a ceres::Jet).
template <typename J>
requires requires(const J& j) { j.a; }
double scalarValue(const J& j) { return scalarValue(j.a); }

/// Converts between scalar types: a plain value becomes a constant (zero derivative).
template <typename T, typename U>
T scalarCast(const U& x) {
    if constexpr (std::is_same_v<T, U>) {
        return x;
    } else {
        return T(scalarValue(x));
    }
}

/// tan x for a soil's constant angle (its friction angle φ and c_s = tan(π/4 + φ/2), evaluated
/// at every contact evaluation while the soil rarely changes): for a `double`, the last argument
/// and its tangent are remembered per call site (`Site`, any distinct type) and thread, and the
/// same argument returns the same tangent, bit for bit; any other scalar is computed.
template <typename Site, typename T>
T rememberedTan(const T& x) {
    using std::tan;
    if constexpr (std::is_same_v<T, double>) {
        // Constant-initialised (no guard on each call): NaN never equals an argument.
        thread_local double last_x = std::numeric_limits<double>::quiet_NaN();
        thread_local double last_tan = 0.0;
        if (x != last_x) {  // NaN never equals: computed, as a NaN argument is
            last_tan = tan(x);
            last_x = x;
        }
        return last_tan;
    } else {
        return tan(x);
    }
}

/// pow(base, exponent) for base > 0 (the caller guarantees it). For a `double` it is std::pow.
/// For an automatic-differentiation scalar with plain (double) parts, one pow instead of the two
/// that ceres::Jet's pow(Jet, Jet) evaluates (its ∂/∂base is g·pow(a, g − 1); here g·pow(a, g)/a,
/// equal to rounding), and log(a) only when the exponent carries derivatives: the stress field's
/// K_s (r(cos θ − cos θ_f))^N, evaluated at every quadrature node, mostly with a constant
/// exponent or a constant base (docs/identification.md §9).
template <typename T>
T positivePow(const T& base, const T& exponent) {
    using std::pow;
    if constexpr (std::is_arithmetic_v<T>) {
        return pow(base, exponent);
    } else if constexpr (requires { requires std::is_same_v<decltype(base.a), double>; }) {
        const double p = std::pow(base.a, exponent.a);
        T out(p);
        if (!(base.v.array() == 0.0).all()) out.v = (exponent.a * p / base.a) * base.v;
        if (!(exponent.v.array() == 0.0).all()) out.v += (p * std::log(base.a)) * exponent.v;
        return out;
    } else {
        return pow(base, exponent);
    }
}

}  // namespace terra
