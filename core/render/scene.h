#pragma once
// The renderer's world: meshes, textures, materials, lights, instances and the environment, addressed
// by generation-checked handles. Pure CPU data, no GL: the Renderer mirrors it on the GPU lazily,
// re-uploading a mesh or texture only when its revision changed.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/render/environment_map.h"
#include "core/render/handles.h"
#include "core/render/irradiance_volume.h"
#include "core/render/light.h"
#include "core/render/material.h"
#include "core/render/mesh_data.h"
#include "core/render/slot_map.h"
#include "core/render/texture_image.h"

namespace sp::render {

// How texels are stored: colour textures are sRGB-encoded, data textures (normal, roughness) linear.
enum class TextureEncoding { Srgb, Linear };

// A coarser version of a mesh, drawn in its place when its geometric error, relative to the mesh's
// bounding radius, is under half a pixel (or shadow-map texel) where it is drawn.
struct MeshLod {
    MeshId mesh;
    // The largest deviation of its outline from the full mesh's, as a fraction of the bounding radius: what
    // moves in an image (surface inside the outline may deviate more along the line of sight).
    float relativeError = 0.0f;
    // The largest distance of its surface from the full mesh's, the same fraction: at least relativeError
    // (setMeshLods() raises it to that), more where a face sags further along the line of sight than the
    // outline does (a UV sphere's quads, at their centres). A point on a coarse level lies up to this far
    // inside the surface the shadow maps were drawn from, so its shadow lookup is offset that much further.
    float surfaceError = 0.0f;
};

// A placed mesh: one material and one object id per submesh slot.
struct Instance {
    MeshId mesh;
    std::vector<MaterialId> materials;    // one per submesh of `mesh`
    std::vector<std::uint32_t> objectIds; // one per submesh; written to object_ids; must be != 0
    Eigen::Affine3d transform = Eigen::Affine3d::Identity(); // mesh-to-world (may scale)
    bool visible = true;
    bool castShadows = true;
    // Whether the irradiance probes see it (UE's bAffectDynamicIndirectLighting): a mesh that changes shape
    // every frame (a walking character) would have them relit and their ray geometry rebuilt every frame for
    // light it barely changes; cameras, shadows and the path tracer's images still see it.
    bool affectIndirectLighting = true;
};

// Light that does not come from analytic lights: a uniform sky, or an environment map (an HDR panorama,
// an analytic sky), which then also fills the pixels that hit no geometry.
struct Environment {
    Environment() = default;
    // A uniform sky.
    Environment(const Eigen::Vector3f& ambient_, const Eigen::Vector3f& background_)
        : ambient(ambient_), background(background_) {}

    Eigen::Vector3f ambient{0.03f, 0.03f, 0.03f}; // uniform sky radiance lighting every surface (no map)
    Eigen::Vector3f background{0.0f, 0.0f, 0.0f}; // hdr_color of pixels that hit no geometry (no map)
    std::shared_ptr<const EnvironmentMap> map;    // radiance from every direction, times mapScale
    Eigen::Vector3f mapScale{1.0f, 1.0f, 1.0f};

    // The radiance arriving from unit direction `direction`.
    Eigen::Vector3f radiance(const Eigen::Vector3f& direction) const {
        return map ? Eigen::Vector3f(map->radiance(direction).cwiseProduct(mapScale)) : ambient;
    }
};

class Scene {
  public:
    // A view shades at most shaders::kMaxLights of them: those whose range reaches it (Renderer::viewLights).
    static constexpr std::size_t kMaxLights = 4096;

    Scene();

    // Meshes. updateMesh keeps the handle and bumps the revision (the GPU copy is re-uploaded).
    // A shared key names content that is the same in every scene adding a mesh (or texture) under it: a
    // built-in shape, a file as last modified. A renderer uploads such content once for all the scenes it
    // draws (an engine's worlds). updateMesh drops the key: the mesh is this scene's own from then on.
    MeshId addMesh(MeshData mesh, std::string sharedKey = {});
    void updateMesh(MeshId id, MeshData mesh);
    // Moves a mesh's vertices, keeping its triangles, uvs and submeshes (a skinned mesh posed): `positions`
    // and `normals` (unit) have its vertex count. Bumps the revision, as updateMesh does, without copying the
    // rest.
    void deformMesh(MeshId id, std::span<const Eigen::Vector3f> positions,
                    std::span<const Eigen::Vector3f> normals);
    void removeMesh(MeshId id); // sp::InvalidState while an instance uses it
    const MeshData& mesh(MeshId id) const;
    std::uint64_t meshRevision(MeshId id) const;
    const std::string& meshSharedKey(MeshId id) const;
    // MeshData::convex() and faceted(), computed when the mesh was added or updated: it cannot shadow itself.
    bool meshConvexFaceted(MeshId id) const;
    // MeshData::windingSpread(), computed when first asked after the mesh was added, updated or deformed.
    float meshWindingSpread(MeshId id) const;
    // MeshData::longestEdge(), computed when first asked after the mesh was added, updated or deformed.
    float meshLongestEdge(MeshId id) const;
    // Levels of detail of a mesh, from finer to coarser (increasing relativeError); each has the mesh's
    // submesh count. A mesh that is some chain's level cannot be removed while that chain names it.
    void setMeshLods(MeshId id, std::vector<MeshLod> lods);
    const std::vector<MeshLod>& meshLods(MeshId id) const;
    // The coarsest level of `id` whose error stays within half a pixel when the mesh's bounding radius
    // covers `radiusInPixels` pixels (or texels); `id` itself when it has no level that coarse.
    MeshId lodFor(MeshId id, double radiusInPixels) const { return chooseLod(id, radiusInPixels).mesh; }
    // The same level with its errors ({id, 0, 0} for the mesh itself).
    MeshLod chooseLod(MeshId id, double radiusInPixels) const;
    // World-space bounding sphere of an instance (its mesh's box, transformed; scale included).
    void boundingSphere(const Instance& instance, Eigen::Vector3d& centre, double& radius) const;
    // World-space axis-aligned box of an instance (its mesh's box, transformed).
    Eigen::AlignedBox3d boundingBox(const Instance& instance) const;

