// PhysicsWorld's vehicles (declared in physics_world.h, described in vehicle.h): Bullet's raycast vehicle
// on a simulated chassis body.

#include <cmath>
#include <numbers>

#include "core/physics/detail/format.h"
#include "core/physics/detail/world_impl.h"

namespace sp::physics {

using detail::BodyRecord;
using detail::toBullet;
using detail::toEigen;

namespace {

void checkDesc(const char* fn, const VehicleDesc& desc) {
    SP_CHECK(!desc.wheels.empty(), InvalidArgument, fn, ": a vehicle needs at least one wheel");
    for (std::size_t i = 0; i < desc.wheels.size(); ++i) {
        const WheelDesc& wheel = desc.wheels[i];
        SP_CHECK(wheel.connectionPoint.allFinite(), InvalidArgument, fn, ": wheel ", i, " connectionPoint ",
                 detail::Vec{wheel.connectionPoint}, " is not finite");
        SP_CHECK(std::isfinite(wheel.radius) && wheel.radius > 0.0, InvalidArgument, fn, ": wheel ", i,
                 " radius ", wheel.radius, " must be > 0");
    }
    detail::checkField(fn, "suspensionRestLength", desc.suspensionRestLength,
                       desc.suspensionRestLength >= 0.0, ">= 0");
    detail::checkField(fn, "suspensionStiffness", desc.suspensionStiffness, desc.suspensionStiffness > 0.0,
                       "> 0");
    detail::checkField(fn, "suspensionCompressionDamping", desc.suspensionCompressionDamping,
                       desc.suspensionCompressionDamping >= 0.0, ">= 0");
    detail::checkField(fn, "suspensionRelaxationDamping", desc.suspensionRelaxationDamping,
                       desc.suspensionRelaxationDamping >= 0.0, ">= 0");
    detail::checkField(fn, "maxSuspensionTravel", desc.maxSuspensionTravel, desc.maxSuspensionTravel >= 0.0,
                       ">= 0");
    detail::checkField(fn, "maxSuspensionForce", desc.maxSuspensionForce, desc.maxSuspensionForce > 0.0,
                       "> 0");
    detail::checkField(fn, "frictionSlip", desc.frictionSlip, desc.frictionSlip >= 0.0, ">= 0");
    detail::checkField(fn, "rollInfluence", desc.rollInfluence,
                       desc.rollInfluence >= 0.0 && desc.rollInfluence <= 1.0, "in [0, 1]");
}

// The wheels' rays: the closest body, passing through sensors and characters as the world's raycasts do
// (Bullet's default caster stops at a trigger volume or a character and then reports no ground at all).
class SolidRaycaster : public btVehicleRaycaster {
  public:
    explicit SolidRaycaster(btDynamicsWorld& world) : world_(world) {}
    void* castRay(const btVector3& from, const btVector3& to, btVehicleRaycasterResult& result) override {
        detail::SolidOnly<btCollisionWorld::ClosestRayResultCallback> ray(from, to);
        world_.rayTest(from, to, ray);
        if (!ray.hasHit())
            return nullptr;
        result.m_hitPointInWorld = ray.m_hitPointWorld;
        result.m_hitNormalInWorld = ray.m_hitNormalWorld.normalized();
        result.m_distFraction = ray.m_closestHitFraction;
        return const_cast<btRigidBody*>(btRigidBody::upcast(ray.m_collisionObject));
    }

