#pragma once
// The random numbers of one path: stratified across a pixel's samples where it pays, independent beyond.
//
// A pixel's samples are not independent draws: sample k of a pixel takes, for each of the path's first
// kStratifiedPairs pairs of dimensions (the point in the pixel, the first vertices' light and bounce
// directions), point k of a 2D Sobol sequence that is Owen-scrambled, with its order shuffled, by a hash of
// the pixel and the pair (Burley, "Practical Hash-based Owen Scrambling", JCGT 2020). Any power-of-two
// prefix of those points covers the square evenly (a (0, 2)-sequence: each of the 2^m elementary boxes of
// area 2^-m holds one of the first 2^m points), so the error of smooth integrands (a pixel's footprint over a
// texture, a diffuse bounce) falls nearly as 1/N instead of 1/sqrt(N). Each point is still uniform on its
// own and the pairs are scrambled independently, so every estimate stays unbiased; pixels are scrambled
// independently, so what error is left is noise, not a pattern. Past the stratified pairs (deep bounces,
// Russian roulette) the numbers come from SplitMix64, one stream per (pixel, sample).
//
// Call sites draw 2D decisions with next2() (a direction, a point on a light), which starts a fresh pair, and
// 1D ones (a lobe, a light to pick) with next(); two next() in a row share a pair.

#include <array>
#include <cstdint>

namespace sp::pathtrace {

class PathSampler {
  public:
    // Pairs of dimensions drawn from the scrambled Sobol sequence: the pixel point, and about two vertices'
    // light, sky and bounce samples.
    static constexpr int kStratifiedPairs = 12;

    // `seed` picks the pixel's (or the probe's) scrambling; `index` is the sample's number in its
    // accumulation (sample 0, 1, 2, ...: each image adds the next ones).
    PathSampler(std::uint64_t seed, std::uint64_t index);

    // A number in [0, 1).
    float next();
    // Two numbers in [0, 1), stratified together.
    std::array<float, 2> next2();

    // The raw generator, for tests: point `index` of the 2D Sobol sequence, bits as drawn (no scrambling).
    static std::array<std::uint32_t, 2> sobol(std::uint32_t index);
    // Owen scrambling of a 32-bit fraction by `seed`: a random permutation of the 2^k aligned intervals at
    // every level k that keeps each interval's points inside its parent.
    static std::uint32_t scramble(std::uint32_t bits, std::uint32_t seed);

  private:
    std::array<float, 2> pair(int which);
    float independent();

    std::uint64_t seed_;
    std::uint64_t index_;
    std::uint64_t stream_; // SplitMix64 state past the stratified pairs
    int dimension_ = 0;    // dimensions used so far
    std::array<float, 2> current_{};
};

} // namespace sp::pathtrace
