#pragma once
// RenderScene: the render-side mirror of one world (no GL). It knows what to mirror by registration: the
// world's RenderSubsystem tells it of actors and components as they begin and end play (track/untrack),
// so a frame never walks the whole world. sync() brings the sp::render::Scene up to date with what it
// tracks: one instance per visible static mesh component, one material per slot resolved by name (see
// material_library.h), lights and the sky, and a glowing tube along each spline component with
// bDrawDebug. It also owns the object ids: one per (component, material slot), from a counter that never
// repeats (0 is the background).

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/animation/skeletal_import.h"
#include "core/reflect/value.h"
#include "core/render/scene.h"
#include "core/sensors/material_library.h"
#include "core/sensors/sky_environment.h"

class AActor;
class AMaterialLibrary;
class AZoneGraphData;
class UActorComponent;
class ULightComponent;
class UPrimitiveComponent;
class USkyAtmosphereComponent;
class USkyLightComponent;
class USkeletalMeshComponent;
class UStaticMeshComponent;
class USplineComponent;

namespace sp::sensors {

// Objects in the order they began play (the world's order), removable by pointer.
template <typename T> class PlayOrder {
  public:
    void add(T* item) {
        if (order_.emplace(item, next_).second)
            items_.emplace(next_++, item);
    }
    void remove(const T* item) {
        if (auto it = order_.find(item); it != order_.end()) {
            items_.erase(it->second);
            order_.erase(it);
        }
    }
    // By the order they began play: (sequence number, item).
    const std::map<std::uint64_t, T*>& items() const { return items_; }

  private:
    std::map<std::uint64_t, T*> items_;
    std::unordered_map<const T*, std::uint64_t> order_;
    std::uint64_t next_ = 0;
};

class RenderScene {
  public:
    struct ObjectIdInfo {
        sp::reflect::ObjectHandle component; // or, for drawn roads, their AZoneGraphData actor
        int slot = -1;
        std::string materialName;
    };

    // What the scene mirrors: actors (material libraries) and components (meshes, splines, lights, skies)
    // in play. Others are ignored; tracking twice or untracking what is not tracked does nothing.
    void track(AActor& actor);
    void untrack(AActor& actor);
    void track(UActorComponent& component);
    void untrack(UActorComponent& component);

    // Brings the render scene up to date with what is tracked. Missing mesh files and textures are logged
    // once and skipped, so that one bad asset does not stop every camera.
    void sync();

    const sp::render::Scene& scene() const { return scene_; }
    // The rasteriser's indirect light (RenderSubsystem lights it from the scene; null: none).
    void setIrradianceVolume(std::shared_ptr<const sp::render::IrradianceVolume> volume) {
        scene_.setIrradianceVolume(std::move(volume));
    }
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

    // The drawn roads of an AZoneGraphData (render_scene_roads.cpp): one mesh of three slots.
    struct RoadEntry {
        sp::render::MeshId mesh;
        sp::render::InstanceId instance;
        std::uint64_t revision = 0; // the graph's the mesh was made from
        std::uint32_t firstId = 0;  // the three slots' object ids, from here
    };