  private:
    btDynamicsWorld& world_;
};

btRaycastVehicle& vehicleOf(const BodyRecord& record, BodyId id, const char* fn) {
    SP_CHECK(record.vehicle, InvalidState, fn, ": body ", id, " has no vehicle");
    return *record.vehicle->vehicle;
}

int checkedWheel(const btRaycastVehicle& vehicle, int wheel, const char* fn) {
    SP_CHECK(wheel >= 0 && wheel < vehicle.getNumWheels(), InvalidArgument, fn, ": wheel ", wheel,
             " is out of range (the vehicle has ", vehicle.getNumWheels(), ")");
    return wheel;
}

} // namespace

void PhysicsWorld::setVehicle(BodyId chassis, const VehicleDesc& desc) {
    constexpr const char* fn = "PhysicsWorld::setVehicle()";
    Impl& w = *impl_;
    BodyRecord& record = w.simulated(chassis, fn);
    checkDesc(fn, desc);
    w.dropVehicle(record);

    btRaycastVehicle::btVehicleTuning tuning;
    tuning.m_suspensionStiffness = desc.suspensionStiffness;
    tuning.m_suspensionCompression = desc.suspensionCompressionDamping;
    tuning.m_suspensionDamping = desc.suspensionRelaxationDamping;
    tuning.m_maxSuspensionTravelCm = desc.maxSuspensionTravel * 100.0; // Bullet's unit
    tuning.m_maxSuspensionForce = desc.maxSuspensionForce;
    tuning.m_frictionSlip = desc.frictionSlip;

    auto vehicle = std::make_unique<detail::VehicleRecord>();
    vehicle->raycaster = std::make_unique<SolidRaycaster>(*w.world);
    vehicle->vehicle =
        std::make_unique<btRaycastVehicle>(tuning, record.body.get(), vehicle->raycaster.get());
    // The chassis' axes for Bullet: right = Y, up = Z, forward = X (forward gives the speed's sign and the
    // wheels' spin; the three indices must differ, as Bullet writes a wheel's basis column by column). A
    // wheel's basis is (up x axle, -axle, up) in those columns: with the axle along -Y it is the chassis'
    // own basis, and the wheel drives along +X.
    vehicle->vehicle->setCoordinateSystem(1, 2, 0);
    for (const WheelDesc& wheel : desc.wheels) {
        btWheelInfo& info = vehicle->vehicle->addWheel(toBullet(wheel.connectionPoint), btVector3(0, 0, -1),
                                                       btVector3(0, -1, 0), desc.suspensionRestLength,
                                                       wheel.radius, tuning, wheel.steered);
        info.m_rollInfluence = desc.rollInfluence;
    }
    vehicle->vehicle->resetSuspension();
    record.vehicle = std::move(vehicle);
    w.applyMotionType(record, true); // no sleeping chassis; the action joins the world
}

void PhysicsWorld::removeVehicle(BodyId chassis) {
    Impl& w = *impl_;
    BodyRecord& record = w.bodies.get(chassis, "PhysicsWorld::removeVehicle()");
    if (!record.vehicle)
        return;
    w.dropVehicle(record);
    w.applyMotionType(record, true); // the chassis may sleep again
}

bool PhysicsWorld::hasVehicle(BodyId chassis) const {
    return impl_->bodies.get(chassis, "PhysicsWorld::hasVehicle()").vehicle != nullptr;
}

int PhysicsWorld::getWheelCount(BodyId chassis) const {
    constexpr const char* fn = "PhysicsWorld::getWheelCount()";
    return vehicleOf(impl_->bodies.get(chassis, fn), chassis, fn).getNumWheels();
}

void PhysicsWorld::setWheelControls(BodyId chassis, int wheel, const WheelControls& controls) {
    constexpr const char* fn = "PhysicsWorld::setWheelControls()";
    Impl& w = *impl_;
    btRaycastVehicle& vehicle = vehicleOf(w.bodies.get(chassis, fn), chassis, fn);
    checkedWheel(vehicle, wheel, fn);
    SP_CHECK(std::isfinite(controls.engineForce), InvalidArgument, fn, ": engineForce ", controls.engineForce,
             " is not finite");
    SP_CHECK(std::isfinite(controls.brakeForce) && controls.brakeForce >= 0.0, InvalidArgument, fn,
             ": brakeForce ", controls.brakeForce, " must be >= 0");
    SP_CHECK(std::isfinite(controls.steering) && std::abs(controls.steering) < std::numbers::pi / 2,
             InvalidArgument, fn, ": steering ", controls.steering, " must be in (-pi/2, pi/2) radians");
    vehicle.applyEngineForce(controls.engineForce, wheel);
    // Bullet's brake is the largest rolling impulse a wheel may resist in one substep.
    vehicle.setBrake(controls.brakeForce * w.settings.fixedTimeStep, wheel);
    vehicle.setSteeringValue(vehicle.getWheelInfo(wheel).m_bIsFrontWheel ? controls.steering : 0.0, wheel);
}

WheelState PhysicsWorld::getWheelState(BodyId chassis, int wheel) const {
    constexpr const char* fn = "PhysicsWorld::getWheelState()";
    const BodyRecord& record = impl_->bodies.get(chassis, fn);
    const btRaycastVehicle& vehicle = vehicleOf(record, chassis, fn);
    const btWheelInfo& info = vehicle.getWheelInfo(checkedWheel(vehicle, wheel, fn));
    WheelState state;
    state.inContact = info.m_raycastInfo.m_isInContact;
    state.contactPoint = toEigen(info.m_raycastInfo.m_contactPointWS);
    state.suspensionLength = info.m_raycastInfo.m_suspensionLength;
    state.rotation = info.m_rotation;
    state.steering = info.m_steering;
    // Computed here from the chassis' pose rather than read from Bullet's wheel transform, whose axes follow
    // Bullet's own convention: the hub hangs suspensionLength below its connection point.
    Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
    local.translation() =
        toEigen(info.m_chassisConnectionPointCS) - Eigen::Vector3d::UnitZ() * state.suspensionLength;
    local.linear() = (Eigen::AngleAxisd(state.steering, Eigen::Vector3d::UnitZ()) *
                      Eigen::AngleAxisd(state.rotation, Eigen::Vector3d::UnitY()))
                         .toRotationMatrix();
    state.poseInChassis = local;
    state.pose = toEigen(record.body->getWorldTransform()) * local;
    return state;
}

} // namespace sp::physics
