// Navigation benchmark: build time of a walled yard and of a generated city block grid, the cost of
// rebuilding the tiles under one new obstacle, and path and random-point queries per second through
// sp::navigation::NavMesh against Detour called directly on the same tiles (the floor: what is left is
// the wrapper's coordinate conversion and result vectors). Never run by the tests.
//
//     build/core/navigation/spear_navigation_bench [--blocks N] [--queries Q]

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include <DetourNavMesh.h>
#include <DetourNavMeshQuery.h>

#include "core/navigation/nav_mesh.h"
#include "core/navigation/tile_builder.h"

namespace {

using sp::navigation::NavMesh;
using sp::navigation::NavMeshSettings;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

void addBox(sp::physics::TriangleSoup& soup, const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = (min + max) / 2.0;
    sp::physics::appendTriangles(sp::physics::Shape::box((max - min) / 2.0), pose, Eigen::AlignedBox3d(),
                                 soup);
}

// A 26 x 18 m yard: ground, fence, an inner wall with a door, four crates (examples/navigation.py).
sp::physics::TriangleSoup yard() {
    sp::physics::TriangleSoup soup;
    addBox(soup, {-13, -9, -1}, {13, 9, 0});
    const double walls[][4] = {{0, -8, 24, 0.3},  {0, 8, 24, 0.3}, {-12, 0, 0.3, 16}, {12, 0, 0.3, 16},
                               {0, -4.5, 0.3, 7}, {0, 5, 0.3, 6},  {-6, 3, 1.5, 1.5}, {-5, -3.5, 2.5, 1},
                               {6, -2, 1.2, 4},   {7.5, 5, 2, 2}};
    for (const auto& w : walls)
        addBox(soup, {w[0] - w[2] / 2, w[1] - w[3] / 2, 0}, {w[0] + w[2] / 2, w[1] + w[3] / 2, 2});
    return soup;
}

// blocks x blocks city blocks of 20 m with 8 m streets, each block four buildings of random heights.
sp::physics::TriangleSoup city(int blocks) {
    sp::physics::TriangleSoup soup;
    const double pitch = 28.0, size = blocks * pitch;
    addBox(soup, {-4, -4, -1}, {size, size, 0});
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> height(4.0, 30.0);
    for (int i = 0; i < blocks; ++i)
        for (int j = 0; j < blocks; ++j)
            for (int k = 0; k < 4; ++k) {
                const double x = i * pitch + (k % 2) * 10.5, y = j * pitch + (k / 2) * 10.5;
                addBox(soup, {x, y, 0}, {x + 9.5, y + 9.5, height(rng)});
            }
    return soup;
}

struct Scene {
    const char* name;
    sp::physics::TriangleSoup soup;
    Eigen::AlignedBox3d region;
};

// Detour on its own: the same tiles in a dtNavMesh of the bench's, queried directly.
struct RawDetour {
    dtNavMesh* mesh = dtAllocNavMesh();
    dtNavMeshQuery* query = dtAllocNavMeshQuery();
    dtQueryFilter filter;

