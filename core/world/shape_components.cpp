#include "core/world/shape_components.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/base/error.h"

UShapeComponent::UShapeComponent() {
    bGenerateOverlapEvents = true;
}

void UBoxComponent::SetBoxExtent(const FVector& InBoxExtent) {
    const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
    std::ostringstream value;
    value << '(' << InBoxExtent.X << ", " << InBoxExtent.Y << ", " << InBoxExtent.Z << ')';
    sp::checkSetting(positive(InBoxExtent.X) && positive(InBoxExtent.Y) && positive(InBoxExtent.Z),
                     "UBoxComponent", "BoxExtent", "finite and > 0 along every axis", value.str());
    BoxExtent = InBoxExtent;
}

Eigen::AlignedBox3d UBoxComponent::GetLocalBounds() const {
    return {-BoxExtent.toEigen(), BoxExtent.toEigen()};
}

Eigen::AlignedBox3d UBoxComponent::worldBox() const {
    const FTransform transform = GetComponentTransform();
    const Eigen::Isometry3d pose = transform.toIsometry();
    const Eigen::Vector3d half = BoxExtent.toEigen().cwiseProduct(transform.Scale3D.toEigen()).cwiseAbs();
    Eigen::AlignedBox3d box;
    for (int corner = 0; corner < 8; ++corner)
        box.extend(pose * Eigen::Vector3d(corner & 1 ? half.x() : -half.x(),
                                          corner & 2 ? half.y() : -half.y(),
                                          corner & 4 ? half.z() : -half.z()));
    return box;
}

void USphereComponent::SetSphereRadius(double InSphereRadius) {
    sp::checkSetting(std::isfinite(InSphereRadius) && InSphereRadius > 0.0, "USphereComponent",
                     "SphereRadius", "> 0", InSphereRadius);
    SphereRadius = InSphereRadius;
}

Eigen::AlignedBox3d USphereComponent::GetLocalBounds() const {
    const Eigen::Vector3d radius = Eigen::Vector3d::Constant(SphereRadius);
    return {-radius, radius};
}

void UCapsuleComponent::SetCapsuleRadius(double Radius) {
    sp::checkSetting(std::isfinite(Radius) && Radius > 0.0, "UCapsuleComponent", "CapsuleRadius", "> 0",
                     Radius);
    CapsuleRadius = Radius;
}

void UCapsuleComponent::SetCapsuleHalfHeight(double HalfHeight) {
    sp::checkSetting(std::isfinite(HalfHeight) && HalfHeight > 0.0, "UCapsuleComponent", "CapsuleHalfHeight",
                     "> 0", HalfHeight);
    CapsuleHalfHeight = HalfHeight;
}

Eigen::AlignedBox3d UCapsuleComponent::GetLocalBounds() const {
    const Eigen::Vector3d half(CapsuleRadius, CapsuleRadius, std::max(CapsuleHalfHeight, CapsuleRadius));
    return {-half, half};
}

ATriggerBox::ATriggerBox() {
    CollisionComponent = CreateDefaultSubobject<UBoxComponent>("CollisionComponent");
}

ATriggerSphere::ATriggerSphere() {
    CollisionComponent = CreateDefaultSubobject<USphereComponent>("CollisionComponent");
}
