#include "core/render/gpu_scene_cache.h"

#include <epoxy/gl.h>

#include <algorithm>

namespace sp::render {

GpuSceneCache::~GpuSceneCache() {
    for (GpuMesh& mesh : meshes_) {
        if (mesh.vao != 0) {
            glDeleteVertexArrays(1, &mesh.vao);
            glDeleteBuffers(4, mesh.buffers);
        }
    }
    for (GpuTexture& texture : textures_)
        if (texture.name != 0)
            glDeleteTextures(1, &texture.name);
}

const GpuMesh& GpuSceneCache::mesh(const Scene& scene, MeshId id) {
    const MeshData& data = scene.mesh(id); // throws for a stale id
    const std::uint64_t revision = scene.meshRevision(id);
    if (id.index >= meshes_.size())
        meshes_.resize(id.index + 1);
    GpuMesh& gpu = meshes_[id.index];
    if (gpu.vao != 0 && gpu.generation == id.generation && gpu.revision == revision)
        return gpu;
    if (gpu.vao == 0) {
        glCreateVertexArrays(1, &gpu.vao);
        glCreateBuffers(4, gpu.buffers);
        glVertexArrayVertexBuffer(gpu.vao, 0, gpu.buffers[0], 0, sizeof(float) * 3);
        glVertexArrayVertexBuffer(gpu.vao, 1, gpu.buffers[1], 0, sizeof(float) * 3);
        glVertexArrayVertexBuffer(gpu.vao, 2, gpu.buffers[2], 0, sizeof(float) * 2);
        glVertexArrayElementBuffer(gpu.vao, gpu.buffers[3]);
        for (GLuint attribute : {0u, 1u, 2u}) {
            glEnableVertexArrayAttrib(gpu.vao, attribute);
            glVertexArrayAttribFormat(gpu.vao, attribute, attribute == 2 ? 2 : 3, GL_FLOAT, GL_FALSE, 0);
            glVertexArrayAttribBinding(gpu.vao, attribute, attribute);
        }
    }
    // Eigen's fixed-size vectors are packed floats, so the std::vectors upload as flat arrays.
    glNamedBufferData(gpu.buffers[0], GLsizeiptr(data.positions.size() * sizeof(float) * 3),
                      data.positions.data(), GL_STATIC_DRAW);
    glNamedBufferData(gpu.buffers[1], GLsizeiptr(data.normals.size() * sizeof(float) * 3),
                      data.normals.data(), GL_STATIC_DRAW);
    glNamedBufferData(gpu.buffers[2], GLsizeiptr(data.uvs.size() * sizeof(float) * 2), data.uvs.data(),
                      GL_STATIC_DRAW);
    glNamedBufferData(gpu.buffers[3], GLsizeiptr(data.indices.size() * sizeof(std::uint32_t)),
                      data.indices.data(), GL_STATIC_DRAW);
    gpu.generation = id.generation;
    gpu.revision = revision;
    gpu.submeshes = data.submeshes;
    ++meshUploads_;
    return gpu;
}

unsigned GpuSceneCache::texture(const Scene& scene, TextureId id) {
    const TextureImage& image = scene.texture(id); // throws for a stale id
    if (id.index >= textures_.size())
        textures_.resize(id.index + 1);
    GpuTexture& gpu = textures_[id.index];
    if (gpu.name != 0 && gpu.generation == id.generation)
        return gpu.name;
    if (gpu.name != 0)
        glDeleteTextures(1, &gpu.name);
    const bool srgb = scene.textureEncoding(id) == TextureEncoding::Srgb;
    int levels = 1;
    for (int size = std::max(image.width, image.height); size > 1; size /= 2)
        ++levels;
    glCreateTextures(GL_TEXTURE_2D, 1, &gpu.name);
    glTextureStorage2D(gpu.name, levels, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, image.width, image.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // Row 0 (top) goes to t = 0, so uv (0, 0) is the image's top-left corner (glTF convention).
    glTextureSubImage2D(gpu.name, 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE,
                        image.rgba.data());
    glGenerateTextureMipmap(gpu.name);
    glTextureParameteri(gpu.name, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(gpu.name, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(gpu.name, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(gpu.name, GL_TEXTURE_WRAP_T, GL_REPEAT);
    gpu.generation = id.generation;
    ++textureUploads_;
    return gpu.name;
}

} // namespace sp::render
