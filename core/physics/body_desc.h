#pragma once

#include <cstdint>

#include <Eigen/Geometry>

#include "core/physics/mobility.h"
#include "core/physics/shape.h"

namespace sp::physics {

// Everything PhysicsWorld::addBody needs to create a body. Each field can also be changed later through
// the PhysicsWorld setter of the same name, except the shape.
struct BodyDesc {
    // The body's geometry in its local frame; the local origin is the centre of mass.
    Shape shape = Shape::box(Eigen::Vector3d(0.5, 0.5, 0.5));
    // Pose of the local frame in the world (rotation must be orthonormal).
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    Mobility mobility = Mobility::Movable;
    // For a Movable body: true to simulate it (dynamic), false to move it only by setPose (kinematic).
    // Ignored for Static bodies.
    bool simulatePhysics = true;
    // Mass in kg; >= 0, and > 0 for a simulated body. Ignored for Static bodies.
    double mass = 1.0;
    // Coulomb friction coefficient, >= 0. Bullet multiplies the two bodies' coefficients at a contact.
    double friction = 0.5;
    // Bounciness in [0, 1]. Bullet multiplies the two bodies' coefficients at a contact, so a bouncing
    // ball needs a restitution above 0 on both it and the floor.
    double restitution = 0.0;
    // Fraction of linear velocity lost per second, in [0, 1].
    double linearDamping = 0.0;
    // Fraction of angular velocity lost per second, in [0, 1].
    double angularDamping = 0.0;
    // Opaque value returned in RayHit::tag, so the owner (an engine component) can be found from a hit.
    uint64_t tag = 0;
    // A sensor (a trigger volume): other bodies pass through it and rays go through it; overlaps() still
    // finds what it touches. Fixed when the body is made.
    bool overlapOnly = false;
};

} // namespace sp::physics
