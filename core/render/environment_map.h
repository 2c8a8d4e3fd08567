#pragma once
// Light from every direction at infinity: an equirectangular radiance map (an HDR photograph of a sky, or
// the analytic sky of sky_model.h) and what both renderers derive from it once, when it is made:
//   - the rasteriser's diffuse term: the irradiance's first three spherical-harmonic bands (Ramamoorthi and
//     Hanrahan 2001, "An Efficient Representation for Irradiance Environment Maps");
//   - its specular term: a chain of maps prefiltered with the GGX lobe of growing roughness (Karis 2013,
//     "Real Shading in Unreal Engine 4", the split sum; the shaders' envBrdfApprox() is the other half);
//   - the path tracer's importance sampling: a piecewise-constant density over the map's texels, in
//     proportion to their luminance times their solid angle (Pharr, Jakob and Humphreys, "Physically Based
//     Rendering", 13.6.5), so that a small bright sun in a photograph does not become fireflies.
//
// Directions are world (right-handed, Z up, X forward, Y left). Row 0 of the map is the zenith (+Z), the
// last row the nadir; the centre column looks along +X and the image runs clockwise seen from above (the
// quarter column looks along +Y, to the left), as a panorama reads when one faces its centre.

#include <array>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sp::render {

inline constexpr float kPi = std::numbers::pi_v<float>;

// An RGB float image: row-major, `width` * `height` texels.
struct RadianceImage {
    int width = 0;
    int height = 0;
    std::vector<Eigen::Vector3f> texels;

    const Eigen::Vector3f& at(int x, int y) const { return texels[std::size_t(y) * std::size_t(width) + x]; }
};

// The linear RGB of a Radiance RGBE file (.hdr, flat or run-length encoded; decoded by stb_image beside the
// textures, texture_image.cpp), row 0 at the top. Throws sp::NotFound when there is no such file and
// sp::InvalidArgument, naming `function`, when it is not one or cannot be decoded.
RadianceImage readRadianceHdr(const std::string& path, const char* function);

class EnvironmentMap {
  public:
    // The prefiltered chain's base size: fine enough for mirror-like reflections of a sky, small enough to
    // prefilter in milliseconds; the lighting base (spherical harmonics, sampling) is the same size.
    static constexpr int kLightingWidth = 256;
    static constexpr int kLightingHeight = 128;
    // Levels of the prefiltered chain: level i holds roughness i / (kSpecularLevels - 1).
    static constexpr int kSpecularLevels = 6;

    // `radiance` (linear RGB, finite, non-negative, width = 2 * height, at least 8 x 4 and at most 16384
    // wide) rotated by `yawDegrees` about +Z (positive turns the panorama to the left, as UE's
    // SourceCubemapAngle). Throws sp::InvalidArgument naming `function` and the bad value.
    EnvironmentMap(RadianceImage radiance, float yawDegrees, const char* function);

    // The radiance arriving from unit direction `direction` (bilinear in the full-resolution map).
    Eigen::Vector3f radiance(const Eigen::Vector3f& direction) const;
    // The mean radiance over the sphere.
    const Eigen::Vector3f& average() const { return average_; }

    // The radiance a white Lambertian surface with unit normal n reflects: irradiance(n) / pi, from the
    // nine spherical-harmonic coefficients (RGB), in the order Y00, Y1-1, Y10, Y11, Y2-2, Y2-1, Y20, Y21,
    // Y22.
    Eigen::Vector3f diffuse(const Eigen::Vector3f& n) const;
    const std::array<Eigen::Vector3f, 9>& diffuseCoefficients() const { return diffuse_; }

    // The prefiltered chain: level 0 is kLightingWidth x kLightingHeight, each level half the one before.
    const std::vector<RadianceImage>& specularLevels() const { return specular_; }
    const RadianceImage& full() const { return full_; }

    // A direction drawn in proportion to luminance times solid angle, from two uniform numbers in [0, 1);
    // returns its density per steradian (0 when the map is black, and nothing can be drawn).
    float sample(float u1, float u2, Eigen::Vector3f& direction) const;
    // The density per steradian sample() draws `direction` with.
    float pdf(const Eigen::Vector3f& direction) const;

    // Unique to this map in the process (caches key on it; a map never changes once made).
    std::uint64_t uid() const { return uid_; }
    // A hash of the radiance (after the turn): equal for maps made alike, in any world and any run, so that
    // what is seeded from the light (the path tracer's samples, the probes) is too.
    std::uint64_t contentHash() const { return contentHash_; }

    // The map's texture coordinates of a direction (u in [0, 1) from the left, v in [0, 1] from the top)
    // and back.
    static Eigen::Vector2f toUv(const Eigen::Vector3f& direction);
    static Eigen::Vector3f fromUv(float u, float v);

  private:
    RadianceImage full_;
    RadianceImage lighting_; // the map, averaged down to kLightingWidth x kLightingHeight
    Eigen::Vector3f average_ = Eigen::Vector3f::Zero();
    std::array<Eigen::Vector3f, 9> diffuse_{};
    std::vector<RadianceImage> specular_;
    // Sampling: the marginal over rows and each row's conditional over columns, as cumulative sums.
    std::vector<float> rowCdf_;    // kLightingHeight + 1
    std::vector<float> columnCdf_; // kLightingHeight * (kLightingWidth + 1)
    std::vector<float> density_;   // each texel's probability (of the lighting map)
    std::uint64_t uid_ = 0;
    std::uint64_t contentHash_ = 0;
};

} // namespace sp::render
