#include "core/navigation/tile_builder.h"

#include <algorithm>
#include <cmath>

#include <DetourAlloc.h>
#include <DetourNavMesh.h>
#include <DetourNavMeshBuilder.h>
#include <Recast.h>

#include "core/base/error.h"

namespace sp::navigation::detail {

namespace {

// Recast's objects, freed with its own allocator.
struct HeightfieldDeleter {
    void operator()(rcHeightfield* p) const { rcFreeHeightField(p); }
};
struct CompactDeleter {
    void operator()(rcCompactHeightfield* p) const { rcFreeCompactHeightfield(p); }
};
struct ContourDeleter {
    void operator()(rcContourSet* p) const { rcFreeContourSet(p); }
};
struct PolyMeshDeleter {
    void operator()(rcPolyMesh* p) const { rcFreePolyMesh(p); }
};
struct DetailDeleter {
    void operator()(rcPolyMeshDetail* p) const { rcFreePolyMeshDetail(p); }
};

constexpr unsigned short kWalkableFlag = 1;

} // namespace

void TileDataDeleter::operator()(unsigned char* data) const {
    dtFree(data);
}

RecastGeometry toRecastGeometry(const physics::TriangleSoup& soup) {
    RecastGeometry geometry;
    geometry.vertices.reserve(soup.vertices.size() * 3);
    for (const Eigen::Vector3d& v : soup.vertices) {
        const Eigen::Vector3f r = toRecast(v);
        geometry.vertices.insert(geometry.vertices.end(), {r.x(), r.y(), r.z()});
    }
    geometry.triangles.assign(soup.indices.begin(), soup.indices.end());
    geometry.bounds.reserve(soup.triangleCount() * 4);
    for (size_t t = 0; t < soup.triangleCount(); ++t) {
        float minX = INFINITY, minZ = INFINITY, maxX = -INFINITY, maxZ = -INFINITY;
        for (int k = 0; k < 3; ++k) {
            const float* v = &geometry.vertices[size_t(geometry.triangles[3 * t + size_t(k)]) * 3];
            minX = std::min(minX, v[0]);
            maxX = std::max(maxX, v[0]);
            minZ = std::min(minZ, v[2]);
            maxZ = std::max(maxZ, v[2]);
        }
        geometry.bounds.insert(geometry.bounds.end(), {minX, minZ, maxX, maxZ});
    }
    return geometry;
}

TileGrid makeTileGrid(const Eigen::AlignedBox3d& worldRegion, const NavMeshSettings& settings) {
    const Eigen::Vector3f a = toRecast(worldRegion.min()), b = toRecast(worldRegion.max());
    TileGrid grid{};
    grid.origin[0] = std::min(a.x(), b.x());
    grid.origin[1] = std::min(a.y(), b.y());
    grid.origin[2] = std::min(a.z(), b.z());
    grid.maxHeight = std::max(a.y(), b.y());
    grid.tileCells = int(std::lround(settings.tileSize / settings.cellSize));
    grid.tileWorldSize = float(grid.tileCells * settings.cellSize);
    const float sizeX = std::max(a.x(), b.x()) - grid.origin[0],
                sizeZ = std::max(a.z(), b.z()) - grid.origin[2];
    grid.end[0] = grid.origin[0] + sizeX;
    grid.end[1] = grid.origin[2] + sizeZ;
    grid.tilesX = std::max(1, int(std::ceil(sizeX / grid.tileWorldSize)));
    grid.tilesZ = std::max(1, int(std::ceil(sizeZ / grid.tileWorldSize)));
    return grid;
}

TileData buildTile(const RecastGeometry& geometry, const NavMeshSettings& s, const TileGrid& grid, int tx,
                   int tz) {
    rcConfig cfg{};
    cfg.cs = float(s.cellSize);
    cfg.ch = float(s.cellHeight);
    cfg.walkableSlopeAngle = float(s.maxSlopeDegrees);
    cfg.walkableHeight = int(std::ceil(s.agentHeight / s.cellHeight));
    cfg.walkableClimb = int(std::floor(s.maxStepHeight / s.cellHeight));
    cfg.walkableRadius = int(std::ceil(s.agentRadius / s.cellSize));
    cfg.maxEdgeLen = int(12.0 / s.cellSize);
    cfg.maxSimplificationError = 1.3f;
    cfg.minRegionArea = int(std::lround(s.minRegionArea / (s.cellSize * s.cellSize)));
    cfg.mergeRegionArea = int(std::lround(4.0 / (s.cellSize * s.cellSize)));
    cfg.maxVertsPerPoly = DT_VERTS_PER_POLYGON;
    cfg.detailSampleDist = float(6.0 * s.cellSize);
    cfg.detailSampleMaxError = float(s.cellHeight);
    cfg.tileSize = grid.tileCells;
    // A border of cells beyond the tile is voxelised too, so that erosion and regions at the tile's
    // edge see the geometry next door and neighbouring tiles meet exactly.
    cfg.borderSize = cfg.walkableRadius + 3;
    cfg.width = cfg.height = cfg.tileSize + 2 * cfg.borderSize;
    const float border = float(cfg.borderSize) * cfg.cs;
    cfg.bmin[0] = grid.origin[0] + float(tx) * grid.tileWorldSize - border;
    cfg.bmin[1] = grid.origin[1];
    cfg.bmin[2] = grid.origin[2] + float(tz) * grid.tileWorldSize - border;
    cfg.bmax[0] = grid.origin[0] + float(tx + 1) * grid.tileWorldSize + border;
    cfg.bmax[1] = grid.maxHeight;
    cfg.bmax[2] = grid.origin[2] + float(tz + 1) * grid.tileWorldSize + border;

    // The triangles that reach into the tile and its border.
    std::vector<int> triangles;
    for (size_t t = 0; t < geometry.triangles.size() / 3; ++t) {
        const float* b = &geometry.bounds[4 * t];
        if (b[0] > cfg.bmax[0] || b[2] < cfg.bmin[0] || b[1] > cfg.bmax[2] || b[3] < cfg.bmin[2])
            continue;
        triangles.insert(triangles.end(), geometry.triangles.begin() + long(3 * t),
                         geometry.triangles.begin() + long(3 * t + 3));
    }
    if (triangles.empty())
        return {};
    const int triangleCount = int(triangles.size() / 3);
    const int vertexCount = int(geometry.vertices.size() / 3);

    rcContext context(false);
    auto check = [&](bool ok, const char* step) {
        SP_CHECK(ok, InvalidState, "navigation: building tile (", tx, ", ", tz, ") failed in ", step);
    };
    std::unique_ptr<rcHeightfield, HeightfieldDeleter> heightfield(rcAllocHeightfield());
    check(heightfield && rcCreateHeightfield(&context, *heightfield, cfg.width, cfg.height, cfg.bmin,
                                             cfg.bmax, cfg.cs, cfg.ch),
          "rcCreateHeightfield");
    std::vector<unsigned char> areas(size_t(triangleCount), RC_NULL_AREA);
    rcMarkWalkableTriangles(&context, cfg.walkableSlopeAngle, geometry.vertices.data(), vertexCount,
                            triangles.data(), triangleCount, areas.data());
    check(rcRasterizeTriangles(&context, geometry.vertices.data(), vertexCount, triangles.data(),
                               areas.data(), triangleCount, *heightfield, cfg.walkableClimb),
          "rcRasterizeTriangles");
    rcFilterLowHangingWalkableObstacles(&context, cfg.walkableClimb, *heightfield);
    rcFilterLedgeSpans(&context, cfg.walkableHeight, cfg.walkableClimb, *heightfield);
    rcFilterWalkableLowHeightSpans(&context, cfg.walkableHeight, *heightfield);

    std::unique_ptr<rcCompactHeightfield, CompactDeleter> compact(rcAllocCompactHeightfield());
    check(compact && rcBuildCompactHeightfield(&context, cfg.walkableHeight, cfg.walkableClimb, *heightfield,
                                               *compact),
          "rcBuildCompactHeightfield");
    heightfield.reset();
    check(rcErodeWalkableArea(&context, cfg.walkableRadius, *compact), "rcErodeWalkableArea");
    // The last row and column of tiles reach past the region: what lies beyond it is cut off (after the
    // erosion, so the region's edge is a cut, not a wall).
    const float low = grid.origin[1] - 1.0f, high = grid.maxHeight + 1.0f;
    const float beyond[4][6] = {
        {cfg.bmin[0] - 1, low, cfg.bmin[2] - 1, grid.origin[0], high, cfg.bmax[2] + 1},
        {grid.end[0], low, cfg.bmin[2] - 1, cfg.bmax[0] + 1, high, cfg.bmax[2] + 1},
        {cfg.bmin[0] - 1, low, cfg.bmin[2] - 1, cfg.bmax[0] + 1, high, grid.origin[2]},
        {cfg.bmin[0] - 1, low, grid.end[1], cfg.bmax[0] + 1, high, cfg.bmax[2] + 1},
    };
    for (const float* box : beyond)
        if (box[0] < box[3] && box[2] < box[5])
            rcMarkBoxArea(&context, box, box + 3, RC_NULL_AREA, *compact);
    check(rcBuildDistanceField(&context, *compact), "rcBuildDistanceField");
    check(rcBuildRegions(&context, *compact, cfg.borderSize, cfg.minRegionArea, cfg.mergeRegionArea),
          "rcBuildRegions");

    std::unique_ptr<rcContourSet, ContourDeleter> contours(rcAllocContourSet());
    check(contours &&
              rcBuildContours(&context, *compact, cfg.maxSimplificationError, cfg.maxEdgeLen, *contours),
          "rcBuildContours");
    if (contours->nconts == 0)
        return {};
    std::unique_ptr<rcPolyMesh, PolyMeshDeleter> mesh(rcAllocPolyMesh());
    check(mesh && rcBuildPolyMesh(&context, *contours, cfg.maxVertsPerPoly, *mesh), "rcBuildPolyMesh");
    std::unique_ptr<rcPolyMeshDetail, DetailDeleter> detail(rcAllocPolyMeshDetail());
    check(detail && rcBuildPolyMeshDetail(&context, *mesh, *compact, cfg.detailSampleDist,
                                          cfg.detailSampleMaxError, *detail),
          "rcBuildPolyMeshDetail");
    if (mesh->npolys == 0)
        return {};
    SP_CHECK(mesh->nverts < 0xffff, InvalidState, "navigation: tile (", tx, ", ", tz, ") has ", mesh->nverts,
             " vertices, more than a Detour tile holds; use a smaller TileSize");
    for (int i = 0; i < mesh->npolys; ++i)
        mesh->flags[i] = mesh->areas[i] == RC_WALKABLE_AREA ? kWalkableFlag : 0;

    dtNavMeshCreateParams params{};
    params.verts = mesh->verts;
    params.vertCount = mesh->nverts;
    params.polys = mesh->polys;
    params.polyAreas = mesh->areas;
    params.polyFlags = mesh->flags;
    params.polyCount = mesh->npolys;
    params.nvp = mesh->nvp;
    params.detailMeshes = detail->meshes;
    params.detailVerts = detail->verts;
    params.detailVertsCount = detail->nverts;
    params.detailTris = detail->tris;
    params.detailTriCount = detail->ntris;
    params.walkableHeight = float(s.agentHeight);
    params.walkableRadius = float(s.agentRadius);
    params.walkableClimb = float(s.maxStepHeight);
    params.tileX = tx;
    params.tileY = tz;
    params.tileLayer = 0;
    std::copy(mesh->bmin, mesh->bmin + 3, params.bmin);
    std::copy(mesh->bmax, mesh->bmax + 3, params.bmax);
    params.cs = cfg.cs;
    params.ch = cfg.ch;
    params.buildBvTree = true;
    unsigned char* data = nullptr;
    int size = 0;
    check(dtCreateNavMeshData(&params, &data, &size), "dtCreateNavMeshData");
    TileData tile;
    tile.data.reset(data);
    tile.size = size;
    return tile;
}

} // namespace sp::navigation::detail
