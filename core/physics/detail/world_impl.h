#pragma once
// PhysicsWorld's state, shared by the files that implement it (physics_world.cpp, vehicle.cpp). Internal:
// it pulls in Bullet.

#include <memory>
#include <vector>

#include <btBulletDynamicsCommon.h>

#include "core/base/error.h"
#include "core/physics/detail/body_record.h"
#include "core/physics/detail/bullet_convert.h"
#include "core/physics/detail/character_record.h"
#include "core/physics/detail/slot_table.h"
#include "core/physics/physics_world.h"
#include "core/physics/ray_hit.h"

namespace sp::physics {

namespace detail {

// A ray callback that sees bodies only: not sensors (bodies without contact response), not characters.
// The world's raycasts and vehicles' wheels use it.
template <typename Callback> struct SolidOnly : Callback {
    using Callback::Callback;
    bool needsCollision(btBroadphaseProxy* proxy) const override {
        const auto* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
        return Callback::needsCollision(proxy) && object->hasContactResponse() && btRigidBody::upcast(object);
    }
};

} // namespace detail

struct PhysicsWorld::Impl {
    Settings settings;
    // Bodies are declared first so that they outlive the world, whose destructor still reads them.
    detail::SlotTable<detail::BodyRecord> bodies;
    detail::SlotTable<detail::CharacterRecord> characters;
    // Keeps the characters' ghost objects' pair lists current (Bullet's ghost objects need it).
    std::unique_ptr<btGhostPairCallback> ghostPairCallback;
    std::unique_ptr<btDefaultCollisionConfiguration> configuration;
    std::unique_ptr<btCollisionDispatcher> dispatcher;
    std::unique_ptr<btDbvtBroadphase> broadphase;
    std::unique_ptr<btSequentialImpulseConstraintSolver> solver;
    std::unique_ptr<btDiscreteDynamicsWorld> world;
    double accumulator = 0.0;
    uint64_t substeps = 0;
    // Bodies with a pending force or torque (may include removed ones, which are skipped).
    std::vector<BodyId> pendingForces;

    ~Impl() {
        characters.forEach([&](BodyId, detail::CharacterRecord& record) { dropCharacter(record); });
        bodies.forEach([&](BodyId, detail::BodyRecord& record) {
            dropVehicle(record);
            world->removeRigidBody(record.body.get());
        });
    }

    // Brings the Bullet body in line with the record's mobility, simulate flag and mass. Re-adding is
    // how Bullet moves a body between the static and dynamic broadphase groups.
    void applyMotionType(detail::BodyRecord& record, bool inWorld) {
        btRigidBody* body = record.body.get();
        if (inWorld)
            world->removeRigidBody(body);
        int flags = body->getCollisionFlags() &
                    ~(btCollisionObject::CF_STATIC_OBJECT | btCollisionObject::CF_KINEMATIC_OBJECT);
        if (record.isSimulated()) {
            btVector3 inertia(0, 0, 0);
            record.shape.shape->calculateLocalInertia(record.mass, inertia);
            body->setMassProps(record.mass, inertia);
        } else {
            body->setMassProps(0, btVector3(0, 0, 0));
            body->setLinearVelocity(btVector3(0, 0, 0));
            body->setAngularVelocity(btVector3(0, 0, 0));
            flags |= record.mobility == Mobility::Static ? btCollisionObject::CF_STATIC_OBJECT
                                                         : btCollisionObject::CF_KINEMATIC_OBJECT;
        }
        // setMassProps(0) marks the body static, so the flags are set after it.
        body->setCollisionFlags(flags);
        body->updateInertiaTensor();
        body->setInterpolationWorldTransform(body->getWorldTransform());
        // Bullet's rule for kinematic bodies; a vehicle's chassis must not sleep either, or it would stop
        // answering its controls.
        if ((record.mobility == Mobility::Movable && !record.simulate) || record.vehicle)
            body->forceActivationState(DISABLE_DEACTIVATION);
        else
            body->forceActivationState(ACTIVE_TAG);
        body->setDeactivationTime(0);
        world->addRigidBody(body);
        updateVehicleAction(record);
    }

    // A vehicle acts on its chassis only while the chassis is simulated (its mass is what the suspension
    // forces scale with).
    void updateVehicleAction(detail::BodyRecord& record) {
        if (!record.vehicle)
            return;
        world->removeAction(record.vehicle->vehicle.get());
        if (record.isSimulated())
            world->addAction(record.vehicle->vehicle.get());
    }

    // A character's record; the id names a character, so a stale one says so (not "body").
    detail::CharacterRecord& character(BodyId id, const char* function) {
        detail::CharacterRecord* record = characters.find(id);
        SP_CHECK(record, StaleObject, function, ": character ", id,
                 " does not exist (removed, or never made)");
        return *record;
    }

    // Takes a character's controller and ghost object out of the Bullet world.
    void dropCharacter(detail::CharacterRecord& record) {
        world->removeAction(record.controller.get());
        world->removeCollisionObject(record.ghost.get());
    }

    // Takes a body's vehicle out of the Bullet world and drops it.
    void dropVehicle(detail::BodyRecord& record) {
        if (!record.vehicle)
            return;
        world->removeAction(record.vehicle->vehicle.get());
        record.vehicle.reset();
    }

    // Wakes the bodies in contact with object, which would otherwise sleep on after it moved or vanished.
    void wakeTouching(const btCollisionObject* object) {
        btDispatcher* d = world->getDispatcher();
        for (int i = 0; i < d->getNumManifolds(); ++i) {
            const btPersistentManifold* manifold = d->getManifoldByIndexInternal(i);
            const btCollisionObject* other = manifold->getBody0() == object   ? manifold->getBody1()
                                             : manifold->getBody1() == object ? manifold->getBody0()
                                                                              : nullptr;
            if (other)
                const_cast<btCollisionObject*>(other)->activate();
        }
    }

    // The record of a simulated body; throws sp::InvalidState for static and kinematic bodies.
    detail::BodyRecord& simulated(BodyId id, const char* function) {
        detail::BodyRecord& record = bodies.get(id, function);
        SP_CHECK(record.mobility != Mobility::Static, InvalidState, function, ": body ", id,
                 " is static; set its mobility to Movable first");
        SP_CHECK(record.simulate, InvalidState, function, ": body ", id,
                 " is not simulated; enable simulatePhysics first");
        return record;
    }

    void addPendingForce(BodyId id, detail::BodyRecord& record, const btVector3& force,
                         const btVector3& torque) {
        if (!record.hasPendingForce)
            pendingForces.push_back(id);
        record.hasPendingForce = true;
        record.pendingForce += force;
        record.pendingTorque += torque;
        record.body->activate(true);
    }

    RayHit makeHit(const btCollisionObject* object, const btVector3& point, const btVector3& normal,
                   double fraction) const {
        RayHit hit;
        // Every body in the Bullet world is live in the table: removeBody takes it out of both.
        hit.body = bodies.idAt(uint32_t(object->getUserIndex()));
        hit.tag = bodies.find(hit.body)->tag;
        hit.point = detail::toEigen(point);
        hit.normal = detail::toEigen(normal).normalized();
        hit.fraction = fraction;
        return hit;
    }
};

} // namespace sp::physics
