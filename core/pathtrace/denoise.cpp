#include "core/pathtrace/denoise.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "core/base/error.h"
#include "core/render/luminance.h"

namespace sp::pathtrace {
namespace {

// Albedo below this is treated as this when dividing it out (a black surface's lighting is not knowable
// from its colour).
constexpr float kAlbedoFloor = 0.02f;
// A pass's luminance tolerance, relative to the pixels' luminance, halving each pass (without a measured
// variance).
constexpr float kLuminanceTolerance = 1.0f;
// With one: how many standard deviations of the pixel's mean a neighbour may differ by (SVGF's sigma_l).
constexpr float kDeviations = 4.0f;
// Samples a pixel needs before its own variance is trusted.
constexpr std::uint64_t kMeasuredFrom = 4;
// Depth tolerance per pixel of tap distance, relative to the depth.
constexpr float kDepthTolerance = 0.05f;
constexpr float kNormalPower = 32.0f;
// A pixel whose lighting is more than this many times its third brightest neighbour's (of its instance) is
// a firefly: a rare path (a caustic of the sun off glossy metal) that the luminance test would otherwise keep
// from its neighbours in every pass, leaving a white speck. The third: at 64 samples such paths are common
// enough that specks touch, and a feature of the lighting is seldom one pixel wide.
constexpr float kFireflyRatio = 2.0f;
constexpr int kFireflyRank = 3;

float luminance(const float* c) {
    return render::luminance(c[0], c[1], c[2]);
}

// Scales each firefly of `lighting` down to its neighbours (the kFireflyRank-th brightest in the 3 x 3
// around it, of its instance). A bright feature two pixels wide has enough neighbours as bright and is kept;
// so is a pixel with too few neighbours of its instance to be measured against. Biased, as clamping is: the
// energy of the rare path is dropped rather than spread.
void removeFireflies(std::vector<float>& lighting, const DenoiseGuides& guides) {
    const std::vector<float> source = lighting;
    const int width = guides.width, height = guides.height;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t p = std::size_t(y) * std::size_t(width) + std::size_t(x);
            if (guides.ids[p] == 0)
                continue;
            std::array<float, 8> around{};
            int count = 0;
            for (int qy = std::max(y - 1, 0); qy <= std::min(y + 1, height - 1); ++qy)
                for (int qx = std::max(x - 1, 0); qx <= std::min(x + 1, width - 1); ++qx) {
                    const std::size_t q = std::size_t(qy) * std::size_t(width) + std::size_t(qx);
                    if (q != p && guides.ids[q] == guides.ids[p])
                        around[std::size_t(count++)] = luminance(&source[q * 3]);
                }
            if (count < kFireflyRank)
                continue;
            std::nth_element(around.begin(), around.begin() + (kFireflyRank - 1), around.begin() + count,
                             std::greater<>());
            const float reference = around[kFireflyRank - 1], own = luminance(&source[p * 3]);
            if (own > kFireflyRatio * reference)
                for (int c = 0; c < 3; ++c)
                    lighting[p * 3 + std::size_t(c)] *= reference / own;
        }
}

} // namespace

