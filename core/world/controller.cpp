#include "core/world/controller.h"

#include <algorithm>
#include <cmath>

#include "core/world/pawn.h"
#include "core/world/world.h"

namespace {

void checkFinite(const FRotator& rotation, const char* context) {
    SP_CHECK(std::isfinite(rotation.Pitch) && std::isfinite(rotation.Yaw) && std::isfinite(rotation.Roll),
             sp::InvalidArgument, context, ": rotation (", rotation.Pitch, ", ", rotation.Yaw, ", ",
             rotation.Roll, ") must be finite");
}

void checkFinite(double value, const char* context) {
    SP_CHECK(std::isfinite(value), sp::InvalidArgument, context, ": Val ", value, " must be finite");
}

} // namespace

AController::AController() {
    CreateDefaultSubobject<USceneComponent>("RootComponent");
}

void AController::Possess(APawn* InPawn) {
    constexpr const char* kContext = "AController.Possess()";
    SP_CHECK(InPawn, sp::InvalidArgument, kContext, ": InPawn is None");
    SP_CHECK(InPawn->GetWorld() == GetWorld(), sp::InvalidArgument, kContext, ": ", InPawn->GetDebugName(),
             " is in another world than ", GetDebugName());
    if (K2_GetPawn() == InPawn)
        return;
    UnPossess();
    if (AController* previous = InPawn->GetController())
        previous->UnPossess();
    pawn_ = InPawn->GetHandle();
    InPawn->SetControllerHandle(GetHandle());
    controlRotation_ = InPawn->GetActorRotation();
    OnPossess(InPawn);
}

void AController::UnPossess() {
    if (APawn* pawn = K2_GetPawn())
        pawn->SetControllerHandle({});
    pawn_ = {};
}

APawn* AController::K2_GetPawn() const {
    return dynamic_cast<APawn*>(sp::reflect::ObjectTable::find(pawn_));
}

void AController::SetControlRotation(const FRotator& NewRotation) {
    checkFinite(NewRotation, "AController.SetControlRotation()");
    controlRotation_ = NewRotation;
}

void AController::EndPlay() {
    UnPossess();
    AActor::EndPlay();
}

AActor* APlayerController::GetViewTarget() const {
    if (auto* target = dynamic_cast<AActor*>(sp::reflect::ObjectTable::find(viewTarget_)))
        return target;
    if (APawn* pawn = K2_GetPawn())
        return pawn;
    return const_cast<APlayerController*>(this);
}

void APlayerController::SetViewTargetWithBlend(AActor* NewViewTarget, double BlendTime) {
    constexpr const char* kContext = "APlayerController.SetViewTargetWithBlend()";
    SP_CHECK(std::isfinite(BlendTime) && BlendTime >= 0.0, sp::InvalidArgument, kContext, ": BlendTime ",
             BlendTime, " must be finite and not negative");
    SP_CHECK(!NewViewTarget || NewViewTarget->GetWorld() == GetWorld(), sp::InvalidArgument, kContext, ": ",
             NewViewTarget->GetDebugName(), " is in another world than ", GetDebugName());
    viewTarget_ = NewViewTarget ? NewViewTarget->GetHandle() : sp::reflect::ObjectHandle{};
}

void APlayerController::GetPlayerViewPoint(FVector& Location, FRotator& Rotation) const {
    Location = GetViewTarget()->GetActorLocation();
    Rotation = GetControlRotation();
}

void APlayerController::AddYawInput(double Val) {
    checkFinite(Val, "APlayerController.AddYawInput()");
    FRotator rotation = GetControlRotation();
    rotation.Yaw += Val;
    SetControlRotation(rotation);
}

void APlayerController::AddPitchInput(double Val) {
    checkFinite(Val, "APlayerController.AddPitchInput()");
    FRotator rotation = GetControlRotation();
    rotation.Pitch = std::clamp(rotation.Pitch + Val, -89.0, 89.0);
    SetControlRotation(rotation);
}

void APlayerController::AddRollInput(double Val) {
    checkFinite(Val, "APlayerController.AddRollInput()");
    FRotator rotation = GetControlRotation();
    rotation.Roll += Val;
    SetControlRotation(rotation);
}

void APlayerController::OnPossess(APawn* /*pawn*/) {
    viewTarget_ = {}; // the view follows the new pawn, as UE's default (bAutoManageActiveCameraTarget)
}
