// Simulated behaviour checked against analytic answers: resting heights, bounces, friction, sleep,
// determinism, and collisions of the hull and mesh shapes.
#include "core/physics/physics_world.h"

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "physics_test_util.h"

namespace sp::physics {
namespace {

using test::addFloor;
using test::at;
using test::dynamicBody;
using test::run;

constexpr double kRestTolerance = 1e-3; // metres

TEST(PhysicsDynamicsTest, BoxComesToRestAtItsHalfExtent) {
    PhysicsWorld world;
    addFloor(world);
    const BodyId box = world.addBody(dynamicBody(Shape::box({0.5, 0.3, 0.2}), 0, 0, 1.0));
    run(world, 3.0);
    const Eigen::Isometry3d pose = world.getPose(box);
    EXPECT_NEAR(pose.translation().z(), 0.2, kRestTolerance);
    EXPECT_LT(world.getLinearVelocity(box).norm(), 1e-3);
    // It lands flat (it may turn a little about Z on impact).
    EXPECT_NEAR(pose.linear()(2, 2), 1.0, 1e-6);
}

TEST(PhysicsDynamicsTest, ShapesRestOnABoxOffItsOriginAtItsTopFace) {
    // A floor slab whose top face is the body's origin plane, scaled and placed as a flat mesh's collision
    // is.
    PhysicsWorld world;
    BodyDesc floor;
    floor.shape = Shape::box({0.5, 0.5, 0.25}, {0, 0, -0.25}).scaled({20, 20, 0.02});
    floor.mobility = Mobility::Static;
    floor.pose = at(0, 0, 1.0);
    world.addBody(floor);
    const BodyId box = world.addBody(dynamicBody(Shape::box({0.5, 0.3, 0.2}), 0, 0, 2.0));
    const BodyId sphere = world.addBody(dynamicBody(Shape::sphere(0.25), 3, 0, 2.0));
    run(world, 3.0);
    EXPECT_NEAR(world.getPose(box).translation().z(), 1.2, kRestTolerance);
    EXPECT_NEAR(world.getPose(sphere).translation().z(), 1.25, kRestTolerance);
    // Its bottom face is 0.01 m below: a ray from underneath stops there.
    const auto hit = world.raycast({0, 0, 0}, {0, 0, 5});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->point.z(), 0.99, 1e-9);
}

TEST(PhysicsDynamicsTest, SphereComesToRestAtItsRadius) {
    PhysicsWorld world;
    addFloor(world);
    const BodyId sphere = world.addBody(dynamicBody(Shape::sphere(0.25), 0, 0, 2.0));
    run(world, 3.0);
    EXPECT_NEAR(world.getPose(sphere).translation().z(), 0.25, kRestTolerance);
}

TEST(PhysicsDynamicsTest, AStackOfBoxesStands) {
    PhysicsWorld world;
    addFloor(world);
    std::vector<BodyId> boxes;
    for (int i = 0; i < 4; ++i)
        boxes.push_back(
            world.addBody(dynamicBody(Shape::box({0.5, 0.5, 0.5}), 0, 0, 0.5 + 1.0 * i + 0.01 * i)));
    run(world, 4.0);
    for (int i = 0; i < 4; ++i) {
        const Eigen::Vector3d p = world.getPose(boxes[size_t(i)]).translation();
        EXPECT_NEAR(p.z(), 0.5 + i, 2 * kRestTolerance) << "box " << i;
        EXPECT_LT(p.head<2>().norm(), 1e-2) << "box " << i; // settles with a millimetre or two of drift
    }
}

TEST(PhysicsDynamicsTest, ScaledAndRoundShapesRestAtTheirScaledSize) {
    PhysicsWorld world;
    addFloor(world);
    const BodyId box = world.addBody(dynamicBody(Shape::box({0.5, 0.5, 0.5}).scaled({2, 1, 0.4}), 0, 0, 1));
    const BodyId cylinder = world.addBody(dynamicBody(Shape::cylinder(0.3, 0.4), 3, 0, 1));
    const BodyId capsule = world.addBody(dynamicBody(Shape::capsule(0.2, 0.3).scaled({1, 1, 2}), 6, 0, 2));
    run(world, 3.0);
    EXPECT_NEAR(world.getPose(box).translation().z(), 0.2, kRestTolerance);
    EXPECT_NEAR(world.getPose(cylinder).translation().z(), 0.4, kRestTolerance);
    // A capsule standing on its cap is unstable; whichever way it ends, its lowest point is on the floor.
    const double capsuleZ = world.getPose(capsule).translation().z();
    EXPECT_TRUE(std::abs(capsuleZ - 0.8) < kRestTolerance || std::abs(capsuleZ - 0.2) < kRestTolerance)
        << capsuleZ;
}

TEST(PhysicsDynamicsTest, ConvexHullRestsOnItsLowestFace) {
    PhysicsWorld world;
    addFloor(world);
    // A square pyramid, base 1 m x 1 m at local z = -0.25, apex at z = 0.75.
    const Shape pyramid = Shape::convexHull(
        {{-0.5, -0.5, -0.25}, {0.5, -0.5, -0.25}, {0.5, 0.5, -0.25}, {-0.5, 0.5, -0.25}, {0, 0, 0.75}});
    const BodyId body = world.addBody(dynamicBody(pyramid, 0, 0, 1.0));
    run(world, 3.0);
    EXPECT_NEAR(world.getPose(body).translation().z(), 0.25, kRestTolerance);
}

TEST(PhysicsDynamicsTest, BodiesLandOnAStaticTriangleMesh) {
    PhysicsWorld world;
    // A 4 m x 4 m square of two triangles at z = 0.5, above nothing.
    BodyDesc ground;
    ground.shape =
        Shape::triangleMesh({{-2, -2, 0.5}, {2, -2, 0.5}, {2, 2, 0.5}, {-2, 2, 0.5}}, {0, 1, 2, 0, 2, 3});
    ground.mobility = Mobility::Static;
    world.addBody(ground);
    const BodyId sphere = world.addBody(dynamicBody(Shape::sphere(0.3), 0.5, 0.5, 2.0));
    const BodyId hull = world.addBody(dynamicBody(Shape::convexHull({{-0.2, -0.2, -0.2},
                                                                     {0.2, -0.2, -0.2},
                                                                     {0.2, 0.2, -0.2},
                                                                     {-0.2, 0.2, -0.2},
                                                                     {-0.2, -0.2, 0.2},
                                                                     {0.2, -0.2, 0.2},
                                                                     {0.2, 0.2, 0.2},
                                                                     {-0.2, 0.2, 0.2}}),
                                                  -1, -1, 1.5));
    run(world, 3.0);
    EXPECT_NEAR(world.getPose(sphere).translation().z(), 0.8, kRestTolerance);
    EXPECT_NEAR(world.getPose(hull).translation().z(), 0.7, kRestTolerance);
}

TEST(PhysicsDynamicsTest, ScaleIsBakedIntoHullsAndPlanes) {
    PhysicsWorld world;
    // The plane z = 0.5, scaled by 2 along Z, is the plane z = 1.
    BodyDesc floor;
    floor.shape = Shape::plane({0, 0, 1}, 0.5).scaled({3, 3, 2});
    floor.mobility = Mobility::Static;
    world.addBody(floor);
    const Shape cube = Shape::convexHull(
        {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}});
    const BodyId flat = world.addBody(dynamicBody(cube.scaled({0.5, 0.5, 0.1}), 0, 0, 2));
    const BodyId ball = world.addBody(dynamicBody(Shape::sphere(0.1).scaled({2, 2, 2}), 3, 0, 2));
    run(world, 3.0);
    EXPECT_NEAR(world.getPose(flat).translation().z(), 1.1, kRestTolerance);
    EXPECT_NEAR(world.getPose(ball).translation().z(), 1.2, kRestTolerance);
}

