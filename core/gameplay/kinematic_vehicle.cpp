#include "core/gameplay/kinematic_vehicle.h"

#include <algorithm>

AKinematicVehicle::AKinematicVehicle() {
    Body = CreateDefaultSubobject<UStaticMeshComponent>("Body");
    Body->StaticMesh = "/Engine/BasicShapes/Cube";
    Body->RelativeScale3D = {1.0, 0.6, 0.4};
    InputComponent = CreateDefaultSubobject<UInputComponent>("InputComponent");
}

void AKinematicVehicle::Tick(double deltaSeconds) {
    AActor::Tick(deltaSeconds);
    const double throttle = std::clamp(InputComponent->GetActionValue("Throttle").X, -1.0, 1.0);
    const double steer = std::clamp(InputComponent->GetActionValue("Steer").X, -1.0, 1.0);
    const FVector move = InputComponent->GetActionValue("Move");
    if (throttle == 0.0 && steer == 0.0 && move.X == 0.0 && move.Y == 0.0)
        return; // no input: leave the transform untouched (a static vehicle must not be "moved")
    FRotator rotation = GetActorRotation();
    rotation.Yaw += steer * MaxYawRateInDegrees * deltaSeconds;
    const Eigen::Vector3d local(std::clamp(throttle + move.X, -1.0, 1.0), std::clamp(move.Y, -1.0, 1.0), 0.0);
    const Eigen::Vector3d velocity = rotation.toQuaternion() * (local * MaxSpeed);
    K2_SetActorLocationAndRotation(FVector::fromEigen(GetActorLocation().toEigen() + velocity * deltaSeconds),
                                   rotation);
}
