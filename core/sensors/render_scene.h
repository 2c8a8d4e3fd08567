#pragma once
// RenderScene: the render-side mirror of one world (no GL). sync() walks the world's actors and brings
// the sp::render::Scene up to date: one instance per visible static mesh component, one material per
// slot resolved by name (see material_library.h), lights and the sky, and a glowing tube along each
// spline component with bDrawDebug. It also owns the object ids:
// one per (component, material slot), from a counter that never repeats (0 is the background).

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/reflect/value.h"
#include "core/render/scene.h"
#include "core/sensors/material_library.h"

class UWorld;
class UStaticMeshComponent;
class USplineComponent;

namespace sp::sensors {

class RenderScene {
  public:
    struct ObjectIdInfo {
        sp::reflect::ObjectHandle component;
        int slot = -1;
        std::string materialName;
    };

    // Brings the render scene up to date with `world`. Missing mesh files and textures are logged once
    // and skipped, so that one bad asset does not stop every camera.
    void sync(UWorld& world);

    const sp::render::Scene& scene() const { return scene_; }
    std::optional<ObjectIdInfo> objectIdInfo(std::uint32_t id) const;
    // 0 when the slot has no id (not rendered yet, or out of range).
    std::uint32_t objectId(sp::reflect::ObjectHandle component, int slot) const;
    // The material_ids value of a material name, 0 when no mesh used it yet.
    std::uint32_t materialId(const std::string& name) const;

  private:
    struct MeshEntry {
        sp::render::MeshId mesh;
        std::vector<std::string> importedNames;                // imported meshes: material name per submesh
        std::vector<sp::render::MaterialId> importedMaterials; // imported meshes: material per submesh
    };
    struct MaterialEntry {
        sp::render::MaterialId id;
        FMaterialDesc desc;
        std::uint32_t value = 0;
    };
    struct InstanceEntry {
        sp::render::InstanceId instance;
        std::vector<std::uint32_t> ids; // per slot
    };

    struct DebugLineEntry {
        sp::render::MeshId mesh;
        sp::render::MaterialId material;
        sp::render::InstanceId instance;
        // What the mesh was built from: the curve's revision, where the spline is, the line's look.
        std::uint64_t revision = 0;
        FTransform transform;
        double thickness = 0.0;
        FLinearColor color;
        std::uint32_t id = 0;
    };

    void syncMesh(UStaticMeshComponent& component, const std::map<std::string, FMaterialDesc>& library);
    void syncDebugLine(const USplineComponent& spline);
    void removeDebugLine(DebugLineEntry& entry);
    const MeshEntry* meshFor(const std::string& name);
    sp::render::MaterialId materialFor(const std::string& name,
                                       const std::map<std::string, FMaterialDesc>& library);
    std::optional<sp::render::TextureId> textureFor(const std::string& path,
                                                    sp::render::TextureEncoding encoding);
    void logOnce(const std::string& key, const std::string& message);

    sp::render::Scene scene_;
    std::map<std::string, MeshEntry> meshes_;
    std::map<std::string, MaterialEntry> materials_;
    std::map<std::string, sp::render::TextureId> textures_;
    std::map<sp::reflect::ObjectHandle, InstanceEntry> instances_;
    std::map<sp::reflect::ObjectHandle, DebugLineEntry> debugLines_;
    std::map<std::uint32_t, ObjectIdInfo> idInfo_;
    std::vector<sp::render::LightId> lights_;
    std::set<std::string> logged_;
    std::uint32_t nextObjectId_ = 1;
    std::uint32_t nextMaterialValue_ = 1;
};

} // namespace sp::sensors
