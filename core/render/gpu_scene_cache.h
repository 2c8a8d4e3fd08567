#pragma once
// GPU copies of one Scene's meshes and textures, uploaded lazily: a mesh is re-uploaded when its slot
// generation or revision changed, a texture when its slot generation changed. Needs a current context.

#include <cstdint>
#include <vector>

#include "core/render/scene.h"

namespace sp::render {

struct GpuMesh {
    unsigned vao = 0;
    unsigned buffers[4] = {}; // positions, normals, uvs, indices
    std::uint32_t generation = 0;
    std::uint64_t revision = 0;
    std::vector<Submesh> submeshes;
};

class GpuSceneCache {
  public:
    GpuSceneCache() = default;
    ~GpuSceneCache();
    GpuSceneCache(const GpuSceneCache&) = delete;
    GpuSceneCache& operator=(const GpuSceneCache&) = delete;

    // The GPU mesh for `id`, uploading it first when needed. Throws sp::StaleObject for a removed id.
    const GpuMesh& mesh(const Scene& scene, MeshId id);
    // GL texture name for `id`, uploading (with mipmaps) first when needed.
    unsigned texture(const Scene& scene, TextureId id);

    std::uint64_t meshUploads() const { return meshUploads_; }
    std::uint64_t textureUploads() const { return textureUploads_; }

  private:
    struct GpuTexture {
        unsigned name = 0;
        std::uint32_t generation = 0;
    };
    std::vector<GpuMesh> meshes_;      // by MeshId::index
    std::vector<GpuTexture> textures_; // by TextureId::index
    std::uint64_t meshUploads_ = 0;
    std::uint64_t textureUploads_ = 0;
};

} // namespace sp::render
