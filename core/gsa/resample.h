#pragma once
/// @file resample.h
/// Bootstrap helpers shared by the Sobol' and Morris estimators (implementation detail of gsa).

#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace terra::gsa {

/// SplitMix64's output function (Steele, Lea & Flood 2014): a bijective 64-bit mix.
inline std::uint64_t splitMix(std::uint64_t x) {
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

/// Indices drawn uniformly from [0, n), n ≤ 2³², reproducibly everywhere: the SplitMix64
/// generator (state += 0x9E3779B97F4A7C15, output splitMix(state)) is fully specified, and the
/// mapping is a multiply-shift of its upper 32 bits (bias below n / 2³², far under any bootstrap's
/// own noise), not an implementation-defined std::uniform_int_distribution.
class Resampler {
public:
    explicit Resampler(std::uint64_t seed) : state_(seed) {}

    std::uint64_t next() { return splitMix(state_ += 0x9E3779B97F4A7C15ull); }
    std::size_t index(std::size_t n) {
        assert(n <= (std::uint64_t{1} << 32));
        return static_cast<std::size_t>(((next() >> 32) * n) >> 32);
    }

private:
    std::uint64_t state_;
};

/// Sample standard deviation (n − 1) of values[offset + k·stride], k = 0 … count − 1; 0 for
/// fewer than two values.
inline double standardDeviation(const std::vector<double>& values, std::size_t offset,
                                std::size_t stride) {
    const std::size_t count = values.size() / stride;
    if (count < 2) return 0.0;
    double mean = 0.0;
    for (std::size_t k = 0; k < count; ++k) mean += values[offset + k * stride];
    mean /= static_cast<double>(count);
    double sum = 0.0;
    for (std::size_t k = 0; k < count; ++k) {
        const double e = values[offset + k * stride] - mean;
        sum += e * e;
    }
    return std::sqrt(sum / static_cast<double>(count - 1));
}

}  // namespace terra::gsa
