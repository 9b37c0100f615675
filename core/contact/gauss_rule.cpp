#include "core/contact/gauss_rule.h"

#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace terra::contact {
namespace {

struct StoredRule {
    std::vector<double> nodes;
    std::vector<double> weights;
    GaussRule rule;
};

// Boost stores the non-negative half of a symmetric rule on [−1, 1]; unfold it onto [0, 1].
template <unsigned N>
StoredRule makeRule() {
    using Gauss = boost::math::quadrature::gauss<double, N>;
    const auto& x = Gauss::abscissa();
    const auto& w = Gauss::weights();
    std::vector<std::pair<double, double>> points;
    for (std::size_t i = 0; i < x.size(); ++i) {
        points.emplace_back(0.5 * (1.0 + x[i]), 0.5 * w[i]);
        if (x[i] != 0.0) points.emplace_back(0.5 * (1.0 - x[i]), 0.5 * w[i]);
    }
    std::sort(points.begin(), points.end());
    StoredRule stored;
    for (const auto& [node, weight] : points) {
        stored.nodes.push_back(node);
        stored.weights.push_back(weight);
    }
    stored.rule = {stored.nodes, stored.weights};
    return stored;
}

struct StoredKronrod {
    std::vector<double> nodes, weights, gauss_weights;
    KronrodRule rule;
};

StoredKronrod makeKronrod() {
    using Kronrod = boost::math::quadrature::gauss_kronrod<double, 15>;
    using Gauss = boost::math::quadrature::gauss<double, 7>;
    const auto& x = Kronrod::abscissa();
    const auto& w = Kronrod::weights();
    const auto& gw = Gauss::weights();
    // Boost's Kronrod abscissae interleave the Gauss nodes at the even indices 0, 2, 4, 6.
    std::vector<std::array<double, 3>> points;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double g = i % 2 == 0 ? gw[i / 2] : 0.0;
        points.push_back({0.5 * (1.0 + x[i]), 0.5 * w[i], 0.5 * g});
        if (x[i] != 0.0) points.push_back({0.5 * (1.0 - x[i]), 0.5 * w[i], 0.5 * g});
    }
    std::sort(points.begin(), points.end());
    StoredKronrod stored;
    for (const auto& p : points) {
        stored.nodes.push_back(p[0]);
        stored.weights.push_back(p[1]);
        stored.gauss_weights.push_back(p[2]);
    }
    stored.rule = {stored.nodes, stored.weights, stored.gauss_weights};
    return stored;
}

}  // namespace

const KronrodRule& kronrodRule() {
    static const StoredKronrod stored = makeKronrod();
    return stored.rule;
}

const GaussRule& gaussRule(int points) {
    static const StoredRule r7 = makeRule<7>();
    static const StoredRule r10 = makeRule<10>();
    static const StoredRule r15 = makeRule<15>();
    static const StoredRule r20 = makeRule<20>();
    static const StoredRule r25 = makeRule<25>();
    static const StoredRule r30 = makeRule<30>();
    switch (points) {
        case 7:
            return r7.rule;
        case 10:
            return r10.rule;
        case 15:
            return r15.rule;
        case 20:
            return r20.rule;
        case 25:
            return r25.rule;
        case 30:
            return r30.rule;
        default:
            throw std::invalid_argument("Gauss rule with " + std::to_string(points) +
                                        " points is not tabulated (7, 10, 15, 20, 25, 30)");
    }
}

}  // namespace terra::contact