std::vector<float> denoise(std::span<const float> color, const DenoiseGuides& guides, int passes) {
    const std::size_t pixels = std::size_t(guides.width) * std::size_t(guides.height);
    SP_CHECK(guides.width > 0 && guides.height > 0, InvalidArgument, "denoise(): the image is ", guides.width,
             "x", guides.height);
    SP_CHECK(passes >= 1 && passes <= 8, InvalidArgument, "denoise(): passes ", passes,
             " is out of range [1, 8]");
    SP_CHECK(color.size() == pixels * 3, InvalidArgument, "denoise(): color has ", color.size(),
             " values for ", pixels, " pixels of 3");
    SP_CHECK(guides.albedo.size() == pixels * 3, InvalidArgument, "denoise(): albedo has ",
             guides.albedo.size(), " values for ", pixels, " pixels of 3");
    SP_CHECK(guides.normal.size() == pixels * 3, InvalidArgument, "denoise(): normal has ",
             guides.normal.size(), " values for ", pixels, " pixels of 3");
    SP_CHECK(guides.depth.size() == pixels, InvalidArgument, "denoise(): depth has ", guides.depth.size(),
             " values for ", pixels, " pixels");
    SP_CHECK(guides.ids.size() == pixels, InvalidArgument, "denoise(): ids has ", guides.ids.size(),
             " values for ", pixels, " pixels");
    SP_CHECK(guides.variance.empty() || guides.variance.size() == pixels, InvalidArgument,
             "denoise(): variance has ", guides.variance.size(), " values for ", pixels, " pixels");
    const bool measured = !guides.variance.empty();
    std::vector<float> variance(guides.variance.begin(), guides.variance.end()),
        nextVariance(variance.size()), spread(variance.size());

    // The lighting: colour over albedo.
    std::vector<float> current(pixels * 3), next(pixels * 3);
    for (std::size_t i = 0; i < pixels * 3; ++i)
        current[i] = color[i] / std::max(guides.albedo[i], kAlbedoFloor);
    removeFireflies(current, guides);

    constexpr float kernel[5] = {1.0f / 16, 1.0f / 4, 3.0f / 8, 1.0f / 4, 1.0f / 16};
    const int width = guides.width, height = guides.height;
    for (int pass = 0; pass < passes; ++pass) {
        const int step = 1 << pass;
        const float tolerance = kLuminanceTolerance / float(1 << pass);
        if (measured) // the standard deviation each pixel's test allows: its variance over its 3 x 3, same
                      // instance
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) {
                    const std::size_t p = std::size_t(y) * std::size_t(width) + std::size_t(x);
                    float sum = 0.0f, total = 0.0f;
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            const int qx = x + dx, qy = y + dy;
                            if (qx < 0 || qy < 0 || qx >= width || qy >= height)
                                continue;
                            const std::size_t q = std::size_t(qy) * std::size_t(width) + std::size_t(qx);
                            if (guides.ids[q] != guides.ids[p])
                                continue;
                            const float w = (dx == 0 ? 2.0f : 1.0f) * (dy == 0 ? 2.0f : 1.0f);
                            sum += w * variance[q];
                            total += w;
                        }
                    spread[p] = kDeviations * std::sqrt(std::max(sum / total, 0.0f));
                }
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const std::size_t p = std::size_t(y) * std::size_t(width) + std::size_t(x);
                const float* cp = &current[p * 3];
                if (guides.ids[p] == 0) { // background: kept as it is, and no tap for others
                    std::copy(cp, cp + 3, &next[p * 3]);
                    continue;
                }
                const float* np = &guides.normal[p * 3];
                const float zp = guides.depth[p], lp = luminance(cp);
                float sum[3] = {0.0f, 0.0f, 0.0f}, total = 0.0f, carried = 0.0f;
                for (int dy = -2; dy <= 2; ++dy) {
                    const int qy = y + dy * step;
                    if (qy < 0 || qy >= height)
                        continue;
                    for (int dx = -2; dx <= 2; ++dx) {
                        const int qx = x + dx * step;
                        if (qx < 0 || qx >= width)
                            continue;
                        const std::size_t q = std::size_t(qy) * std::size_t(width) + std::size_t(qx);
                        if (guides.ids[q] != guides.ids[p])
                            continue;
                        const float* cq = &current[q * 3];
                        const float* nq = &guides.normal[q * 3];
                        const float facing = std::max(0.0f, np[0] * nq[0] + np[1] * nq[1] + np[2] * nq[2]);
                        const float taps = float(std::max(std::abs(dx), std::abs(dy)) * step);
                        const float depth =
                            std::abs(zp - guides.depth[q]) / (kDepthTolerance * zp * taps + 1e-4f);
                        float lighting = 0.0f; // the exponent of the luminance test
                        if (measured) {
                            lighting = std::abs(lp - luminance(cq)) / (spread[p] + 1e-6f);
                        } else {
                            const float light = std::abs(lp - luminance(cq)) /
                                                (tolerance * 0.5f * (lp + luminance(cq)) + 1e-4f);
                            lighting = light * light;
                        }
                        const float w = kernel[dx + 2] * kernel[dy + 2] * std::pow(facing, kNormalPower) *
                                        std::exp(-depth - lighting);
                        for (int c = 0; c < 3; ++c)
                            sum[c] += w * cq[c];
                        total += w;
                        if (measured)
                            carried += w * w * variance[q];
                    }
                }
                for (int c = 0; c < 3; ++c) // total > 0: the pixel itself is a tap of weight > 0
                    next[p * 3 + std::size_t(c)] = total > 0.0f ? sum[c] / total : cp[c];
                if (measured)
                    nextVariance[p] = total > 0.0f ? carried / (total * total) : variance[p];
            }
        std::swap(current, next);
        std::swap(variance, nextVariance);
    }
    for (std::size_t i = 0; i < pixels * 3; ++i)
        current[i] =
            guides.ids[i / 3] == 0 ? color[i] : current[i] * std::max(guides.albedo[i], kAlbedoFloor);
    return current;
}

std::vector<float> denoise(const Accumulation& image, int passes) {
    const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height);
    SP_CHECK(image.samples > 0 && image.sum.size() == pixels * 3 && image.albedoSum.size() == pixels * 3 &&
                 image.directSum.size() == pixels * 3 && image.ids.size() == pixels,
             InvalidArgument, "denoise(): the accumulation holds no samples of a ", image.width, "x",
             image.height, " image");
    const double scale = 1.0 / double(image.samples);
    std::vector<float> color(pixels * 3), albedo(pixels * 3), normal(pixels * 3), depth(pixels), variance;
    const bool measured = image.samples >= kMeasuredFrom && image.indirectSquareSum.size() == pixels;
    if (measured)
        variance.resize(pixels);
    for (std::size_t p = 0; p < pixels; ++p) {
        double length = 0.0;
        for (std::size_t c = 0; c < 3; ++c) {
            color[p * 3 + c] = float((image.sum[p * 3 + c] - image.directSum[p * 3 + c]) * scale);
            albedo[p * 3 + c] = float(image.albedoSum[p * 3 + c] * scale);
            length += image.normalSum[p * 3 + c] * image.normalSum[p * 3 + c];
        }
        length = std::sqrt(length);
        for (std::size_t c = 0; c < 3; ++c)
            normal[p * 3 + c] = length > 0.0 ? float(image.normalSum[p * 3 + c] / length) : 0.0f;
        depth[p] = float(image.depthSum[p] * scale);
        if (measured) { // of the mean's luminance, over the albedo as the filter sees it
            const double mean = render::luminance<double>(color[p * 3], color[p * 3 + 1], color[p * 3 + 2]);
            const double spread =
                std::max(0.0, image.indirectSquareSum[p] * scale - mean * mean) / double(image.samples - 1);
            const double reflectance =
                std::max(double(render::luminance(albedo[p * 3], albedo[p * 3 + 1], albedo[p * 3 + 2])),
                         double(kAlbedoFloor));
            variance[p] = float(spread / (reflectance * reflectance));
        }
    }
    // The lights' direct light stays as it is (sharp shadows); the rest (sky, indirect) is filtered.
    std::vector<float> out =
        denoise(color, {image.width, image.height, albedo, normal, depth, image.ids, variance}, passes);
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] += float(image.directSum[i] * scale);
    return out;
}

} // namespace sp::pathtrace
