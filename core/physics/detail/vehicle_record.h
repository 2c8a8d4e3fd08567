#pragma once
// A body's raycast vehicle: Bullet's action and the ray caster it uses.

#include <memory>

#include <BulletDynamics/Vehicle/btRaycastVehicle.h>

namespace sp::physics::detail {

struct VehicleRecord {
    std::unique_ptr<btVehicleRaycaster> raycaster;
    std::unique_ptr<btRaycastVehicle> vehicle; // declared after the ray caster it points to
};

} // namespace sp::physics::detail
