#pragma once
// AWheeledVehiclePawn: a car simulated by Bullet's raycast vehicle (core/physics/vehicle.h). Its chassis
// is a simulated box that collides with the world; four wheels on spring-damper suspensions drive it from
// the "Throttle", "Steer", "Brake" and "Handbrake" input actions (injected for the car or for the
// controller that possesses it). The wheel meshes follow the simulated wheels after every physics step.

#include <array>

#include "core/gameplay/pawn.h"
#include "core/physics/body_id.h"
#include "core/physics/physics_world.h"
#include "core/physics/vehicle.h"
#include "core/world/input_component.h"
#include "core/world/static_mesh_component.h"

/// The state of one wheel of a wheeled vehicle after the last physics step.
SPSTRUCT()
struct FWheelState {
    SP_GENERATED_BODY()

    /// True while the wheel touches the ground.
    SPPROPERTY()
    bool bInContact = false;
    /// The wheel's centre, world space (metres).
    SPPROPERTY()
    FVector Location;
    /// Where the wheel touches the ground, world space (meaningful while bInContact).
    SPPROPERTY()
    FVector ContactPoint;
    /// Suspension length in metres (the rest length less the compression).
    SPPROPERTY()
    double SuspensionLength = 0.0;
    /// Degrees the wheel has rolled (forward is positive).
    SPPROPERTY()
    double RotationInDegrees = 0.0;
    /// Steering angle in degrees, positive to the left.
    SPPROPERTY()
    double SteerAngleInDegrees = 0.0;

    friend bool operator==(const FWheelState&, const FWheelState&) = default;
};

/// A four-wheeled, rear-driven car on Bullet's raycast vehicle. Input actions (X component): "Throttle" in
/// [-1, 1] (negative reverses), "Steer" in [-1, 1] (positive turns left), "Brake" in [0, 1] (all wheels),
/// "Handbrake" in [0, 1] (rear wheels). Its X axis is forward.
SPCLASS()
class AWheeledVehiclePawn : public APawn {
    SP_GENERATED_BODY()
  public:
    AWheeledVehiclePawn();

    /// The chassis (the root component): a simulated box; its scale is the car's size, its mass the car's.
    SPPROPERTY(ReadOnly, NotNull)
    UStaticMeshComponent* Mesh = nullptr;

    /// The cabin on top of the chassis (no collision: the chassis box is the car's body).
    SPPROPERTY(ReadOnly, NotNull)
    UStaticMeshComponent* Cabin = nullptr;

    /// The wheel meshes, which follow the simulated wheels (no collision: the wheels are rays).
    SPPROPERTY(ReadOnly, NotNull)
    UStaticMeshComponent* WheelFrontLeft = nullptr;
    SPPROPERTY(ReadOnly, NotNull)
    UStaticMeshComponent* WheelFrontRight = nullptr;
    SPPROPERTY(ReadOnly, NotNull)
    UStaticMeshComponent* WheelRearLeft = nullptr;
    SPPROPERTY(ReadOnly, NotNull)
    UStaticMeshComponent* WheelRearRight = nullptr;

    /// Receives the injected actions.
    SPPROPERTY(ReadOnly, NotNull)
    UInputComponent* InputComponent = nullptr;

    /// Driving force in newtons at full throttle, shared by the rear wheels (>= 0).
    SPPROPERTY(Setter = SetMaxEngineForce)
    double MaxEngineForce = 6000.0;

    /// Braking force in newtons per wheel at full brake (>= 0).
    SPPROPERTY(Setter = SetMaxBrakeForce)
    double MaxBrakeForce = 4000.0;

    /// Front wheels' steering angle in degrees at full steer, in [0, 80].
    SPPROPERTY(Setter = SetMaxSteerAngle, meta = (ClampMin = 0, ClampMax = 80))
    double MaxSteerAngle = 35.0;

    /// Tyre radius in metres (> 0).
    SPPROPERTY(Setter = SetWheelRadius)
    double WheelRadius = 0.35;

    /// Suspension spring rate per kilogram of the car's mass, N/m/kg (> 0): the car sinks
    /// 9.81 / (4 * SuspensionStiffness) metres under its weight.
    SPPROPERTY(Setter = SetSuspensionStiffness)
    double SuspensionStiffness = 40.0;

    /// Tyre grip: the largest driving and cornering force over the load on the wheel (>= 0).
    SPPROPERTY(Setter = SetTireFriction)
    double TireFriction = 1.5;

    /// Sets MaxEngineForce (newtons, >= 0).
    SPFUNCTION()
    void SetMaxEngineForce(double NewForce);
    /// Sets MaxBrakeForce (newtons, >= 0).
    SPFUNCTION()
    void SetMaxBrakeForce(double NewForce);
    /// Sets MaxSteerAngle (degrees, in [0, 80]).
    SPFUNCTION()
    void SetMaxSteerAngle(double NewAngle);
    /// Sets WheelRadius (metres, > 0).
    SPFUNCTION()
    void SetWheelRadius(double NewRadius);
    /// Sets SuspensionStiffness (N/m/kg, > 0).
    SPFUNCTION()
    void SetSuspensionStiffness(double NewStiffness);
    /// Sets TireFriction (>= 0).
    SPFUNCTION()
    void SetTireFriction(double NewFriction);

    /// Returns the speed along the car's forward axis in metres per second (negative when reversing).
    SPFUNCTION()
    double GetForwardSpeed() const;

    /// Returns the number of wheels.
    SPFUNCTION()
    int GetNumWheels() const { return int(Wheels.size()); }

    /// Returns the state of wheel WheelIndex (0 front left, 1 front right, 2 rear left, 3 rear right).
    SPFUNCTION()
    FWheelState GetWheelState(int WheelIndex) const;

    void BeginPlay() override;
    void Tick(double deltaSeconds) override;
    void EndPlay() override;

    // Moves the wheel meshes to the simulated wheels.
    void PostPhysicsTick() override;

    // Sets the controls for the next physics step (clamped as the input actions are): what Tick does from
    // the input actions, and what a controller that drives the car directly calls after the actors ticked.
    void ApplyControls(double throttle, double steer, double brake, double handbrake);

  private:
    // The vehicle as the properties describe it, for the chassis' current size.
    sp::physics::VehicleDesc describe() const;
    // Puts the wheel meshes where the simulated wheels are, or at rest under the chassis (physics null).
    void placeWheelMeshes(const sp::physics::PhysicsWorld* physics);
    // The chassis body with this car's vehicle on it, set up or rebuilt when the body or the properties
    // changed; an unset id while the chassis is not simulated.
    sp::physics::BodyId vehicleBody(const char* function);

    // The wheel meshes in GetWheelState's order.
    std::array<UStaticMeshComponent*, 4> Wheels{};
    sp::physics::BodyId body_;
    sp::physics::VehicleDesc desc_;
};
