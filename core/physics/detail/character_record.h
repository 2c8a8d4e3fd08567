#pragma once
// What PhysicsWorld keeps per character: its collision shape, the ghost object that finds its contacts, and
// Bullet's controller that moves it.

#include <memory>

#include <BulletCollision/CollisionDispatch/btGhostObject.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletDynamics/Character/btKinematicCharacterController.h>

#include "core/physics/character.h"

namespace sp::physics::detail {

struct CharacterRecord {
    CharacterDesc desc;
    std::unique_ptr<btCylinderShapeZ> shape;
    std::unique_ptr<btPairCachingGhostObject> ghost;
    std::unique_ptr<btKinematicCharacterController> controller; // declared last: destroyed first
    Eigen::Vector3d walkVelocity = Eigen::Vector3d::Zero();
    // Where the last step() started, and the mean velocity over its substeps (what the controller reports
    // mixes a per-substep walk displacement with a vertical velocity).
    Eigen::Vector3d stepStart = Eigen::Vector3d::Zero();
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
};

} // namespace sp::physics::detail
