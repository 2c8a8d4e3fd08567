#include "core/physics/physics_world.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <ostream>

#include <btBulletDynamicsCommon.h>

#include "core/base/error.h"
#include "core/physics/detail/body_record.h"
#include "core/physics/detail/bullet_convert.h"
#include "core/physics/detail/format.h"
#include "core/physics/detail/slot_table.h"
#include "core/physics/detail/world_impl.h"

namespace sp::physics {

using detail::BodyRecord;
using detail::toBullet;
using detail::toEigen;

namespace {

using detail::Vec;

void checkVector(const char* function, const char* name, const Eigen::Vector3d& v) {
    SP_CHECK(v.allFinite(), InvalidArgument, function, ": ", name, ' ', Vec{v}, " is not finite");
}

void checkPose(const char* function, const Eigen::Isometry3d& pose) {
    checkVector(function, "pose translation", pose.translation());
    const Eigen::Matrix3d r = pose.linear();
    // Bullet stores a rotation; anything else (scale, shear) would be silently dropped.
    SP_CHECK(r.allFinite() &&
                 (r * r.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-6 &&
                 r.determinant() > 0.0,
             InvalidArgument, function, ": pose rotation is not a rotation matrix (orthonormal, det +1)");
}

void checkInRange(const char* function, const char* name, double value, double lo, double hi) {
    SP_CHECK(std::isfinite(value) && value >= lo && value <= hi, InvalidArgument, function, ": ", name, ' ',
             value, " must be in [", lo, ", ", hi, "]");
}

void checkFriction(const char* function, double friction) {
    SP_CHECK(std::isfinite(friction) && friction >= 0.0, InvalidArgument, function, ": friction ", friction,
             " must be >= 0");
}

} // namespace

PhysicsWorld::PhysicsWorld(const Settings& settings) : impl_(std::make_unique<Impl>()) {
    checkVector("PhysicsWorld::PhysicsWorld()", "gravity", settings.gravity);
    SP_CHECK(std::isfinite(settings.fixedTimeStep) && settings.fixedTimeStep > 0.0, InvalidArgument,
             "PhysicsWorld::PhysicsWorld(): fixedTimeStep ", settings.fixedTimeStep, " must be > 0");
    SP_CHECK(settings.solverIterations >= 1, InvalidArgument,
             "PhysicsWorld::PhysicsWorld(): solverIterations ", settings.solverIterations, " must be >= 1");
    Impl& w = *impl_;
    w.settings = settings;
    w.configuration = std::make_unique<btDefaultCollisionConfiguration>();
    w.dispatcher = std::make_unique<btCollisionDispatcher>(w.configuration.get());
    w.broadphase = std::make_unique<btDbvtBroadphase>();
    w.solver = std::make_unique<btSequentialImpulseConstraintSolver>();
    w.world = std::make_unique<btDiscreteDynamicsWorld>(w.dispatcher.get(), w.broadphase.get(),
                                                        w.solver.get(), w.configuration.get());
    w.world->setGravity(toBullet(settings.gravity));
    // Characters' sweeps may end this far inside what they hit (Bullet's default lets them sink 4 cm).
    w.world->getDispatchInfo().m_allowedCcdPenetration = 1e-4;
    w.ghostPairCallback = std::make_unique<btGhostPairCallback>();
    w.broadphase->getOverlappingPairCache()->setInternalGhostPairCallback(w.ghostPairCallback.get());
    w.world->getSolverInfo().m_numIterations = settings.solverIterations;
}

PhysicsWorld::~PhysicsWorld() = default;

// --- Simulation ---

int PhysicsWorld::step(double dt) {
    SP_CHECK(std::isfinite(dt) && dt >= 0.0, InvalidArgument, "PhysicsWorld::step(): dt ", dt,
             " must be finite and >= 0");
    Impl& w = *impl_;
    const double h = w.settings.fixedTimeStep;
    // The allowance makes four 1/240 s substeps fit in a 1/60 s frame although 1/60 / (1/240) may round
    // to 3.999...; without it a frame would now and then run one substep short.
    const double count = std::floor((w.accumulator + dt) / h * (1.0 + 1e-9));
    SP_CHECK(count <= double(INT_MAX), InvalidArgument, "PhysicsWorld::step(): dt ", dt, " would need ",
             count, " substeps of ", h, " s");
    w.accumulator = std::max(0.0, w.accumulator + dt - count * h);
    const int n = int(count);
    w.characters.forEach([&](BodyId, detail::CharacterRecord& record) {
        record.stepStart = toEigen(record.ghost->getWorldTransform().getOrigin());
    });
    for (int i = 0; i < n; ++i) {
        for (BodyId id : w.pendingForces)
            if (BodyRecord* record = w.bodies.find(id); record && record->hasPendingForce) {
                record->body->applyCentralForce(record->pendingForce);
                record->body->applyTorque(record->pendingTorque);
            }
        // maxSubSteps = 0 makes Bullet take exactly one step of length h: the fixed-step accounting
        // is ours, and Bullet's own accumulator and motion-state interpolation stay out of the way.
        w.world->stepSimulation(h, 0, h);
    }
    if (n > 0) {
        for (BodyId id : w.pendingForces)
            if (BodyRecord* record = w.bodies.find(id)) {
                record->pendingForce.setZero();
                record->pendingTorque.setZero();
                record->hasPendingForce = false;
            }
        w.pendingForces.clear();
        w.characters.forEach([&](BodyId, detail::CharacterRecord& record) {
            record.velocity =
                (toEigen(record.ghost->getWorldTransform().getOrigin()) - record.stepStart) / (n * h);
        });
    }
    w.substeps += uint64_t(n);
    return n;
}

uint64_t PhysicsWorld::substepCount() const {
    return impl_->substeps;
}

double PhysicsWorld::simulatedTime() const {
    return double(impl_->substeps) * impl_->settings.fixedTimeStep;
}

const PhysicsWorld::Settings& PhysicsWorld::settings() const {
    return impl_->settings;
}

void PhysicsWorld::setGravity(const Eigen::Vector3d& gravity) {
    checkVector("PhysicsWorld::setGravity()", "gravity", gravity);
    impl_->settings.gravity = gravity;
    impl_->world->setGravity(toBullet(gravity));
    impl_->characters.forEach(
        [&](BodyId, detail::CharacterRecord& record) { record.controller->setGravity(toBullet(gravity)); });
    impl_->bodies.forEach([](BodyId, BodyRecord& record) { record.body->activate(); });
}

Eigen::Vector3d PhysicsWorld::getGravity() const {
    return impl_->settings.gravity;
}

// --- Bodies ---

BodyId PhysicsWorld::addBody(const BodyDesc& desc) {
    constexpr const char* fn = "PhysicsWorld::addBody()";
    checkPose(fn, desc.pose);
    const bool simulated = desc.mobility == Mobility::Movable && desc.simulatePhysics;
    if (desc.mobility == Mobility::Movable) {
        SP_CHECK(std::isfinite(desc.mass) && desc.mass >= 0.0, InvalidArgument, fn, ": mass ", desc.mass,
                 " must be >= 0 for a movable body");
        SP_CHECK(!simulated || desc.mass > 0.0, InvalidArgument, fn, ": mass ", desc.mass,
                 " must be > 0 for a simulated body");
    }
    checkFriction(fn, desc.friction);
    checkInRange(fn, "restitution", desc.restitution, 0.0, 1.0);
    checkInRange(fn, "linearDamping", desc.linearDamping, 0.0, 1.0);
    checkInRange(fn, "angularDamping", desc.angularDamping, 0.0, 1.0);

    BodyRecord record;
    record.shape = detail::buildCollisionShape(desc.shape);
    record.source = desc.shape;
    record.overlapOnly = desc.overlapOnly;
    SP_CHECK(!simulated || !record.shape.staticOnly, InvalidArgument, fn, ": a ", desc.shape.type(),
             desc.shape.type() == ShapeType::Box ? " shape off the body's origin" : " shape",
             " cannot be simulated; make the body Static, or Movable with simulatePhysics = false");
    record.tag = desc.tag;
    record.mobility = desc.mobility;
    record.simulate = desc.simulatePhysics;
    // A static body keeps a valid mass for when it is made Movable later.
    record.mass = std::isfinite(desc.mass) && desc.mass >= 0.0 ? desc.mass : 0.0;

    btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, record.shape.shape.get());
    info.m_startWorldTransform = toBullet(desc.pose);
    info.m_friction = desc.friction;
    info.m_restitution = desc.restitution;
    info.m_linearDamping = desc.linearDamping;
    info.m_angularDamping = desc.angularDamping;
    record.body = std::make_unique<btRigidBody>(info);
    if (desc.overlapOnly) // kept by applyMotionType, which changes only the static and kinematic flags
        record.body->setCollisionFlags(record.body->getCollisionFlags() |
                                       btCollisionObject::CF_NO_CONTACT_RESPONSE);

