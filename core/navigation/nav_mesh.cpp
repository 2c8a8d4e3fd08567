#include "core/navigation/nav_mesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include <DetourNavMesh.h>
#include <DetourNavMeshQuery.h>

#include "core/base/error.h"
#include "core/base/progress.h"
#include "core/navigation/tile_builder.h"

namespace sp::navigation {

namespace {

struct NavMeshDeleter {
    void operator()(dtNavMesh* p) const { dtFreeNavMesh(p); }
};
struct QueryDeleter {
    void operator()(dtNavMeshQuery* p) const { dtFreeNavMeshQuery(p); }
};

// Detour's node pool indexes nodes with 16 bits: the most a search may visit. Paths across the largest
// meshes (16384 tiles) fit; a search that runs out reports the goal unreachable (Partial).
constexpr int kMaxPathPolygons = 65534;
constexpr int kQueryNodes = 65534;
// Regions larger than this (metres along an axis) are refused: float coordinates lose centimetres.
constexpr double kMaxRegionSize = 1.0e5;
// Tries before giving up on a point inside the radius: the candidates are the polygons that meet the
// disc, so a miss needs a polygon mostly outside it; 64 misses in a row means there is (almost) nothing.
constexpr int kRadiusTries = 64;

// A world half-extent in Recast's frame (axes swapped, sizes stay positive).
std::array<float, 3> extentToRecast(const Eigen::Vector3d& extent) {
    return {float(extent.x()), float(extent.z()), float(extent.y())};
}

struct PolyEntry {
    dtPolyRef ref = 0;
    double area = 0.0; // horizontal
    float minX = 0, minZ = 0, maxX = 0, maxZ = 0;
    int component = 0; // polygons linked to each other share it
};

// Union-find over polygon indices, for the connected parts of the mesh.
int findRoot(std::vector<int>& parent, int i) {
    while (parent[size_t(i)] != i) {
        parent[size_t(i)] = parent[size_t(parent[size_t(i)])];
        i = parent[size_t(i)];
    }
    return i;
}

double uniform(std::mt19937_64& rng) {
    return std::uniform_real_distribution<double>(0.0, 1.0)(rng);
}

// An index drawn with probability proportional to its weight, given the running sums of the weights.
size_t drawByWeight(const std::vector<double>& running, std::mt19937_64& rng) {
    const double pick = uniform(rng) * running.back();
    return std::min(size_t(std::upper_bound(running.begin(), running.end(), pick) - running.begin()),
                    running.size() - 1);
}

} // namespace

const char* statusName(Path::Status status) {
    switch (status) {
    case Path::Status::Success:
        return "Success";
    case Path::Status::Partial:
        return "Partial";
    case Path::Status::StartOff:
        return "StartOff";
    case Path::Status::EndOff:
        return "EndOff";
    case Path::Status::NoMesh:
        return "NoMesh";
    }
    return "?";
}

struct NavMesh::Impl {
    NavMeshSettings settings;
    Eigen::AlignedBox3d region;
    detail::TileGrid grid{};
    std::unique_ptr<dtNavMesh, NavMeshDeleter> mesh;
    std::unique_ptr<dtNavMeshQuery, QueryDeleter> query;
    dtQueryFilter filter;
    std::vector<PolyEntry> polys;
    std::vector<double> cumulative; // running sum of polys[i].area
    std::unordered_map<dtPolyRef, int> indexOf;
    int tiles = 0;
    int maxPolygonsPerTile = 0;

    Impl() {
        filter.setIncludeFlags(0xffff);
        filter.setExcludeFlags(0);
    }

