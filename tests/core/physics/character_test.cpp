// Characters: a character stands on the floor at its half height, walks at its walk velocity, climbs a step
// no higher than its step height and not a higher one, stops at a wall, falls, and jumps to v^2 / 2g.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "core/base/error.h"
#include "core/physics/physics_world.h"
#include "physics_test_util.h"

namespace sp::physics {
namespace {

using test::addFloor;
using test::at;
using test::expectThrowMessage;
using test::run;

constexpr double kGravity = 9.81;

BodyId addStaticBox(PhysicsWorld& world, const Eigen::Vector3d& halfExtents, const Eigen::Vector3d& centre) {
    BodyDesc desc;
    desc.shape = Shape::box(halfExtents);
    desc.mobility = Mobility::Static;
    desc.pose = at(centre.x(), centre.y(), centre.z());
    return world.addBody(desc);
}

BodyId addCharacter(PhysicsWorld& world, double x, double z) {
    CharacterDesc desc;
    desc.position = Eigen::Vector3d(x, 0.0, z);
    return world.addCharacter(desc);
}

TEST(CharacterTest, StandsAtItsHalfHeightAndWalks) {
    PhysicsWorld world;
    addFloor(world);
    const BodyId character = addCharacter(world, 0.0, 2.0);
    run(world, 0.05);
    EXPECT_FALSE(world.isCharacterOnGround(character)); // falling
    run(world, 1.5);
    EXPECT_TRUE(world.isCharacterOnGround(character));
    EXPECT_NEAR(world.getCharacterPosition(character).z(), 0.9, 0.02);
    world.setCharacterWalkVelocity(character, {2.0, 0.0, 5.0}); // the vertical part is ignored
    const Eigen::Vector3d start = world.getCharacterPosition(character);
    run(world, 1.0);
    const Eigen::Vector3d moved = world.getCharacterPosition(character) - start;
    EXPECT_NEAR(moved.x(), 2.0, 1e-6);
    EXPECT_NEAR(moved.y(), 0.0, 1e-9);
    EXPECT_NEAR(moved.z(), 0.0, 1e-3);
    EXPECT_NEAR(world.getCharacterVelocity(character).x(), 2.0, 1e-6);
}

TEST(CharacterTest, ClimbsAStepUpToItsStepHeightAndStopsAtAWall) {
    PhysicsWorld world;
    addFloor(world);
    addStaticBox(world, {2.0, 3.0, 0.15}, {4.0, 0.0, 0.15}); // a 0.3 m step from x = 2 to 6
    addStaticBox(world, {0.2, 3.0, 1.5}, {8.0, 0.0, 1.5});   // a wall with its face at x = 7.8
    const BodyId character = addCharacter(world, 0.0, 0.95);
    run(world, 0.5);
    world.setCharacterWalkVelocity(character, {2.0, 0.0, 0.0});
    run(world, 2.0); // at x = 4: on the step
    EXPECT_NEAR(world.getCharacterPosition(character).z(), 0.3 + 0.9, 0.03);
    run(world, 3.0); // would be at x = 10: the wall stops it
    const Eigen::Vector3d stopped = world.getCharacterPosition(character);
    EXPECT_NEAR(stopped.z(), 0.9, 0.02) << "pressed against the wall, it stays on the floor";
    EXPECT_LE(stopped.x() + 0.35, 7.8 + 0.01);
    EXPECT_GT(stopped.x() + 0.35, 7.8 - 0.1);
    EXPECT_NEAR(world.getCharacterVelocity(character).x(), 0.0, 0.05);
}

TEST(CharacterTest, AStepHigherThanItsStepHeightStopsIt) {
    PhysicsWorld world;
    addFloor(world);
    addStaticBox(world, {2.0, 3.0, 0.3}, {4.0, 0.0, 0.3}); // 0.6 m: above the 0.45 m step height
    const BodyId character = addCharacter(world, 0.0, 0.95);
    run(world, 0.5);
    world.setCharacterWalkVelocity(character, {2.0, 0.0, 0.0});
    run(world, 3.0);
    EXPECT_NEAR(world.getCharacterPosition(character).z(), 0.9, 0.02);
    EXPECT_LE(world.getCharacterPosition(character).x() + 0.35, 2.0 + 0.01);
}

TEST(CharacterTest, JumpsToTheHeightItsJumpSpeedGives) {
    PhysicsWorld world;
    addFloor(world);
    const BodyId character = addCharacter(world, 0.0, 0.95);
    run(world, 1.0);
    const double ground = world.getCharacterPosition(character).z();
    ASSERT_TRUE(world.jumpCharacter(character));
    double apex = ground;
    for (int i = 0; i < 120; ++i) {
        world.step(1.0 / 240.0);
        apex = std::max(apex, world.getCharacterPosition(character).z());
        if (i == 10) {
            EXPECT_FALSE(world.jumpCharacter(character)); // no jumping in the air
        }
    }
    EXPECT_NEAR(apex - ground, 4.2 * 4.2 / (2 * kGravity), 0.03);
    run(world, 1.0);
    EXPECT_TRUE(world.isCharacterOnGround(character));
    EXPECT_NEAR(world.getCharacterPosition(character).z(), ground, 0.01);
}

TEST(CharacterTest, SensorsDoNotPushIt) {
    // A character's capsule is also a sensor body (for triggers), which follows it a step late: the
    // character must pass through it, and through any other sensor.
    PhysicsWorld world;
    addFloor(world);
    const BodyId character = addCharacter(world, 0.0, 0.95);
    BodyDesc desc;
    desc.shape = Shape::capsule(0.35, 0.55);
    desc.simulatePhysics = false;
    desc.overlapOnly = true;
    desc.pose = at(0.0, 0.0, 0.9);
    const BodyId sensor = world.addBody(desc);
    desc.shape = Shape::box({1.0, 1.0, 0.2});
    desc.pose = at(2.0, 0.0, 0.3);
    world.addBody(desc); // a low trigger volume in its way
    world.setCharacterWalkVelocity(character, {1.5, 0.0, 0.0});
    for (int frame = 0; frame < 180; ++frame) {
        const Eigen::Vector3d before = world.getCharacterPosition(character);
        world.step(1.0 / 60.0);
        world.setPose(sensor, at(before.x(), before.y(), before.z()));
        ASSERT_NEAR(world.getCharacterPosition(character).z(), 0.9, 0.02) << "frame " << frame;
    }
    EXPECT_NEAR(world.getCharacterPosition(character).x(), 4.5, 1e-6);
}

TEST(CharacterTest, ASensorFollowingItToAWallDoesNotLiftIt) {
    PhysicsWorld world;
    addStaticBox(world, {3.0, 2.5, 0.05}, {0.0, 0.0, -0.05}); // a floor box with its top at z = 0
    addStaticBox(world, {3.0, 0.05, 1.4}, {0.0, -2.55, 1.4}); // a wall with its face at y = -2.5
    const BodyId character = addCharacter(world, 0.0, 0.95);
    BodyDesc desc;
    desc.shape = Shape::capsule(0.35, 0.55);
    desc.simulatePhysics = false;
    desc.overlapOnly = true;
    desc.pose = at(0.0, 0.0, 0.95);
    const BodyId sensor = world.addBody(desc);
    run(world, 0.5);
    world.setCharacterWalkVelocity(character, {0.0, -1.5, 0.0});
    for (int frame = 0; frame < 150; ++frame) {
        const Eigen::Vector3d now = world.getCharacterPosition(character);
        world.setPose(sensor, at(now.x(), now.y(), now.z()));
        world.step(1.0 / 60.0);
        ASSERT_NEAR(world.getCharacterPosition(character).z(), 0.9, 0.02)
            << "frame " << frame << " at y = " << world.getCharacterPosition(character).y();
    }
    EXPECT_NEAR(world.getCharacterPosition(character).y(), -2.15, 0.02);
}

TEST(CharacterTest, TeleportsAndIsRemovedCleanly) {
    PhysicsWorld world;
    addFloor(world);
    const BodyId character = addCharacter(world, 0.0, 0.95);
    world.setCharacterWalkVelocity(character, {0.0, 1.0, 0.0});
    world.setCharacterPosition(character, {5.0, 1.0, 3.0});
    EXPECT_EQ(world.getCharacterPosition(character), Eigen::Vector3d(5.0, 1.0, 3.0));
    run(world, 1.5);
    EXPECT_NEAR(world.getCharacterPosition(character).z(), 0.9, 0.02);
    EXPECT_NEAR(world.getCharacterPosition(character).y(), 2.5, 1e-6); // it kept walking after the teleport
    world.setCharacterWalkVelocity(character, Eigen::Vector3d::Zero());
    // Rays and overlaps see bodies only.
    EXPECT_FALSE(world.raycast({5.0, 2.5, 5.0}, {5.0, 2.5, 1.5}).has_value());
    world.removeCharacter(character);
    EXPECT_FALSE(world.isValidCharacter(character));
    expectThrowMessage<StaleObject>(
        [&] { world.getCharacterPosition(character); },
        "PhysicsWorld::getCharacterPosition(): character 0:0 does not exist (removed, "
        "or never made)");
    CharacterDesc bad;
    bad.halfHeight = 0.2;
    expectThrowMessage<InvalidArgument>([&] { world.addCharacter(bad); },
                                        "PhysicsWorld::addCharacter(): halfHeight 0.2 must be >= radius");
    run(world, 0.1);
}

} // namespace
} // namespace sp::physics