    Impl& w = *impl_;
    const BodyId id = w.bodies.insert(std::move(record));
    BodyRecord& stored = w.bodies.get(id, fn);
    stored.body->setUserIndex(int(id.index));
    w.applyMotionType(stored, false);
    return id;
}

void PhysicsWorld::removeBody(BodyId id) {
    Impl& w = *impl_;
    BodyRecord& record = w.bodies.get(id, "PhysicsWorld::removeBody()");
    w.wakeTouching(record.body.get());
    w.dropVehicle(record);
    w.world->removeRigidBody(record.body.get());
    w.bodies.erase(id);
}

bool PhysicsWorld::isValid(BodyId id) const {
    return impl_->bodies.find(id) != nullptr;
}

size_t PhysicsWorld::bodyCount() const {
    return impl_->bodies.size();
}

std::vector<BodyId> PhysicsWorld::bodies() const {
    std::vector<BodyId> ids;
    ids.reserve(impl_->bodies.size());
    impl_->bodies.forEach([&](BodyId id, const BodyRecord&) { ids.push_back(id); });
    return ids;
}

Eigen::Isometry3d PhysicsWorld::getPose(BodyId id) const {
    return toEigen(impl_->bodies.get(id, "PhysicsWorld::getPose()").body->getWorldTransform());
}

void PhysicsWorld::setPose(BodyId id, const Eigen::Isometry3d& pose) {
    constexpr const char* fn = "PhysicsWorld::setPose()";
    Impl& w = *impl_;
    BodyRecord& record = w.bodies.get(id, fn);
    SP_CHECK(record.mobility != Mobility::Static, InvalidState, fn, ": body ", id,
             " is static; set its mobility to Movable first");
    checkPose(fn, pose);
    btRigidBody* body = record.body.get();
    w.wakeTouching(body);
    const btTransform transform = toBullet(pose);
    body->setWorldTransform(transform);
    // A teleport: without this a kinematic body would get the jump as velocity on the next substep.
    body->setInterpolationWorldTransform(transform);
    w.world->updateSingleAabb(body);
    body->activate(true);
}

Eigen::Vector3d PhysicsWorld::getLinearVelocity(BodyId id) const {
    return toEigen(impl_->bodies.get(id, "PhysicsWorld::getLinearVelocity()").body->getLinearVelocity());
}

Eigen::Vector3d PhysicsWorld::getAngularVelocity(BodyId id) const {
    return toEigen(impl_->bodies.get(id, "PhysicsWorld::getAngularVelocity()").body->getAngularVelocity());
}

void PhysicsWorld::setLinearVelocity(BodyId id, const Eigen::Vector3d& velocity) {
    constexpr const char* fn = "PhysicsWorld::setLinearVelocity()";
    BodyRecord& record = impl_->simulated(id, fn);
    checkVector(fn, "velocity", velocity);
    record.body->setLinearVelocity(toBullet(velocity));
    record.body->activate(true);
}

void PhysicsWorld::setAngularVelocity(BodyId id, const Eigen::Vector3d& velocity) {
    constexpr const char* fn = "PhysicsWorld::setAngularVelocity()";
    BodyRecord& record = impl_->simulated(id, fn);
    checkVector(fn, "velocity", velocity);
    record.body->setAngularVelocity(toBullet(velocity));
    record.body->activate(true);
}

void PhysicsWorld::applyForce(BodyId id, const Eigen::Vector3d& force) {
    constexpr const char* fn = "PhysicsWorld::applyForce()";
    BodyRecord& record = impl_->simulated(id, fn);
    checkVector(fn, "force", force);
    impl_->addPendingForce(id, record, toBullet(force), btVector3(0, 0, 0));
}

void PhysicsWorld::applyForce(BodyId id, const Eigen::Vector3d& force, const Eigen::Vector3d& worldPoint) {
    constexpr const char* fn = "PhysicsWorld::applyForce()";
    BodyRecord& record = impl_->simulated(id, fn);
    checkVector(fn, "force", force);
    checkVector(fn, "worldPoint", worldPoint);
    const btVector3 arm = toBullet(worldPoint) - record.body->getCenterOfMassPosition();
    impl_->addPendingForce(id, record, toBullet(force), arm.cross(toBullet(force)));
}

void PhysicsWorld::applyTorque(BodyId id, const Eigen::Vector3d& torque) {
    constexpr const char* fn = "PhysicsWorld::applyTorque()";
    BodyRecord& record = impl_->simulated(id, fn);
    checkVector(fn, "torque", torque);
    impl_->addPendingForce(id, record, btVector3(0, 0, 0), toBullet(torque));
}

void PhysicsWorld::applyImpulse(BodyId id, const Eigen::Vector3d& impulse) {
    constexpr const char* fn = "PhysicsWorld::applyImpulse()";
    BodyRecord& record = impl_->simulated(id, fn);
    checkVector(fn, "impulse", impulse);
    record.body->applyCentralImpulse(toBullet(impulse));
    record.body->activate(true);
}

void PhysicsWorld::applyImpulse(BodyId id, const Eigen::Vector3d& impulse,
                                const Eigen::Vector3d& worldPoint) {
    constexpr const char* fn = "PhysicsWorld::applyImpulse()";
    BodyRecord& record = impl_->simulated(id, fn);
    checkVector(fn, "impulse", impulse);
    checkVector(fn, "worldPoint", worldPoint);
    record.body->applyImpulse(toBullet(impulse),
                              toBullet(worldPoint) - record.body->getCenterOfMassPosition());
    record.body->activate(true);
}

// --- Body properties ---

Mobility PhysicsWorld::getMobility(BodyId id) const {
    return impl_->bodies.get(id, "PhysicsWorld::getMobility()").mobility;
}

void PhysicsWorld::setMobility(BodyId id, Mobility mobility) {
    constexpr const char* fn = "PhysicsWorld::setMobility()";
    Impl& w = *impl_;
    BodyRecord& record = w.bodies.get(id, fn);
    SP_CHECK(mobility == Mobility::Static || mobility == Mobility::Movable, InvalidArgument, fn,
             ": mobility ", int(mobility), " is not a Mobility value");
    if (record.mobility == mobility)
        return;
    if (mobility == Mobility::Movable && record.simulate) {
        SP_CHECK(!record.shape.staticOnly, InvalidState, fn, ": body ", id,
                 " has a shape that cannot be simulated; call setSimulatePhysics(false) first");
        SP_CHECK(record.mass > 0.0, InvalidState, fn, ": body ", id, " has mass ", record.mass,
                 "; set a mass > 0 (setMass) before making it a simulated Movable body");
    }
    w.wakeTouching(record.body.get());
    record.mobility = mobility;
    w.applyMotionType(record, true);
}

bool PhysicsWorld::isSimulatingPhysics(BodyId id) const {
    return impl_->bodies.get(id, "PhysicsWorld::isSimulatingPhysics()").isSimulated();
}

void PhysicsWorld::setSimulatePhysics(BodyId id, bool simulate) {
    constexpr const char* fn = "PhysicsWorld::setSimulatePhysics()";
    Impl& w = *impl_;
    BodyRecord& record = w.bodies.get(id, fn);
    if (record.simulate == simulate)
        return;
    if (simulate && record.mobility == Mobility::Movable) {
        SP_CHECK(!record.shape.staticOnly, InvalidState, fn, ": body ", id,
                 " has a shape that cannot be simulated (a plane, a triangle mesh or a box off its origin)");
        SP_CHECK(record.mass > 0.0, InvalidState, fn, ": body ", id, " has mass ", record.mass,
                 "; set a mass > 0 (setMass) before simulating it");
    }
    record.simulate = simulate;
    if (record.mobility == Mobility::Movable) {
        w.wakeTouching(record.body.get());
        w.applyMotionType(record, true);
    }
}

double PhysicsWorld::getMass(BodyId id) const {
    return impl_->bodies.get(id, "PhysicsWorld::getMass()").mass;
}

void PhysicsWorld::setMass(BodyId id, double mass) {
    constexpr const char* fn = "PhysicsWorld::setMass()";
    BodyRecord& record = impl_->bodies.get(id, fn);
    SP_CHECK(std::isfinite(mass) && mass >= 0.0, InvalidArgument, fn, ": mass ", mass, " must be >= 0");
    SP_CHECK(!record.isSimulated() || mass > 0.0, InvalidArgument, fn, ": mass ", mass,
             " must be > 0 for simulated body ", id);
    record.mass = mass;
    if (record.isSimulated()) {
        btVector3 inertia(0, 0, 0);
        record.shape.shape->calculateLocalInertia(mass, inertia);
        record.body->setMassProps(mass, inertia);
        record.body->updateInertiaTensor();
        // Bullet caches gravity as a force (mass * g) per body.
        record.body->setGravity(impl_->world->getGravity());
        record.body->activate(true);
    }
}

double PhysicsWorld::getFriction(BodyId id) const {
    return impl_->bodies.get(id, "PhysicsWorld::getFriction()").body->getFriction();
}

void PhysicsWorld::setFriction(BodyId id, double friction) {
    constexpr const char* fn = "PhysicsWorld::setFriction()";
    BodyRecord& record = impl_->bodies.get(id, fn);
    checkFriction(fn, friction);
    record.body->setFriction(friction);
    record.body->activate();
}

double PhysicsWorld::getRestitution(BodyId id) const {
    return impl_->bodies.get(id, "PhysicsWorld::getRestitution()").body->getRestitution();
}

void PhysicsWorld::setRestitution(BodyId id, double restitution) {
    constexpr const char* fn = "PhysicsWorld::setRestitution()";
    BodyRecord& record = impl_->bodies.get(id, fn);
    checkInRange(fn, "restitution", restitution, 0.0, 1.0);
    record.body->setRestitution(restitution);
    record.body->activate();
}

double PhysicsWorld::getLinearDamping(BodyId id) const {
    return impl_->bodies.get(id, "PhysicsWorld::getLinearDamping()").body->getLinearDamping();
}

void PhysicsWorld::setLinearDamping(BodyId id, double damping) {
    constexpr const char* fn = "PhysicsWorld::setLinearDamping()";
    BodyRecord& record = impl_->bodies.get(id, fn);
    checkInRange(fn, "damping", damping, 0.0, 1.0);
    record.body->setDamping(damping, record.body->getAngularDamping());
}

double PhysicsWorld::getAngularDamping(BodyId id) const {
    return impl_->bodies.get(id, "PhysicsWorld::getAngularDamping()").body->getAngularDamping();
}

void PhysicsWorld::setAngularDamping(BodyId id, double damping) {
    constexpr const char* fn = "PhysicsWorld::setAngularDamping()";
    BodyRecord& record = impl_->bodies.get(id, fn);
    checkInRange(fn, "damping", damping, 0.0, 1.0);
    record.body->setDamping(record.body->getLinearDamping(), damping);
}

uint64_t PhysicsWorld::getTag(BodyId id) const {
    return impl_->bodies.get(id, "PhysicsWorld::getTag()").tag;
}

const Shape& PhysicsWorld::getShape(BodyId id) const {
    return *impl_->bodies.get(id, "PhysicsWorld::getShape()").source;
}

bool PhysicsWorld::isOverlapOnly(BodyId id) const {
    return impl_->bodies.get(id, "PhysicsWorld::isOverlapOnly()").overlapOnly;
}

void PhysicsWorld::setTag(BodyId id, uint64_t tag) {
    impl_->bodies.get(id, "PhysicsWorld::setTag()").tag = tag;
}

bool PhysicsWorld::isAwake(BodyId id) const {
    const BodyRecord& record = impl_->bodies.get(id, "PhysicsWorld::isAwake()");
    return record.mobility != Mobility::Static && record.body->isActive();
}

// --- Queries ---

std::optional<RayHit> PhysicsWorld::raycast(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
    checkVector("PhysicsWorld::raycast()", "from", from);
    checkVector("PhysicsWorld::raycast()", "to", to);
    if (from == to)
        return std::nullopt;
    detail::SolidOnly<btCollisionWorld::ClosestRayResultCallback> result(toBullet(from), toBullet(to));
    impl_->world->rayTest(result.m_rayFromWorld, result.m_rayToWorld, result);
    if (!result.hasHit())
        return std::nullopt;
    return impl_->makeHit(result.m_collisionObject, result.m_hitPointWorld, result.m_hitNormalWorld,
                          result.m_closestHitFraction);
}

std::vector<RayHit> PhysicsWorld::raycastAll(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
    checkVector("PhysicsWorld::raycastAll()", "from", from);
    checkVector("PhysicsWorld::raycastAll()", "to", to);
    std::vector<RayHit> hits;
    if (from == to)
        return hits;
    detail::SolidOnly<btCollisionWorld::AllHitsRayResultCallback> result(toBullet(from), toBullet(to));
    impl_->world->rayTest(result.m_rayFromWorld, result.m_rayToWorld, result);
    hits.reserve(size_t(result.m_collisionObjects.size()));
    for (int i = 0; i < result.m_collisionObjects.size(); ++i)
        hits.push_back(impl_->makeHit(result.m_collisionObjects[i], result.m_hitPointWorld[i],
                                      result.m_hitNormalWorld[i], result.m_hitFractions[i]));
    // Bullet reports hits in broadphase order, and one per triangle for planes and meshes: sort them
    // along the ray (ties by slot, for stability) and keep each body's closest hit.
    std::sort(hits.begin(), hits.end(), [](const RayHit& a, const RayHit& b) {
        return a.fraction != b.fraction ? a.fraction < b.fraction : a.body.index < b.body.index;
    });
    std::vector<RayHit> closest;
    std::vector<uint32_t> seenIndices;
    for (const RayHit& hit : hits)
        if (std::find(seenIndices.begin(), seenIndices.end(), hit.body.index) == seenIndices.end()) {
            seenIndices.push_back(hit.body.index);
            closest.push_back(hit);
        }
    return closest;
}

} // namespace sp::physics
