#include "core/physics/triangles.h"

#include <cmath>
#include <map>
#include <utility>

#include <gtest/gtest.h>

#include "physics_test_util.h"

namespace sp::physics {
namespace {

using test::at;

constexpr double kPi = 3.14159265358979323846;

// The volume enclosed by the soup: positive when every triangle winds outwards.
double signedVolume(const TriangleSoup& soup) {
    double volume = 0.0;
    for (size_t t = 0; t < soup.triangleCount(); ++t) {
        const Eigen::Vector3d& a = soup.vertices[soup.indices[3 * t]];
        const Eigen::Vector3d& b = soup.vertices[soup.indices[3 * t + 1]];
        const Eigen::Vector3d& c = soup.vertices[soup.indices[3 * t + 2]];
        volume += a.dot(b.cross(c)) / 6.0;
    }
    return volume;
}

// A closed, consistently wound surface uses every directed edge once and its reverse once.
bool isClosedAndConsistent(const TriangleSoup& soup) {
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (size_t t = 0; t < soup.triangleCount(); ++t)
        for (int k = 0; k < 3; ++k)
            ++edges[{soup.indices[3 * t + k], soup.indices[3 * t + (k + 1) % 3]}];
    for (const auto& [edge, count] : edges)
        if (count != 1 || edges.count({edge.second, edge.first}) != 1)
            return false;
    return true;
}

TriangleSoup trianglesOf(const Shape& shape, const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity()) {
    TriangleSoup soup;
    appendTriangles(shape, pose, Eigen::AlignedBox3d(), soup);
    return soup;
}

TEST(TrianglesTest, BoxIsClosedOutwardAndExact) {
    const TriangleSoup soup = trianglesOf(Shape::box({1, 2, 3}).scaled({2, 1, 1}));
    EXPECT_EQ(soup.triangleCount(), 12u);
    EXPECT_NEAR(signedVolume(soup), 8.0 * 2 * 2 * 3, 1e-9);
    EXPECT_TRUE(
        soup.bounds().isApprox(Eigen::AlignedBox3d(Eigen::Vector3d(-2, -2, -3), Eigen::Vector3d(2, 2, 3))));
}

TEST(TrianglesTest, ABoxOffItsOriginKeepsItsScaledCentre) {
    const TriangleSoup soup =
        trianglesOf(Shape::box({1, 2, 0.5}, {0, 0, -0.5}).scaled({2, 1, 2}), at(1, 0, 0));
    EXPECT_NEAR(signedVolume(soup), 4.0 * 4.0 * 2.0, 1e-9);
    EXPECT_TRUE(
        soup.bounds().isApprox(Eigen::AlignedBox3d(Eigen::Vector3d(-1, -2, -2), Eigen::Vector3d(3, 2, 0))));
}

TEST(TrianglesTest, RoundShapesAreClosedOutwardAndCloseToTheirVolume) {
    struct Case {
        Shape shape;
        double volume;
    };
    const Case cases[] = {
        {Shape::sphere(1.5), 4.0 / 3.0 * kPi * 1.5 * 1.5 * 1.5},
        {Shape::capsule(0.5, 1.0), kPi * 0.25 * 2.0 + 4.0 / 3.0 * kPi * 0.125},
        {Shape::cylinder(0.5, 2.0), kPi * 0.25 * 4.0},
    };
    for (const Case& c : cases) {
        const TriangleSoup soup = trianglesOf(c.shape);
        EXPECT_TRUE(isClosedAndConsistent(soup)) << c.shape.type();
        const double volume = signedVolume(soup);
        EXPECT_GT(volume, 0.9 * c.volume) << c.shape.type(); // inscribed polyhedra lose a few percent
        EXPECT_LE(volume, c.volume) << c.shape.type();
    }
}

TEST(TrianglesTest, PoseMovesAndTurnsTheSurface) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translate(Eigen::Vector3d(10, 0, 0));
    pose.rotate(Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitX()));
    const TriangleSoup soup = trianglesOf(Shape::box({1, 2, 3}), pose);
    EXPECT_TRUE(
        soup.bounds().isApprox(Eigen::AlignedBox3d(Eigen::Vector3d(9, -3, -2), Eigen::Vector3d(11, 3, 2))));
    EXPECT_NEAR(signedVolume(soup), 48.0, 1e-9); // a rotation keeps the winding outward
}

TEST(TrianglesTest, ConvexHullKeepsTheHullAndWindsOutward) {
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 8; ++i)
        points.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    points.emplace_back(0.2, 0.1, 0.0); // inside: not part of the hull
    const TriangleSoup soup = trianglesOf(Shape::convexHull(points).scaled({1, 1, 0.5}));
    EXPECT_TRUE(isClosedAndConsistent(soup));
    EXPECT_NEAR(signedVolume(soup), 4.0, 1e-9);
}

TEST(TrianglesTest, TriangleMeshKeepsItsTriangles) {
    const TriangleSoup soup =
        trianglesOf(Shape::triangleMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}).scaled({2, 3, 1}));
    ASSERT_EQ(soup.triangleCount(), 1u);
    EXPECT_EQ(soup.vertices[2], Eigen::Vector3d(0, 3, 0));
}

TEST(TrianglesTest, PlaneCoversTheBoundsFacingItsNormal) {
    const Eigen::AlignedBox3d bounds(Eigen::Vector3d(-5, -5, -1), Eigen::Vector3d(15, 5, 3));
    TriangleSoup soup;
    appendTriangles(Shape::plane({0, 0, 1}, 0.5), Eigen::Isometry3d::Identity(), bounds, soup);
    ASSERT_EQ(soup.triangleCount(), 2u);
    for (size_t t = 0; t < 2; ++t) {
        const Eigen::Vector3d& a = soup.vertices[soup.indices[3 * t]];
        const Eigen::Vector3d n = (soup.vertices[soup.indices[3 * t + 1]] - a)
                                      .cross(soup.vertices[soup.indices[3 * t + 2]] - a)
                                      .normalized();
        EXPECT_TRUE(n.isApprox(Eigen::Vector3d::UnitZ()));
    }
    const Eigen::AlignedBox3d covered = soup.bounds();
    EXPECT_NEAR(covered.min().z(), 0.5, 1e-12);
    EXPECT_NEAR(covered.max().z(), 0.5, 1e-12);
    EXPECT_LE(covered.min().x(), -5.0);
    EXPECT_GE(covered.max().x(), 15.0);
    EXPECT_LE(covered.min().y(), -5.0);
    EXPECT_GE(covered.max().y(), 5.0);

    TriangleSoup none;
    appendTriangles(Shape::plane(), Eigen::Isometry3d::Identity(), Eigen::AlignedBox3d(), none);
    EXPECT_EQ(none.triangleCount(), 0u);
}

} // namespace
} // namespace sp::physics
