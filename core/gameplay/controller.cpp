#include "core/gameplay/controller.h"

#include <algorithm>
#include <cmath>

#include "core/gameplay/navigation_system.h"
#include "core/gameplay/pawn.h"
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

std::optional<const AActor*> AController::GetInputForwardTarget() const {
    return K2_GetPawn();
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

// -- AAIController -----------------------------------------------------------------------------------

FVector AAIController::goalLocation() const {
    if (const auto* goal = dynamic_cast<const AActor*>(sp::reflect::ObjectTable::find(goalActor_)))
        return goal->GetActorLocation();
    return destination_;
}

bool AAIController::arrived(const APawn& pawn, Eigen::Vector3d& offset) const {
    offset = goalLocation().toEigen() - pawn.GetActorLocation().toEigen();
    if (pawn.IsWalking())
        offset.z() = 0.0;
    return offset.norm() <= stopDistance(pawn);
}

double AAIController::stopDistance(const APawn& pawn) const {
    return acceptanceRadius_ + (stopOnOverlap_ ? pawn.GetAgentRadius() : 0.0);
}

void AAIController::checkAcceptanceRadius(double radius, const char* function) {
    // Checked before anything is changed: a refused request leaves the move in progress as it was.
    SP_CHECK(std::isfinite(radius) && radius >= 0.0, sp::InvalidArgument, "AAIController.", function,
             "(): AcceptanceRadius ", radius, " must be >= 0");
}

EPathFollowingRequestResult AAIController::start(bool usePathfinding) {
    moving_ = false;
    followingPath_ = false;
    const APawn* pawn = K2_GetPawn();
    if (!pawn)
        return EPathFollowingRequestResult::Failed;
    Eigen::Vector3d offset;
    if (arrived(*pawn, offset))
        return EPathFollowingRequestResult::AlreadyAtGoal;
    ARecastNavMesh* navigation =
        usePathfinding && pawn->IsWalking() ? sp::gameplay::defaultNavigationIfAny(*GetWorld()) : nullptr;
    if (navigation) {
        if (!planPath(*pawn, *navigation))
            return EPathFollowingRequestResult::Failed;
        followingPath_ = true;
    }
    moving_ = true;
    return EPathFollowingRequestResult::RequestSuccessful;
}

bool AAIController::planPath(const APawn& pawn, ARecastNavMesh& navigation) {
    const sp::navigation::Path path =
        navigation.findPath(pawn.GetActorLocation(), goalLocation(), "AAIController.MoveToLocation()");
    if (path.points.empty())
        return false;
    path_.assign(path.points.begin() + 1, path.points.end());
    nextCorner_ = 0;
    plannedGoal_ = goalLocation();
    return true;
}

bool AAIController::advanceOnPath(const APawn& pawn) {
    // A goal actor that left the path's end by a metre is planned for again (the move ends when the
    // navigation data went away meanwhile).
    if (!goalActor_.isNull() && (goalLocation().toEigen() - plannedGoal_.toEigen()).norm() > 1.0) {
        ARecastNavMesh* navigation = sp::gameplay::defaultNavigationIfAny(*GetWorld());
        if (!navigation || !planPath(pawn, *navigation))
            return false;
    }
    const Eigen::Vector3d at = pawn.GetActorLocation().toEigen();
    // Corners count as reached within a step's length (at least 10 cm), horizontally.
    const double reach = std::max(0.1, pawn.GetMovementSpeed() * 0.05);
    while (nextCorner_ + 1 < path_.size() && (path_[nextCorner_] - at).head<2>().norm() <= reach)
        ++nextCorner_;
    if (nextCorner_ + 1 < path_.size())
        return true;
    return !path_.empty() && (path_.back() - at).head<2>().norm() > stopDistance(pawn);
}

EPathFollowingRequestResult AAIController::MoveToLocation(const FVector& Dest, double AcceptanceRadius,
                                                          bool bStopOnOverlap, bool bUsePathfinding) {
    SP_CHECK(Dest.isFinite(), sp::InvalidArgument, "AAIController.MoveToLocation(): Dest must be finite");
    checkAcceptanceRadius(AcceptanceRadius, "MoveToLocation");
    destination_ = Dest;
    goalActor_ = {};
    acceptanceRadius_ = AcceptanceRadius;
    stopOnOverlap_ = bStopOnOverlap;
    return start(bUsePathfinding);
}

EPathFollowingRequestResult AAIController::MoveToActor(AActor* Goal, double AcceptanceRadius,
                                                       bool bStopOnOverlap, bool bUsePathfinding) {
    checkAcceptanceRadius(AcceptanceRadius, "MoveToActor");
    moving_ = false;
    if (!Goal)
        return EPathFollowingRequestResult::Failed;
    SP_CHECK(Goal->GetWorld() == GetWorld(), sp::InvalidArgument,
             "AAIController.MoveToActor(): ", Goal->GetDebugName(), " is in another world than ",
             GetDebugName());
    goalActor_ = Goal->GetHandle();
    destination_ = Goal->GetActorLocation();
    acceptanceRadius_ = AcceptanceRadius;
    stopOnOverlap_ = bStopOnOverlap;
    return start(bUsePathfinding);
}

void AAIController::StopMovement() {
    moving_ = false;
}

FVector AAIController::GetImmediateMoveDestination() const {
    if (moving_ && followingPath_ && nextCorner_ < path_.size())
        return FVector::fromEigen(path_[nextCorner_]);
    if (moving_)
        return goalLocation();
    const APawn* pawn = K2_GetPawn();
    return pawn ? pawn->GetActorLocation() : GetActorLocation();
}

void AAIController::Tick(double deltaSeconds) {
    AController::Tick(deltaSeconds);
    APawn* pawn = K2_GetPawn();
    if (!moving_ || !pawn)
        return;
    if (!goalActor_.isNull() && !sp::reflect::ObjectTable::find(goalActor_)) {
        moving_ = false; // the goal actor is gone
        return;
    }
    Eigen::Vector3d offset;
    if (arrived(*pawn, offset)) {
        moving_ = false;
        return;
    }
    if (followingPath_) {
        if (!advanceOnPath(*pawn)) {
            moving_ = false; // at the path's end (for an unreachable goal, as near as the mesh allows)
            return;
        }
        offset = path_[nextCorner_] - pawn->GetActorLocation().toEigen();
        offset.z() = 0.0;
    }
    // Face where it goes, and ask for the input that covers the rest in this step, at most a full unit (the
    // pawn's own speed): the last step lands on the goal instead of passing it.
    const double speed = pawn->GetMovementSpeed();
    SetControlRotation(FRotator{GetControlRotation().Pitch, std::atan2(offset.y(), offset.x()) * 180.0 / M_PI,
                                GetControlRotation().Roll});
    const double reach = speed * deltaSeconds;
    const double scale = reach > 0.0 ? std::min(1.0, offset.norm() / reach) : 1.0;
    pawn->AddMovementInput(FVector::fromEigen(offset.normalized()), scale);
}
