#include "core/gameplay/pawn.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/gameplay/controller.h"

APawn::APawn() {
    CreateDefaultSubobject<USceneComponent>("RootComponent");
}

AController* APawn::GetController() const {
    auto* controller = dynamic_cast<AController*>(sp::reflect::ObjectTable::find(controller_));
    // The link is two-sided: a controller that has since possessed another pawn no longer controls this one.
    return controller && controller->K2_GetPawn() == this ? controller : nullptr;
}

bool APawn::IsPlayerControlled() const {
    const AController* controller = GetController();
    return controller && controller->IsPlayerController();
}

FRotator APawn::GetControlRotation() const {
    const AController* controller = GetController();
    return controller ? controller->GetControlRotation() : GetActorRotation();
}

void APawn::AddMovementInput(const FVector& WorldDirection, double ScaleValue) {
    SP_CHECK(WorldDirection.isFinite() && std::isfinite(ScaleValue), sp::InvalidArgument,
             "APawn.AddMovementInput(): WorldDirection and ScaleValue must be finite");
    pendingMovement_ = FVector::fromEigen(pendingMovement_.toEigen() + WorldDirection.toEigen() * ScaleValue);
}

void APawn::TurnControllerView(double yawAxis, double pitchAxis, double yawRate, double pitchRate,
                               double deltaSeconds) {
    AController* controller = GetController();
    if (!controller)
        return;
    FRotator control = controller->GetControlRotation();
    control.Yaw += yawAxis * yawRate * deltaSeconds;
    control.Pitch = std::clamp(control.Pitch + pitchAxis * pitchRate * deltaSeconds, -89.0, 89.0);
    if (!(control == controller->GetControlRotation()))
        controller->SetControlRotation(control);
}

FVector APawn::ConsumeMovementInput() {
    return std::exchange(pendingMovement_, FVector{});
}

void APawn::Tick(double deltaSeconds) {
    AActor::Tick(deltaSeconds);
    const AController* controller = GetController();
    if (!controller ||
        !(bUseControllerRotationPitch || bUseControllerRotationYaw || bUseControllerRotationRoll))
        return;
    const FRotator control = controller->GetControlRotation();
    FRotator rotation = GetActorRotation();
    const FRotator before = rotation;
    if (bUseControllerRotationPitch)
        rotation.Pitch = control.Pitch;
    if (bUseControllerRotationYaw)
        rotation.Yaw = control.Yaw;
    if (bUseControllerRotationRoll)
        rotation.Roll = control.Roll;
    if (!(rotation == before)) // an unchanged pawn is not "moved" (a static root must stay untouched)
        SetActorRotation(rotation);
}

void APawn::EndPlay() {
    if (AController* controller = GetController())
        controller->UnPossess();
    AActor::EndPlay();
}

ADefaultPawn::ADefaultPawn() {
    InputComponent = CreateDefaultSubobject<UInputComponent>("InputComponent");
}

void ADefaultPawn::Tick(double deltaSeconds) {
    APawn::Tick(deltaSeconds);
    const auto axis = [this](const char* action) {
        return std::clamp(InputComponent->GetActionValue(action).X, -1.0, 1.0);
    };
    TurnControllerView(axis("Turn"), axis("LookUp"), BaseTurnRate, BaseLookUpRate, deltaSeconds);
    // Forward follows the view (pitch included, as a flying camera does); right stays level; up is world up.
    const FRotator view = GetControlRotation();
    const Eigen::Vector3d forward = view.toQuaternion() * Eigen::Vector3d::UnitX();
    const Eigen::Vector3d right = FRotator{0.0, view.Yaw, 0.0}.toQuaternion() * -Eigen::Vector3d::UnitY();
    Eigen::Vector3d input = forward * axis("MoveForward") + right * axis("MoveRight") +
                            Eigen::Vector3d::UnitZ() * axis("MoveUp") + ConsumeMovementInput().toEigen();
    if (input.isZero())
        return; // no input: leave the transform untouched
    if (input.norm() > 1.0)
        input.normalize();
    SetActorLocation(FVector::fromEigen(GetActorLocation().toEigen() + input * MaxSpeed * deltaSeconds));
}