    BuildStats buildRange(const physics::TriangleSoup& geometry, int x0, int z0, int x1, int z1);
    void indexPolygons();
    std::optional<std::pair<dtPolyRef, Eigen::Vector3f>> nearest(const Eigen::Vector3d& point,
                                                                 const Eigen::Vector3d& extent) const;
    Eigen::Vector3d pointInPolygon(const PolyEntry& entry, std::mt19937_64& rng) const;
    // The point of the polygon at (x, z) in Recast's frame, when (x, z) lies on it.
    std::optional<Eigen::Vector3d> pointOnPolygon(const PolyEntry& entry, float x, float z) const;
};

NavMesh::NavMesh() : impl_(std::make_unique<Impl>()) {}
NavMesh::~NavMesh() = default;

BuildStats NavMesh::Impl::buildRange(const physics::TriangleSoup& geometry, int x0, int z0, int x1, int z1) {
    const auto start = std::chrono::steady_clock::now();
    const detail::RecastGeometry recast = detail::toRecastGeometry(geometry);
    BuildStats stats;
    base::Progress progress("navigation: building " + std::to_string((x1 - x0 + 1) * (z1 - z0 + 1)) +
                                " tiles",
                            double(x1 - x0 + 1) * double(z1 - z0 + 1));
    try {
        for (int tz = z0; tz <= z1; ++tz) {
            for (int tx = x0; tx <= x1; ++tx) {
                detail::TileData tile = detail::buildTile(recast, settings, grid, tx, tz);
                ++stats.tilesBuilt;
                progress.advance();
                if (const dtTileRef old = mesh->getTileRefAt(tx, tz, 0))
                    mesh->removeTile(old, nullptr, nullptr);
                if (!tile.data)
                    continue;
                // Detour 1.5.1 does not check this itself: more polygons than the reference's polygon bits
                // hold would alias another tile's.
                const int polygons = reinterpret_cast<const dtMeshHeader*>(tile.data.get())->polyCount;
                SP_CHECK(polygons <= maxPolygonsPerTile, InvalidState, "navigation: tile (", tx, ", ", tz,
                         ") has ", polygons, " polygons, more than the ", maxPolygonsPerTile,
                         " a tile holds with this many tiles; use a larger TileSize");
                const dtStatus status =
                    mesh->addTile(tile.data.get(), tile.size, DT_TILE_FREE_DATA, 0, nullptr);
                SP_CHECK(dtStatusSucceed(status), InvalidState, "navigation: Detour refused tile (", tx, ", ",
                         tz, ") (status 0x", std::hex, status, ")");
                tile.data.release(); // the mesh owns it now
                ++stats.tilesWithMesh;
            }
        }
    } catch (...) {
        indexPolygons(); // the tiles replaced so far are gone: queries must not reach them
        throw;
    }
    indexPolygons();
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return stats;
}

void NavMesh::Impl::indexPolygons() {
    polys.clear();
    indexOf.clear();
    tiles = 0;
    const dtNavMesh& m = *mesh;
    // By tile position, not by Detour's slot (which depends on the order tiles were rebuilt in), so that a
    // seed draws the same points from equal meshes however they were built.
    for (int i = 0; i < grid.tilesX * grid.tilesZ; ++i) {
        const dtMeshTile* tile = m.getTileAt(i % grid.tilesX, i / grid.tilesX, 0);
        if (!tile || !tile->header || tile->header->polyCount == 0)
            continue;
        ++tiles;
        const dtPolyRef base = m.getPolyRefBase(tile);
        for (int p = 0; p < tile->header->polyCount; ++p) {
            const dtPoly& poly = tile->polys[p];
            if (poly.getType() != DT_POLYTYPE_GROUND)
                continue;
            PolyEntry entry;
            entry.ref = base | dtPolyRef(p);
            entry.minX = entry.minZ = INFINITY;
            entry.maxX = entry.maxZ = -INFINITY;
            double twiceArea = 0.0;
            for (int k = 0; k < poly.vertCount; ++k) {
                const float* a = &tile->verts[poly.verts[k] * 3];
                const float* b = &tile->verts[poly.verts[(k + 1) % poly.vertCount] * 3];
                twiceArea += double(a[0]) * b[2] - double(b[0]) * a[2];
                entry.minX = std::min(entry.minX, a[0]);
                entry.maxX = std::max(entry.maxX, a[0]);
                entry.minZ = std::min(entry.minZ, a[2]);
                entry.maxZ = std::max(entry.maxZ, a[2]);
            }
            entry.area = std::abs(twiceArea) / 2.0;
            indexOf[entry.ref] = int(polys.size());
            polys.push_back(entry);
        }
    }
    // Connected parts: polygons joined by a link (within a tile or across tiles) are reachable.
    std::vector<int> parent(polys.size());
    std::iota(parent.begin(), parent.end(), 0);
    for (size_t i = 0; i < polys.size(); ++i) {
        const dtMeshTile* tile = nullptr;
        const dtPoly* poly = nullptr;
        m.getTileAndPolyByRefUnsafe(polys[i].ref, &tile, &poly);
        for (unsigned int k = poly->firstLink; k != DT_NULL_LINK; k = tile->links[k].next) {
            const auto it = indexOf.find(tile->links[k].ref);
            if (it != indexOf.end())
                parent[size_t(findRoot(parent, int(i)))] = findRoot(parent, it->second);
        }
    }
    cumulative.resize(polys.size());
    double sum = 0.0;
    for (size_t i = 0; i < polys.size(); ++i) {
        polys[i].component = findRoot(parent, int(i));
        sum += polys[i].area;
        cumulative[i] = sum;
    }
}

BuildStats NavMesh::build(const physics::TriangleSoup& geometry, const Eigen::AlignedBox3d& region,
                          const NavMeshSettings& settings) {
    validate(settings, "NavMesh::build()");
    SP_CHECK(!region.isEmpty() && region.sizes().minCoeff() > 0.0 && region.sizes().allFinite() &&
                 region.min().cwiseAbs().maxCoeff() <= kMaxRegionSize &&
                 region.max().cwiseAbs().maxCoeff() <= kMaxRegionSize,
             InvalidArgument, "NavMesh::build(): the region to build over is empty, not finite or beyond ",
             kMaxRegionSize, " m of the origin");
    // Counted in doubles first: a huge region must be refused, not overflow an int.
    const double tiles =
        std::ceil(region.sizes().x() / settings.tileSize) * std::ceil(region.sizes().y() / settings.tileSize);
    SP_CHECK(tiles <= 16384.0, InvalidArgument, "NavMesh::build(): ", tiles, " tiles of TileSize ",
             settings.tileSize,
             " m cover the region; at most 16384 fit: use a larger TileSize or a smaller region");
    Impl& d = *impl_;
    d.settings = settings;
    d.region = region;
    d.grid = detail::makeTileGrid(region, settings);
    const int tileCount = d.grid.tilesX * d.grid.tilesZ;
    int tileBits = 0;
    while ((1 << tileBits) < tileCount)
        ++tileBits;
    dtNavMeshParams params{};
    std::copy(d.grid.origin, d.grid.origin + 3, params.orig);
    params.tileWidth = params.tileHeight = d.grid.tileWorldSize;
    params.maxTiles = 1 << tileBits;
    params.maxPolys = 1 << (22 - tileBits);
    d.maxPolygonsPerTile = params.maxPolys;
    d.mesh.reset(dtAllocNavMesh());
    d.query.reset(dtAllocNavMeshQuery());
    SP_CHECK(d.mesh && dtStatusSucceed(d.mesh->init(&params)), InvalidState,
             "NavMesh::build(): dtNavMesh::init failed");
    SP_CHECK(d.query && dtStatusSucceed(d.query->init(d.mesh.get(), kQueryNodes)), InvalidState,
             "NavMesh::build(): dtNavMeshQuery::init failed");
    return d.buildRange(geometry, 0, 0, d.grid.tilesX - 1, d.grid.tilesZ - 1);
}

BuildStats NavMesh::rebuildTiles(const physics::TriangleSoup& geometry, const Eigen::AlignedBox3d& changed) {
    SP_CHECK(isBuilt(), InvalidState, "NavMesh::rebuildTiles(): the mesh was never built");
    Impl& d = *impl_;
    if (changed.isEmpty())
        return {};
    // A tile voxelises its border too: a change that far outside it still reaches it.
    const double reach = (std::ceil(d.settings.agentRadius / d.settings.cellSize) + 3) * d.settings.cellSize;
    const Eigen::Vector3f a = detail::toRecast(changed.min()), b = detail::toRecast(changed.max());
    auto tileOf = [&](float coordinate, float origin, int count) {
        const double tile = std::floor((double(coordinate) - origin) / d.grid.tileWorldSize);
        return int(std::clamp(tile, 0.0, double(count - 1))); // clamped before the conversion
    };
    const float minX = std::min(a.x(), b.x()) - float(reach), maxX = std::max(a.x(), b.x()) + float(reach);
    const float minZ = std::min(a.z(), b.z()) - float(reach), maxZ = std::max(a.z(), b.z()) + float(reach);
    if (maxX < d.grid.origin[0] || maxZ < d.grid.origin[2] ||
        minX > d.grid.origin[0] + float(d.grid.tilesX) * d.grid.tileWorldSize ||
        minZ > d.grid.origin[2] + float(d.grid.tilesZ) * d.grid.tileWorldSize)
        return {}; // outside the mesh's region
    return d.buildRange(geometry, tileOf(minX, d.grid.origin[0], d.grid.tilesX),
                        tileOf(minZ, d.grid.origin[2], d.grid.tilesZ),
                        tileOf(maxX, d.grid.origin[0], d.grid.tilesX),
                        tileOf(maxZ, d.grid.origin[2], d.grid.tilesZ));
}

bool NavMesh::isBuilt() const {
    return impl_->mesh != nullptr;
}
const NavMeshSettings& NavMesh::settings() const {
    return impl_->settings;
}
const Eigen::AlignedBox3d& NavMesh::region() const {
    return impl_->region;
}
int NavMesh::tileCount() const {
    return impl_->tiles;
}
int NavMesh::polygonCount() const {
    return int(impl_->polys.size());
}
double NavMesh::area() const {
    return impl_->cumulative.empty() ? 0.0 : impl_->cumulative.back();
}

Eigen::Vector3d NavMesh::defaultQueryExtent() const {
    const double side = std::max(2.0 * impl_->settings.agentRadius, 0.5);
    return {side, side, impl_->settings.agentHeight};
}

std::optional<std::pair<dtPolyRef, Eigen::Vector3f>>
NavMesh::Impl::nearest(const Eigen::Vector3d& point, const Eigen::Vector3d& extent) const {
    if (!mesh || polys.empty() || !point.allFinite() || !extent.allFinite())
        return std::nullopt;
    // Detour visits every tile slot the extent covers: it is cut to the region (nothing lies beyond), and
    // a point farther from the region than the extent reaches finds nothing.
    const Eigen::Vector3d reach = extent.cwiseAbs().cwiseMin(region.sizes() + Eigen::Vector3d::Ones());
    const Eigen::Vector3d inside = point.cwiseMax(region.min()).cwiseMin(region.max());
    if (((point - inside).cwiseAbs().array() > reach.array()).any())
        return std::nullopt;
    const Eigen::Vector3f center = detail::toRecast(point);
    const std::array<float, 3> half = extentToRecast(reach);
    dtPolyRef ref = 0;
    Eigen::Vector3f nearestPoint;
    query->findNearestPoly(center.data(), half.data(), &filter, &ref, nearestPoint.data());
    if (!ref)
        return std::nullopt;
    return std::pair{ref, nearestPoint};
}

std::optional<Eigen::Vector3d> NavMesh::project(const Eigen::Vector3d& point,
                                                const Eigen::Vector3d& extent) const {
    const auto found = impl_->nearest(point, extent);
    if (!found)
        return std::nullopt;
    return detail::fromRecast(found->second.data());
}

bool NavMesh::isNavigable(const Eigen::Vector3d& point, double maxVerticalDistance) const {
    const auto found = impl_->nearest(point, {0.01, 0.01, maxVerticalDistance});
    if (!found)
        return false;
    const Eigen::Vector3d onMesh = detail::fromRecast(found->second.data());
    return (onMesh - point).head<2>().norm() <= 0.01 &&
           std::abs(onMesh.z() - point.z()) <= maxVerticalDistance;
}

Path NavMesh::findPath(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                       const Eigen::Vector3d& extent) const {
    Path path;
    const Impl& d = *impl_;
    if (!d.mesh || d.polys.empty())
        return path;
    const auto from = d.nearest(start, extent);
    if (!from) {
        path.status = Path::Status::StartOff;
        return path;
    }
    const auto to = d.nearest(end, extent);
    if (!to) {
        path.status = Path::Status::EndOff;
        return path;
    }
    std::vector<dtPolyRef> corridor(kMaxPathPolygons);
    int corridorSize = 0;
    d.query->findPath(from->first, to->first, from->second.data(), to->second.data(), &d.filter,
                      corridor.data(), &corridorSize, kMaxPathPolygons);
    if (corridorSize == 0) {
        path.status = Path::Status::StartOff;
        return path;
    }
    Eigen::Vector3f goal = to->second;
    path.status = Path::Status::Success;
    if (corridor[size_t(corridorSize - 1)] != to->first) {
        // Unreachable: head for the point of the last polygon reached that is closest to the end.
        path.status = Path::Status::Partial;
        d.query->closestPointOnPoly(corridor[size_t(corridorSize - 1)], to->second.data(), goal.data(),
                                    nullptr);
    }
    std::vector<float> corners(size_t(kMaxPathPolygons) * 3);
    int cornerCount = 0;
    d.query->findStraightPath(from->second.data(), goal.data(), corridor.data(), corridorSize, corners.data(),
                              nullptr, nullptr, &cornerCount, kMaxPathPolygons, 0);
    for (int i = 0; i < cornerCount; ++i) {
        path.points.push_back(detail::fromRecast(&corners[size_t(i) * 3]));
        if (i > 0)
            path.length += (path.points[size_t(i)] - path.points[size_t(i) - 1]).norm();
    }
    return path;
}

Eigen::Vector3d NavMesh::Impl::pointInPolygon(const PolyEntry& entry, std::mt19937_64& rng) const {
    const dtMeshTile* tile = nullptr;
    const dtPoly* poly = nullptr;
    mesh->getTileAndPolyByRefUnsafe(entry.ref, &tile, &poly);
    auto vertex = [&](int k) { return &tile->verts[poly->verts[k] * 3]; };
    // A fan from the first vertex; a triangle by its area, then a uniform point in it.
    double fan[DT_VERTS_PER_POLYGON] = {};
    double total = 0.0;
    for (int k = 1; k + 1 < poly->vertCount; ++k) {
        const float *a = vertex(0), *b = vertex(k), *c = vertex(k + 1);
        total += std::abs((double(b[0]) - a[0]) * (double(c[2]) - a[2]) -
                          (double(c[0]) - a[0]) * (double(b[2]) - a[2])) /
                 2.0;
        fan[k] = total;
    }
    const double pick = uniform(rng) * total;
    int k = 1;
    while (k + 2 < poly->vertCount && fan[k] < pick)
        ++k;
    double s = uniform(rng), t = uniform(rng);
    if (s + t > 1.0) {
        s = 1.0 - s;
        t = 1.0 - t;
    }
    const float *a = vertex(0), *b = vertex(k), *c = vertex(k + 1);
    float p[3];
    for (int i = 0; i < 3; ++i)
        p[i] = float(a[i] + s * (double(b[i]) - a[i]) + t * (double(c[i]) - a[i]));
    float height = 0.0f;
    if (dtStatusSucceed(query->getPolyHeight(entry.ref, p, &height)))
        p[1] = height; // the detail mesh's height, closer to the ground than the polygon's plane
    return detail::fromRecast(p);
}

std::optional<Eigen::Vector3d> NavMesh::Impl::pointOnPolygon(const PolyEntry& entry, float x, float z) const {
    if (x < entry.minX || x > entry.maxX || z < entry.minZ || z > entry.maxZ)
        return std::nullopt;
    const dtMeshTile* tile = nullptr;
    const dtPoly* poly = nullptr;
    mesh->getTileAndPolyByRefUnsafe(entry.ref, &tile, &poly);
    // Convex: on it when on the same side of every edge.
    bool positive = false, negative = false;
    for (int k = 0; k < poly->vertCount; ++k) {
        const float* a = &tile->verts[poly->verts[k] * 3];
        const float* b = &tile->verts[poly->verts[(k + 1) % poly->vertCount] * 3];
        const double side =
            (double(b[0]) - a[0]) * (double(z) - a[2]) - (double(b[2]) - a[2]) * (double(x) - a[0]);
        positive = positive || side > 0.0;
        negative = negative || side < 0.0;
    }
    if (positive && negative)
        return std::nullopt;
    float p[3] = {x, tile->verts[poly->verts[0] * 3 + 1], z};
    float height = 0.0f;
    if (dtStatusSucceed(query->getPolyHeight(entry.ref, p, &height)))
        p[1] = height;
    return detail::fromRecast(p);
}

std::optional<Eigen::Vector3d> NavMesh::randomPoint(std::mt19937_64& rng) const {
    const Impl& d = *impl_;
    if (d.polys.empty())
        return std::nullopt;
    return d.pointInPolygon(d.polys[drawByWeight(d.cumulative, rng)], rng);
}

std::optional<Eigen::Vector3d> NavMesh::randomPointInRadius(const Eigen::Vector3d& origin, double radius,
                                                            bool reachableOnly, const Eigen::Vector3d& extent,
                                                            std::mt19937_64& rng) const {
    const Impl& d = *impl_;
    SP_CHECK(std::isfinite(radius) && radius >= 0.0, InvalidArgument,
             "NavMesh::randomPointInRadius(): radius ", radius, " must be a finite number >= 0");
    int component = -1;
    Eigen::Vector3f centre = detail::toRecast(origin);
    if (reachableOnly) {
        const auto found = d.nearest(origin, extent);
        if (!found)
            return std::nullopt;
        component = d.polys[size_t(d.indexOf.at(found->first))].component;
    }
    // The polygons that meet the disc (by their bounds), drawn by area; points outside it are redrawn.
    std::vector<size_t> candidates;
    std::vector<double> running;
    double sum = 0.0;
    const float r = float(radius);
    for (size_t i = 0; i < d.polys.size(); ++i) {
        const PolyEntry& e = d.polys[i];
        if ((component >= 0 && e.component != component) || e.minX > centre.x() + r ||
            e.maxX < centre.x() - r || e.minZ > centre.z() + r || e.maxZ < centre.z() - r)
            continue;
        sum += e.area;
        candidates.push_back(i);
        running.push_back(sum);
    }
    if (candidates.empty() || sum <= 0.0)
        return std::nullopt;
    const Eigen::Vector2d centre2(centre.x(), -centre.z());
    // Two exact ways to a uniform point of (mesh within the disc): when the disc is smaller than the
    // polygons it meets, draw in the disc and keep a point that lies on one of them; otherwise draw on the
    // polygons and keep a point that lies in the disc. Either way a try succeeds with a good chance.
    const double discArea = M_PI * radius * radius;
    if (discArea < sum) {
        for (int attempt = 0; attempt < kRadiusTries; ++attempt) {
            const double angle = 2.0 * M_PI * uniform(rng), distance = radius * std::sqrt(uniform(rng));
            const float x = centre.x() + float(distance * std::cos(angle));
            const float z = centre.z() + float(distance * std::sin(angle));
            for (size_t candidate : candidates)
                if (auto p = d.pointOnPolygon(d.polys[candidate], x, z))
                    return p;
        }
        return std::nullopt;
    }
    for (int attempt = 0; attempt < kRadiusTries; ++attempt) {
        const Eigen::Vector3d p = d.pointInPolygon(d.polys[candidates[drawByWeight(running, rng)]], rng);
        if ((p.head<2>() - centre2).norm() <= radius)
            return p;
    }
    return std::nullopt;
}

std::vector<std::array<Eigen::Vector3d, 3>> NavMesh::triangles() const {
    std::vector<std::array<Eigen::Vector3d, 3>> result;
    const Impl& d = *impl_;
    for (const PolyEntry& entry : d.polys) {
        const dtMeshTile* tile = nullptr;
        const dtPoly* poly = nullptr;
        d.mesh->getTileAndPolyByRefUnsafe(entry.ref, &tile, &poly);
        const dtPolyDetail& pd = tile->detailMeshes[poly - tile->polys];
        for (int j = 0; j < pd.triCount; ++j) {
            const unsigned char* t = &tile->detailTris[(pd.triBase + unsigned(j)) * 4];
            std::array<Eigen::Vector3d, 3> triangle;
            for (int k = 0; k < 3; ++k) {
                const float* v = t[k] < poly->vertCount
                                     ? &tile->verts[poly->verts[t[k]] * 3]
                                     : &tile->detailVerts[(pd.vertBase + t[k] - poly->vertCount) * 3];
                triangle[size_t(k)] = detail::fromRecast(v);
            }
            result.push_back(triangle);
        }
    }
    return result;
}

} // namespace sp::navigation
