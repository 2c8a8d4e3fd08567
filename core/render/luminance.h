#pragma once
// Luminance of linear Rec. 709 / sRGB-primaries RGB (ITU-R BT.709 weights): what exposure metering, light
// sampling and the denoiser's edge tests weigh colours by. Pure logic.

#include <Eigen/Core>

namespace sp::render {

inline constexpr float kLuminanceR = 0.2126f, kLuminanceG = 0.7152f, kLuminanceB = 0.0722f;

inline float luminance(float r, float g, float b) {
    return kLuminanceR * r + kLuminanceG * g + kLuminanceB * b;
}

inline float luminance(const Eigen::Vector3f& c) {
    return luminance(c.x(), c.y(), c.z());
}

} // namespace sp::render