    // Textures (for Material's texture slots).
    TextureId addTexture(TextureImage image, TextureEncoding encoding = TextureEncoding::Srgb,
                         std::string sharedKey = {});
    void removeTexture(TextureId id); // sp::InvalidState while a material uses it
    const TextureImage& texture(TextureId id) const;
    TextureEncoding textureEncoding(TextureId id) const;
    const std::string& textureSharedKey(TextureId id) const;

    MaterialId addMaterial(const Material& material);
    void setMaterial(MaterialId id, const Material& material);
    void removeMaterial(MaterialId id); // sp::InvalidState while an instance uses it
    const Material& material(MaterialId id) const;
    // The value written to material_ids for this material.
    std::uint32_t materialIdValue(MaterialId id) const;
    // Which of a material's factors some material of the scene multiplies by a texture: those can vary across
    // an instance; the others are its material's factors at every pixel of it.
    struct TexturedFactors {
        bool baseColor = false;
        bool roughnessMetallic = false; // and ambient occlusion (the texture's R: Material)
    };
    TexturedFactors texturedFactors() const;

    LightId addLight(const Light& light); // sp::InvalidState beyond kMaxLights
    void setLight(LightId id, const Light& light);
    void removeLight(LightId id);
    const Light& light(LightId id) const;

    InstanceId addInstance(const Instance& instance);
    void setInstance(InstanceId id, const Instance& instance);
    void setTransform(InstanceId id, const Eigen::Affine3d& transform);
    void removeInstance(InstanceId id);
    const Instance& instance(InstanceId id) const;

    void setEnvironment(const Environment& environment) { environment_ = environment; }
    const Environment& environment() const { return environment_; }

    // Indirect light for the rasteriser (irradiance_volume.h): with one, the shading blends its probes in
    // place of the environment's uniform ambient term; null (the default) shades with the ambient term.
    // Validated here; the renderer uploads it again whenever the pointer or its revision changes.
    void setIrradianceVolume(std::shared_ptr<const IrradianceVolume> volume);
    const std::shared_ptr<const IrradianceVolume>& irradianceVolume() const { return irradianceVolume_; }

    std::size_t meshCount() const { return meshes_.size(); }
    std::size_t textureCount() const { return textures_.size(); }
    std::size_t materialCount() const { return materials_.size(); }
    std::size_t lightCount() const { return lights_.size(); }
    std::size_t instanceCount() const { return instances_.size(); }

    // Process-unique identity of this scene (keys the renderer's GPU caches).
    std::uint64_t uid() const { return uid_; }

    template <typename Fn> void forEachInstance(Fn&& fn) const { instances_.forEach(fn); }
    template <typename Fn> void forEachLight(Fn&& fn) const { lights_.forEach(fn); }

    // Whether a sphere reaches inside every plane (a, b, c, d, inside where a·x + b·y + c·z + d >= 0, unit
    // normals): whether it meets a view frustum, conservatively.
    static bool reachesInside(std::span<const Eigen::Vector4d> planes, const Eigen::Vector3d& centre,
                              double radius);
    // World-space bounding sphere of all visible instances (centre, radius); radius 0 when empty. With
    // `within` (planes a, b, c, d, inside where a·x + b·y + c·z + d >= 0, unit normals: a view frustum),
    // of those whose bounding sphere reaches inside every plane: what a camera sees.
    void bounds(Eigen::Vector3d& centre, double& radius, std::span<const Eigen::Vector4d> within = {}) const;

  private:
    struct MeshEntry {
        MeshData data;
        std::uint64_t revision = 0;
        Eigen::Vector3f min, max;
        bool convexFaceted = false;
        // Found when the renderer first asks (only of the level of detail it draws, only with the settings
        // that use them): a skinned mesh's levels are deformed every frame, and most are not drawn.
        mutable std::optional<float> windingSpread;
        mutable std::optional<float> longestEdge;
        std::vector<MeshLod> lods;
        std::string sharedKey;
    };
    // The entry's bounds and whether it is convex and faceted, from its data; forgets the rest.
    static void describe(MeshEntry& entry);
    struct TextureEntry {
        TextureImage image;
        TextureEncoding encoding;
        std::string sharedKey;
    };
    void checkInstance(const Instance& instance, const char* function) const;
    void checkMaterialTextures(const Material& material, const char* function) const;

    SlotMap<MeshEntry, MeshId> meshes_;
    SlotMap<TextureEntry, TextureId> textures_;
    SlotMap<Material, MaterialId> materials_;
    SlotMap<Light, LightId> lights_;
    SlotMap<Instance, InstanceId> instances_;
    Environment environment_;
    std::shared_ptr<const IrradianceVolume> irradianceVolume_;
    std::uint64_t uid_;
    std::uint64_t nextRevision_ = 1;
};

} // namespace sp::render
