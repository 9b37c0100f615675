#include "core/gsa/sobol_sequence.h"

#include <boost/random/sobol.hpp>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace terra::gsa {
namespace {

constexpr std::size_t kMaxDimension = boost::random::default_sobol_table::max_dimension;

// The top 52 bits plus one half, exactly representable (below 2^52 doubles resolve halves), so
// that u ∈ [2⁻⁵³, 1 − 2⁻⁵³]; with 53 bits the half would round away and u could reach 1.
double toUnit(std::uint64_t bits) { return (static_cast<double>(bits >> 12) + 0.5) * 0x1p-52; }

}  // namespace

SobolSequence::SobolSequence(std::size_t dimension, std::uint64_t seed) {
    if (dimension == 0 || dimension > kMaxDimension) {
        throw std::invalid_argument("Sobol' sequence dimension " + std::to_string(dimension) +
                                    " is outside the allowed range [1, " +
                                    std::to_string(kMaxDimension) + "]");
    }
    // mt19937_64's output sequence is fixed by the C++ standard: the shift is the same everywhere.
    std::mt19937_64 engine(seed);
    shift_.resize(dimension);
    for (std::uint64_t& s : shift_) s = engine();
}

void SobolSequence::generate(std::uint64_t first, std::size_t count, std::span<double> out) const {
    const std::size_t d = dimension();
    if (out.size() != count * d) {
        throw std::invalid_argument(
            "SobolSequence::generate: output holds " + std::to_string(out.size()) + " values, " +
            std::to_string(count) + " points need " + std::to_string(count * d));
    }
    if (count == 0) return;
    std::size_t row = 0;
    // Point 0 is the origin; Boost's generator starts at point 1 and, after seed(k), continues
    // with point k + 1 (Gray-code update: the state is exact integer XORs, so any start gives the
    // same bits).
    if (first == 0) {
        for (std::size_t j = 0; j < d; ++j) out[j] = toUnit(shift_[j]);
        row = 1;
    }
    if (row == count) return;
    boost::random::sobol engine(d);
    const std::uint64_t start = first + row;  // ≥ 1
    if (start > 1) engine.seed(start - 1);
    for (; row < count; ++row) {
        for (std::size_t j = 0; j < d; ++j) out[row * d + j] = toUnit(engine() ^ shift_[j]);
    }
}

}  // namespace terra::gsa