    RawDetour(const Scene& scene, const NavMeshSettings& settings) {
        const auto geometry = sp::navigation::detail::toRecastGeometry(scene.soup);
        const auto grid = sp::navigation::detail::makeTileGrid(scene.region, settings);
        dtNavMeshParams params{};
        std::copy(grid.origin, grid.origin + 3, params.orig);
        params.tileWidth = params.tileHeight = grid.tileWorldSize;
        params.maxTiles = 1024;
        params.maxPolys = 1 << 12;
        mesh->init(&params);
        for (int z = 0; z < grid.tilesZ; ++z)
            for (int x = 0; x < grid.tilesX; ++x) {
                auto tile = sp::navigation::detail::buildTile(geometry, settings, grid, x, z);
                if (tile.data &&
                    dtStatusSucceed(mesh->addTile(tile.data.get(), tile.size, DT_TILE_FREE_DATA, 0, nullptr)))
                    tile.data.release();
            }
        query->init(mesh, 8192);
    }
    ~RawDetour() {
        dtFreeNavMeshQuery(query);
        dtFreeNavMesh(mesh);
    }
    // The same steps as NavMesh::findPath: nearest polygons, corridor, corners.
    double path(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
        const Eigen::Vector3f start = sp::navigation::detail::toRecast(a),
                              end = sp::navigation::detail::toRecast(b);
        const float extent[3] = {0.7f, 1.8f, 0.7f};
        dtPolyRef startRef = 0, endRef = 0;
        float startPoint[3], endPoint[3];
        query->findNearestPoly(start.data(), extent, &filter, &startRef, startPoint);
        query->findNearestPoly(end.data(), extent, &filter, &endRef, endPoint);
        static dtPolyRef corridor[4096];
        static float corners[4096 * 3];
        int count = 0, cornerCount = 0;
        query->findPath(startRef, endRef, startPoint, endPoint, &filter, corridor, &count, 4096);
        query->findStraightPath(startPoint, endPoint, corridor, count, corners, nullptr, nullptr,
                                &cornerCount, 4096);
        return cornerCount;
    }
};

std::mt19937* gRandom = nullptr;
float frand() {
    return std::uniform_real_distribution<float>(0.0f, 1.0f)(*gRandom);
}

void run(const Scene& scene, int queries) {
    NavMeshSettings settings;
    NavMesh mesh;
    const auto build = mesh.build(scene.soup, scene.region, settings);
    std::printf("%-14s %7zu triangles  %4d tiles  %6d polygons  %8.1f m^2  build %8.1f ms\n", scene.name,
                scene.soup.triangleCount(), mesh.tileCount(), mesh.polygonCount(), mesh.area(),
                build.seconds * 1e3);

    // One crate appears: the tiles under it are rebuilt.
    sp::physics::TriangleSoup changed = scene.soup;
    const Eigen::Vector3d centre = scene.region.center();
    const Eigen::AlignedBox3d crate(Eigen::Vector3d(centre.x() - 3.6, centre.y() - 0.5, 0),
                                    Eigen::Vector3d(centre.x() - 2.6, centre.y() + 0.5, 1));
    addBox(changed, crate.min(), crate.max());
    const auto rebuild = mesh.rebuildTiles(changed, crate);
    std::printf("%-14s rebuild under one crate: %d of %d tiles, %.1f ms\n", "", rebuild.tilesBuilt,
                mesh.tileCount(), rebuild.seconds * 1e3);

    // Paths between random navigable points: through the wrapper, then Detour directly.
    std::mt19937_64 rng(5);
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 2 * queries; ++i)
        points.push_back(*mesh.randomPoint(rng));
    auto start = Clock::now();
    double total = 0.0;
    for (int i = 0; i < queries; ++i)
        total +=
            mesh.findPath(points[size_t(2 * i)], points[size_t(2 * i + 1)], mesh.defaultQueryExtent()).length;
    const double ours = secondsSince(start) / queries;
    RawDetour raw(Scene{scene.name, changed, scene.region}, settings);
    start = Clock::now();
    double corners = 0.0;
    for (int i = 0; i < queries; ++i)
        corners += raw.path(points[size_t(2 * i)], points[size_t(2 * i + 1)]);
    const double floor = secondsSince(start) / queries;
    std::printf("%-14s path (mean %.1f m, %.1f corners): %7.1f us, Detour directly %7.1f us, ratio %.2f\n",
                "", total / queries, corners / queries, ours * 1e6, floor * 1e6, ours / floor);

    start = Clock::now();
    for (int i = 0; i < queries; ++i)
        mesh.randomPoint(rng);
    const double random = secondsSince(start) / queries;
    std::mt19937 detourRandom(5);
    gRandom = &detourRandom;
    start = Clock::now();
    dtPolyRef ref = 0;
    float point[3];
    for (int i = 0; i < queries; ++i)
        raw.query->findRandomPoint(&raw.filter, frand, &ref, point);
    const double detour = secondsSince(start) / queries;
    std::printf(
        "%-14s random point (area-uniform): %7.2f us, Detour's findRandomPoint (tile-uniform) %7.2f us, "
        "ratio %.2f\n",
        "", random * 1e6, detour * 1e6, random / detour);
}

} // namespace

int main(int argc, char** argv) {
    int blocks = 8, queries = 2000;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--blocks") && i + 1 < argc)
            blocks = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--queries") && i + 1 < argc)
            queries = std::atoi(argv[++i]);
        else {
            std::fprintf(stderr, "usage: %s [--blocks N] [--queries Q]\n", argv[0]);
            return 2;
        }
    }
    run({"yard", yard(),
         Eigen::AlignedBox3d(Eigen::Vector3d(-12.5, -8.5, -0.5), Eigen::Vector3d(12.5, 8.5, 2.5))},
        queries);
    const double size = blocks * 28.0;
    char name[32];
    std::snprintf(name, sizeof name, "city %dx%d", blocks, blocks);
    run({name, city(blocks),
         Eigen::AlignedBox3d(Eigen::Vector3d(-4, -4, -0.5), Eigen::Vector3d(size, size, 31))},
        queries);
    return 0;
}
