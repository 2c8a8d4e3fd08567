#pragma once
// Recast's half of the navigation mesh: voxelises the geometry around one tile and turns it into Detour
// tile data. Recast works Y up; the world is Z up, so geometry enters Recast's frame as (x, z, -y), a
// rotation, which keeps triangles' winding (and so which side is up).

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/navigation/nav_mesh_settings.h"
#include "core/physics/triangles.h"

namespace sp::navigation::detail {

inline Eigen::Vector3f toRecast(const Eigen::Vector3d& p) {
    return {float(p.x()), float(p.z()), float(-p.y())};
}
inline Eigen::Vector3d fromRecast(const float* p) {
    return {double(p[0]), -double(p[2]), double(p[1])};
}

// Geometry in Recast's frame, with each triangle's horizontal bounds for picking a tile's triangles.
struct RecastGeometry {
    std::vector<float> vertices; // x, y, z triples
    std::vector<int> triangles;  // index triples
    std::vector<float> bounds;   // per triangle: min x, min z, max x, max z
};
RecastGeometry toRecastGeometry(const physics::TriangleSoup& soup);

// The tile layout over the navigable region, in Recast's frame.
struct TileGrid {
    float origin[3];     // minimum corner of the region
    float maxHeight;     // top of the region (Recast y)
    float end[2];        // the far corner of the region in x and z (the last tiles may reach past it)
    int tileCells;       // cells along a tile's side
    float tileWorldSize; // tileCells * cell size
    int tilesX, tilesZ;  // tiles along x and z
};
TileGrid makeTileGrid(const Eigen::AlignedBox3d& worldRegion, const NavMeshSettings& settings);

// Detour tile data, owned until handed to dtNavMesh::addTile (which frees it with DT_TILE_FREE_DATA).
struct TileDataDeleter {
    void operator()(unsigned char* data) const;
};
struct TileData {
    std::unique_ptr<unsigned char, TileDataDeleter> data;
    int size = 0;
};

// Builds tile (tx, tz), walkable only inside the region; returns no data when the tile has no walkable
// polygon. Throws sp::InvalidState
// naming the Recast step that failed.
TileData buildTile(const RecastGeometry& geometry, const NavMeshSettings& settings, const TileGrid& grid,
                   int tx, int tz);

} // namespace sp::navigation::detail
