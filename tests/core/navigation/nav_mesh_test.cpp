#include "core/navigation/nav_mesh.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/base/error.h"

namespace sp::navigation {
namespace {

constexpr double kPi = 3.14159265358979323846;

void addBox(physics::TriangleSoup& soup, const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = (min + max) / 2.0;
    physics::appendTriangles(physics::Shape::box((max - min) / 2.0), pose, Eigen::AlignedBox3d(), soup);
}

// A 20 x 10 m floor (top at z = 0) split at x = 0 by a 0.2 m thick, 2 m high wall, with a gap for
// y in [2, 3] when `gap`.
physics::TriangleSoup wallLayout(bool gap) {
    physics::TriangleSoup soup;
    addBox(soup, {-10, -5, -0.2}, {10, 5, 0});
    if (gap) {
        addBox(soup, {-0.1, -5, 0}, {0.1, 2, 2});
        addBox(soup, {-0.1, 3, 0}, {0.1, 5, 2});
    } else {
        addBox(soup, {-0.1, -5, 0}, {0.1, 5, 2});
    }
    return soup;
}

const Eigen::AlignedBox3d kRegion(Eigen::Vector3d(-10, -5, -1), Eigen::Vector3d(10, 5, 3));

NavMeshSettings agent(double radius = 0.3) {
    NavMeshSettings settings;
    settings.agentRadius = radius;
    settings.tileSize = 6.4; // several tiles, so paths and samples cross tile borders
    return settings;
}

bool insideWall(const Eigen::Vector3d& p) {
    return std::abs(p.x()) < 0.1 && (p.y() < 2.0 || p.y() > 3.0);
}

TEST(NavMeshTest, PathThroughAGapHasTheLengthOfTheTautString) {
    NavMesh mesh;
    const BuildStats stats = mesh.build(wallLayout(true), kRegion, agent());
    EXPECT_GT(stats.tilesWithMesh, 1);
    EXPECT_EQ(stats.tilesBuilt, 4 * 2);
    const Path path = mesh.findPath({-4, 0, 0}, {4, 0, 0}, mesh.defaultQueryExtent());
    ASSERT_EQ(path.status, Path::Status::Success);
    ASSERT_GE(path.points.size(), 3u);
    EXPECT_NEAR(path.points.front().x(), -4.0, 1e-3);
    EXPECT_NEAR(path.points.back().x(), 4.0, 1e-3);

    // The shortest way keeps the agent radius r from the wall's ends: straight to the circle of radius
    // r around the corner (-0.1, 2), along it, across the wall's 0.2 m end, and the mirror image.
    const double r = 0.3;
    const Eigen::Vector2d corner(-0.1, 2.0), start(-4.0, 0.0);
    const double d = (start - corner).norm();
    const double towardsStart = std::atan2(start.y() - corner.y(), start.x() - corner.x()) + 2 * kPi;
    const double tangentAngle = towardsStart - std::acos(r / d);
    const double expected = 2.0 * (std::sqrt(d * d - r * r) + r * (tangentAngle - kPi / 2)) + 0.2;
    EXPECT_NEAR(path.length, expected, 0.25) << "expected " << expected;

    // Never through the wall: every centimetre of every segment is outside it, and the path uses the gap.
    bool throughGap = false;
    for (size_t i = 0; i + 1 < path.points.size(); ++i) {
        const Eigen::Vector3d a = path.points[i], b = path.points[i + 1];
        const int steps = int((b - a).norm() / 0.01) + 1;
        for (int k = 0; k <= steps; ++k) {
            const Eigen::Vector3d p = a + (b - a) * (double(k) / steps);
            EXPECT_FALSE(insideWall(p)) << p.transpose();
            throughGap = throughGap || (std::abs(p.x()) < 0.1 && p.y() > 2.0 && p.y() < 3.0);
        }
    }
    EXPECT_TRUE(throughGap);
}

TEST(NavMeshTest, UnreachableAndOffMeshGoalsSayWhy) {
    NavMesh mesh;
    mesh.build(wallLayout(false), kRegion, agent());
    const Path blocked = mesh.findPath({-4, 0, 0}, {4, 0, 0}, mesh.defaultQueryExtent());
    EXPECT_EQ(blocked.status, Path::Status::Partial);
    ASSERT_FALSE(blocked.points.empty());
    // It gets as close as it can: to the wall, on its own side.
    EXPECT_LT(blocked.points.back().x(), -0.1);
    EXPECT_GT(blocked.points.back().x(), -0.6);

    EXPECT_EQ(mesh.findPath({-4, 0, 0}, {40, 0, 0}, mesh.defaultQueryExtent()).status, Path::Status::EndOff);
    EXPECT_EQ(mesh.findPath({-4, 0, 10}, {4, 0, 0}, mesh.defaultQueryExtent()).status,
              Path::Status::StartOff);
    NavMesh empty;
    EXPECT_EQ(empty.findPath({0, 0, 0}, {1, 0, 0}, {1, 1, 1}).status, Path::Status::NoMesh);
    EXPECT_STREQ(statusName(Path::Status::Partial), "Partial");
}

TEST(NavMeshTest, ProjectionAndNavigability) {
    NavMesh mesh;
    mesh.build(wallLayout(true), kRegion, agent());
    const auto above = mesh.project({-3, 1, 0.5}, mesh.defaultQueryExtent());
    ASSERT_TRUE(above.has_value());
    EXPECT_NEAR(above->x(), -3.0, 1e-3);
    EXPECT_NEAR(above->y(), 1.0, 1e-3);
    EXPECT_NEAR(above->z(), 0.0, 0.06); // within a cell height of the floor
    EXPECT_FALSE(mesh.project({-3, 1, 8.0}, mesh.defaultQueryExtent()).has_value());
    // On the wall's top (2 m up, 0.2 m wide): no mesh, the agent does not fit.
    EXPECT_FALSE(mesh.isNavigable({0, 0, 2.0}, 0.1));
    EXPECT_TRUE(mesh.isNavigable({-3, 1, 0.02}, 0.1));
    EXPECT_FALSE(mesh.isNavigable({-3, 1, 1.0}, 0.1));
    EXPECT_FALSE(mesh.isNavigable({-9.9, 1, 0.0}, 0.1)); // within the agent radius of the floor's edge
}

TEST(NavMeshTest, RandomPointsAreUniformOverTheArea) {
    physics::TriangleSoup floor;
    addBox(floor, {-5, -5, -0.2}, {5, 5, 0});
    NavMesh mesh;
    NavMeshSettings settings = agent(0.5);
    settings.tileSize = 3.2; // tiles of unequal walkable area: the edge tiles lose the agent radius
    mesh.build(floor, Eigen::AlignedBox3d(Eigen::Vector3d(-5, -5, -1), Eigen::Vector3d(5, 5, 3)), settings);
    EXPECT_GT(mesh.tileCount(), 4);
    // The walkable square loses the agent radius from each edge, plus up to a cell to voxelisation.
    const double half = std::sqrt(mesh.area()) / 2.0;
    EXPECT_LE(half, 5.0 - 0.5 + 1e-6);
    EXPECT_GE(half, 5.0 - 0.5 - 0.1);

    // Counts in a 5 x 5 grid over the walkable square, against equal expectations.
    std::mt19937_64 rng(7);
    constexpr int kSamples = 20000, kCells = 5;
    std::vector<int> counts(kCells * kCells, 0);
    for (int i = 0; i < kSamples; ++i) {
        const auto p = mesh.randomPoint(rng);
        ASSERT_TRUE(p.has_value());
        ASSERT_TRUE(mesh.isNavigable(*p, 0.1)) << p->transpose();
        const int cx = std::clamp(int((p->x() + half) / (2 * half) * kCells), 0, kCells - 1);
        const int cy = std::clamp(int((p->y() + half) / (2 * half) * kCells), 0, kCells - 1);
        ++counts[size_t(cy * kCells + cx)];
    }
    const double expected = double(kSamples) / (kCells * kCells);
    double chiSquare = 0.0;
    for (int c : counts)
        chiSquare += (c - expected) * (c - expected) / expected;
    EXPECT_LT(chiSquare, 51.2); // the 0.1 % tail of chi-square with 24 degrees of freedom

    // The same seed gives the same points.
    std::mt19937_64 a(3), b(3);
    EXPECT_EQ(*mesh.randomPoint(a), *mesh.randomPoint(b));
}

TEST(NavMeshTest, RandomPointsInRadiusStayInTheDiscAndOnTheReachablePart) {
    NavMesh mesh;
    mesh.build(wallLayout(false), kRegion, agent());
    std::mt19937_64 rng(11);
    for (int i = 0; i < 500; ++i) {
        const auto p = mesh.randomPointInRadius({-0.5, 0, 0}, 2.0, true, mesh.defaultQueryExtent(), rng);
        ASSERT_TRUE(p.has_value());
        EXPECT_LE((p->head<2>() - Eigen::Vector2d(-0.5, 0)).norm(), 2.0 + 1e-9);
        EXPECT_LT(p->x(), 0.0); // the other side of the wall is not reachable
    }
    int otherSide = 0;
    for (int i = 0; i < 500; ++i)
        otherSide +=
            mesh.randomPointInRadius({-0.5, 0, 0}, 2.0, false, mesh.defaultQueryExtent(), rng)->x() > 0;
    EXPECT_GT(otherSide, 50); // without reachability both sides count
    EXPECT_FALSE(mesh.randomPointInRadius({0, 0, 9}, 2.0, true, mesh.defaultQueryExtent(), rng).has_value());
    // A disc far smaller than the polygons it meets is still found every time (drawn in the disc).
    for (int i = 0; i < 200; ++i) {
        const auto p = mesh.randomPointInRadius({-4, 1, 0}, 0.05, true, mesh.defaultQueryExtent(), rng);
        ASSERT_TRUE(p.has_value());
        EXPECT_LE((p->head<2>() - Eigen::Vector2d(-4, 1)).norm(), 0.05 + 1e-6);
    }
    const auto exact = mesh.randomPointInRadius({-4, 1, 0}, 0.0, false, mesh.defaultQueryExtent(), rng);
    ASSERT_TRUE(exact.has_value());
    EXPECT_NEAR(exact->x(), -4.0, 1e-5);
    EXPECT_NEAR(exact->y(), 1.0, 1e-5);
}

TEST(NavMeshTest, RebuildingTilesMatchesAFullBuild) {
    NavMesh mesh;
    const BuildStats first = mesh.build(wallLayout(true), kRegion, agent());
    physics::TriangleSoup changed = wallLayout(true);
    addBox(changed, {-6, -1, 0}, {-5, 1, 1}); // a crate appears west of the wall
    const BuildStats partial = mesh.rebuildTiles(
        changed, Eigen::AlignedBox3d(Eigen::Vector3d(-6, -1, 0), Eigen::Vector3d(-5, 1, 1)));
    EXPECT_LT(partial.tilesBuilt, first.tilesBuilt);
    EXPECT_GT(partial.tilesBuilt, 0);
    NavMesh fresh;
    fresh.build(changed, kRegion, agent());
    EXPECT_EQ(mesh.polygonCount(), fresh.polygonCount());
    EXPECT_NEAR(mesh.area(), fresh.area(), 1e-9);
    EXPECT_FALSE(mesh.isNavigable({-5.5, 0, 0.0}, 0.1));
    // Equal meshes draw equal points from equal seeds, however their tiles were built.
    std::mt19937_64 a(9), b(9);
    for (int i = 0; i < 20; ++i)
        EXPECT_EQ(*mesh.randomPoint(a), *fresh.randomPoint(b));
    // Nothing to do for a change outside the region.
    EXPECT_EQ(mesh.rebuildTiles(changed,
                                Eigen::AlignedBox3d(Eigen::Vector3d(50, 50, 0), Eigen::Vector3d(51, 51, 1)))
                  .tilesBuilt,
              0);
}

TEST(NavMeshTest, TrianglesCoverTheArea) {
    NavMesh mesh;
    mesh.build(wallLayout(true), kRegion, agent());
    double area = 0.0;
    for (const auto& t : mesh.triangles())
        area += std::abs((t[1] - t[0]).head<2>().x() * (t[2] - t[0]).head<2>().y() -
                         (t[2] - t[0]).head<2>().x() * (t[1] - t[0]).head<2>().y()) /
                2.0;
    EXPECT_NEAR(area, mesh.area(), 1e-3 * mesh.area());
}

TEST(NavMeshTest, BadSettingsAndRegionsAreRefusedByName) {
    NavMesh mesh;
    NavMeshSettings settings;
    settings.maxSlopeDegrees = 95;
    try {
        mesh.build(wallLayout(true), kRegion, settings);
        FAIL() << "no error";
    } catch (const InvalidArgument& error) {
        EXPECT_STREQ(error.what(), "NavMesh::build(): AgentMaxSlope = 95 must be in (0, 90) degrees");
    }
    EXPECT_THROW(mesh.build(wallLayout(true), Eigen::AlignedBox3d(), NavMeshSettings()), InvalidArgument);
    EXPECT_THROW(mesh.rebuildTiles(wallLayout(true), kRegion), InvalidState);
    EXPECT_FALSE(mesh.isBuilt());
    // Counts that would overflow are refused before anything is allocated.
    try {
        mesh.build(wallLayout(true),
                   Eigen::AlignedBox3d(Eigen::Vector3d(-5e4, -5e4, -1), Eigen::Vector3d(5e4, 5e4, 3)),
                   NavMeshSettings());
        FAIL() << "no error";
    } catch (const InvalidArgument& error) {
        EXPECT_NE(
            std::string(error.what()).find("tiles of TileSize 12.8 m cover the region; at most 16384 fit"),
            std::string::npos)
            << error.what();
    }
    EXPECT_THROW(mesh.build(wallLayout(true),
                            Eigen::AlignedBox3d(Eigen::Vector3d(-1e30, -1, -1), Eigen::Vector3d(1, 1, 1)),
                            NavMeshSettings()),
                 InvalidArgument);
    settings = NavMeshSettings();
    settings.agentRadius = 1e10;
    EXPECT_THROW(mesh.build(wallLayout(true), kRegion, settings), InvalidArgument);
    // A huge query extent or a far point costs no more than the region.
    mesh.build(wallLayout(true), kRegion, agent());
    EXPECT_TRUE(mesh.project({-3, 1, 0}, {1e9, 1e9, 1e9}).has_value());
    EXPECT_FALSE(mesh.project({1e30, 0, 0}, {1, 1, 1}).has_value());
}

} // namespace
} // namespace sp::navigation
