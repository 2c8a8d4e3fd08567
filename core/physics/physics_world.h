#pragma once
// A rigid-body physics world on Bullet. It owns every body; callers hold BodyIds. All quantities are
// SI (metres, kilograms, seconds), right-handed with Z up; Bullet types never appear here.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "core/physics/body_desc.h"
#include "core/physics/body_id.h"
#include "core/physics/character.h"
#include "core/physics/mobility.h"
#include "core/physics/ray_hit.h"
#include "core/physics/vehicle.h"
#include "core/physics/world_settings.h"

namespace sp::physics {

// A set of rigid bodies advanced together in fixed substeps. Every call that takes a BodyId throws
// sp::StaleObject when the body was removed or never existed. Not thread-safe; one thread at a time.
class PhysicsWorld {
  public:
    using Settings = WorldSettings;

    // Creates an empty world; throws sp::InvalidArgument for a non-finite gravity, a time step that is
    // not > 0 or a solver iteration count below 1.
    explicit PhysicsWorld(const Settings& settings = Settings());
    ~PhysicsWorld();
    PhysicsWorld(const PhysicsWorld&) = delete;
    PhysicsWorld& operator=(const PhysicsWorld&) = delete;

    // --- Simulation ---

    // Advances time by dt seconds (>= 0): adds dt to an accumulator and runs as many whole fixed
    // substeps as it holds (up to a 1e-9 relative rounding allowance), keeping the remainder for the
    // next call. Returns the number of substeps run. Forces applied since the last substep act during
    // every substep of this call and are cleared once at least one substep ran.
    int step(double dt);
    // Substeps run since construction.
    uint64_t substepCount() const;
    // Simulated time in seconds: substepCount() * fixedTimeStep.
    double simulatedTime() const;
    const Settings& settings() const;
    // Gravity acceleration in m/s^2; applies to every simulated body from the next substep.
    void setGravity(const Eigen::Vector3d& gravity);
    Eigen::Vector3d getGravity() const;

    // --- Bodies ---

    // Creates a body; throws sp::InvalidArgument naming the bad field of desc.
    BodyId addBody(const BodyDesc& desc);
    // Destroys the body and wakes the bodies touching it; its id (and every copy) becomes stale.
    void removeBody(BodyId id);
    // True while id names a body of this world.
    bool isValid(BodyId id) const;
    // Number of bodies in the world.
    size_t bodyCount() const;
    // Ids of all bodies, in slot order.
    std::vector<BodyId> bodies() const;

    // Pose of the body's local frame (its centre of mass) in the world.
    Eigen::Isometry3d getPose(BodyId id) const;
    // Teleports a Movable body (keeps its velocities) and wakes it and the bodies touching it; throws
    // sp::InvalidState for a Static body.
    void setPose(BodyId id, const Eigen::Isometry3d& pose);

    // Velocity in m/s of the centre of mass (zero for static bodies).
    Eigen::Vector3d getLinearVelocity(BodyId id) const;
    // Angular velocity in rad/s, world axes.
    Eigen::Vector3d getAngularVelocity(BodyId id) const;
    // The setters and appliers below need a simulated body and throw sp::InvalidState otherwise; all
    // of them wake the body.
    void setLinearVelocity(BodyId id, const Eigen::Vector3d& velocity);
    void setAngularVelocity(BodyId id, const Eigen::Vector3d& velocity);
    // Adds a force in newtons at the centre of mass for the next step() call.
    void applyForce(BodyId id, const Eigen::Vector3d& force);
    // Adds a force in newtons at a world point for the next step() call (it also adds a torque).
    void applyForce(BodyId id, const Eigen::Vector3d& force, const Eigen::Vector3d& worldPoint);
    // Adds a torque in N*m (world axes) for the next step() call.
    void applyTorque(BodyId id, const Eigen::Vector3d& torque);
    // Changes the velocity at once by impulse / mass (impulse in N*s at the centre of mass).
    void applyImpulse(BodyId id, const Eigen::Vector3d& impulse);
    // Applies an impulse in N*s at a world point, changing linear and angular velocity at once.
    void applyImpulse(BodyId id, const Eigen::Vector3d& impulse, const Eigen::Vector3d& worldPoint);

    // --- Body properties (same meaning and limits as the BodyDesc fields) ---

