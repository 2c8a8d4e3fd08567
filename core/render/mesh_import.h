#pragma once
// Mesh import through assimp (OBJ, PLY, glTF/GLB and the other formats assimp reads): one MeshData
// whose submeshes are the file's material groups (node transforms baked in), plus a basic PBR material
// per submesh. No GL.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/render/material.h"
#include "core/render/mesh_data.h"
#include "core/render/scene.h"
#include "core/render/texture_image.h"

namespace sp::render {

// One submesh's material as read from the file; textures are decoded but not yet in a Scene.
struct ImportedMaterial {
    std::string name;
    Material material; // texture ids unset
    std::optional<TextureImage> baseColorTexture;
    std::optional<TextureImage> roughnessMetallicTexture; // with the occlusion map's R packed in (Material)
    std::optional<TextureImage> normalTexture;
};

struct ImportedMesh {
    MeshData mesh;
    std::vector<ImportedMaterial> materials; // one per submesh
};

// Reads a mesh file. Throws sp::NotFound naming the path when it does not exist, sp::InvalidArgument
// when assimp cannot read it (unsupported format, corrupt data) or it holds no triangles. A file read before
// is taken from a process-wide cache (the most recently used kImportCacheBytes) while it and every file
// its import read or looked for (material library, buffers, textures) keep their size and modification
// time: physics and each world's renderer import a file, and a large one reads for seconds.
ImportedMesh importMesh(const std::string& path);
inline constexpr std::size_t kImportCacheBytes = std::size_t(256) << 20;
// The mesh files importMesh() has read in this process (not those it took from its cache).
std::uint64_t meshFilesRead();

// Handles of an imported mesh added to a scene.
struct ImportedMeshIds {
    MeshId mesh;
    std::vector<MaterialId> materials; // one per submesh, ready for Instance::materials
};

// Adds the mesh, its textures and its materials to `scene`. With `shared`, the mesh and textures are added
// under keys naming their content (content_key.h), so that a renderer drawing several scenes that import
// the same asset uploads it once (Scene::addMesh).
ImportedMeshIds addToScene(Scene& scene, const ImportedMesh& imported, bool shared = false);
// Adds only the materials (and their textures), as addToScene does: one per entry of `materials`.
std::vector<MaterialId> addMaterialsToScene(Scene& scene, const std::vector<ImportedMaterial>& materials,
                                            bool shared = false);

} // namespace sp::render
