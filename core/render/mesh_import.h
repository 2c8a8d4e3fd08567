#pragma once
// Mesh import through assimp (OBJ, PLY, glTF/GLB and the other formats assimp reads): one MeshData
// whose submeshes are the file's material groups (node transforms baked in), plus a basic PBR material
// per submesh. No GL.

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
    std::optional<TextureImage> roughnessMetallicTexture;
    std::optional<TextureImage> normalTexture;
};

struct ImportedMesh {
    MeshData mesh;
    std::vector<ImportedMaterial> materials; // one per submesh
};

// Reads a mesh file. Throws sp::NotFound naming the path when it does not exist, sp::InvalidArgument
// when assimp cannot read it (unsupported format, corrupt data) or it holds no triangles.
ImportedMesh importMesh(const std::string& path);

// Handles of an imported mesh added to a scene.
struct ImportedMeshIds {
    MeshId mesh;
    std::vector<MaterialId> materials; // one per submesh, ready for Instance::materials
};

// Adds the mesh, its textures and its materials to `scene`. With `shared`, the mesh and textures are added
// under keys naming their content (content_key.h), so that a renderer drawing several scenes that import
// the same asset uploads it once (Scene::addMesh).
ImportedMeshIds addToScene(Scene& scene, const ImportedMesh& imported, bool shared = false);

} // namespace sp::render
