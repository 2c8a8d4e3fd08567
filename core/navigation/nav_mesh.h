#pragma once
// NavMesh: a tiled navigation mesh (Recast builds it, Detour answers queries) over a region of static
// geometry, for one agent. World coordinates, metres, Z up. Tiles are rebuilt one by one when the
// geometry under them changes (rebuildTiles), so a change costs the tiles it touches.
//
// Random points are uniform over the mesh's area (polygons drawn by area across all tiles, then a
// uniform point inside; Detour's own sampler draws tiles with equal weight, which is not uniform), and
// deterministic for a given generator state. Not thread-safe: queries share one Detour query object.

#include <array>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "core/navigation/nav_mesh_settings.h"
#include "core/physics/triangles.h"

namespace sp::navigation {

struct BuildStats {
    int tilesBuilt = 0;    // tiles voxelised
    int tilesWithMesh = 0; // of them, those that hold walkable polygons
    double seconds = 0.0;
};

struct Path {
    // Why a path query ended as it did.
    enum class Status {
        Success,  // a complete path from start to end
        Partial,  // end is unreachable: the path leads to the reachable point closest to it
        StartOff, // start is not within the query extent of the mesh
        EndOff,   // end is not within the query extent of the mesh
        NoMesh,   // the mesh is empty
    };
    Status status = Status::NoMesh;
    std::vector<Eigen::Vector3d> points; // corners from (projected) start to (projected) end
    double length = 0.0;                 // of the polyline, metres
};
const char* statusName(Path::Status status);

class NavMesh {
  public:
    NavMesh();
    ~NavMesh();
    NavMesh(const NavMesh&) = delete;
    NavMesh& operator=(const NavMesh&) = delete;

    // Builds every tile over `region` from `geometry` (which may extend beyond it); replaces any
    // previous mesh. Throws sp::InvalidArgument for bad settings or an empty region.
    BuildStats build(const physics::TriangleSoup& geometry, const Eigen::AlignedBox3d& region,
                     const NavMeshSettings& settings);
    // Rebuilds the tiles whose voxelised area meets `changed` from `geometry` (all of it, as it is now),
    // keeping the others. Needs a built mesh.
    BuildStats rebuildTiles(const physics::TriangleSoup& geometry, const Eigen::AlignedBox3d& changed);

    bool isBuilt() const;
    const NavMeshSettings& settings() const;
    const Eigen::AlignedBox3d& region() const;
    int tileCount() const; // tiles holding polygons
    int polygonCount() const;
    double area() const; // walkable area (horizontal projection), square metres

    // The extent searched around a point when none is given: two agent radii (at least half a metre)
    // sideways, an agent height up and down.
    Eigen::Vector3d defaultQueryExtent() const;

    // The point of the mesh nearest `point` within `extent` (half sizes per world axis), if any.
    std::optional<Eigen::Vector3d> project(const Eigen::Vector3d& point, const Eigen::Vector3d& extent) const;
    // Whether `point` is over the mesh (within a centimetre sideways) and at most maxVerticalDistance
    // above or below its surface.
    bool isNavigable(const Eigen::Vector3d& point, double maxVerticalDistance) const;
    // The shortest path between the projections of start and end (found within `extent`).
    Path findPath(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                  const Eigen::Vector3d& extent) const;

    // A point uniform over the whole mesh; nullopt when it is empty.
    std::optional<Eigen::Vector3d> randomPoint(std::mt19937_64& rng) const;
    // A point uniform over the part of the mesh within `radius` (horizontally) of `origin`; with
    // reachableOnly, only the part connected to the polygon under origin (projected within `extent`).
    // nullopt when there is none (origin off the mesh, or nothing within the radius).
    std::optional<Eigen::Vector3d> randomPointInRadius(const Eigen::Vector3d& origin, double radius,
                                                       bool reachableOnly, const Eigen::Vector3d& extent,
                                                       std::mt19937_64& rng) const;

    // The mesh's surface as triangles (Detour's detail mesh), for drawing.
    std::vector<std::array<Eigen::Vector3d, 3>> triangles() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace sp::navigation
