#include "core/gsa/sobol_sequence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace terra::gsa {
namespace {

std::vector<double> points(const SobolSequence& s, std::uint64_t first, std::size_t count) {
    std::vector<double> out(count * s.dimension());
    s.generate(first, count, out);
    return out;
}

TEST(SobolSequence, ChunksAreBitIdenticalToOneRun) {
    const SobolSequence s(6, 42);
    const std::vector<double> whole = points(s, 0, 1000);
    std::vector<double> pieces;
    const std::uint64_t bounds[] = {0, 1, 2, 257, 600, 1000};
    for (std::size_t c = 0; c + 1 < std::size(bounds); ++c) {
        const std::vector<double> chunk = points(s, bounds[c], bounds[c + 1] - bounds[c]);
        pieces.insert(pieces.end(), chunk.begin(), chunk.end());
    }
    ASSERT_EQ(pieces.size(), whole.size());
    EXPECT_EQ(std::memcmp(pieces.data(), whole.data(), whole.size() * sizeof(double)), 0);
}

TEST(SobolSequence, UnshiftedStartIsTheJoeKuoSequence) {
    // The published first points of the Sobol' sequence (dimension 1: van der Corput; dimensions
    // 2 and 3 from Joe & Kuo's new-joe-kuo-6.21201 table): 0, 1/2, 3/4, 1/4, 3/8, 7/8, 5/8, 1/8.
    // With a digital shift e, point k is x_k XOR e: XOR-ing two points removes the shift.
    const SobolSequence s(3, 7);
    const std::vector<double> p = points(s, 0, 8);
    auto bits = [](double u) { return static_cast<std::uint64_t>(std::floor(u * 0x1p52)); };
    const double expected[8][3] = {{0, 0, 0},
                                   {0.5, 0.5, 0.5},
                                   {0.75, 0.25, 0.25},
                                   {0.25, 0.75, 0.75},
                                   {0.375, 0.375, 0.625},
                                   {0.875, 0.875, 0.125},
                                   {0.625, 0.125, 0.875},
                                   {0.125, 0.625, 0.375}};
    for (int k = 1; k < 8; ++k) {
        for (int j = 0; j < 3; ++j) {
            const std::uint64_t unshifted = bits(p[k * 3 + j]) ^ bits(p[j]);
            EXPECT_EQ(unshifted, bits(expected[k][j])) << "point " << k << ", dimension " << j;
        }
    }
}

TEST(SobolSequence, PointsAreStrictlyInsideTheUnitCube) {
    for (std::uint64_t seed : {0u, 1u, 2u}) {
        for (double u : points(SobolSequence(4, seed), 0, 4096)) {
            EXPECT_GT(u, 0.0);
            EXPECT_LT(u, 1.0);
        }
    }
    // A shifted coordinate of all ones or all zeros maps to the centre of the last or first cell.
    const std::vector<double> p = points(SobolSequence(1, 0), 0, 1);
    EXPECT_EQ(std::floor(p[0] * 0x1p52) + 0.5, p[0] * 0x1p52);
}

TEST(SobolSequence, FirstPowerOfTwoPointsAreAZeroNetInTheFirstTwoDimensions) {
    // The first 2^m points of Sobol's first two coordinates form a (0, m, 2)-net: each box
    // [a 2^-i, (a+1) 2^-i) × [b 2^-(m-i), (b+1) 2^-(m-i)) holds exactly one point. A digital shift
    // permutes these boxes, so the property survives the randomisation.
    constexpr int m = 10;
    constexpr std::size_t n = std::size_t{1} << m;
    const std::vector<double> p = points(SobolSequence(2, 3), 0, n);
    for (int i = 0; i <= m; ++i) {
        std::vector<int> count(n, 0);
        for (std::size_t k = 0; k < n; ++k) {
            const auto a = static_cast<std::size_t>(std::floor(p[2 * k] * (1 << i)));
            const auto b = static_cast<std::size_t>(std::floor(p[2 * k + 1] * (1 << (m - i))));
            ++count[a * (std::size_t{1} << (m - i)) + b];
        }
        for (std::size_t box = 0; box < n; ++box) ASSERT_EQ(count[box], 1) << "i = " << i;
    }
}

TEST(SobolSequence, SeedChangesTheShiftOnly) {
    const std::vector<double> a = points(SobolSequence(2, 1), 0, 16);
    const std::vector<double> b = points(SobolSequence(2, 1), 0, 16);
    const std::vector<double> c = points(SobolSequence(2, 2), 0, 16);
    EXPECT_EQ(a, b);
    EXPECT_NE(a, c);
}

TEST(SobolSequence, RejectsBadDimensionsAndSizes) {
    EXPECT_THROW(SobolSequence(0, 1), std::invalid_argument);
    EXPECT_THROW(SobolSequence(100000, 1), std::invalid_argument);
    std::vector<double> out(5);
    EXPECT_THROW(SobolSequence(2, 1).generate(0, 3, out), std::invalid_argument);
}

}  // namespace
}  // namespace terra::gsa
