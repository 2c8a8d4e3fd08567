#include "core/world/math.h"

#include <algorithm>
#include <cmath>

namespace {
constexpr double kDegToRad = M_PI / 180.0;
constexpr double kRadToDeg = 180.0 / M_PI;
} // namespace

Eigen::Quaterniond FRotator::toQuaternion() const {
    using Eigen::AngleAxisd;
    using Eigen::Vector3d;
    return AngleAxisd(Yaw * kDegToRad, Vector3d::UnitZ()) *
           AngleAxisd(-Pitch * kDegToRad, Vector3d::UnitY()) *
           AngleAxisd(Roll * kDegToRad, Vector3d::UnitX());
}

FRotator FRotator::fromQuaternion(const Eigen::Quaterniond& q) {
    const Eigen::Matrix3d m = q.normalized().toRotationMatrix();
    // m = Rz(y) Ry(-p) Rx(r): m(2,0) = sin(p); clamp for the poles.
    const double sinPitch = std::clamp(m(2, 0), -1.0, 1.0);
    FRotator r;
    r.Pitch = std::asin(sinPitch) * kRadToDeg;
    if (std::abs(sinPitch) < 1.0 - 1e-12) {
        r.Yaw = std::atan2(m(1, 0), m(0, 0)) * kRadToDeg;
        r.Roll = std::atan2(m(2, 1), m(2, 2)) * kRadToDeg;
    } else { // gimbal lock: put everything in yaw
        r.Yaw = std::atan2(-m(0, 1), m(1, 1)) * kRadToDeg;
        r.Roll = 0.0;
    }
    return r;
}

Eigen::Isometry3d FTransform::toIsometry() const {
    Eigen::Isometry3d iso = Eigen::Isometry3d::Identity();
    iso.linear() = Rotation.toEigen().normalized().toRotationMatrix();
    iso.translation() = Translation.toEigen();
    return iso;
}

FTransform FTransform::composedWith(const FTransform& parent) const {
    // world = parent.T * parent.R * parent.S * (T * R * S); with non-uniform parent scale and a rotated
    // child the exact result has shear, which a TRS cannot hold; like UE we scale componentwise.
    const Eigen::Quaterniond parentRotation = parent.Rotation.toEigen().normalized();
    const Eigen::Vector3d scaledTranslation = Translation.toEigen().cwiseProduct(parent.Scale3D.toEigen());
    FTransform world;
    world.Translation = FVector::fromEigen(parent.Translation.toEigen() + parentRotation * scaledTranslation);
    world.Rotation = FQuat::fromEigen((parentRotation * Rotation.toEigen()).normalized());
    world.Scale3D = FVector::fromEigen(Scale3D.toEigen().cwiseProduct(parent.Scale3D.toEigen()));
    return world;
}

FTransform FTransform::relativeTo(const FTransform& parent) const {
    const Eigen::Quaterniond parentInverse = parent.Rotation.toEigen().normalized().conjugate();
    const Eigen::Vector3d parentScale = parent.Scale3D.toEigen();
    FTransform relative;
    relative.Translation = FVector::fromEigen(
        (parentInverse * (Translation.toEigen() - parent.Translation.toEigen())).cwiseQuotient(parentScale));
    relative.Rotation = FQuat::fromEigen((parentInverse * Rotation.toEigen()).normalized());
    relative.Scale3D = FVector::fromEigen(Scale3D.toEigen().cwiseQuotient(parentScale));
    return relative;
}
