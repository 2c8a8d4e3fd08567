#pragma once
// Procedural meshes with normals and uvs, one submesh each, centred at the origin, Z up.

#include "core/render/mesh_data.h"

namespace sp::render::primitives {

// Axis-aligned box with the given full extents (metres), flat-shaded faces.
MeshData box(const Eigen::Vector3f& size = Eigen::Vector3f::Ones());
// UV sphere of the given radius.
MeshData sphere(float radius = 0.5f, int segments = 32, int rings = 16);
// Plane in the XY plane facing +Z, sizeX by sizeY metres.
MeshData plane(float sizeX = 1.0f, float sizeY = 1.0f);
// Cylinder along Z with caps, height centred at the origin.
MeshData cylinder(float radius = 0.5f, float height = 1.0f, int segments = 32);
// An open tube of the given radius through `path` (at least two points; repeated points are skipped),
// its rings turned along the path without twisting (parallel transport): a line that can be rendered.
// Coordinates are the path's own (no centring). Throws sp::InvalidArgument for fewer than two distinct
// points or a radius that is not > 0.
MeshData tube(const std::vector<Eigen::Vector3f>& path, float radius, int sides = 6);

} // namespace sp::render::primitives
