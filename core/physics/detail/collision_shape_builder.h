#pragma once
// Turns a Shape description into a Bullet collision shape plus the buffers Bullet keeps pointers into.

#include <memory>
#include <vector>

#include <BulletCollision/CollisionShapes/btCollisionShape.h>
#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>

#include "core/physics/shape.h"

namespace sp::physics::detail {

// A Bullet shape and everything it references. Movable (moving a std::vector keeps its buffer, so the
// mesh interface's pointers stay valid); destroy only after the body using it.
struct BuiltShape {
    std::vector<btScalar> vertices;
    std::vector<int> indices;
    std::unique_ptr<btTriangleIndexVertexArray> mesh;
    std::unique_ptr<btCollisionShape> child; // a compound shape's one child, which it points to
    std::unique_ptr<btCollisionShape> shape;
    // Planes, triangle meshes and boxes off the body's origin: Bullet can collide them but they cannot be
    // simulated (no inertia, or none about the origin the body turns about).
    bool staticOnly = false;
};

// Builds the shape with its scale baked into the geometry, so that Bullet's margins stay exact: the
// collision surface matches the described geometry (up to rounded edges of at most 4 cm).
BuiltShape buildCollisionShape(const Shape& shape);

} // namespace sp::physics::detail
