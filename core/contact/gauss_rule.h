#pragma once
/// @file gauss_rule.h
/// Gauss–Legendre rules on [0, 1], from Boost.Math's tabulated abscissae and weights.

#include <span>

namespace terra::contact {

/// An N-point Gauss–Legendre rule on [0, 1]: exact for polynomials of degree 2N − 1.
struct GaussRule {
    std::span<const double> nodes;    ///< in (0, 1), ascending
    std::span<const double> weights;  ///< summing to 1
};

/// The rule with `points` nodes; `points` is one of 7, 10, 15, 20, 25, 30 (Boost's tables).
/// Throws std::invalid_argument otherwise.
const GaussRule& gaussRule(int points);

/// The 15-point Gauss–Kronrod rule on [0, 1] with its embedded 7-point Gauss rule: the Kronrod
/// weights give the integral, the difference to the Gauss weights an error estimate.
struct KronrodRule {
    std::span<const double> nodes;          ///< 15 nodes in (0, 1), ascending
    std::span<const double> weights;        ///< Kronrod weights (exact to degree 22)
    std::span<const double> gauss_weights;  ///< Gauss weights at the same nodes, 0 where unused
};

/// Boost's 15-point Gauss–Kronrod rule mapped to [0, 1].
const KronrodRule& kronrodRule();

}  // namespace terra::contact
