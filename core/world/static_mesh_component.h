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
    /// file. Setting it is SetStaticMesh(): a name that is neither raises NotFoundError.
    SPPROPERTY(Setter = SetStaticMesh)
    std::string StaticMesh;

    /// One material asset per mesh slot; an empty entry uses the default material.
    SPPROPERTY()
    std::vector<std::string> Materials;

    /// Sets the mesh asset: a built-in shape (/Engine/BasicShapes/Cube, Sphere, Cylinder, Plane) or a mesh
    /// file, found as every asset is (the working directory, then SPEAR_ASSET_PATH, then the built-in
    /// assets; while a scene file loads, its own folder first). Returns true; raises NotFoundError naming the
    /// name and where it was looked for when there is no such shape or file, InvalidArgumentError when the
    /// file cannot be read as a mesh or is outside the server's file roots. The mesh is kept as it was then.
    SPFUNCTION()
    bool SetStaticMesh(const std::string& NewMesh);

    /// Sets the material of one slot, growing the list as needed.
    SPFUNCTION()
    void SetMaterial(int ElementIndex, const std::string& Material);

    Eigen::AlignedBox3d GetLocalBounds() const override;
    ECollisionPrimitive GetMeshCollisionPrimitive() const override;

    // The mesh to load for StaticMesh: the file it names relative to the folder of the scene file it was
    // read from, when it is there (a scene's own meshes travel with it, as in glTF or USD), else StaticMesh
    // itself (a built-in shape, or a file found through the asset search path, core/base/asset_path.h).
    // Assigning StaticMesh any other value drops the scene's folder.
    const std::string& GetMeshAsset() const;

    // While one lives on this thread, SetStaticMesh() looks for a relative mesh file in `folder` first: the
    // scene loader's (core/scene), for the folder of the scene file it reads.
    class SceneFolderScope {
      public:
        explicit SceneFolderScope(std::string folder);
        ~SceneFolderScope();
        SceneFolderScope(const SceneFolderScope&) = delete;
        SceneFolderScope& operator=(const SceneFolderScope&) = delete;

      private:
        std::string previous_;
    };

  private:
    std::string resolvedName_; // the StaticMesh value resolvedFile_ was found for
    std::string resolvedFile_;
};
