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

}  // namespace terra::contact
