// Body lifetime, ids, validation messages and the immediate effects of calls (no settling needed).
#include "core/physics/physics_world.h"

#include <gtest/gtest.h>

#include "core/base/error.h"
#include "physics_test_util.h"

namespace sp::physics {
namespace {

using test::at;
using test::dynamicBody;
using test::expectThrowMessage;

TEST(PhysicsWorldTest, DefaultSettings) {
    PhysicsWorld world;
    EXPECT_EQ(world.getGravity(), Eigen::Vector3d(0, 0, -9.81));
    EXPECT_EQ(world.settings().fixedTimeStep, 1.0 / 240.0);
    EXPECT_EQ(world.bodyCount(), 0u);
}

TEST(PhysicsWorldTest, RejectsBadSettings) {
    PhysicsWorld::Settings settings;
    settings.fixedTimeStep = 0;
    expectThrowMessage<InvalidArgument>([&] { PhysicsWorld world(settings); },
                                        "PhysicsWorld::PhysicsWorld(): fixedTimeStep 0 must be > 0");
}

TEST(PhysicsWorldTest, StepRunsWholeSubstepsAndCarriesTheRemainder) {
    PhysicsWorld world;
    EXPECT_EQ(world.step(1.0 / 60.0), 4);
    EXPECT_EQ(world.step(1.0 / 480.0), 0);
    EXPECT_EQ(world.step(1.0 / 480.0), 1);
    EXPECT_EQ(world.step(0.0), 0);
    EXPECT_EQ(world.substepCount(), 5u);
    // A thousand 1/60 s frames are exactly 4000 substeps, with no rounding drift.
    for (int i = 0; i < 1000; ++i)
        world.step(1.0 / 60.0);
    EXPECT_EQ(world.substepCount(), 4005u);
    expectThrowMessage<InvalidArgument>([&] { world.step(-1); },
                                        "PhysicsWorld::step(): dt -1 must be finite and >= 0");
}

TEST(PhysicsWorldTest, AddRemoveAndStaleIds) {
    PhysicsWorld world;
    const BodyId a = world.addBody(dynamicBody(Shape::sphere(1), 0, 0, 0));
    const BodyId b = world.addBody(dynamicBody(Shape::sphere(1), 5, 0, 0));
    EXPECT_EQ(a, (BodyId{0, 0}));
    EXPECT_EQ(b, (BodyId{1, 0}));
    EXPECT_EQ(world.bodyCount(), 2u);
    world.removeBody(a);
    EXPECT_FALSE(world.isValid(a));
    EXPECT_TRUE(world.isValid(b));
    EXPECT_EQ(world.bodyCount(), 1u);

    // The freed slot is reused with a new generation; the old id stays stale.
    const BodyId c = world.addBody(dynamicBody(Shape::sphere(1), 0, 5, 0));
    EXPECT_EQ(c, (BodyId{0, 1}));
    EXPECT_FALSE(world.isValid(a));
    EXPECT_EQ(world.bodies(), (std::vector<BodyId>{c, b}));

    expectThrowMessage<StaleObject>([&] { world.setPose(a, at(0, 0, 1)); },
                                    "PhysicsWorld::setPose(): body 0:0 was removed");
    expectThrowMessage<StaleObject>([&] { world.getPose(a); },
                                    "PhysicsWorld::getPose(): body 0:0 was removed");
    expectThrowMessage<StaleObject>([&] { world.removeBody(a); },
                                    "PhysicsWorld::removeBody(): body 0:0 was removed");
    expectThrowMessage<StaleObject>(
        [&] {
            world.applyImpulse(a, {1, 0, 0});
        },
        "PhysicsWorld::applyImpulse(): body 0:0 was removed");
    expectThrowMessage<StaleObject>(
        [&] {
            world.getLinearVelocity(BodyId{7, 0});
        },
        "PhysicsWorld::getLinearVelocity(): body 7:0 does not exist in this world");
    expectThrowMessage<StaleObject>([&] { world.getMass(BodyId::invalid()); },
                                    "PhysicsWorld::getMass(): body invalid does not exist in this world");
}

TEST(PhysicsWorldTest, BodiesKeepTheShapeTheyWereBuiltFrom) {
    PhysicsWorld world;
    BodyDesc sensor = dynamicBody(Shape::box({1, 2, 3}).scaled({2, 2, 2}), 0, 0, 0);
    sensor.overlapOnly = true;
    const BodyId a = world.addBody(sensor);
    const BodyId b = world.addBody(dynamicBody(Shape::sphere(1), 5, 0, 0));
    EXPECT_EQ(world.getShape(a).type(), ShapeType::Box);
    EXPECT_EQ(world.getShape(a).halfExtents(), Eigen::Vector3d(1, 2, 3));
    EXPECT_EQ(world.getShape(a).scale(), Eigen::Vector3d(2, 2, 2));
    EXPECT_TRUE(world.isOverlapOnly(a));
    EXPECT_EQ(world.getShape(b).type(), ShapeType::Sphere);
    EXPECT_FALSE(world.isOverlapOnly(b));
    world.removeBody(a);
    expectThrowMessage<StaleObject>([&] { world.getShape(a); },
                                    "PhysicsWorld::getShape(): body 0:0 was removed");
}

TEST(PhysicsWorldTest, IdsFromAnotherWorldAreUnknownOrStale) {
    PhysicsWorld first;
    PhysicsWorld second;
    const BodyId id = first.addBody(dynamicBody(Shape::sphere(1), 0, 0, 0));
    EXPECT_FALSE(second.isValid(id));
}

TEST(PhysicsWorldTest, AddBodyRejectsBadFieldsNamingTheValue) {
    PhysicsWorld world;
    BodyDesc desc;
    desc.mass = -1;
    expectThrowMessage<InvalidArgument>([&] { world.addBody(desc); },
                                        "PhysicsWorld::addBody(): mass -1 must be >= 0 for a movable body");
    desc.mass = 0;
    expectThrowMessage<InvalidArgument>([&] { world.addBody(desc); },
                                        "PhysicsWorld::addBody(): mass 0 must be > 0 for a simulated body");
    desc.simulatePhysics = false; // a kinematic body needs no mass
    EXPECT_NO_THROW(world.addBody(desc));

    desc = BodyDesc();
    desc.restitution = 1.5;
    expectThrowMessage<InvalidArgument>([&] { world.addBody(desc); },
                                        "PhysicsWorld::addBody(): restitution 1.5 must be in [0, 1]");
    desc = BodyDesc();
    desc.friction = -0.1;
    expectThrowMessage<InvalidArgument>([&] { world.addBody(desc); },
                                        "PhysicsWorld::addBody(): friction -0.1 must be >= 0");
    desc = BodyDesc();
    desc.pose.linear() *= 2.0;
    expectThrowMessage<InvalidArgument>(
        [&] { world.addBody(desc); },
        "PhysicsWorld::addBody(): pose rotation is not a rotation matrix (orthonormal, det +1)");
    desc = BodyDesc();
    desc.shape = Shape::plane();
    expectThrowMessage<InvalidArgument>(
        [&] { world.addBody(desc); }, "PhysicsWorld::addBody(): a Plane shape cannot be simulated; make the "
                                      "body Static, or Movable with simulatePhysics = false");
    desc.shape = Shape::box({1, 1, 1}, {0, 0, -1});
    expectThrowMessage<InvalidArgument>(
        [&] { world.addBody(desc); },
        "PhysicsWorld::addBody(): a Box shape off the body's origin cannot be "
        "simulated; make the body Static, or Movable with simulatePhysics = false");
    EXPECT_EQ(world.bodyCount(), 1u);
}

TEST(PhysicsWorldTest, StaticBodiesCannotBeMovedOrPushed) {
    PhysicsWorld world;
    BodyDesc desc;
    desc.mobility = Mobility::Static;
    const BodyId id = world.addBody(desc);
    expectThrowMessage<InvalidState>([&] { world.setPose(id, at(0, 0, 1)); },
                                     "PhysicsWorld::setPose(): body 0:0 is static; set its mobility to "
                                     "Movable first");
    expectThrowMessage<InvalidState>(
        [&] {
            world.applyForce(id, {0, 0, 1});
        },
        "PhysicsWorld::applyForce(): body 0:0 is static; set its mobility to "
        "Movable first");
    EXPECT_FALSE(world.isAwake(id));

    world.setMobility(id, Mobility::Movable);
    world.setPose(id, at(0, 0, 1));
    EXPECT_EQ(world.getPose(id).translation(), Eigen::Vector3d(0, 0, 1));
}

TEST(PhysicsWorldTest, KinematicBodiesMoveOnlyBySetPose) {
    PhysicsWorld world;
    BodyDesc desc = dynamicBody(Shape::box({1, 1, 1}), 0, 0, 5);
    desc.simulatePhysics = false;
    const BodyId id = world.addBody(desc);
    test::run(world, 0.5);
    EXPECT_EQ(world.getPose(id).translation(), Eigen::Vector3d(0, 0, 5)); // no gravity
    expectThrowMessage<InvalidState>(
        [&] {
            world.applyImpulse(id, {1, 0, 0});
        },
        "PhysicsWorld::applyImpulse(): body 0:0 is not simulated; enable "
        "simulatePhysics first");
    world.setPose(id, at(1, 2, 3));
    EXPECT_EQ(world.getPose(id).translation(), Eigen::Vector3d(1, 2, 3));

    world.setSimulatePhysics(id, true);
    EXPECT_TRUE(world.isSimulatingPhysics(id));
    test::run(world, 0.5);
    EXPECT_LT(world.getPose(id).translation().z(), 2.0); // now it falls
}

TEST(PhysicsWorldTest, PoseRoundTripsExactly) {
    PhysicsWorld world;
    const BodyId id = world.addBody(dynamicBody(Shape::box({1, 1, 1}), 0, 0, 0));
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translate(Eigen::Vector3d(1.25, -2.5, 3.0));
    pose.rotate(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()));
    world.setPose(id, pose);
    EXPECT_TRUE(world.getPose(id).isApprox(pose, 1e-15));
}

TEST(PhysicsWorldTest, ImpulseChangesVelocityByImpulseOverMass) {
    PhysicsWorld::Settings settings;
    settings.gravity.setZero();
    PhysicsWorld world(settings);
    const BodyId id = world.addBody(dynamicBody(Shape::sphere(0.5), 0, 0, 0, 4.0));
    world.applyImpulse(id, {2, 0, -6});
    EXPECT_TRUE(world.getLinearVelocity(id).isApprox(Eigen::Vector3d(0.5, 0, -1.5), 1e-12));
    world.applyImpulse(id, {2, 0, -6});
    EXPECT_TRUE(world.getLinearVelocity(id).isApprox(Eigen::Vector3d(1.0, 0, -3.0), 1e-12));

    // Off-centre: the same linear change plus angular L = r x J, w = I^-1 L with I = 2/5 m r^2.
    const BodyId spun = world.addBody(dynamicBody(Shape::sphere(0.5), 10, 0, 0, 4.0));
    world.applyImpulse(spun, {0, 2, 0}, {10.5, 0, 0});
    EXPECT_TRUE(world.getLinearVelocity(spun).isApprox(Eigen::Vector3d(0, 0.5, 0), 1e-12));
    const double inertia = 0.4 * 4.0 * 0.25;
    EXPECT_TRUE(world.getAngularVelocity(spun).isApprox(Eigen::Vector3d(0, 0, 0.5 * 2 / inertia), 1e-12));
}

TEST(PhysicsWorldTest, ForceActsForOneStepCall) {
    PhysicsWorld::Settings settings;
    settings.gravity.setZero();
    PhysicsWorld world(settings);
    const BodyId id = world.addBody(dynamicBody(Shape::sphere(0.5), 0, 0, 0, 2.0));
    world.applyForce(id, {4, 0, 0});
    world.step(1.0 / 60.0); // a = F/m = 2 m/s^2 for 1/60 s
    EXPECT_NEAR(world.getLinearVelocity(id).x(), 2.0 / 60.0, 1e-12);
    world.step(1.0 / 60.0); // cleared
    EXPECT_NEAR(world.getLinearVelocity(id).x(), 2.0 / 60.0, 1e-12);

    // A step that runs no substep keeps the force for the next one.
    world.applyTorque(id, {0, 0, 0.2});
    world.step(0.001);
    world.step(1.0 / 60.0 - 0.001);
    const double inertia = 0.4 * 2.0 * 0.25;
    EXPECT_NEAR(world.getAngularVelocity(id).z(), 0.2 / inertia / 60.0, 1e-9);
}

TEST(PhysicsWorldTest, GravityAccelerationMatchesSettings) {
    PhysicsWorld world;
    const BodyId id = world.addBody(dynamicBody(Shape::sphere(0.5), 0, 0, 100, 3.0));
    test::run(world, 1.0);
    EXPECT_NEAR(world.getLinearVelocity(id).z(), -9.81, 1e-9);
    world.setGravity({0, 0, 0});
    EXPECT_EQ(world.getGravity(), Eigen::Vector3d::Zero());
    test::run(world, 1.0);
    EXPECT_NEAR(world.getLinearVelocity(id).z(), -9.81, 1e-9);
}

TEST(PhysicsWorldTest, PropertiesRoundTripAndValidate) {
    PhysicsWorld world;
    const BodyId id = world.addBody(dynamicBody(Shape::box({0.5, 0.5, 0.5}), 0, 0, 0, 2.0));
    world.setMass(id, 3.0);
    world.setFriction(id, 0.8);
    world.setRestitution(id, 0.25);
    world.setLinearDamping(id, 0.1);
    world.setAngularDamping(id, 0.2);
    world.setTag(id, 0xfeedbeefcafeULL);
    EXPECT_EQ(world.getMass(id), 3.0);
    EXPECT_EQ(world.getFriction(id), 0.8);
    EXPECT_EQ(world.getRestitution(id), 0.25);
    EXPECT_EQ(world.getLinearDamping(id), 0.1);
    EXPECT_EQ(world.getAngularDamping(id), 0.2);
    EXPECT_EQ(world.getTag(id), 0xfeedbeefcafeULL);
    expectThrowMessage<InvalidArgument>([&] { world.setMass(id, 0.0); },
                                        "PhysicsWorld::setMass(): mass 0 must be > 0 for simulated body 0:0");
    expectThrowMessage<InvalidArgument>([&] { world.setLinearDamping(id, 2.0); },
                                        "PhysicsWorld::setLinearDamping(): damping 2 must be in [0, 1]");

    // The new mass is used by the next impulse.
    world.applyImpulse(id, {3, 0, 0});
    EXPECT_NEAR(world.getLinearVelocity(id).x(), 1.0, 1e-12);
}

TEST(PhysicsWorldTest, MobilityChangesAreChecked) {
    PhysicsWorld world;
    BodyDesc desc;
    desc.shape = Shape::triangleMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
    desc.mobility = Mobility::Static;
    const BodyId mesh = world.addBody(desc);
    expectThrowMessage<InvalidState>([&] { world.setMobility(mesh, Mobility::Movable); },
                                     "PhysicsWorld::setMobility(): body 0:0 has a shape that cannot be "
                                     "simulated; call setSimulatePhysics(false) first");
    world.setSimulatePhysics(mesh, false);
    world.setMobility(mesh, Mobility::Movable);
    EXPECT_EQ(world.getMobility(mesh), Mobility::Movable);
    EXPECT_FALSE(world.isSimulatingPhysics(mesh));
}

} // namespace
} // namespace sp::physics
