// The computed intrinsic images against the definitions, value by value, in float32 rounded to float16.

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "core/render/derived_images.h"
#include "core/render/image_buffer.h"

namespace sp::render {
namespace {

std::vector<std::uint16_t> halves(std::size_t count, float low, float high, std::mt19937& random) {
    std::uniform_real_distribution<float> value(low, high);
    std::vector<std::uint16_t> out(count);
    for (auto& h : out)
        h = floatToHalf(value(random));
    return out;
}

// Pixel counts around the eight the vector path takes at once: its tail goes through the scalar path.
class DerivedImages : public ::testing::TestWithParam<std::size_t> {};

TEST_P(DerivedImages, DiffuseOnlyIsBaseTimesDielectricTimesIllumination) {
    const std::size_t pixels = GetParam();
    std::mt19937 random(7);
    const auto base = halves(3 * pixels, 0.0f, 1.0f, random), metallic = halves(pixels, 0.0f, 1.0f, random),
               illumination = halves(3 * pixels, 0.0f, 40.0f, random);
    std::vector<std::uint16_t> out(3 * pixels, 0xffff);
    computeDiffuseOnly(base.data(), metallic.data(), illumination.data(), out.data(), pixels);
    for (std::size_t p = 0; p < pixels; ++p)
        for (std::size_t c = 0; c < 3; ++c) {
            const float expected = halfToFloat(base[3 * p + c]) * (1.0f - halfToFloat(metallic[p])) *
                                   halfToFloat(illumination[3 * p + c]);
            ASSERT_EQ(out[3 * p + c], floatToHalf(expected)) << "pixel " << p << " channel " << c;
        }
}

TEST_P(DerivedImages, SpecularResidualIsHdrLessDiffuse) {
    const std::size_t pixels = GetParam();
    std::mt19937 random(11);
    const auto hdr = halves(4 * pixels, -1.0f, 60.0f, random),
               diffuse = halves(3 * pixels, 0.0f, 30.0f, random);
    std::vector<std::uint16_t> out(3 * pixels, 0xffff);
    computeSpecularResidual(hdr.data(), diffuse.data(), out.data(), pixels);
    for (std::size_t p = 0; p < pixels; ++p)
        for (std::size_t c = 0; c < 3; ++c) {
            const float expected = halfToFloat(hdr[4 * p + c]) - halfToFloat(diffuse[3 * p + c]);
            ASSERT_EQ(out[3 * p + c], floatToHalf(expected)) << "pixel " << p << " channel " << c;
        }
}

INSTANTIATE_TEST_SUITE_P(PixelCounts, DerivedImages, ::testing::Values(0, 1, 7, 8, 9, 16, 61 * 37));

} // namespace
} // namespace sp::render
