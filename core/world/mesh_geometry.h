#pragma once
// The geometry of a mesh file (OBJ, PLY, glTF, ... through the renderer's importer), as physics and
// bounds need it: vertices in metres, triangles, and the bounding box. Loaded once per path.

#include <Eigen/Geometry>

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace sp::world {

struct MeshGeometry {
    std::vector<Eigen::Vector3d> vertices;
    std::vector<uint32_t> indices; // three per triangle
    Eigen::AlignedBox3d bounds;
};

// True when `mesh` names a file rather than a built-in shape ("/Engine/BasicShapes/...").
bool isMeshFile(std::string_view mesh);

// The geometry of the file at `path`, loaded on first use. Throws sp::NotFound naming `function` and
// the path when there is no such file, sp::InvalidArgument when it cannot be read as a mesh.
std::shared_ptr<const MeshGeometry> loadMeshGeometry(const std::string& path, std::string_view function);

// Like loadMeshGeometry, but nullptr instead of an error (for bounds queries, which must not throw).
std::shared_ptr<const MeshGeometry> findMeshGeometry(const std::string& path);

} // namespace sp::world