// Highest point of the sphere's centre after its first bounce.
double reboundHeight(double restitution) {
    PhysicsWorld world;
    addFloor(world, 1.0);
    BodyDesc ball = dynamicBody(Shape::sphere(0.1), 0, 0, 1.1);
    ball.restitution = restitution;
    const BodyId id = world.addBody(ball);
    bool bounced = false;
    double highest = 0.0;
    for (int frame = 0; frame < 240; ++frame) {
        world.step(1.0 / 120.0);
        const double vz = world.getLinearVelocity(id).z();
        bounced = bounced || vz > 0.0;
        if (bounced)
            highest = std::max(highest, world.getPose(id).translation().z() - 0.1);
    }
    return highest;
}

TEST(PhysicsDynamicsTest, RestitutionControlsTheBounce) {
    // Dropped from 1 m, a ball with restitution e rises to e^2 m.
    EXPECT_LT(reboundHeight(0.0), 0.01);
    const double high = reboundHeight(0.9);
    EXPECT_NEAR(high, 0.81, 0.08);
}

// Distance a box slides on the floor after being launched at 3 m/s.
double slideDistance(double friction) {
    PhysicsWorld world;
    addFloor(world, 0.0, 1.0);
    BodyDesc desc = dynamicBody(Shape::box({0.25, 0.25, 0.25}), 0, 0, 0.25);
    desc.friction = friction;
    const BodyId id = world.addBody(desc);
    run(world, 0.2);
    world.setLinearVelocity(id, {3, 0, 0});
    run(world, 3.0);
    return world.getPose(id).translation().x();
}

TEST(PhysicsDynamicsTest, FrictionStopsASlidingBoxAtTheCoulombDistance) {
    // Coulomb: d = v^2 / (2 mu g).
    EXPECT_NEAR(slideDistance(0.5), 9.0 / (2 * 0.5 * 9.81), 0.05);
    EXPECT_NEAR(slideDistance(0.2), 9.0 / (2 * 0.2 * 9.81), 0.1);
}

