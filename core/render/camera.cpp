#include "core/render/camera.h"

#include <cmath>

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
    return p;
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
