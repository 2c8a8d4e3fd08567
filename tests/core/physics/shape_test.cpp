#include "core/physics/shape.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/base/error.h"
#include "physics_test_util.h"

namespace sp::physics {
namespace {

using test::expectThrowMessage;

TEST(ShapeTest, FactoriesKeepTheirParameters) {
    const Shape box = Shape::box({1, 2, 3});
    EXPECT_EQ(box.type(), ShapeType::Box);
    EXPECT_EQ(box.halfExtents(), Eigen::Vector3d(1, 2, 3));
    EXPECT_EQ(box.scale(), Eigen::Vector3d::Ones());

    const Shape capsule = Shape::capsule(0.5, 1.0);
    EXPECT_EQ(capsule.type(), ShapeType::Capsule);
    EXPECT_EQ(capsule.radius(), 0.5);
    EXPECT_EQ(capsule.halfHeight(), 1.0);
}

TEST(ShapeTest, PlaneIsNormalisedWithoutMovingIt) {
    const Shape plane = Shape::plane({0, 0, 2}, 4.0);
    EXPECT_EQ(plane.normal(), Eigen::Vector3d::UnitZ());
    EXPECT_EQ(plane.offset(), 2.0);
}

TEST(ShapeTest, RejectsBadDimensionsWithTheValue) {
    expectThrowMessage<InvalidArgument>(
        [] {
            Shape::box({1, 0, 1});
        },
        "Shape::box(): half extents (1, 0, 1) must all be > 0");
    expectThrowMessage<InvalidArgument>(
        [] {
            Shape::box({1, 1, 1}, {0, std::nan(""), 0});
        },
        "Shape::box(): centre (0, nan, 0) is not finite");
    expectThrowMessage<InvalidArgument>([] { Shape::sphere(-2); }, "Shape::sphere(): radius -2 must be > 0");
    expectThrowMessage<InvalidArgument>([] { Shape::capsule(1, -1); },
                                        "Shape::capsule(): halfLength -1 must be >= 0");
    expectThrowMessage<InvalidArgument>([] { Shape::cylinder(1, 0); },
                                        "Shape::cylinder(): halfHeight 0 must be > 0");
    expectThrowMessage<InvalidArgument>(
        [] {
            Shape::plane({0, 0, 0});
        },
        "Shape::plane(): normal (0, 0, 0) must be finite and nonzero");
}

TEST(ShapeTest, ConvexHullNeedsVolume) {
    expectThrowMessage<InvalidArgument>(
        [] {
            Shape::convexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
        },
        "Shape::convexHull(): 3 points given; a hull needs at least 4");
    expectThrowMessage<InvalidArgument>(
        [] {
            Shape::convexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
        },
        "Shape::convexHull(): the 4 points lie in one plane; a hull needs volume");
    EXPECT_EQ(Shape::convexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}).points().size(), 4u);
}

TEST(ShapeTest, TriangleMeshChecksIndices) {
    const std::vector<Eigen::Vector3d> vertices{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    expectThrowMessage<InvalidArgument>(
        [&] {
            Shape::triangleMesh(vertices, {0, 1});
        },
        "Shape::triangleMesh(): 2 indices given; need a nonzero multiple of 3");
    expectThrowMessage<InvalidArgument>(
        [&] {
            Shape::triangleMesh(vertices, {0, 1, 3});
        },
        "Shape::triangleMesh(): index 2 is 3 but there are only 3 vertices");
    const Shape mesh = Shape::triangleMesh(vertices, {0, 1, 2});
    EXPECT_EQ(mesh.indices().size(), 3u);
}

TEST(ShapeTest, ScaleComposesAndRespectsBulletLimits) {
    const Shape box = Shape::box({1, 1, 1}).scaled({2, 1, 1}).scaled({1, 3, 1});
    EXPECT_EQ(box.scale(), Eigen::Vector3d(2, 3, 1));
    EXPECT_EQ(Shape::sphere(1).scaled({2, 2, 2}).scale(), Eigen::Vector3d(2, 2, 2));
    expectThrowMessage<InvalidArgument>(
        [] {
            Shape::sphere(1).scaled({1, 2, 1});
        },
        "Shape::scaled(): scale (1, 2, 1) is not uniform; a sphere takes a uniform scale only");
    expectThrowMessage<InvalidArgument>(
        [] {
            Shape::cylinder(1, 1).scaled({1, 2, 3});
        },
        "Shape::scaled(): scale (1, 2, 3) has x != y; a Cylinder along Z needs the same scale on x and y");
    EXPECT_EQ(Shape::capsule(1, 1).scaled({2, 2, 5}).scale(), Eigen::Vector3d(2, 2, 5));
    // A scale read back from a rotated transform is uniform but for its last bits: taken as uniform, made so.
    EXPECT_EQ(Shape::sphere(1).scaled({1, 1 + 1e-12, 1 - 1e-12}).scale(), Eigen::Vector3d(1, 1, 1));
    EXPECT_EQ(Shape::capsule(1, 1).scaled({2, 2 * (1 + 1e-12), 5}).scale(), Eigen::Vector3d(2, 2, 5));
    EXPECT_THROW(Shape::sphere(1).scaled({1, 1.0001, 1}), InvalidArgument);
    expectThrowMessage<InvalidArgument>(
        [] {
            Shape::box({1, 1, 1}).scaled({1, -1, 1});
        },
        "Shape::scaled(): scale (1, -1, 1) must be > 0 on every axis");
}

} // namespace
} // namespace sp::physics
