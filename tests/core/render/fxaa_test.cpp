// fxaa(): a staircase edge comes out closer to the edge's true coverage (its area-averaged image), both
// ways round; flat images, faint gradients and pixels away from edges are copied bit for bit; the result
// does not depend on the thread count, and degenerate sizes work.

#include "core/render/fxaa.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace sp::render {
namespace {

constexpr int kW = 96, kH = 64;
using Image = std::vector<std::uint8_t>;

double toLinear(double c) {
    c /= 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
std::uint8_t toSrgb(double linear) {
    const double c = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
    return std::uint8_t(std::lround(std::clamp(c, 0.0, 1.0) * 255.0));
}

// A bright half-plane over a dark one, below the line y = y0 + slope * x (or, transposed, right of
// x = x0 + slope * y), each pixel `samples` x `samples` times sampled and averaged in linear light: 1 sample
// at the pixel centre is the aliased render, 16 x 16 the reference.
Image halfPlane(double slope, bool transposed, int samples) {
    const std::uint8_t dark[3] = {30, 40, 50}, bright[3] = {230, 210, 190};
    Image image(std::size_t(kW) * kH * 4);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            double covered = 0.0;
            for (int sy = 0; sy < samples; ++sy)
                for (int sx = 0; sx < samples; ++sx) {
                    const double px = x + (sx + 0.5) / samples, py = y + (sy + 0.5) / samples;
                    covered += transposed ? (px > 40.3 + slope * py) : (py > 20.3 + slope * px);
                }
            covered /= samples * samples;
            std::uint8_t* p = &image[4 * (std::size_t(y) * kW + x)];
            for (int c = 0; c < 3; ++c)
                p[c] = toSrgb((1.0 - covered) * toLinear(dark[c]) + covered * toLinear(bright[c]));
            p[3] = 255;
        }
    return image;
}

double meanError(const Image& a, const Image& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
        sum += std::abs(int(a[i]) - int(b[i]));
    return sum / double(a.size());
}

Image filtered(Image image, int width, int height, int threads = 1) {
    fxaa(image.data(), width, height, threads);
    return image;
}

TEST(FxaaTest, StaircaseEdgesComeOutCloserToTheirCoverage) {
    for (bool transposed : {false, true})
        for (double slope : {0.1, 0.25, 0.45}) {
            const Image aliased = halfPlane(slope, transposed, 1);
            const Image reference = halfPlane(slope, transposed, 16);
            const Image smooth = filtered(aliased, kW, kH);
            const double before = meanError(aliased, reference), after = meanError(smooth, reference);
            EXPECT_LT(after, 0.6 * before)
                << "slope " << slope << (transposed ? ", vertical" : ", horizontal") << ": mean error "
                << before << " -> " << after;
        }
}

TEST(FxaaTest, CopiesPixelsAwayFromEdgesAndFaintGradientsBitForBit) {
    const Image aliased = halfPlane(0.25, false, 1);
    const Image smooth = filtered(aliased, kW, kH);
    int changedFar = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const double edgeY = 20.3 + 0.25 * (x + 0.5);
            const std::size_t i = 4 * (std::size_t(y) * kW + x);
            if (std::abs(y + 0.5 - edgeY) > 3.0)
                for (int c = 0; c < 4; ++c)
                    changedFar += aliased[i + std::size_t(c)] != smooth[i + std::size_t(c)];
            EXPECT_EQ(smooth[i + 3], 255);
        }
    EXPECT_EQ(changedFar, 0);

    // A gradient of one 8-bit step per pixel is below the edge threshold: no pixel changes.
    Image gradient(std::size_t(kW) * kH * 4);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 4; ++c)
                gradient[4 * (std::size_t(y) * kW + x) + std::size_t(c)] =
                    std::uint8_t(c == 3 ? 255 : 60 + x);
    EXPECT_EQ(filtered(gradient, kW, kH), gradient);
}

TEST(FxaaTest, TheResultDoesNotDependOnTheThreadCount) {
    // Tall enough that the rows split across threads (at least 64 Ki pixels each).
    const int width = 320, height = 1024;
    Image image(std::size_t(width) * height * 4);
    std::uint32_t state = 12345;
    for (std::size_t i = 0; i < image.size(); ++i) {
        state = state * 1664525u + 1013904223u;
        // Blocks of 3 x 5 pixels, each dark or bright: edges everywhere.
        const std::size_t pixel = i / 4, x = pixel % std::size_t(width), y = pixel / std::size_t(width);
        image[i] = ((x / 3 + y / 5 * 7) * 2654435761u >> 7) % 2 ? 220 : std::uint8_t(20 + state % 8);
    }
    const Image one = filtered(image, width, height, 1);
    for (int threads : {2, 3, 4})
        EXPECT_EQ(filtered(image, width, height, threads), one) << threads << " threads";
}

TEST(FxaaTest, AnImageOfEdgesEverywhereFiltersToTheSameBytesAsBefore) {
    // Pins the filter's exact output (a checksum of an image of random blocks and odd sizes, every row and
    // column edge case): a faster way of finding edges must find the same ones.
    const struct {
        int width, height;
        std::uint64_t hash;
    } cases[] = {{333, 257, 8456460426139982564ull},
                 {1, 9, 10160150102551005539ull},
                 {9, 1, 14683601576206096322ull},
                 {31, 2, 15164357907642108558ull}};
    for (const auto& [width, height, expected] : cases) {
        Image image(std::size_t(width) * std::size_t(height) * 4);
        std::uint32_t state = 777;
        for (std::size_t i = 0; i < image.size(); ++i) {
            state = state * 1664525u + 1013904223u;
            const std::size_t pixel = i / 4, x = pixel % std::size_t(width), y = pixel / std::size_t(width);
            image[i] = std::uint8_t(((x / 2 + y / 3 * 5) * 2654435761u >> 9) % 3 * 100 + state % 24);
        }
        const Image out = filtered(image, width, height, 2);
        if (width > 100) { // edges everywhere: many pixels filtered
            EXPECT_GT(meanError(out, image), 1.0);
        }
        std::uint64_t hash = 1469598103934665603ull; // FNV-1a
        for (std::uint8_t byte : out)
            hash = (hash ^ byte) * 1099511628211ull;
        EXPECT_EQ(hash, expected) << width << "x" << height;
    }
}

TEST(FxaaTest, DegenerateSizesWork) {
    for (auto [w, h] : {std::pair{1, 1}, std::pair{1, 7}, std::pair{7, 1}, std::pair{2, 2}}) {
        Image image(std::size_t(w) * std::size_t(h) * 4);
        for (std::size_t i = 0; i < image.size(); ++i)
            image[i] = (i / 4) % 2 ? 255 : 0;
        const Image out = filtered(image, w, h);
        for (std::size_t i = 3; i < out.size(); i += 4)
            EXPECT_EQ(out[i], image[i]) << w << "x" << h;
    }
    fxaa(nullptr, 0, 0); // nothing to do
}

} // namespace
} // namespace sp::render
