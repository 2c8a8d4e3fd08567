#include "core/render/camera.h"

#include <cmath>
#include <utility>
#include <vector>

#include "core/base/error.h"

namespace sp::render {

void CameraParams::validate(const char* function) const {
    SP_CHECK(width > 0 && width <= 16384, InvalidArgument, function, "(): width must be in [1, 16384], got ",
             width);
    SP_CHECK(height > 0 && height <= 16384, InvalidArgument, function,
             "(): height must be in [1, 16384], got ", height);
    SP_CHECK(hfovDeg > 0.0 && hfovDeg < 180.0, InvalidArgument, function,
             "(): hfovDeg must be in (0, 180), got ", hfovDeg);
    SP_CHECK(nearClip > 0.0, InvalidArgument, function, "(): nearClip must be > 0, got ", nearClip);
    SP_CHECK(farClip > nearClip, InvalidArgument, function, "(): farClip must be > nearClip (", nearClip,
             "), got ", farClip);
    SP_CHECK(std::isfinite(exposure) && exposure >= 0.0f, InvalidArgument, function,
             "(): exposure must be finite and >= 0, got ", exposure);
    SP_CHECK(shadowResolution >= 16 && shadowResolution <= 8192, InvalidArgument, function,
             "(): shadowResolution must be in [16, 8192], got ", shadowResolution);
    SP_CHECK(std::isfinite(apertureRadius) && apertureRadius >= 0.0, InvalidArgument, function,
             "(): apertureRadius must be finite and >= 0, got ", apertureRadius);
    SP_CHECK(std::isfinite(focusDistance) && focusDistance > 0.0, InvalidArgument, function,
             "(): focusDistance must be finite and > 0, got ", focusDistance);
    SP_CHECK(vignetteIntensity >= 0.0f && vignetteIntensity <= 1.0f, InvalidArgument, function,
             "(): vignetteIntensity must be in [0, 1], got ", vignetteIntensity);
    SP_CHECK(msaaSamples == 2 || msaaSamples == 4 || msaaSamples == 8, InvalidArgument, function,
             "(): msaaSamples must be 2, 4 or 8, got ", msaaSamples);
    SP_CHECK(maxAnisotropy >= 0 && maxAnisotropy <= 16, InvalidArgument, function,
             "(): maxAnisotropy must be in [0, 16], got ", maxAnisotropy);
    SP_CHECK(mipBias >= -2.0f && mipBias <= 2.0f, InvalidArgument, function,
             "(): mipBias must be in [-2, 2], got ", mipBias);
    SP_CHECK(spatialSamples == 1 || spatialSamples == 2 || spatialSamples == 4 || spatialSamples == 8 ||
                 spatialSamples == 16,
             InvalidArgument, function, "(): spatialSamples must be 1, 2, 4, 8 or 16, got ", spatialSamples);
    SP_CHECK(ambientOcclusionIntensity >= 0.0f && ambientOcclusionIntensity <= 1.0f, InvalidArgument,
             function, "(): ambientOcclusionIntensity must be in [0, 1], got ", ambientOcclusionIntensity);
    SP_CHECK(ambientOcclusionRadius > 0.0f && ambientOcclusionRadius <= 100.0f, InvalidArgument, function,
             "(): ambientOcclusionRadius must be in (0, 100] metres, got ", ambientOcclusionRadius);
}

std::string toneMapName(ToneMap toneMap) {
    switch (toneMap) {
    case ToneMap::Aces:
        return "aces";
    case ToneMap::Reinhard:
        return "reinhard";
    case ToneMap::Linear:
        return "linear";
    }
    return "?";
}

Eigen::Matrix4d Camera::viewMatrix() const {
    // Body (x forward, y left, z up) -> GL eye (x right, y up, z backward).
    Eigen::Matrix4d bodyToEye = Eigen::Matrix4d::Zero();
    bodyToEye(0, 1) = -1.0;
    bodyToEye(1, 2) = 1.0;
    bodyToEye(2, 0) = -1.0;
    bodyToEye(3, 3) = 1.0;
    return bodyToEye * pose.inverse(Eigen::Isometry).matrix();
}

double Camera::focalLengthPixels() const {
    return 0.5 * params.width / std::tan(0.5 * params.hfovDeg * M_PI / 180.0);
}

Eigen::Matrix4d Camera::projectionMatrix(bool flipY) const {
    const double sx = 1.0 / std::tan(0.5 * params.hfovDeg * M_PI / 180.0);
    const double sy = sx * params.width / params.height;
    const double n = params.nearClip, f = params.farClip;
    Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
    p(0, 0) = sx;
    p(1, 1) = flipY ? -sy : sy;
    p(2, 2) = -(f + n) / (f - n);
    p(2, 3) = -2.0 * f * n / (f - n);
    p(3, 2) = -1.0;
    // The image moved by -subpixelOffset, so that a pixel's centre shows the scene at its centre plus the
    // offset: a translation in normalised device coordinates (y runs down the image when flipped).
    const double tx = -2.0 * subpixelOffset.x() / params.width;
    const double ty = (flipY ? -2.0 : 2.0) * subpixelOffset.y() / params.height;
    p(0, 2) = -tx; // clip x += tx w, with w = -z_eye
    p(1, 2) = -ty;
    return p;
}

std::span<const Eigen::Vector2d> spatialSamplePattern(int count) {
    // 2, 4, 8: Direct3D 11's standard positions, in sixteenths of a pixel. 16: the rank-1 lattice of
    // generator 5, sample i at ((i + 1/2) / 16, ((5 i mod 16) + 1/2) / 16) in the square: of the 16-point
    // lattices, the smallest error in the area a straight edge covers (RMS over edges of random angle and
    // offset: 0.034 of the pixel, against 0.055 for the 8 samples and 0.089 for the 4).
    static const auto scaled = [](std::initializer_list<std::pair<int, int>> points) {
        std::vector<Eigen::Vector2d> pattern;
        for (auto [x, y] : points)
            pattern.emplace_back(x / 16.0, y / 16.0);
        return pattern;
    };
    static const std::vector<Eigen::Vector2d>
        one = scaled({{0, 0}}),
        two = scaled({{4, 4}, {-4, -4}}), four = scaled({{-2, -6}, {6, -2}, {-6, 2}, {2, 6}}),
        eight = scaled({{1, -3}, {-1, 3}, {5, 1}, {-3, -5}, {-5, 5}, {-7, -1}, {3, 7}, {7, -7}}),
        sixteen = [] {
            std::vector<Eigen::Vector2d> pattern;
            for (int i = 0; i < 16; ++i)
                pattern.emplace_back((i + 0.5) / 16.0 - 0.5, ((5 * i) % 16 + 0.5) / 16.0 - 0.5);
            return pattern;
        }();
    switch (count) {
    case 1:
        return one;
    case 2:
        return two;
    case 4:
        return four;
    case 8:
        return eight;
    case 16:
        return sixteen;
    default:
        SP_THROW(InvalidArgument, "spatialSamplePattern(): count must be 1, 2, 4, 8 or 16, got ", count);
    }
}

std::array<Eigen::Vector4d, 6> Camera::frustumPlanes() const {
    const Eigen::Matrix4d viewProjection = projectionMatrix(true) * viewMatrix();
    std::array<Eigen::Vector4d, 6> planes;
    for (int i = 0; i < 3; ++i) {
        planes[2 * i] = (viewProjection.row(3) + viewProjection.row(i)).transpose();
        planes[2 * i + 1] = (viewProjection.row(3) - viewProjection.row(i)).transpose();
    }
    for (Eigen::Vector4d& plane : planes)
        plane /= plane.head<3>().norm();
    return planes;
}

Eigen::Vector3d Camera::project(const Eigen::Vector3d& world) const {
    Eigen::Vector3d body = pose.inverse(Eigen::Isometry) * world;
    const double fpx = focalLengthPixels();
    const double u = 0.5 * params.width - fpx * body.y() / body.x();
    const double v = 0.5 * params.height - fpx * body.z() / body.x();
    return {u, v, body.x()};
}

} // namespace sp::render
