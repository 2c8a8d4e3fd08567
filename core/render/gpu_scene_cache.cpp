#include "core/render/gpu_scene_cache.h"

#include <epoxy/gl.h>

#include <algorithm>

#include "core/render/instances.h"

namespace sp::render {
namespace {

// (Re)fills a mesh's buffers; glNamedBufferData reallocates them at the new sizes.
void upload(GpuMesh& gpu, const MeshData& data) {
    // Eigen's fixed-size vectors are packed floats, so the std::vectors upload as flat arrays.
    glNamedBufferData(gpu.buffers[0], GLsizeiptr(data.positions.size() * sizeof(float) * 3),
                      data.positions.data(), GL_STATIC_DRAW);
    glNamedBufferData(gpu.buffers[1], GLsizeiptr(data.normals.size() * sizeof(float) * 3),
                      data.normals.data(), GL_STATIC_DRAW);
    glNamedBufferData(gpu.buffers[2], GLsizeiptr(data.uvs.size() * sizeof(float) * 2), data.uvs.data(),
                      GL_STATIC_DRAW);
    glNamedBufferData(gpu.buffers[3], GLsizeiptr(data.indices.size() * sizeof(std::uint32_t)),
                      data.indices.data(), GL_STATIC_DRAW);
    gpu.submeshes = data.submeshes;
}

// Allocates the texture's storage (immutable: a new image needs a new GpuTexture) and fills it.
void upload(GpuTexture& gpu, const TextureImage& image, TextureEncoding encoding) {
    int levels = 1;
    for (int size = std::max(image.width, image.height); size > 1; size /= 2)
        ++levels;
    glTextureStorage2D(gpu.name, levels, encoding == TextureEncoding::Srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8,
                       image.width, image.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // Row 0 (top) goes to t = 0, so uv (0, 0) is the image's top-left corner (glTF convention).
    glTextureSubImage2D(gpu.name, 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE,
                        image.rgba.data());
    glGenerateTextureMipmap(gpu.name);
    // Filtering and wrapping are the renderer's texture sampler's, bound with the texture for every draw
    // (Renderer::anisotropicFiltering()).
}

// The upload under `key`, made (and counted in `uploads`) by `make` when no cache holds one.
template <typename Gpu, typename Make>
std::shared_ptr<Gpu> sharedUpload(std::map<std::string, std::weak_ptr<Gpu>, std::less<>>& uploads,
                                  const std::string& key, std::uint64_t& count, Make make) {
    std::weak_ptr<Gpu>& entry = uploads[key];
    std::shared_ptr<Gpu> gpu = entry.lock();
    if (!gpu) {
        gpu = make();
        entry = gpu;
        ++count;
    }
    return gpu;
}

} // namespace

GpuMesh::GpuMesh() {
    glCreateVertexArrays(1, &vao);
    glCreateBuffers(4, buffers);
    glVertexArrayVertexBuffer(vao, 0, buffers[0], 0, sizeof(float) * 3);
    glVertexArrayVertexBuffer(vao, 1, buffers[1], 0, sizeof(float) * 3);
    glVertexArrayVertexBuffer(vao, 2, buffers[2], 0, sizeof(float) * 2);
    glVertexArrayElementBuffer(vao, buffers[3]);
    for (GLuint attribute : {0u, 1u, 2u}) {
        glEnableVertexArrayAttrib(vao, attribute);
        glVertexArrayAttribFormat(vao, attribute, attribute == 2 ? 2 : 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(vao, attribute, attribute);
    }
    configureInstanceAttributes(vao); // the renderer binds its instance records per draw
}

GpuMesh::~GpuMesh() {
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(4, buffers);
}

GpuTexture::GpuTexture() {
    glCreateTextures(GL_TEXTURE_2D, 1, &name);
}

GpuTexture::~GpuTexture() {
    glDeleteTextures(1, &name);
}

void SharedUploads::prune() {
    std::erase_if(meshes, [](const auto& entry) { return entry.second.expired(); });
    std::erase_if(textures, [](const auto& entry) { return entry.second.expired(); });
}

const GpuMesh& GpuSceneCache::mesh(const Scene& scene, MeshId id) {
    const MeshData& data = scene.mesh(id); // throws for a stale id
    const std::uint64_t revision = scene.meshRevision(id);
    if (id.index >= meshes_.size())
        meshes_.resize(id.index + 1);
    Slot<GpuMesh>& slot = meshes_[id.index];
    if (slot.gpu && slot.generation == id.generation && slot.revision == revision)
        return *slot.gpu;
    if (const std::string& key = scene.meshSharedKey(id); !key.empty()) {
        slot.gpu = sharedUpload(shared_.meshes, key, meshUploads_, [&] {
            auto gpu = std::make_shared<GpuMesh>();
            upload(*gpu, data);
            return gpu;
        });
        slot.shared = true;
    } else {
        if (!slot.gpu || slot.shared) // the buffers of a shared upload are not this scene's to refill
            slot.gpu = std::make_shared<GpuMesh>();
        upload(*slot.gpu, data);
        slot.shared = false;
        ++meshUploads_;
    }
    slot.generation = id.generation;
    slot.revision = revision;
    return *slot.gpu;
}

const GpuMesh& GpuSceneCache::refined(const Scene& scene, MeshId id, int times) {
    const MeshData& data = scene.mesh(id); // throws for a stale id
    const std::uint64_t revision = scene.meshRevision(id);
    Refined& entry = refined_[{id.index, times}];
    if (!entry.gpu || entry.generation != id.generation || entry.revision != revision) {
        auto make = [&] {
            auto gpu = std::make_shared<GpuMesh>();
            upload(*gpu, data.subdivided(times));
            return gpu;
        };
        // An asset's mesh is the same in every world, and so is its subdivision: one upload for all.
        if (const std::string& key = scene.meshSharedKey(id); !key.empty()) {
            entry.gpu =
                sharedUpload(shared_.meshes, key + "#subdivided" + std::to_string(times), meshUploads_, make);
        } else {
            entry.gpu = make();
            ++meshUploads_;
        }
        entry.generation = id.generation;
        entry.revision = revision;
    }
    return *entry.gpu;
}

unsigned GpuSceneCache::texture(const Scene& scene, TextureId id) {
    const TextureImage& image = scene.texture(id); // throws for a stale id
    if (id.index >= textures_.size())
        textures_.resize(id.index + 1);
    Slot<GpuTexture>& slot = textures_[id.index];
    if (slot.gpu && slot.generation == id.generation)
        return slot.gpu->name;
    const TextureEncoding encoding = scene.textureEncoding(id);
    auto make = [&] {
        auto gpu = std::make_shared<GpuTexture>();
        upload(*gpu, image, encoding);
        return gpu;
    };
    if (const std::string& key = scene.textureSharedKey(id); !key.empty()) {
        slot.gpu = sharedUpload(shared_.textures, key, textureUploads_, make);
        slot.shared = true;
    } else {
        slot.gpu = make();
        slot.shared = false;
        ++textureUploads_;
    }
    slot.generation = id.generation;
    return slot.gpu->name;
}

} // namespace sp::render
