#pragma once
/// @file sobol_sequence.h
/// Sobol' low-discrepancy points (Joe–Kuo direction numbers, as Boost.Random's `sobol`), randomised
/// by a seeded digital shift, with random access by index so that any range of points can be
/// generated on its own (chunks evaluated elsewhere give the same numbers; docs/sensitivity.md).

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace terra::gsa {

/// The points x_k ⊕ e (k = 0, 1, …) of the `dimension`-dimensional Sobol' sequence x_k, each
/// coordinate XOR-ed with a 64-bit shift e drawn from std::mt19937_64(seed) (a digital shift keeps
/// every elementary-interval balance property of the sequence). Coordinates are returned as
/// (⌊y / 2¹²⌋ + ½) 2⁻⁵² for the 64-bit shifted value y: the centre of its 2⁻⁵² cell, strictly
/// inside (0, 1), so that inverse CDFs stay finite.
class SobolSequence {
public:
    /// Throws std::invalid_argument when dimension is 0 or above Boost's table (3667).
    SobolSequence(std::size_t dimension, std::uint64_t seed);

    std::size_t dimension() const { return shift_.size(); }

    /// Points first … first + count − 1, row-major into `out` (count × dimension values).
    /// The same point has the same bits whichever range it is generated in.
    void generate(std::uint64_t first, std::size_t count, std::span<double> out) const;

private:
    std::vector<std::uint64_t> shift_;
};

}  // namespace terra::gsa
