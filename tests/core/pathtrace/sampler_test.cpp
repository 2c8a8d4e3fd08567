// The path sampler (core/pathtrace/sampler.h): Sobol points, Owen scrambling, the (0, 2)-sequence property of
// each stratified pair across a pixel's samples, and what it buys over independent numbers.
#include "core/pathtrace/sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

namespace sp::pathtrace {
namespace {

// Whether `points` (2^m of them) put one point in each elementary box of every shape 2^k x 2^(m-k).
bool isNet(const std::vector<std::array<float, 2>>& points, int m) {
    for (int k = 0; k <= m; ++k) {
        std::set<std::pair<int, int>> boxes;
        for (const auto& p : points)
            boxes.insert({int(p[0] * float(1 << k)), int(p[1] * float(1 << (m - k)))});
        if (boxes.size() != points.size())
            return false;
    }
    return true;
}

TEST(PathSampler, SobolStartsAsPublished) {
    const std::uint32_t half = 1u << 31, quarter = 1u << 30;
    EXPECT_EQ(PathSampler::sobol(0), (std::array<std::uint32_t, 2>{0, 0}));
    EXPECT_EQ(PathSampler::sobol(1), (std::array<std::uint32_t, 2>{half, half}));
    EXPECT_EQ(PathSampler::sobol(2), (std::array<std::uint32_t, 2>{quarter, half + quarter}));
    EXPECT_EQ(PathSampler::sobol(3), (std::array<std::uint32_t, 2>{half + quarter, quarter}));
}

TEST(PathSampler, ScramblingPermutesEveryLevelWithinItsParent) {
    for (std::uint32_t seed : {0u, 1u, 0xDEADBEEFu, 12345u}) {
        // The 256 intervals of width 2^-8 go to 256 distinct ones, and each output's top bits depend on the
        // input's top bits only: two inputs in one interval land in one interval.
        std::set<std::uint32_t> top;
        for (std::uint32_t i = 0; i < 256; ++i) {
            const std::uint32_t a = PathSampler::scramble(i << 24, seed);
            const std::uint32_t b = PathSampler::scramble((i << 24) | 0x00ABCDEFu, seed);
            EXPECT_EQ(a >> 24, b >> 24) << "seed " << seed << ", interval " << i;
            top.insert(a >> 24);
        }
        EXPECT_EQ(top.size(), 256u) << "seed " << seed;
    }
}

TEST(PathSampler, EveryPairIsANetOverAPixelsSamples) {
    for (std::uint64_t seed : {1ull, 77ull, 0x123456789ABCDEFull}) {
        for (int pair = 0; pair < PathSampler::kStratifiedPairs; ++pair) {
            // The first 64 samples, and an aligned block further on (an image adds samples to the last).
            for (std::uint64_t first : {0ull, 128ull}) {
                std::vector<std::array<float, 2>> points;
                for (std::uint64_t index = first; index < first + 64; ++index) {
                    PathSampler sampler(seed, index);
                    for (int skip = 0; skip < pair; ++skip)
                        sampler.next2();
                    points.push_back(sampler.next2());
                }
                EXPECT_TRUE(isNet(points, 6)) << "seed " << seed << ", pair " << pair << ", from " << first;
            }
        }
    }
}

TEST(PathSampler, OneDimensionalDrawsShareAPairAndNext2StartsAFreshOne) {
    PathSampler a(5, 3), b(5, 3);
    const float first = a.next(), second = a.next();
    const std::array<float, 2> pair = b.next2();
    EXPECT_EQ(first, pair[0]);
    EXPECT_EQ(second, pair[1]);
    PathSampler c(5, 3), d(5, 3);
    c.next();                         // half of pair 0
    const auto afterHalf = c.next2(); // pair 1
    d.next2();
    EXPECT_EQ(afterHalf, d.next2());
}

TEST(PathSampler, SameSeedAndIndexSameNumbersOthersDiffer) {
    PathSampler a(9, 4), b(9, 4), c(10, 4), e(9, 5);
    for (int i = 0; i < 40; ++i) { // past the stratified pairs too
        const float x = a.next();
        EXPECT_EQ(x, b.next());
        EXPECT_GE(x, 0.0f);
        EXPECT_LT(x, 1.0f);
    }
    EXPECT_NE(PathSampler(9, 4).next2(), c.next2());
    EXPECT_NE(PathSampler(9, 4).next2(), e.next2());
}

TEST(PathSampler, EachNumberIsUniformAndPairsAreUncorrelated) {
    // Over many pixels (seeds), one sample's numbers: mean 1/2, variance 1/12, no correlation between pairs.
    constexpr int kPixels = 20000;
    double sum = 0.0, square = 0.0, product = 0.0;
    for (int seed = 0; seed < kPixels; ++seed) {
        PathSampler sampler(std::uint64_t(seed) * 7919u, 6);
        const float x = sampler.next2()[0];
        const float y = sampler.next2()[1];
        sum += x;
        square += double(x) * x;
        product += (x - 0.5) * (y - 0.5);
    }
    EXPECT_NEAR(sum / kPixels, 0.5, 0.01);
    EXPECT_NEAR(square / kPixels - (sum / kPixels) * (sum / kPixels), 1.0 / 12.0, 0.005);
    EXPECT_NEAR(product / kPixels, 0.0, 0.005);
}

TEST(PathSampler, ASmoothIntegralConvergesFarFasterThanIndependentNumbers) {
    // The mean of x * y over 256 samples of a pixel: independent numbers leave an error of
    // sd(x y) / 16 = 0.0138; the scrambled net, far less.
    double squared = 0.0;
    constexpr int kPixels = 200;
    for (int seed = 0; seed < kPixels; ++seed) {
        double mean = 0.0;
        for (std::uint64_t index = 0; index < 256; ++index) {
            const auto [x, y] = PathSampler(std::uint64_t(seed) + 1000, index).next2();
            mean += double(x) * double(y) / 256.0;
        }
        squared += (mean - 0.25) * (mean - 0.25);
    }
    const double independent = std::sqrt(1.0 / 9.0 - 1.0 / 16.0) / 16.0;
    EXPECT_LT(std::sqrt(squared / kPixels), 0.1 * independent);
}

} // namespace
} // namespace sp::pathtrace
