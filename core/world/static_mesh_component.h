#pragma once
// UStaticMeshComponent: a primitive that shows a mesh asset with one material per slot.

#include <string>
#include <vector>

#include "core/world/primitive_component.h"

/// A component that renders a static mesh.
SPCLASS()
class UStaticMeshComponent : public UPrimitiveComponent {
    SP_GENERATED_BODY()
  public:
    /// The mesh asset: a built-in shape ("/Engine/BasicShapes/Cube", "Sphere", "Cylinder", "Plane") or a
    /// file.
    SPPROPERTY()
    std::string StaticMesh;

    /// One material asset per mesh slot; an empty entry uses the default material.
    SPPROPERTY()
    std::vector<std::string> Materials;

    /// Sets the mesh asset; returns false when the name is not a known mesh.
    SPFUNCTION()
    bool SetStaticMesh(const std::string& NewMesh);

    /// Sets the material of one slot, growing the list as needed.
    SPFUNCTION()
    void SetMaterial(int ElementIndex, const std::string& Material);

    Eigen::AlignedBox3d GetLocalBounds() const override;
    ECollisionPrimitive GetMeshCollisionPrimitive() const override;
};
