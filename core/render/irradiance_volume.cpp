#include "core/render/irradiance_volume.h"

#include <algorithm>
#include <cmath>

#include "core/base/error.h"
#include "core/render/image_buffer.h"

namespace sp::render {
namespace {

std::uint32_t halves(float low, float high) {
    return std::uint32_t(floatToHalf(low)) | (std::uint32_t(floatToHalf(high)) << 16);
}

std::uint32_t bytes(float a, float b, float c, float d) {
    const auto byte = [](float v) {
        return std::uint32_t(
            std::lround(std::clamp(v / IrradianceVolume::kMaxFreeDistance, 0.0f, 1.0f) * 255.0f));
    };
    return byte(a) | (byte(b) << 8) | (byte(c) << 16) | (byte(d) << 24);
}

} // namespace

void IrradianceVolume::validate(const char* function) const {
    for (int axis = 0; axis < 3; ++axis)
        SP_CHECK(counts[axis] >= 2 && counts[axis] <= 256, InvalidArgument, function,
                 ": IrradianceVolume::counts[", axis, "] must be in [2, 256], got ", counts[axis]);
    SP_CHECK(std::isfinite(spacing) && spacing > 0.0, InvalidArgument, function,
             ": IrradianceVolume::spacing must be positive and finite, got ", spacing);
    SP_CHECK(origin.allFinite(), InvalidArgument, function, ": IrradianceVolume::origin must be finite");
    const std::size_t expected = std::size_t(counts.x()) * std::size_t(counts.y()) * std::size_t(counts.z());
    SP_CHECK(probes.size() == expected, InvalidArgument, function, ": IrradianceVolume has ", probes.size(),
             " probes for counts ", counts.x(), "x", counts.y(), "x", counts.z(), " (", expected, ")");
    for (std::size_t i = 0; i < probes.size(); ++i) {
        const IrradianceProbe& probe = probes[i];
        const bool finite = probe.constant.allFinite() && probe.linear.allFinite() &&
                            std::all_of(probe.freeDistance.begin(), probe.freeDistance.end(),
                                        [](float d) { return std::isfinite(d) && d >= 0.0f; });
        SP_CHECK(finite, InvalidArgument, function, ": IrradianceVolume probe ", i,
                 " has a value that is not finite (or a negative free distance)");
    }
}

Eigen::Vector3f IrradianceVolume::radiance(const Eigen::Vector3d& p, const Eigen::Vector3f& n) const {
    const Eigen::Vector3f top = (counts - Eigen::Vector3i::Ones()).cast<float>();
    const Eigen::Vector3f g = (((p - origin) / spacing).cast<float>() + n * kNormalOffset)
                                  .cwiseMax(Eigen::Vector3f::Zero())
                                  .cwiseMin(top);
    Eigen::Vector3i base;
    for (int axis = 0; axis < 3; ++axis)
        base[axis] = std::min(int(g[axis]), counts[axis] - 2);
    const Eigen::Vector3f f = g - base.cast<float>();
    Eigen::Vector3f constant = Eigen::Vector3f::Zero();
    Eigen::Matrix3f linear = Eigen::Matrix3f::Zero();
    float total = 0.0f;
    for (int i = 0; i < 8; ++i) {
        const Eigen::Vector3i o(i & 1, (i >> 1) & 1, i >> 2);
        const Eigen::Vector3i c = base + o;
        const IrradianceProbe& probe = probes[index(c.x(), c.y(), c.z())];
        const Eigen::Vector3f d = g - c.cast<float>(); // from the probe to the point, in cells
        float trilinear = 1.0f, excess = -1e30f;
        for (int axis = 0; axis < 3; ++axis) {
            trilinear *= o[axis] != 0 ? f[axis] : 1.0f - f[axis];
            // Quantised as the texture stores it.
            const float reach =
                std::round(std::min(probe.freeDistance[std::size_t(2 * axis + (d[axis] >= 0.0f ? 1 : 0))] /
                                        kMaxFreeDistance,
                                    1.0f) *
                           255.0f) /
                255.0f * kMaxFreeDistance;
            excess = std::max(excess, std::abs(d[axis]) - reach);
        }
        const float visible = std::clamp(1.0f - 4.0f * excess, 0.0f, 1.0f);
        const float length = d.norm();
        const float facing = length > 1e-4f ? -d.dot(n) / length : 1.0f;
        const float front = facing * 0.5f + 0.5f;
        const float w = trilinear * (visible * (front * front + 0.2f) + 1e-3f);
        constant += w * probe.constant;
        linear += w * probe.linear;
        total += w;
    }
    return ((constant + linear * n) / total).cwiseMax(0.0f);
}

std::vector<std::uint32_t> IrradianceVolume::packed() const {
    std::vector<std::uint32_t> texels;
    texels.reserve(probes.size() * 8);
    for (const IrradianceProbe& probe : probes) {
        const Eigen::Vector3f& c = probe.constant;
        const Eigen::Matrix3f& l = probe.linear;
        const std::array<float, 6>& free = probe.freeDistance;
        // Texel 0: constant RGB, then the slopes along X and the first two along Y (column by column).
        texels.insert(texels.end(), {halves(c.x(), c.y()), halves(c.z(), l(0, 0)), halves(l(1, 0), l(2, 0)),
                                     halves(l(0, 1), l(1, 1))});
        // Texel 1: the rest of the slopes, then the free distances.
        texels.insert(texels.end(),
                      {halves(l(2, 1), l(0, 2)), halves(l(1, 2), l(2, 2)),
                       bytes(free[0], free[1], free[2], free[3]), bytes(free[4], free[5], 0, 0)});
    }
    return texels;
}

} // namespace sp::render
