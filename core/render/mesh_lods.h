#pragma once
// Coarser levels of detail of a mesh (Scene::setMeshLods()), made by meshoptimizer's simplifier: an imported
// mesh of many small triangles is drawn through one of them where it is small in the image. Pure logic, no
// GL.

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/render/mesh_data.h"

namespace sp::render {

// Meshes of fewer triangles get no levels: their vertex and set-up work is small beside their pixels'.
inline constexpr std::size_t kLeastLodTriangles = 2048;
// A level's error bound, as a fraction of the mesh's bounding radius, past which no coarser level is made.
inline constexpr float kMostLodError = 0.25f;

// A mesh's levels of detail, fine to coarse, each with its MeshLod::relativeError.
using MeshLevels = std::vector<std::pair<MeshData, float>>;

// The levels of a validated mesh from fine to coarse, each with its MeshLod::relativeError (how far its
// surface moved: the largest distance from a vertex of the mesh to the level's triangles, as a fraction of
// the mesh's bounding radius; never decreasing): each has about half the triangles of the one before it,
// every submesh simplified on its own, with the edges it shares with other submeshes kept where they are
// (no cracks between materials) and no submesh emptied. Levels stop when one saves under a fifth of its
// predecessor's triangles or its bound passes kMostLodError; none for meshes of under kLeastLodTriangles
// triangles. A level holds only the vertices it uses, with their normals and uvs. `levelDone` (if set) is
// called as each level is made.
MeshLevels simplifiedLods(const MeshData& mesh, const std::function<void()>& levelDone = {});

// simplifiedLods() of a mesh whose content `key` names (contentKey()), made once per process while they stay
// among the most recently used kLodCacheBytes: the worlds of a vectorised environment that import one asset
// share its levels instead of each simplifying it again (a million triangles: about 2 s each).
std::shared_ptr<const MeshLevels> sharedLods(const std::string& key, const MeshData& mesh,
                                             const std::function<void()>& levelDone = {});
inline constexpr std::size_t kLodCacheBytes = std::size_t(256) << 20;

} // namespace sp::render
