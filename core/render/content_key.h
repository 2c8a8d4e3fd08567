#pragma once
// Keys naming content by what it is: the shared keys (Scene::addMesh, addTexture) of meshes and textures
// imported from files, so that worlds loading the same asset share one upload while a file changed on disk,
// a texture edited beside its mesh or a copy with another name can never be taken for another. Two
// independent 64-bit hashes of the bytes and their length: a collision between two different assets is
// beyond any practical concern (this is not a defence against crafted inputs).

#include <string>

#include "core/render/mesh_data.h"
#include "core/render/scene.h"
#include "core/render/texture_image.h"

namespace sp::render {

// "mesh:<32 hex digits>" over positions, normals, uvs, indices and submeshes (validated data).
std::string contentKey(const MeshData& mesh);
// "texture:<width>x<height>:<srgb|linear>:<32 hex digits>" over the pixels; the encoding is part of what
// is uploaded (the GL format), so the same pixels read as colour and as data are two uploads.
std::string contentKey(const TextureImage& image, TextureEncoding encoding);

} // namespace sp::render
