#pragma once
// UPrimitiveComponent: a scene component with geometry (bounds now; rendering and collision build on it).

#include <Eigen/Geometry>

#include "core/world/scene_component.h"

/// A scene component that has geometry.
SPCLASS(Abstract)
class UPrimitiveComponent : public USceneComponent {
    SP_GENERATED_BODY()
  public:
    /// Returns the world-space axis-aligned bounds as centre Origin and half size BoxExtent.
    SPFUNCTION()
    void GetBounds(FVector& Origin, FVector& BoxExtent) const;

    // Bounds in the component's own space (before its scale); empty when it has no geometry.
    virtual Eigen::AlignedBox3d GetLocalBounds() const { return {}; }
    // World-space bounds of the transformed local box.
    Eigen::AlignedBox3d GetWorldBounds() const;
};
