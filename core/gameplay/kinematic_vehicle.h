#pragma once
// AKinematicVehicle: an actor driven by injected input that moves kinematically in its Tick (no wheels,
// tyres or mass: it goes where its input says, through walls and over what is in its way, like a mobile
// robot base commanded by velocity). AWheeledVehiclePawn (wheeled_vehicle.h) is the simulated car.
// "Throttle" (X in [-1, 1]) drives along its forward axis, "Steer" (X in [-1, 1], positive turns left) yaws
// it, and "Move" (X forward, Y left, in [-1, 1]) drives it sideways too.

#include "core/world/actor.h"
#include "core/world/input_component.h"
#include "core/world/static_mesh_component.h"

/// A box-shaped vehicle moved kinematically (not simulated: it passes through geometry) by the "Throttle",
/// "Steer" and "Move" input actions. For a car simulated with wheels, see AWheeledVehiclePawn.
SPCLASS()
class AKinematicVehicle : public AActor {
    SP_GENERATED_BODY()
  public:
    AKinematicVehicle();

    /// The vehicle's body (the root component).
    SPPROPERTY(ReadOnly, NotNull)
    UStaticMeshComponent* Body = nullptr;

    /// Receives the injected actions.
    SPPROPERTY(ReadOnly, NotNull)
    UInputComponent* InputComponent = nullptr;

    /// Speed in metres per second at full throttle.
    SPPROPERTY()
    double MaxSpeed = 2.0;

    /// Yaw rate in degrees per second at full steering.
    SPPROPERTY()
    double MaxYawRateInDegrees = 90.0;

    void Tick(double deltaSeconds) override;
};
