#pragma once
// GPU copies of one Scene's meshes and textures, uploaded lazily: a mesh is re-uploaded when its slot
// generation or revision changed, a texture when its slot generation changed. Content the scene added
// under a shared key (Scene::addMesh, addTexture) is uploaded once for every cache of the same
// SharedUploads (a renderer's scenes) and freed when no cache uses it any more. Needs a current context;
// so does destroying the cache.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/render/scene.h"

namespace sp::render {

// A mesh's vertex array and buffers, deleted with it.
struct GpuMesh {
    GpuMesh();
    ~GpuMesh();
    GpuMesh(const GpuMesh&) = delete;
    GpuMesh& operator=(const GpuMesh&) = delete;

    unsigned vao = 0;
    unsigned buffers[4] = {}; // positions, normals, uvs, indices
    std::vector<Submesh> submeshes;
};

// A texture name, deleted with it.
struct GpuTexture {
    GpuTexture();
    ~GpuTexture();
    GpuTexture(const GpuTexture&) = delete;
    GpuTexture& operator=(const GpuTexture&) = delete;

    unsigned name = 0;
};

// The uploads the caches of one renderer share, by shared key; each lives while a cache holds it.
struct SharedUploads {
    std::map<std::string, std::weak_ptr<GpuMesh>, std::less<>> meshes;
    std::map<std::string, std::weak_ptr<GpuTexture>, std::less<>> textures;
    // Forgets the keys whose upload no cache holds any more.
    void prune();
};

class GpuSceneCache {
  public:
    explicit GpuSceneCache(SharedUploads& shared) : shared_(shared) {}
    GpuSceneCache(const GpuSceneCache&) = delete;
    GpuSceneCache& operator=(const GpuSceneCache&) = delete;

    // The GPU mesh for `id`, uploading it first when needed. Throws sp::StaleObject for a removed id.
    const GpuMesh& mesh(const Scene& scene, MeshId id);
    // The GPU mesh of `id` subdivided `times` times (MeshData::subdivided()), made and uploaded when first
    // asked for (shared between scenes as the mesh itself is); a scene's other revision or generation of the
    // mesh replaces it.
    const GpuMesh& refined(const Scene& scene, MeshId id, int times);
    // GL texture name for `id`, uploading (with mipmaps) first when needed.

    unsigned texture(const Scene& scene, TextureId id);

    // Uploads this cache made (a shared upload counts in the cache that made it).
    std::uint64_t meshUploads() const { return meshUploads_; }
    std::uint64_t textureUploads() const { return textureUploads_; }

  private:
    template <typename Gpu> struct Slot {
        std::shared_ptr<Gpu> gpu; // this scene's own copy, or one under a shared key
        bool shared = false;
        std::uint32_t generation = 0;
        std::uint64_t revision = 0;
    };
    SharedUploads& shared_;
    std::vector<Slot<GpuMesh>> meshes_;      // by MeshId::index
    std::vector<Slot<GpuTexture>> textures_; // by TextureId::index
    struct Refined {
        std::uint32_t generation = 0;
        std::uint64_t revision = 0;
        std::shared_ptr<GpuMesh> gpu; // this scene's own, or one under a shared key
    };
    std::map<std::pair<std::uint32_t, int>, Refined> refined_; // by (MeshId::index, times)
    std::uint64_t meshUploads_ = 0;
    std::uint64_t textureUploads_ = 0;
};

} // namespace sp::render
