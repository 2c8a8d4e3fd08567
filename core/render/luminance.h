#pragma once
// Luminance of linear RGB in Rec. 709 / sRGB primaries (ITU-R BT.709 weights): what exposure metering, white
// balance, the sky's scale, light sampling and the denoiser's edge tests weigh colours by. Pure logic.

#include <Eigen/Core>

namespace sp::render {

template <typename T> T luminance(T r, T g, T b) {
    return T(0.2126) * r + T(0.7152) * g + T(0.0722) * b;
}

template <typename T> T luminance(const Eigen::Matrix<T, 3, 1>& c) {
    return luminance(c.x(), c.y(), c.z());
}

} // namespace sp::render
