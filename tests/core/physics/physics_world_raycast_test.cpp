#include "core/physics/physics_world.h"

#include <gtest/gtest.h>

#include "physics_test_util.h"

namespace sp::physics {
namespace {

using test::addFloor;
using test::at;

class RaycastTest : public ::testing::Test {
  protected:
    RaycastTest() {
        floor = addFloor(world);
        BodyDesc desc;
        desc.shape = Shape::box({0.5, 0.5, 0.5});
        desc.pose = at(0, 0, 2);
        desc.tag = 42;
        box = world.addBody(desc);
        desc.shape = Shape::sphere(1.0);
        desc.pose = at(5, 0, 1);
        desc.tag = 7;
        sphere = world.addBody(desc);
    }

    PhysicsWorld world;
    BodyId floor;
    BodyId box;
    BodyId sphere;
};

TEST_F(RaycastTest, HitsTheClosestBodyWithPointNormalAndFraction) {
    // Straight down onto the box top at z = 2.5: fraction (10 - 2.5) / 10.
    const std::optional<RayHit> hit = world.raycast({0.1, 0.2, 10}, {0.1, 0.2, 0});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, box);
    EXPECT_EQ(hit->tag, 42u);
    EXPECT_TRUE(hit->point.isApprox(Eigen::Vector3d(0.1, 0.2, 2.5), 1e-9));
    EXPECT_TRUE(hit->normal.isApprox(Eigen::Vector3d(0, 0, 1), 1e-9));
    EXPECT_NEAR(hit->fraction, 0.75, 1e-9);
}

TEST_F(RaycastTest, HitsASphereSideways) {
    const std::optional<RayHit> hit = world.raycast({0, 0, 1}, {10, 0, 1});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, sphere);
    EXPECT_EQ(hit->tag, 7u);
    EXPECT_TRUE(hit->point.isApprox(Eigen::Vector3d(4, 0, 1), 1e-6));
    EXPECT_TRUE(hit->normal.isApprox(Eigen::Vector3d(-1, 0, 0), 1e-6));
    EXPECT_NEAR(hit->fraction, 0.4, 1e-6);
}

TEST_F(RaycastTest, HitsTheFloorBetweenBodies) {
    const std::optional<RayHit> hit = world.raycast({2, 3, 4}, {2, 3, -4});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, floor);
    EXPECT_TRUE(hit->point.isApprox(Eigen::Vector3d(2, 3, 0), 1e-9));
    EXPECT_NEAR(hit->fraction, 0.5, 1e-9);
}

TEST_F(RaycastTest, MissesWhenNothingIsInTheWay) {
    EXPECT_FALSE(world.raycast({0, 0, 10}, {0, 0, 3})); // stops short of the box
    EXPECT_FALSE(world.raycast({-5, -5, 5}, {5, -5, 5}));
    EXPECT_FALSE(world.raycast({1, 1, 1}, {1, 1, 1}));
    world.removeBody(box);
    const std::optional<RayHit> hit = world.raycast({0.1, 0.2, 10}, {0.1, 0.2, -1});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, floor);
}

TEST_F(RaycastTest, SeesABodyRightAfterItMoves) {
    world.setPose(box, at(20, 0, 2));
    EXPECT_EQ(world.raycast({0.1, 0.2, 10}, {0.1, 0.2, -1})->body, floor);
    EXPECT_EQ(world.raycast({20, 0, 10}, {20, 0, -1})->body, box);
}

TEST_F(RaycastTest, AllHitsComeSortedAlongTheRay) {
    BodyDesc desc;
    desc.shape = Shape::box({0.5, 0.5, 0.5});
    desc.pose = at(0, 0, 5);
    const BodyId upper = world.addBody(desc);
    const std::vector<RayHit> hits = world.raycastAll({0, 0, 10}, {0, 0, -1});
    ASSERT_EQ(hits.size(), 3u);
    EXPECT_EQ(hits[0].body, upper);
    EXPECT_EQ(hits[1].body, box);
    EXPECT_EQ(hits[2].body, floor);
    EXPECT_NEAR(hits[0].point.z(), 5.5, 1e-9);
    EXPECT_NEAR(hits[2].fraction, 10.0 / 11.0, 1e-9);
}

TEST_F(RaycastTest, UsesTheBodyRotation) {
    // Turned 90 degrees about X, the box's local y half extent (0.2) lies along world Z.
    BodyDesc desc;
    desc.shape = Shape::box({1.0, 0.2, 0.5});
    desc.pose = at(0, 10, 2);
    desc.pose.rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
    const BodyId turned = world.addBody(desc);
    std::optional<RayHit> hit = world.raycast({0.9, 10, 10}, {0.9, 10, 0});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, turned);
    EXPECT_NEAR(hit->point.z(), 2.2, 1e-9);
    EXPECT_TRUE(hit->normal.isApprox(Eigen::Vector3d::UnitZ(), 1e-9));
    hit = world.raycast({0, -5, 2}, {0, 20, 2}); // the box at y = 0 is in the way
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, box);
    hit = world.raycast({0, 0, 2}, {0, 20, 2}); // starting inside a body, the ray does not hit it
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, turned);
    hit = world.raycast({0, 5, 2}, {0, 20, 2});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, turned);
    EXPECT_NEAR(hit->point.y(), 9.5, 1e-9);
    EXPECT_TRUE(hit->normal.isApprox(-Eigen::Vector3d::UnitY(), 1e-9));
}

TEST(RaycastMeshTest, HitsATriangleMeshFromEitherSide) {
    PhysicsWorld world;
    BodyDesc desc;
    desc.shape = Shape::triangleMesh({{-1, -1, 1}, {1, -1, 1}, {0, 1, 1}}, {0, 1, 2});
    desc.mobility = Mobility::Static;
    const BodyId mesh = world.addBody(desc);
    std::optional<RayHit> hit = world.raycast({0, 0, 3}, {0, 0, 0});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->body, mesh);
    EXPECT_TRUE(hit->point.isApprox(Eigen::Vector3d(0, 0, 1), 1e-9));
    EXPECT_TRUE(hit->normal.isApprox(Eigen::Vector3d(0, 0, 1), 1e-9));
    hit = world.raycast({0, 0, -1}, {0, 0, 3});
    ASSERT_TRUE(hit);
    EXPECT_TRUE(hit->normal.isApprox(Eigen::Vector3d(0, 0, -1), 1e-9));
    EXPECT_NEAR(hit->fraction, 0.5, 1e-9);
    EXPECT_FALSE(world.raycast({2, 2, 3}, {2, 2, 0}));
}

} // namespace
} // namespace sp::physics