TEST(PhysicsDynamicsTest, SleepingBodiesWakeWhenTouchedByTheApi) {
    PhysicsWorld world;
    addFloor(world);
    const BodyId box = world.addBody(dynamicBody(Shape::box({0.5, 0.5, 0.5}), 0, 0, 0.5));
    run(world, 4.0);
    ASSERT_FALSE(world.isAwake(box));
    world.applyImpulse(box, {0, 0, 5});
    EXPECT_TRUE(world.isAwake(box));
    run(world, 0.1);
    EXPECT_GT(world.getPose(box).translation().z(), 0.6);

    run(world, 5.0);
    ASSERT_FALSE(world.isAwake(box));
    world.applyForce(box, {0, 0, 30});
    EXPECT_TRUE(world.isAwake(box));

    run(world, 5.0);
    ASSERT_FALSE(world.isAwake(box));
    world.setPose(box, at(0, 0, 2));
    EXPECT_TRUE(world.isAwake(box));
    run(world, 1.0);
    EXPECT_NEAR(world.getPose(box).translation().z(), 0.5, 0.01);
}

TEST(PhysicsDynamicsTest, RemovingASupportWakesWhatRestsOnIt) {
    PhysicsWorld world;
    addFloor(world);
    const BodyId bottom = world.addBody(dynamicBody(Shape::box({0.5, 0.5, 0.5}), 0, 0, 0.5));
    const BodyId top = world.addBody(dynamicBody(Shape::box({0.5, 0.5, 0.5}), 0, 0, 1.5));
    run(world, 4.0);
    ASSERT_FALSE(world.isAwake(top));
    world.removeBody(bottom);
    EXPECT_TRUE(world.isAwake(top));
    run(world, 2.0);
    EXPECT_NEAR(world.getPose(top).translation().z(), 0.5, kRestTolerance);
}

// Poses of a small pile of mixed bodies after 2 s, flattened to doubles.
std::vector<double> simulatePile() {
    PhysicsWorld world;
    addFloor(world);
    std::vector<BodyId> ids;
    for (int i = 0; i < 12; ++i) {
        const Shape shape = i % 3 == 0   ? Shape::box({0.2, 0.3, 0.1})
                            : i % 3 == 1 ? Shape::sphere(0.2)
                                         : Shape::capsule(0.1, 0.2);
        Eigen::Isometry3d pose = at(0.07 * (i % 4), 0.05 * (i % 3), 0.5 + 0.45 * i);
        pose.rotate(Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d(1, 2, 3).normalized()));
        BodyDesc desc = dynamicBody(shape, 0, 0, 0, 1.0 + 0.1 * i);
        desc.pose = pose;
        ids.push_back(world.addBody(desc));
    }
    for (int frame = 0; frame < 120; ++frame) {
        if (frame == 30)
            world.applyImpulse(ids[5], {1, 0, 0.5},
                               world.getPose(ids[5]).translation() + Eigen::Vector3d(0, 0.1, 0));
        world.step(1.0 / 60.0);
    }
    std::vector<double> values;
    for (BodyId id : ids) {
        const Eigen::Isometry3d pose = world.getPose(id);
        values.insert(values.end(), pose.data(), pose.data() + 16);
    }
    return values;
}

TEST(PhysicsDynamicsTest, SameCallsGiveBitIdenticalPoses) {
    const std::vector<double> first = simulatePile();
    const std::vector<double> second = simulatePile();
    ASSERT_EQ(first.size(), second.size());
    EXPECT_EQ(std::memcmp(first.data(), second.data(), first.size() * sizeof(double)), 0);
}

TEST(PhysicsDynamicsTest, TwoWorldsSteppedInterleavedStayIdentical) {
    PhysicsWorld a;
    PhysicsWorld b;
    for (PhysicsWorld* world : {&a, &b}) {
        addFloor(*world);
        for (int i = 0; i < 8; ++i)
            world->addBody(dynamicBody(Shape::box({0.2, 0.2, 0.2}), 0.05 * i, 0, 0.5 + 0.5 * i));
    }
    for (int frame = 0; frame < 120; ++frame) {
        a.step(1.0 / 60.0);
        b.step(1.0 / 60.0);
    }
    for (BodyId id : a.bodies()) {
        const Eigen::Matrix4d pa = a.getPose(id).matrix();
        const Eigen::Matrix4d pb = b.getPose(id).matrix();
        EXPECT_EQ(std::memcmp(pa.data(), pb.data(), sizeof(double) * 16), 0) << "body " << id.index;
    }
}

TEST(PhysicsDynamicsTest, KinematicBodyPushesSimulatedOnes) {
    PhysicsWorld::Settings settings;
    settings.gravity.setZero();
    PhysicsWorld world(settings);
    BodyDesc pusher = dynamicBody(Shape::box({0.5, 0.5, 0.5}), -2, 0, 0);
    pusher.simulatePhysics = false;
    const BodyId kinematic = world.addBody(pusher);
    const BodyId ball = world.addBody(dynamicBody(Shape::sphere(0.5), 0, 0, 0));
    for (int frame = 0; frame < 60; ++frame) {
        world.setPose(kinematic, at(-2 + 2.0 * frame / 60.0, 0, 0));
        world.step(1.0 / 60.0);
    }
    EXPECT_GT(world.getPose(ball).translation().x(), 0.5);
}

} // namespace
} // namespace sp::physics
