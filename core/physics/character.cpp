// PhysicsWorld's characters (declared in physics_world.h, described in character.h): Bullet's kinematic
// character controller, one upright-cylinder ghost object each.

#include <cmath>
#include <numbers>

#include "core/physics/detail/format.h"
#include "core/physics/detail/world_impl.h"

namespace sp::physics {

using detail::CharacterRecord;
using detail::toBullet;
using detail::toEigen;

namespace {

void checkDesc(const char* fn, const CharacterDesc& desc) {
    detail::checkField(fn, "radius", desc.radius, desc.radius > 0.0, "> 0");
    detail::checkField(fn, "halfHeight", desc.halfHeight, desc.halfHeight >= desc.radius, ">= radius");
    SP_CHECK(desc.position.allFinite(), InvalidArgument, fn, ": position ", detail::Vec{desc.position},
             " is not finite");
    detail::checkField(fn, "stepHeight", desc.stepHeight, desc.stepHeight >= 0.0, ">= 0");
    detail::checkField(fn, "maxSlopeDegrees", desc.maxSlopeDegrees,
                       desc.maxSlopeDegrees > 0.0 && desc.maxSlopeDegrees < 90.0, "in (0, 90)");
    detail::checkField(fn, "jumpSpeed", desc.jumpSpeed, desc.jumpSpeed >= 0.0, ">= 0");
}

void applySettings(CharacterRecord& record) {
    record.controller->setStepHeight(record.desc.stepHeight);
    record.controller->setMaxSlope(record.desc.maxSlopeDegrees * std::numbers::pi / 180.0);
    record.controller->setJumpSpeed(record.desc.jumpSpeed);
    // Bullet caps a jump's height by this; the jump speed alone decides it here.
    record.controller->setMaxJumpHeight(1e6);
}

} // namespace

BodyId PhysicsWorld::addCharacter(const CharacterDesc& desc) {
    constexpr const char* fn = "PhysicsWorld::addCharacter()";
    checkDesc(fn, desc);
    Impl& w = *impl_;
    CharacterRecord record;
    record.desc = desc;
    // The controller sweeps an upright cylinder of the capsule's size: a rounded bottom would slide up
    // over any edge below its centre (Bullet's controller follows the contact normal), climbing steps
    // well above the step height.
    record.shape = std::make_unique<btCylinderShapeZ>(btVector3(desc.radius, desc.radius, desc.halfHeight));
    record.ghost = std::make_unique<btPairCachingGhostObject>();
    record.ghost->setWorldTransform(btTransform(btQuaternion::getIdentity(), toBullet(desc.position)));
    record.ghost->setCollisionShape(record.shape.get());
    record.ghost->setCollisionFlags(btCollisionObject::CF_CHARACTER_OBJECT);
    record.ghost->setUserIndex(-1); // not a body: rays and overlaps skip it
    record.controller = std::make_unique<btKinematicCharacterController>(
        record.ghost.get(), record.shape.get(), desc.stepHeight, btVector3(0, 0, 1));
    record.controller->setGravity(toBullet(w.settings.gravity));
    applySettings(record);
    record.stepStart = desc.position;
    const BodyId id = w.characters.insert(std::move(record));
    CharacterRecord& stored = *w.characters.find(id);
    w.world->addCollisionObject(stored.ghost.get(), btBroadphaseProxy::CharacterFilter,
                                btBroadphaseProxy::StaticFilter | btBroadphaseProxy::DefaultFilter);
    w.world->addAction(stored.controller.get());
    return id;
}

void PhysicsWorld::removeCharacter(BodyId character) {
    Impl& w = *impl_;
    w.dropCharacter(w.character(character, "PhysicsWorld::removeCharacter()"));
    w.characters.erase(character);
}

bool PhysicsWorld::isValidCharacter(BodyId character) const {
    return impl_->characters.find(character) != nullptr;
}

void PhysicsWorld::setCharacterDesc(BodyId character, const CharacterDesc& desc) {
    constexpr const char* fn = "PhysicsWorld::setCharacterDesc()";
    CharacterRecord& record = impl_->character(character, fn);
    checkDesc(fn, desc);
    SP_CHECK(desc.radius == record.desc.radius && desc.halfHeight == record.desc.halfHeight, InvalidArgument,
             fn, ": the capsule's size cannot change; make a new character");
    const Eigen::Vector3d position = record.desc.position;
    record.desc = desc;
    record.desc.position = position; // the position is the character's own (setCharacterPosition)
    applySettings(record);
}

const CharacterDesc& PhysicsWorld::getCharacterDesc(BodyId character) const {
    return impl_->character(character, "PhysicsWorld::getCharacterDesc()").desc;
}

void PhysicsWorld::setCharacterWalkVelocity(BodyId character, const Eigen::Vector3d& velocity) {
    constexpr const char* fn = "PhysicsWorld::setCharacterWalkVelocity()";
    CharacterRecord& record = impl_->character(character, fn);
    SP_CHECK(velocity.allFinite(), InvalidArgument, fn, ": velocity ", detail::Vec{velocity},
             " is not finite");
    record.walkVelocity = Eigen::Vector3d(velocity.x(), velocity.y(), 0.0);
    // Bullet moves a character by its walk direction in every substep: a displacement, not a velocity.
    record.controller->setWalkDirection(toBullet(record.walkVelocity * impl_->settings.fixedTimeStep));
}

bool PhysicsWorld::jumpCharacter(BodyId character) {
    CharacterRecord& record = impl_->character(character, "PhysicsWorld::jumpCharacter()");
    if (!record.controller->canJump())
        return false;
    record.controller->jump(); // at the jump speed, along up
    return true;
}

Eigen::Vector3d PhysicsWorld::getCharacterPosition(BodyId character) const {
    const CharacterRecord& record = impl_->character(character, "PhysicsWorld::getCharacterPosition()");
    return toEigen(record.ghost->getWorldTransform().getOrigin());
}

void PhysicsWorld::setCharacterPosition(BodyId character, const Eigen::Vector3d& position) {
    constexpr const char* fn = "PhysicsWorld::setCharacterPosition()";
    CharacterRecord& record = impl_->character(character, fn);
    SP_CHECK(position.allFinite(), InvalidArgument, fn, ": position ", detail::Vec{position},
             " is not finite");
    record.controller->warp(toBullet(position));
    record.controller->reset(impl_->world.get()); // no fall or jump carried over
    // reset() also stops the walk; the character keeps walking as it was told.
    record.controller->setWalkDirection(toBullet(record.walkVelocity * impl_->settings.fixedTimeStep));
    record.stepStart = position;
    record.velocity.setZero();
}

bool PhysicsWorld::isCharacterOnGround(BodyId character) const {
    return impl_->character(character, "PhysicsWorld::isCharacterOnGround()").controller->onGround();
}

Eigen::Vector3d PhysicsWorld::getCharacterVelocity(BodyId character) const {
    return impl_->character(character, "PhysicsWorld::getCharacterVelocity()").velocity;
}

} // namespace sp::physics
