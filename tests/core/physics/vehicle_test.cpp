// Raycast vehicles: a car rests on its springs at the analytic height, drives along its X axis, turns
// left for positive steering, brakes, is stopped by a wall, and is deterministic.
#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/base/error.h"
#include "core/physics/physics_world.h"
#include "physics_test_util.h"

namespace sp::physics {
namespace {

using test::addFloor;
using test::at;
using test::dynamicBody;
using test::expectThrowMessage;
using test::run;

constexpr double kMass = 1500.0;
constexpr double kGravity = 9.81;

// A 4 x 1.8 x 0.7 m box on four wheels of radius 0.35 m hung from 0.3 m below its centre.
VehicleDesc carDesc() {
    VehicleDesc desc;
    for (double x : {1.3, -1.3})
        for (double y : {0.8, -0.8})
            desc.wheels.push_back({Eigen::Vector3d(x, y, -0.3), 0.35, x > 0});
    return desc;
}

BodyId addCar(PhysicsWorld& world, double x = 0.0) {
    const BodyId chassis = world.addBody(dynamicBody(Shape::box({2.0, 0.9, 0.35}), x, 0, 1.0, kMass));
    world.setVehicle(chassis, carDesc());
    return chassis;
}

void drive(PhysicsWorld& world, BodyId car, double engineForce, double steering = 0.0, double brake = 0.0) {
    for (int wheel = 0; wheel < 4; ++wheel) {
        WheelControls controls;
        controls.engineForce = wheel >= 2 ? engineForce : 0.0; // rear-wheel drive
        controls.steering = steering;
        controls.brakeForce = brake;
        world.setWheelControls(car, wheel, controls);
    }
}

std::string toString(BodyId id) {
    std::ostringstream out;
    out << id;
    return out.str();
}

double yawOf(const Eigen::Isometry3d& pose) {
    const Eigen::Vector3d forward = pose.linear() * Eigen::Vector3d::UnitX();
    return std::atan2(forward.y(), forward.x());
}

TEST(VehicleTest, RestsOnItsSpringsAtTheAnalyticHeight) {
    PhysicsWorld world;
    addFloor(world);
    const BodyId car = addCar(world);
    run(world, 4.0);
    // Each spring carries a quarter of the weight: stiffness * mass * compression = mass * g / 4.
    const double compression = kGravity / (4.0 * carDesc().suspensionStiffness);
    const double suspension = carDesc().suspensionRestLength - compression;
    EXPECT_NEAR(world.getPose(car).translation().z(), 0.3 + suspension + 0.35, 1e-3);
    // At rest: it stays put. Bullet runs vehicles after it integrates the bodies, so the velocity read
    // between steps holds the springs' last impulse, which the next substep's gravity cancels: g * h up.
    const Eigen::Vector3d rested = world.getPose(car).translation();
    run(world, 1.0);
    EXPECT_LT((world.getPose(car).translation() - rested).norm(), 1e-6);
    EXPECT_NEAR(world.getLinearVelocity(car).z(), kGravity * world.settings().fixedTimeStep, 1e-6);
    ASSERT_EQ(world.getWheelCount(car), 4);
    for (int wheel = 0; wheel < 4; ++wheel) {
        const WheelState state = world.getWheelState(car, wheel);
        EXPECT_TRUE(state.inContact);
        EXPECT_NEAR(state.suspensionLength, suspension, 1e-3);
        EXPECT_NEAR(state.pose.translation().z(), 0.35, 1e-3); // the hub is a radius above the ground
        EXPECT_NEAR(state.contactPoint.z(), 0.0, 1e-9);
    }
}

TEST(VehicleTest, EngineForceDrivesItForwardAndTheWheelsRoll) {
    PhysicsWorld world;
    addFloor(world, 0.0, 0.8);
    const BodyId car = addCar(world);
    run(world, 1.0);
    drive(world, car, 2000.0);
    run(world, 2.0);
    const Eigen::Vector3d velocity = world.getLinearVelocity(car);
    // 4000 N on 1500 kg for 2 s: 5.3 m/s, less what the tyres lose.
    EXPECT_GT(velocity.x(), 4.5);
    EXPECT_LT(velocity.x(), 5.4);
    EXPECT_NEAR(velocity.y(), 0.0, 1e-6);
    const Eigen::Vector3d travelled = world.getPose(car).translation();
    // A wheel rolls distance / radius radians (it rolled a little while the car settled, too).
    EXPECT_NEAR(world.getWheelState(car, 0).rotation, travelled.x() / 0.35, 0.05 * travelled.x() / 0.35);
    drive(world, car, -2000.0); // reverse
    run(world, 4.0);
    EXPECT_LT(world.getLinearVelocity(car).x(), -1.0);
}

TEST(VehicleTest, PositiveSteeringTurnsLeftAndBrakesStopIt) {
    PhysicsWorld world;
    addFloor(world, 0.0, 0.8);
    const BodyId car = addCar(world);
    run(world, 1.0);
    drive(world, car, 1500.0, 0.3);
    run(world, 3.0);
    EXPECT_GT(yawOf(world.getPose(car)), 0.3);
    EXPECT_GT(world.getPose(car).translation().y(), 1.0);
    EXPECT_NEAR(world.getWheelState(car, 0).steering, 0.3, 1e-12);
    EXPECT_EQ(world.getWheelState(car, 2).steering, 0.0); // rear wheels do not steer
    drive(world, car, 0.0, 0.0, 6000.0);
    run(world, 3.0);
    EXPECT_LT(world.getLinearVelocity(car).norm(), 0.05);
}

TEST(VehicleTest, AWallStopsIt) {
    PhysicsWorld world;
    addFloor(world, 0.0, 0.8);
    BodyDesc wall;
    wall.shape = Shape::box({0.2, 5.0, 1.5});
    wall.mobility = Mobility::Static;
    wall.pose = at(10.0, 0.0, 1.5);
    world.addBody(wall);
    const BodyId car = addCar(world);
    drive(world, car, 3000.0);
    run(world, 6.0);
    // The chassis' front (x + 2) never passes the wall's face (x = 9.8) by more than the contact slop.
    EXPECT_LT(world.getPose(car).translation().x() + 2.0, 9.8 + 0.05);
    EXPECT_GT(world.getPose(car).translation().x(), 6.0);
}

TEST(VehicleTest, ItsWheelsRollThroughASensorPad) {
    // A trigger volume on the road, its top between the chassis and the road: the wheels' rays go
    // through it to the road, as the world's raycasts do.
    PhysicsWorld world;
    addFloor(world);
    BodyDesc pad;
    pad.shape = Shape::box({5.0, 5.0, 0.2});
    pad.pose = at(0.0, 0.0, 0.2);
    pad.mobility = Mobility::Static;
    pad.overlapOnly = true;
    world.addBody(pad);
    const BodyId car = addCar(world);
    run(world, 4.0);
    EXPECT_NEAR(
        world.getPose(car).translation().z(),
        0.3 + carDesc().suspensionRestLength - kGravity / (4.0 * carDesc().suspensionStiffness) + 0.35, 1e-3);
    for (int wheel = 0; wheel < 4; ++wheel)
        EXPECT_NEAR(world.getWheelState(car, wheel).contactPoint.z(), 0.0, 1e-9);
}

TEST(VehicleTest, RunsAreBitIdentical) {
    auto trajectory = [] {
        PhysicsWorld world;
        addFloor(world, 0.0, 0.8);
        const BodyId car = addCar(world);
        std::vector<double> samples;
        for (int frame = 0; frame < 240; ++frame) {
            drive(world, car, 2500.0 * std::sin(frame * 0.02), 0.4 * std::cos(frame * 0.03));
            world.step(1.0 / 60.0);
            const Eigen::Isometry3d pose = world.getPose(car);
            samples.insert(samples.end(), pose.data(), pose.data() + 16);
        }
        return samples;
    };
    const std::vector<double> first = trajectory(), second = trajectory();
    ASSERT_EQ(first.size(), second.size());
    EXPECT_EQ(std::memcmp(first.data(), second.data(), first.size() * sizeof(double)), 0);
}

TEST(VehicleTest, GoesWithItsBodyAndActsOnlyWhileSimulated) {
    PhysicsWorld world;
    addFloor(world);
    const BodyId car = addCar(world);
    world.setSimulatePhysics(car, false); // kinematic: the vehicle stays but does not act
    EXPECT_TRUE(world.hasVehicle(car));
    run(world, 0.5);
    EXPECT_EQ(world.getPose(car).translation().z(), 1.0);
    world.setSimulatePhysics(car, true);
    run(world, 3.0);
    EXPECT_NEAR(world.getPose(car).translation().z(), 0.3 + 0.25 - kGravity / 160.0 + 0.35, 1e-3);
    world.removeVehicle(car);
    EXPECT_FALSE(world.hasVehicle(car));
    run(world, 2.0); // no springs: the box rests on the floor
    EXPECT_NEAR(world.getPose(car).translation().z(), 0.35, 1e-3);
    const BodyId second = addCar(world, 5.0);
    world.removeBody(second);
    run(world, 0.1);
    expectThrowMessage<StaleObject>([&] { world.hasVehicle(second); },
                                    "PhysicsWorld::hasVehicle(): body " + toString(second) + " was removed");
}

TEST(VehicleTest, BadInputIsRefusedWithTheFieldNamed) {
    PhysicsWorld world;
    BodyDesc ground;
    ground.mobility = Mobility::Static;
    const BodyId fixed = world.addBody(ground);
    expectThrowMessage<InvalidState>([&] { world.setVehicle(fixed, carDesc()); },
                                     "PhysicsWorld::setVehicle(): body " + toString(fixed) +
                                         " is static; set its mobility to Movable first");
    const BodyId body = world.addBody(dynamicBody(Shape::box({2.0, 0.9, 0.35}), 0, 0, 1.0, kMass));
    expectThrowMessage<InvalidState>([&] { world.getWheelCount(body); },
                                     "PhysicsWorld::getWheelCount(): body " + toString(body) +
                                         " has no vehicle");
    VehicleDesc desc = carDesc();
    desc.wheels[2].radius = 0.0;
    expectThrowMessage<InvalidArgument>([&] { world.setVehicle(body, desc); },
                                        "PhysicsWorld::setVehicle(): wheel 2 radius 0 must be > 0");
    desc = carDesc();
    desc.rollInfluence = 2.0;
    expectThrowMessage<InvalidArgument>([&] { world.setVehicle(body, desc); },
                                        "PhysicsWorld::setVehicle(): rollInfluence 2 must be in [0, 1]");
    expectThrowMessage<InvalidArgument>([&] { world.setVehicle(body, VehicleDesc{}); },
                                        "PhysicsWorld::setVehicle(): a vehicle needs at least one wheel");
    world.setVehicle(body, carDesc());
    expectThrowMessage<InvalidArgument>([&] { world.setWheelControls(body, 4, {}); },
                                        "PhysicsWorld::setWheelControls(): wheel 4 is out of range (the "
                                        "vehicle has 4)");
    WheelControls controls;
    controls.brakeForce = -1.0;
    expectThrowMessage<InvalidArgument>([&] { world.setWheelControls(body, 0, controls); },
                                        "PhysicsWorld::setWheelControls(): brakeForce -1 must be >= 0");
    controls = {};
    controls.steering = 2.0;
    expectThrowMessage<InvalidArgument>([&] { world.setWheelControls(body, 0, controls); },
                                        "PhysicsWorld::setWheelControls(): steering 2 must be in (-pi/2, "
                                        "pi/2) radians");
}

} // namespace
} // namespace sp::physics
