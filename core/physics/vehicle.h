#pragma once
// Wheeled vehicles on Bullet's raycast vehicle: the chassis is an ordinary simulated body and each wheel
// is a ray cast down from the chassis with a spring-damper suspension and a tyre friction model, so a car
// drives on any static or dynamic geometry and its chassis collides like every other body.
//
// Frames: the chassis body's local frame has X forward, Y left and Z up (the engine's convention); wheels
// hang along -Z and roll about the Y axis.

#include <vector>

#include <Eigen/Geometry>

namespace sp::physics {

struct WheelDesc {
    // Where the suspension is attached, in the chassis body's frame (inside the chassis shape, so that the
    // wheel's ray does not hit its own chassis).
    Eigen::Vector3d connectionPoint = Eigen::Vector3d::Zero();
    // Tyre radius in metres, > 0.
    double radius = 0.35;
    // Whether WheelControls::steering turns this wheel (front wheels of a car).
    bool steered = false;

    bool operator==(const WheelDesc&) const = default;
};

struct VehicleDesc {
    std::vector<WheelDesc> wheels; // at least one
    // Suspension length with no load, metres (>= 0); the wheel's centre hangs this far below its
    // connection point when the spring is relaxed.
    double suspensionRestLength = 0.25;
    // Spring rate per kilogram of chassis mass, N/m/kg (> 0): a wheel pushes with
    // stiffness * mass * compression, so a car of any mass sinks the same under gravity.
    double suspensionStiffness = 40.0;
    // Damping per kilogram of chassis mass while the spring compresses and while it extends, N*s/m/kg (>= 0).
    double suspensionCompressionDamping = 5.0;
    double suspensionRelaxationDamping = 7.5;
    // How far the suspension may move from its rest length either way, metres (>= 0).
    double maxSuspensionTravel = 0.2;
    // The largest force one suspension pushes with, newtons (> 0).
    double maxSuspensionForce = 1e5;
    // Tyre grip: the largest sideways and driving impulse a wheel transmits, relative to its suspension
    // load (>= 0).
    double frictionSlip = 1.5;
    // How much of a wheel's sideways impulse acts at the contact height rather than the chassis' centre of
    // mass, in [0, 1]: lower values make the car less likely to roll over.
    double rollInfluence = 0.1;

    bool operator==(const VehicleDesc&) const = default;
};

// What drives one wheel until it is changed.
struct WheelControls {
    double engineForce = 0.0; // newtons along the wheel's heading (negative: backwards)
    double brakeForce = 0.0;  // newtons (>= 0) resisting the wheel's rolling; ignored while engineForce != 0
    double steering = 0.0;    // radians about the chassis' Z axis, positive turns left (steered wheels only)
};

struct WheelState {
    // The wheel's centre and orientation in the world: X along its heading, Y along its axle, spun by
    // `rotation` about Y.
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    // The same, in the chassis body's frame.
    Eigen::Isometry3d poseInChassis = Eigen::Isometry3d::Identity();
    bool inContact = false;
    // Where the wheel's ray met the ground (meaningful while inContact), world coordinates.
    Eigen::Vector3d contactPoint = Eigen::Vector3d::Zero();
    double suspensionLength = 0.0; // metres
    double rotation = 0.0;         // radians rolled since the vehicle was made (forward is positive)
    double steering = 0.0;         // radians, as set by WheelControls
};

} // namespace sp::physics