    Mobility getMobility(BodyId id) const;
    // Makes the body Static or Movable, keeping its pose; a Static body loses its velocities.
    void setMobility(BodyId id, Mobility mobility);
    // True for a Movable body with simulatePhysics set (a dynamic body).
    bool isSimulatingPhysics(BodyId id) const;
    // Switches a Movable body between dynamic and kinematic; for a Static body the flag is only stored.
    void setSimulatePhysics(BodyId id, bool simulate);
    // Mass in kg, kept (and returned) even while the body is static or kinematic.
    double getMass(BodyId id) const;
    // Sets the mass (>= 0, > 0 while simulated); the inertia follows, assuming uniform density.
    void setMass(BodyId id, double mass);
    double getFriction(BodyId id) const;
    // Sets the friction coefficient (>= 0).
    void setFriction(BodyId id, double friction);
    double getRestitution(BodyId id) const;
    // Sets the restitution, in [0, 1].
    void setRestitution(BodyId id, double restitution);
    double getLinearDamping(BodyId id) const;
    // Sets the fraction of linear velocity lost per second, in [0, 1].
    void setLinearDamping(BodyId id, double damping);
    double getAngularDamping(BodyId id) const;
    // Sets the fraction of angular velocity lost per second, in [0, 1].
    void setAngularDamping(BodyId id, double damping);
    uint64_t getTag(BodyId id) const;
    // The shape the body was built from (its scale included), in the body's local frame.
    const Shape& getShape(BodyId id) const;
    // True for a sensor body (BodyDesc::overlapOnly): it reports overlaps and blocks nothing.
    bool isOverlapOnly(BodyId id) const;
    // Sets the value reported in RayHit::tag for this body.
    void setTag(BodyId id, uint64_t tag);
    // False while the body sleeps (Bullet deactivation); static bodies always report false.
    bool isAwake(BodyId id) const;

    // --- Vehicles (core/physics/vehicle.h) ---

    // Makes a simulated body the chassis of a raycast vehicle with desc's wheels, replacing the vehicle it
    // had; its wheels start relaxed and uncontrolled. Throws sp::InvalidArgument naming the bad field of
    // desc, sp::InvalidState for a body that is not simulated. The vehicle acts only while the body is
    // simulated and goes with the body.
    void setVehicle(BodyId chassis, const VehicleDesc& desc);
    // Takes the vehicle off a body (nothing happens for a body without one).
    void removeVehicle(BodyId chassis);
    bool hasVehicle(BodyId chassis) const;
    // Number of wheels of the body's vehicle; throws sp::InvalidState for a body without one.
    int getWheelCount(BodyId chassis) const;
    // Sets what drives a wheel from the next substep on; throws sp::InvalidArgument for a wheel index out
    // of range or a non-finite or negative brake force or a steering angle outside (-pi/2, pi/2).
    void setWheelControls(BodyId chassis, int wheel, const WheelControls& controls);
    WheelState getWheelState(BodyId chassis, int wheel) const;

    // --- Characters (core/physics/character.h) ---
    // Characters have ids of their own (a BodyId names a character here, never a body); every call that
    // takes one throws sp::StaleObject for a removed or unknown character.

    // Creates a character standing (or falling) at desc.position; throws sp::InvalidArgument naming the
    // bad field of desc.
    BodyId addCharacter(const CharacterDesc& desc);
    void removeCharacter(BodyId character);
    bool isValidCharacter(BodyId character) const;
    // Changes the step height, slope and jump speed (radius, height and position must stay as they are:
    // make a new character for another capsule; use setCharacterPosition to move it).
    void setCharacterDesc(BodyId character, const CharacterDesc& desc);
    const CharacterDesc& getCharacterDesc(BodyId character) const;
    // The horizontal velocity (m/s, world axes; the vertical part is ignored) it walks at from the next
    // substep until changed.
    void setCharacterWalkVelocity(BodyId character, const Eigen::Vector3d& velocity);
    // Starts a jump at the jump speed when it stands on the ground; returns whether it jumped.
    bool jumpCharacter(BodyId character);
    // The capsule's centre.
    Eigen::Vector3d getCharacterPosition(BodyId character) const;
    // Moves it there at once (no sweep), keeping its walk velocity; its fall stops.
    void setCharacterPosition(BodyId character, const Eigen::Vector3d& position);
    // Whether it stood on the ground in the last substep (a new character counts as standing until it steps).
    bool isCharacterOnGround(BodyId character) const;
    // Its velocity in the last substep: the walk velocity it managed and its vertical speed.
    Eigen::Vector3d getCharacterVelocity(BodyId character) const;

    // --- Queries ---

    // The closest body hit by the segment from -> to, if any. A zero-length segment hits nothing, and a
    // segment that starts inside a convex shape does not hit that shape.
    std::optional<RayHit> raycast(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;
    // Every body hit by the segment, each at its closest hit, closest first.
    std::vector<RayHit> raycastAll(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;
    // Rays of both kinds pass through overlapOnly bodies (sensors).

    // The bodies whose shapes intersect this body's shape now (touching or penetrating, exact for convex
    // shapes; two concave shapes never overlap), in id order, of any mobility, sensors included; not the
    // body itself.
    std::vector<BodyId> overlaps(BodyId id) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace sp::physics