    // A coarser level of a skinned mesh: its own mesh, whose vertices are some of the full mesh's
    // (`vertices`: which), moved with them.
    struct SkinnedLevel {
        sp::render::MeshId mesh;
        std::vector<std::uint32_t> vertices;
        std::vector<Eigen::Vector3f> positions, normals;
    };
    // A posed skinned mesh: the component's own mesh, its vertices skinned again whenever the pose changed.
    struct SkinnedEntry {
        std::shared_ptr<const sp::animation::SkeletalMeshData> asset; // what `mesh` was made from
        bool bodyParts = false;                                       // split by body part (bBodyPartIds)
        sp::render::MeshId mesh;
        std::vector<SkinnedLevel> levels; // levels of detail, fine to coarse
        // Per slot of `mesh`: the file's material slot it is drawn with (the same slot unless split by body
        // part), that material and its name.
        std::vector<std::uint32_t> fileSlots;
        std::vector<sp::render::MaterialId> importedMaterials;
        std::vector<std::string> importedNames;
        std::uint64_t poseRevision = 0;
        std::vector<Eigen::Vector3f> positions, normals; // skinning's output, kept for its storage
    };
    void syncMesh(UStaticMeshComponent& component, const std::map<std::string, FMaterialDesc>& library);
    void syncSkinnedMesh(USkeletalMeshComponent& component,
                         const std::map<std::string, FMaterialDesc>& library);
    void removeSkinnedMesh(SkinnedEntry& entry);
    // A skinned mesh file's materials, added once for every component showing it (as meshFor() does for
    // static meshes): the same material_ids value for every character's skin.
    struct SkinnedMaterials {
        std::shared_ptr<const sp::animation::SkeletalMeshData> asset; // kept alive: the key is its address
        std::vector<sp::render::MaterialId> ids;                      // per material slot of the file
        std::vector<std::string> names;
    };
    const SkinnedMaterials&
    skinnedMaterialsFor(const std::shared_ptr<const sp::animation::SkeletalMeshData>& asset,
                        const std::string& fileName);
    // Removes the instance of `component` from the render scene; the ids it had stay its own.
    void removeInstanceOf(sp::reflect::ObjectHandle component);
    // Levels of detail for a skinned mesh made from `data`, as imported static meshes get (mesh_lods.h).
    void addSkinnedLevels(SkinnedEntry& entry, const sp::render::MeshData& data);
    // The instance of a mesh component: its mesh drawn with one material per slot (an empty name: the file's
    // own material for the slot, `imported`), ids handed out per slot.
    void placeInstance(const UPrimitiveComponent& component, sp::render::MeshId mesh,
                       const std::vector<std::string>& materialNames,
                       const std::vector<sp::render::MaterialId>& imported,
                       const std::vector<std::string>& importedNames,
                       const std::map<std::string, FMaterialDesc>& library,
                       bool affectIndirectLighting = true);
    void syncDebugLine(const USplineComponent& spline);
    void syncRoads(AZoneGraphData& data, const std::map<std::string, FMaterialDesc>& library);
    void removeRoads(RoadEntry& entry);
    void removeDebugLine(DebugLineEntry& entry);
    const MeshEntry* meshFor(const std::string& name);
    sp::render::MaterialId materialFor(const std::string& name,
                                       const std::map<std::string, FMaterialDesc>& library);
    // The texture uploaded under `key` (made by `load` the first time; a failure is logged once, naming
    // `shown`, and gives nullopt: the material keeps its factors).
    std::optional<sp::render::TextureId> cachedTexture(const std::string& key, const std::string& shown,
                                                       sp::render::TextureEncoding encoding,
                                                       const std::function<sp::render::TextureImage()>& load);
    std::optional<sp::render::TextureId> textureFor(const std::string& path,
                                                    sp::render::TextureEncoding encoding);
    // The material's one texture of occlusion, roughness and metallic (sp::render::Material), from its
    // RoughnessMetallicTexture and OcclusionTexture (either may be ""; none: nullopt), loaded and packed
    // once.
    std::optional<sp::render::TextureId> occlusionRoughnessMetallicFor(const std::string& roughnessMetallic,
                                                                       const std::string& occlusion);
    void logOnce(const std::string& key, const std::string& message);

    PlayOrder<const AMaterialLibrary> libraries_;
    PlayOrder<UStaticMeshComponent> meshComponents_;
    PlayOrder<USkeletalMeshComponent> skinnedComponents_;
    PlayOrder<const USplineComponent> splines_;
    PlayOrder<AZoneGraphData> roadData_;
    std::map<sp::reflect::ObjectHandle, RoadEntry> roads_;
    PlayOrder<const ULightComponent> lightComponents_;
    PlayOrder<const USkyLightComponent> skies_;
    PlayOrder<const USkyAtmosphereComponent> atmospheres_;
    SkyEnvironment sky_;

    sp::render::Scene scene_;
    std::map<std::string, MeshEntry> meshes_;
    std::map<std::string, MaterialEntry> materials_;
    std::map<std::string, sp::render::TextureId> textures_;
    std::map<sp::reflect::ObjectHandle, InstanceEntry> instances_;
    std::map<sp::reflect::ObjectHandle, SkinnedEntry> skinned_;
    std::map<const sp::animation::SkeletalMeshData*, SkinnedMaterials> skinnedMaterials_;
    std::map<sp::reflect::ObjectHandle, DebugLineEntry> debugLines_;
    std::map<std::uint32_t, ObjectIdInfo> idInfo_;
    std::vector<sp::render::LightId> lights_;
    std::set<std::string> logged_;
    std::uint32_t nextObjectId_ = 1;
    std::uint32_t nextMaterialValue_ = 1;
};

} // namespace sp::sensors
