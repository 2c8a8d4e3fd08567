#pragma once
// What PhysicsWorld keeps per body: the Bullet body, its shape, and the settings Bullet does not store
// in a form we can read back (mobility, the simulate flag, the mass of a non-simulated body).

#include <cstdint>
#include <memory>
#include <optional>

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include "core/physics/detail/collision_shape_builder.h"
#include "core/physics/detail/vehicle_record.h"
#include "core/physics/mobility.h"
#include "core/physics/shape.h"

namespace sp::physics::detail {

struct BodyRecord {
    // Declared before body so that it is destroyed after it.
    BuiltShape shape;
    // The description it was built from, for those who need the geometry itself (navigation).
    std::optional<Shape> source; // set by addBody
    std::unique_ptr<btRigidBody> body;
    uint64_t tag = 0;
    bool overlapOnly = false;
    Mobility mobility = Mobility::Movable;
    bool simulate = true;
    // Kept here because Bullet stores only the inverse mass, which is 0 unless the body is simulated.
    double mass = 1.0;
    // Forces and torques from applyForce/applyTorque, re-applied on every substep of the next step().
    btVector3 pendingForce{0, 0, 0};
    btVector3 pendingTorque{0, 0, 0};
    bool hasPendingForce = false;
    // The raycast vehicle whose chassis this body is, if any: in the Bullet world while the body is
    // simulated.
    std::unique_ptr<VehicleRecord> vehicle;

    bool isSimulated() const { return mobility == Mobility::Movable && simulate; }
};

} // namespace sp::physics::detail
