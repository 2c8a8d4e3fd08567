#pragma once
// Indirect light for the rasteriser: a regular grid of irradiance probes over the scene (the first two
// spherical-harmonic bands of the light arriving at each probe, from every direction, bounced or not), which
// the shading blends per pixel in place of the uniform sky term. Pure CPU data: whoever lights the probes
// (sp::pathtrace::ProbeLighting, with Embree rays) sets it on the Scene, and the Renderer uploads it as a
// 3D texture when its revision changes.
//
// Blending (the shaders' irradianceBlend(), mirrored by IrradianceVolume::radiance() for tests): the eight
// probes around the point, moved a little along its normal, weighted trilinearly, by how much each probe
// lies in front of the surface (Majercik et al. 2019, "Dynamic Diffuse Global Illumination with Ray-Traced
// Irradiance Fields", the "backface" weight), and by whether the point lies in the probe's free box: the
// box around the probe bounded by the first surface along each axis. A wall between a probe and the point
// ends that box before the point, so sunlight outside a closed room does not leak into it. The box stands
// in for DDGI's per-direction depth moments at two texel fetches per probe, which a software rasteriser can
// afford at 1080p; it is exact for walls along the axes and conservative (some leaking) for slanted ones.

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace sp::render {

// What a probe knows of the light and the space around it.
struct IrradianceProbe {
    // The radiance a white Lambertian surface facing unit normal n reflects there is max(constant + linear n,
    // 0) per channel: the irradiance's bands 0 and 1 divided by pi. Column j of `linear` is the RGB slope
    // along world axis j.
    Eigen::Vector3f constant = Eigen::Vector3f::Zero();
    Eigen::Matrix3f linear = Eigen::Matrix3f::Zero();
    // How far the probe sees free space along -X, +X, -Y, +Y, -Z, +Z, in cells (probe spacings), at most
    // kMaxFreeDistance; all 0 for a probe inside geometry, which no point then uses.
    std::array<float, 6> freeDistance{};
};

struct IrradianceVolume {
    // A free box further than this does not change the blend: points blend probes at most a cell away, plus
    // the normal offset.
    static constexpr float kMaxFreeDistance = 2.0f;
    // How far (in cells) a point is moved along its normal before the probes are blended: off the surface, so
    // that a probe just behind it does not count as seeing it.
    static constexpr float kNormalOffset = 0.25f;

    Eigen::Vector3d origin = Eigen::Vector3d::Zero(); // world position of probe (0, 0, 0)
    double spacing = 1.0;                             // metres between neighbouring probes, along every axis
    Eigen::Vector3i counts{2, 2, 2};                  // probes along X, Y, Z, each at least 2
    std::vector<IrradianceProbe> probes;              // counts.prod(), X fastest, then Y, then Z
    // Bumped by whoever changes the probes, so that the renderer uploads them again.
    std::uint64_t revision = 0;

    std::size_t index(int x, int y, int z) const {
        return (std::size_t(z) * std::size_t(counts.y()) + std::size_t(y)) * std::size_t(counts.x()) +
               std::size_t(x);
    }
    Eigen::Vector3d position(int x, int y, int z) const {
        return origin + spacing * Eigen::Vector3d(double(x), double(y), double(z));
    }
    // Throws sp::InvalidArgument naming the bad field: counts below 2 or above 256 per axis, spacing not
    // positive and finite, the wrong number of probes, values that are not finite.
    void validate(const char* function) const;

    // The blended radiance a white Lambertian surface at world point p with unit normal n reflects: what the
    // shaders compute (single precision, before the texture's float16 rounding).
    Eigen::Vector3f radiance(const Eigen::Vector3d& p, const Eigen::Vector3f& n) const;

    // The probes as the renderer's RGBA32UI 3D texture of (2 counts.x, counts.y, counts.z) texels, two per
    // probe along X: float16 pairs of constant and linear, then the free distances as 8-bit fractions of
    // kMaxFreeDistance (see irradianceBlend() in shaders.cpp).
    std::vector<std::uint32_t> packed() const;
};

} // namespace sp::render
