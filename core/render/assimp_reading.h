#pragma once
// What importMesh() does to read a file with assimp, for importers of the other things a mesh file holds
// (core/animation's skeletons, skins and clips): the same checks on the files it refers to, the same progress
// report and the same materials.

#include <filesystem>
#include <string>
#include <vector>

#include "core/render/mesh_import.h"

struct aiScene;
namespace Assimp {
class Importer;
}

namespace sp::render {

// Reads `path` (resolved and checked by the caller; `userPath` is what the user named) with assimp's
// post-processing `flags`. A file it refers to must be a regular file, as the mesh file itself (a FIFO would
// block the engine); `filesRead` gets every file it opened or looked for. Throws sp::InvalidArgument
// "<function>(): cannot read '<userPath>': <assimp's reason>". The scene belongs to `importer`.
const aiScene* readWithAssimp(Assimp::Importer& importer, const std::string& path,
                              const std::string& userPath, unsigned flags,
                              std::vector<std::string>& filesRead, const char* function);

// Material `index` of `scene` as importMesh() reads it, its textures decoded (named relative to `directory`;
// those looked for are added to `filesRead`).
ImportedMaterial importMaterial(const aiScene& scene, unsigned index, const std::filesystem::path& directory,
                                std::vector<std::string>& filesRead);

// glTF's axes (+Y up) turned into spear's (+Z up): a quarter turn about X, (x, y, z) -> (x, -z, y). Whether a
// file is glTF (.gltf, .glb), whose axes those are; other formats are read as they are.
bool isYUpFormat(const std::string& path);

} // namespace sp::render
