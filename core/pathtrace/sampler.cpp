#include "core/pathtrace/sampler.h"

namespace sp::pathtrace {
namespace {

std::uint64_t splitMix(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// A 64-bit value mixed into 32 bits (one SplitMix64 step from it).
std::uint32_t hash(std::uint64_t value) {
    return std::uint32_t(splitMix(value) >> 32);
}

std::uint32_t reverseBits(std::uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
    x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
    return (x >> 16) | (x << 16);
}

// The 24 high bits of a fraction as a float in [0, 1) (a float holds no more).
float fraction(std::uint32_t bits) {
    return float(bits >> 8) * (1.0f / 16777216.0f);
}

} // namespace

std::array<std::uint32_t, 2> PathSampler::sobol(std::uint32_t index) {
    // Dimension 0 is the van der Corput sequence (the index's bits mirrored); dimension 1's direction
    // numbers are Pascal's triangle mod 2: each is the one before xor itself shifted by one.
    std::uint32_t second = 0;
    for (std::uint32_t v = 1u << 31, i = index; i != 0; i >>= 1, v ^= v >> 1)
        if (i & 1u)
            second ^= v;
    return {reverseBits(index), second};
}

std::uint32_t PathSampler::scramble(std::uint32_t bits, std::uint32_t seed) {
    // Laine and Karras' observation, as Burley uses it: with the bits mirrored, Owen scrambling is any
    // permutation in which each bit depends on the seed and the bits below it only; additions, and products
    // with an even number xored in, are such permutations. The constants are Burley's.
    std::uint32_t x = reverseBits(bits);
    x += seed;
    x ^= x * 0x6C50B47Cu;
    x ^= x * 0xB82F1E52u;
    x ^= x * 0xC7AFE638u;
    x ^= x * 0x8D22F6E6u;
    return reverseBits(x);
}

PathSampler::PathSampler(std::uint64_t seed, std::uint64_t index)
    : seed_(seed ^ (index >> 32) * 0xD6E8FEB86659FD93ull), // past 2^32 samples, another scrambling
      index_(index), stream_(seed ^ index * 0xD1B54A32D192ED03ull) {}

std::array<float, 2> PathSampler::pair(int which) {
    const std::uint64_t key = seed_ + std::uint64_t(which + 1) * 0xA0761D6478BD642Full;
    // The sample's place in the pair's sequence, shuffled per pixel and pair (Owen scrambling of the index:
    // any power-of-two prefix is still a whole aligned block of the sequence), so that pairs are not
    // correlated through the index they share.
    const std::uint32_t shuffled = scramble(std::uint32_t(index_), hash(key));
    const std::array<std::uint32_t, 2> point = sobol(shuffled);
    return {fraction(scramble(point[0], hash(key ^ 0x1))), fraction(scramble(point[1], hash(key ^ 0x2)))};
}

float PathSampler::independent() {
    return fraction(std::uint32_t(splitMix(stream_) >> 32));
}

float PathSampler::next() {
    const int d = dimension_++;
    if (d >= 2 * kStratifiedPairs)
        return independent();
    if (d % 2 == 0)
        current_ = pair(d / 2);
    return current_[std::size_t(d % 2)];
}

std::array<float, 2> PathSampler::next2() {
    dimension_ += dimension_ % 2; // a fresh pair: the half of one a next() began is left unused
    const int d = dimension_;
    dimension_ += 2;
    if (d >= 2 * kStratifiedPairs)
        return {independent(), independent()};
    return pair(d / 2);
}

} // namespace sp::pathtrace
