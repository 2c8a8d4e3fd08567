#pragma once
// Helpers shared by the physics tests.

#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "core/physics/physics_world.h"

namespace sp::physics::test {

// Expects f() to throw exactly E (or a subclass) with exactly the given message.
template <typename E> void expectThrowMessage(const std::function<void()>& f, const std::string& message) {
    try {
        f();
        ADD_FAILURE() << "expected an exception with message: " << message;
    } catch (const E& e) {
        EXPECT_EQ(std::string(e.what()), message);
    } catch (const std::exception& e) {
        ADD_FAILURE() << "wrong exception type, message: " << e.what();
    }
}

inline Eigen::Isometry3d at(double x, double y, double z) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(x, y, z);
    return pose;
}

// A static floor: the plane z = 0.
inline BodyId addFloor(PhysicsWorld& world, double restitution = 0.0, double friction = 0.5) {
    BodyDesc floor;
    floor.shape = Shape::plane();
    floor.mobility = Mobility::Static;
    floor.restitution = restitution;
    floor.friction = friction;
    return world.addBody(floor);
}

// A simulated body of the given shape and mass at (x, y, z).
inline BodyDesc dynamicBody(const Shape& shape, double x, double y, double z, double mass = 1.0) {
    BodyDesc desc;
    desc.shape = shape;
    desc.pose = at(x, y, z);
    desc.mass = mass;
    return desc;
}

// Steps seconds of simulated time in 1/60 s frames.
inline void run(PhysicsWorld& world, double seconds) {
    const int frames = int(seconds * 60.0 + 0.5);
    for (int i = 0; i < frames; ++i)
        world.step(1.0 / 60.0);
}

} // namespace sp::physics::test
