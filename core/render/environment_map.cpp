#include "core/render/environment_map.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <string>

#include <Eigen/Geometry>

#include "core/base/error.h"
#include "core/base/parallel.h"
#include "core/render/luminance.h"

namespace sp::render {
namespace {

std::uint64_t nextUid() {
    static std::atomic<std::uint64_t> counter{0};
    return ++counter;
}

// Bilinear lookup at texture coordinates (u wraps around, v is clamped), texel centres at (i + 0.5) / size.
Eigen::Vector3f bilinear(const RadianceImage& image, float u, float v) {
    u -= std::floor(u); // [0, 1), so that x below is in [-0.5, width - 0.5)
    const float x = u * float(image.width) - 0.5f,
                y = std::clamp(v * float(image.height) - 0.5f, 0.0f, float(image.height - 1));
    const float fx = std::floor(x), fy = std::floor(y);
    const float tx = x - fx, ty = y - fy;
    const int y0 = int(fy), y1 = std::min(y0 + 1, image.height - 1);
    int x0 = std::min(int(fx), image.width - 1), x1 = x0 + 1;
    if (x0 < 0)
        x0 += image.width;
    if (x1 >= image.width)
        x1 -= image.width;
    return (image.at(x0, y0) * (1.0f - tx) + image.at(x1, y0) * tx) * (1.0f - ty) +
           (image.at(x0, y1) * (1.0f - tx) + image.at(x1, y1) * tx) * ty;
}

// The image turned about +Z by `yawDegrees` (to the left): column x takes the old image at x + the turn.
RadianceImage turned(RadianceImage image, float yawDegrees) {
    const float shift = std::fmod(yawDegrees, 360.0f) / 360.0f;
    if (shift == 0.0f)
        return image;
    RadianceImage out{image.width, image.height, std::vector<Eigen::Vector3f>(image.texels.size())};
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            out.texels[std::size_t(y) * std::size_t(image.width) + std::size_t(x)] =
                bilinear(image, (float(x) + 0.5f) / float(image.width) + shift,
                         (float(y) + 0.5f) / float(image.height));
    return out;
}

// `image` averaged (or, when smaller, interpolated) to width x height: each texel is the mean of a grid of
// bilinear lookups over its footprint, fine enough to see every source texel.
RadianceImage resampled(const RadianceImage& image, int width, int height) {
    const int steps = std::max(1, (image.width + width - 1) / width);
    RadianceImage out{width, height, std::vector<Eigen::Vector3f>(std::size_t(width) * std::size_t(height))};
    parallelFor(height, hardwareThreads(), [&](int y) {
        for (int x = 0; x < width; ++x) {
            Eigen::Vector3f sum = Eigen::Vector3f::Zero();
            for (int j = 0; j < steps; ++j)
                for (int i = 0; i < steps; ++i)
                    sum += bilinear(image, (float(x) + (float(i) + 0.5f) / float(steps)) / float(width),
                                    (float(y) + (float(j) + 0.5f) / float(steps)) / float(height));
            out.texels[std::size_t(y) * std::size_t(width) + std::size_t(x)] = sum / float(steps * steps);
        }
    });
    return out;
}

// The solid angle of a texel of row y of an equirectangular image width x height.
float texelSolidAngle(int y, int width, int height) {
    const float theta0 = kPi * float(y) / float(height), theta1 = kPi * float(y + 1) / float(height);
    return 2.0f * kPi / float(width) * (std::cos(theta0) - std::cos(theta1));
}

std::array<float, 9> shBasis(const Eigen::Vector3f& d) {
    const float x = d.x(), y = d.y(), z = d.z();
    return {0.282095f,
            0.488603f * y,
            0.488603f * z,
            0.488603f * x,
            1.092548f * x * y,
            1.092548f * y * z,
            0.315392f * (3.0f * z * z - 1.0f),
            1.092548f * x * z,
            0.546274f * (x * x - y * y)};
}

// The GGX half vector about +Z for roughness^2 = a (Karis 2013).
Eigen::Vector3f ggxHalfVector(float u1, float u2, float a) {
    const float phi = 2.0f * kPi * u1;
    const float cosTheta = std::sqrt((1.0f - u2) / (1.0f + (a * a - 1.0f) * u2));
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

// The radical inverse in base 2 of i (the Hammersley set's second coordinate).
float radicalInverse(std::uint32_t i) {
    i = (i << 16u) | (i >> 16u);
    i = ((i & 0x55555555u) << 1u) | ((i & 0xAAAAAAAAu) >> 1u);
    i = ((i & 0x33333333u) << 2u) | ((i & 0xCCCCCCCCu) >> 2u);
    i = ((i & 0x0F0F0F0Fu) << 4u) | ((i & 0xF0F0F0F0u) >> 4u);
    i = ((i & 0x00FF00FFu) << 8u) | ((i & 0xFF00FF00u) >> 8u);
    return float(i) * 2.3283064365386963e-10f;
}

// Level `level` of the chain: the lighting map convolved with the GGX lobe of roughness level / (levels - 1)
// about each texel's direction (taken as normal and view, as the split sum does), reading a box pyramid of
// the lighting map at the level whose texels are about one sample's solid angle (Colbert and Krivanek 2007,
// "GPU-Based Importance Sampling"), so that few samples do not alias.
RadianceImage prefiltered(const std::vector<RadianceImage>& pyramid, int level) {
    // Few samples suffice where each reads the pyramid level of its own solid angle (the level of roughness
    // 0.2, the largest, is most of the time: a moving sun makes a new map every frame).
    constexpr int kSamples = 32;
    const float roughness = float(level) / float(EnvironmentMap::kSpecularLevels - 1);
    const float a = roughness * roughness, a2 = a * a;
    const int width = pyramid[0].width >> level, height = pyramid[0].height >> level;
    const float texelAngle = 4.0f * kPi / float(pyramid[0].width * pyramid[0].height);
    // The samples are the same about every texel's direction: their directions in the texel's frame (the
    // half vector's mirror of the view, which is the normal) and the pyramid level each reads, made once.
    struct Sample {
        Eigen::Vector3f l; // in the frame whose z is the texel's direction
        float nol;
        int lod;
    };
    std::vector<Sample> samples;
    float weight = 0.0f;
    for (int i = 0; i < kSamples; ++i) {
        const Eigen::Vector3f h =
            ggxHalfVector((float(i) + 0.5f) / float(kSamples), radicalInverse(std::uint32_t(i)), a);
        const Eigen::Vector3f l = 2.0f * h.z() * h - Eigen::Vector3f::UnitZ();
        if (l.z() <= 0.0f)
            continue;
        // With n = v the sample's density per steradian is D(h) / 4.
        const float denominator = h.z() * h.z() * (a2 - 1.0f) + 1.0f;
        const float d = a2 / std::max(kPi * denominator * denominator, 1e-12f);
        const float sampleAngle = 1.0f / (float(kSamples) * std::max(d * 0.25f, 1e-12f));
        const int lod = std::clamp(int(std::lround(0.5f * std::log2(sampleAngle / texelAngle) + 1.0f)), 0,
                                   int(pyramid.size()) - 1);
        samples.push_back({l, l.z(), lod});
        weight += l.z();
    }
    RadianceImage out{width, height, std::vector<Eigen::Vector3f>(std::size_t(width) * std::size_t(height))};
    parallelFor(height, hardwareThreads(), [&](int y) {
        for (int x = 0; x < width; ++x) {
            const Eigen::Vector3f n =
                EnvironmentMap::fromUv((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height));
            const Eigen::Vector3f helper =
                std::abs(n.z()) < 0.999f ? Eigen::Vector3f::UnitZ() : Eigen::Vector3f::UnitX();
            const Eigen::Vector3f tx = helper.cross(n).normalized(), ty = n.cross(tx);
            Eigen::Vector3f sum = Eigen::Vector3f::Zero();
            for (const Sample& sample : samples) {
                const Eigen::Vector2f uv =
                    EnvironmentMap::toUv(tx * sample.l.x() + ty * sample.l.y() + n * sample.l.z());
                sum += bilinear(pyramid[std::size_t(sample.lod)], uv.x(), uv.y()) * sample.nol;
            }
            out.texels[std::size_t(y) * std::size_t(width) + std::size_t(x)] =
                weight > 0.0f ? Eigen::Vector3f(sum / weight) : Eigen::Vector3f::Zero();
        }
    });
    return out;
}

} // namespace

Eigen::Vector2f EnvironmentMap::toUv(const Eigen::Vector3f& direction) {
    const float phi = std::atan2(direction.y(), direction.x()); // 0 straight up or down, as the shaders
    float u = 0.5f - phi / (2.0f * kPi);
    u -= std::floor(u);
    const float v = std::acos(std::clamp(direction.z(), -1.0f, 1.0f)) / kPi;
    return {u, v};
}

Eigen::Vector3f EnvironmentMap::fromUv(float u, float v) {
    const float phi = kPi * (1.0f - 2.0f * u), theta = kPi * v;
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

EnvironmentMap::EnvironmentMap(RadianceImage radiance, float yawDegrees, const char* function)
    : uid_(nextUid()) {
    SP_CHECK(radiance.height >= 4 && radiance.width == 2 * radiance.height && radiance.width <= 16384,
             InvalidArgument, function, ": an environment map must be equirectangular (width = 2 x height), ",
             "8 x 4 to 16384 x 8192 texels, got ", radiance.width, " x ", radiance.height);
    SP_CHECK(radiance.texels.size() == std::size_t(radiance.width) * std::size_t(radiance.height),
             InvalidArgument, function, ": ", radiance.texels.size(), " texels for a ", radiance.width, " x ",
             radiance.height, " environment map");
    for (const Eigen::Vector3f& texel : radiance.texels)
        SP_CHECK(texel.allFinite() && texel.minCoeff() >= 0.0f, InvalidArgument, function,
                 ": an environment map's radiance must be finite and non-negative, got (", texel.x(), ", ",
                 texel.y(), ", ", texel.z(), ")");
    SP_CHECK(std::isfinite(yawDegrees), InvalidArgument, function, ": the map's angle must be finite, got ",
             yawDegrees);
    full_ = turned(std::move(radiance), yawDegrees);
    lighting_ = resampled(full_, kLightingWidth, kLightingHeight);
    // FNV-1a over the turned map's float bits, four bytes at a time: about what the validation above costs.
    contentHash_ = 0xcbf29ce484222325ull ^ (std::uint64_t(full_.width) << 32 | std::uint32_t(full_.height));
    for (const Eigen::Vector3f& texel : full_.texels)
        for (int c = 0; c < 3; ++c) {
            std::uint32_t bits = 0;
            std::memcpy(&bits, &texel[c], sizeof bits);
            contentHash_ = (contentHash_ ^ bits) * 0x100000001b3ull;
        }

    // Spherical harmonics of the radiance, then of the irradiance (the clamped cosine's bands: pi, 2 pi / 3,
    // pi / 4), divided by pi.
    std::array<Eigen::Vector3f, 9> coefficients;
    coefficients.fill(Eigen::Vector3f::Zero());
    float totalAngle = 0.0f;
    for (int y = 0; y < kLightingHeight; ++y) {
        const float angle = texelSolidAngle(y, kLightingWidth, kLightingHeight);
        for (int x = 0; x < kLightingWidth; ++x) {
            const Eigen::Vector3f& l = lighting_.at(x, y);
            const std::array<float, 9> basis = shBasis(fromUv((float(x) + 0.5f) / float(kLightingWidth),
                                                              (float(y) + 0.5f) / float(kLightingHeight)));
            for (int i = 0; i < 9; ++i)
                coefficients[std::size_t(i)] += l * (basis[std::size_t(i)] * angle);
            average_ += l * angle;
            totalAngle += angle;
        }
    }
    average_ /= totalAngle;
    const float band[9] = {1.0f, 2.0f / 3.0f, 2.0f / 3.0f, 2.0f / 3.0f, 0.25f, 0.25f, 0.25f, 0.25f, 0.25f};
    for (int i = 0; i < 9; ++i)
        diffuse_[std::size_t(i)] = coefficients[std::size_t(i)] * band[i];

    std::vector<RadianceImage> pyramid{lighting_};
    while (pyramid.back().height > 1) {
        const RadianceImage& above = pyramid.back();
        RadianceImage below{above.width / 2, above.height / 2, {}};
        below.texels.resize(std::size_t(below.width) * std::size_t(below.height));
        for (int y = 0; y < below.height; ++y)
            for (int x = 0; x < below.width; ++x)
                below.texels[std::size_t(y) * std::size_t(below.width) + std::size_t(x)] =
                    (above.at(2 * x, 2 * y) + above.at(2 * x + 1, 2 * y) + above.at(2 * x, 2 * y + 1) +
                     above.at(2 * x + 1, 2 * y + 1)) *
                    0.25f;
        pyramid.push_back(std::move(below));
    }
    specular_.push_back(lighting_);
    for (int level = 1; level < kSpecularLevels; ++level)
        specular_.push_back(prefiltered(pyramid, level));

    // Sampling: each texel in proportion to its luminance times sin(theta) (its solid angle).
    density_.resize(std::size_t(kLightingWidth) * kLightingHeight);
    columnCdf_.assign(std::size_t(kLightingHeight) * (kLightingWidth + 1), 0.0f);
    rowCdf_.assign(kLightingHeight + 1, 0.0f);
    for (int y = 0; y < kLightingHeight; ++y) {
        const float sinTheta = std::sin(kPi * (float(y) + 0.5f) / float(kLightingHeight));
        float* cdf = &columnCdf_[std::size_t(y) * (kLightingWidth + 1)];
        for (int x = 0; x < kLightingWidth; ++x) {
            const float f = luminance(lighting_.at(x, y)) * sinTheta;
            density_[std::size_t(y) * kLightingWidth + std::size_t(x)] = f;
            cdf[x + 1] = cdf[x] + f;
        }
        rowCdf_[std::size_t(y) + 1] = rowCdf_[std::size_t(y)] + cdf[kLightingWidth];
    }
    const float total = rowCdf_.back();
    if (total > 0.0f)
        for (float& f : density_)
            f /= total; // each texel's probability
}

Eigen::Vector3f EnvironmentMap::radiance(const Eigen::Vector3f& direction) const {
    const Eigen::Vector2f uv = toUv(direction);
    return bilinear(full_, uv.x(), uv.y());
}

Eigen::Vector3f EnvironmentMap::diffuse(const Eigen::Vector3f& n) const {
    const std::array<float, 9> basis = shBasis(n);
    Eigen::Vector3f sum = Eigen::Vector3f::Zero();
    for (int i = 0; i < 9; ++i)
        sum += diffuse_[std::size_t(i)] * basis[std::size_t(i)];
    return sum.cwiseMax(0.0f);
}

float EnvironmentMap::sample(float u1, float u2, Eigen::Vector3f& direction) const {
    const float total = rowCdf_.back();
    if (!(total > 0.0f))
        return 0.0f;
    // The row, then the column within it, each with the fraction of the way through its cell.
    const float rowTarget = u1 * total;
    const int y =
        std::clamp(int(std::upper_bound(rowCdf_.begin(), rowCdf_.end(), rowTarget) - rowCdf_.begin()) - 1, 0,
                   kLightingHeight - 1);
    const float rowMass = rowCdf_[std::size_t(y) + 1] - rowCdf_[std::size_t(y)];
    const float fy =
        rowMass > 0.0f ? std::clamp((rowTarget - rowCdf_[std::size_t(y)]) / rowMass, 0.0f, 1.0f) : 0.5f;
    const float* cdf = &columnCdf_[std::size_t(y) * (kLightingWidth + 1)];
    const float columnTarget = u2 * cdf[kLightingWidth];
    const int x = std::clamp(int(std::upper_bound(cdf, cdf + kLightingWidth + 1, columnTarget) - cdf) - 1, 0,
                             kLightingWidth - 1);
    const float columnMass = cdf[x + 1] - cdf[x];
    const float fx = columnMass > 0.0f ? std::clamp((columnTarget - cdf[x]) / columnMass, 0.0f, 1.0f) : 0.5f;
    const float v = (float(y) + fy) / float(kLightingHeight);
    direction = fromUv((float(x) + fx) / float(kLightingWidth), v);
    // The drawn texel's density (the direction, looked up again, may round into a neighbour at its edge).
    const float sinTheta = std::sin(kPi * v);
    if (sinTheta <= 0.0f)
        return 0.0f;
    return density_[std::size_t(y) * kLightingWidth + std::size_t(x)] * float(kLightingWidth) *
           float(kLightingHeight) / (2.0f * kPi * kPi * sinTheta);
}

float EnvironmentMap::pdf(const Eigen::Vector3f& direction) const {
    if (!(rowCdf_.back() > 0.0f))
        return 0.0f;
    const Eigen::Vector2f uv = toUv(direction);
    const int x = std::clamp(int(uv.x() * float(kLightingWidth)), 0, kLightingWidth - 1);
    const int y = std::clamp(int(uv.y() * float(kLightingHeight)), 0, kLightingHeight - 1);
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - direction.z() * direction.z()));
    if (sinTheta <= 0.0f)
        return 0.0f;
    // The texel's probability over its area of the unit square, per steradian (d omega = 2 pi^2 sin du dv).
    const float perUv = density_[std::size_t(y) * kLightingWidth + std::size_t(x)] * float(kLightingWidth) *
                        float(kLightingHeight);
    return perUv / (2.0f * kPi * kPi * sinTheta);
}

} // namespace sp::render
