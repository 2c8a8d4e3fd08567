#include "core/world/primitive_component.h"

Eigen::AlignedBox3d UPrimitiveComponent::GetWorldBounds() const {
    const Eigen::AlignedBox3d local = GetLocalBounds();
    Eigen::AlignedBox3d world;
    if (local.isEmpty())
        return world;
    const FTransform transform = GetComponentTransform();
    const Eigen::Isometry3d pose = transform.toIsometry();
    const Eigen::Vector3d scale = transform.Scale3D.toEigen();
    for (int corner = 0; corner < 8; ++corner)
        world.extend(pose * local.corner(Eigen::AlignedBox3d::CornerType(corner)).cwiseProduct(scale));
    return world;
}

void UPrimitiveComponent::GetBounds(FVector& Origin, FVector& BoxExtent) const {
    const Eigen::AlignedBox3d bounds = GetWorldBounds();
    Origin = bounds.isEmpty() ? GetComponentLocation() : FVector::fromEigen(bounds.center());
    BoxExtent = bounds.isEmpty() ? FVector{} : FVector::fromEigen(bounds.sizes() / 2.0);
}
