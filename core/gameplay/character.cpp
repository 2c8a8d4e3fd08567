#include "core/gameplay/character.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/base/error.h"
#include "core/world/physics_hooks.h"
#include "core/world/physics_subsystem.h"
#include "core/world/world.h"

namespace {

sp::physics::PhysicsWorld& physicsOf(const AActor& actor) {
    return actor.GetWorld()->GetSubsystem<sp::world::PhysicsSubsystem>().GetPhysicsWorld();
}

const ACharacter* characterOf(const UCharacterMovementComponent& movement) {
    const auto* character = dynamic_cast<const ACharacter*>(movement.GetOwner());
    return character && character->HasBegunPlay() ? character : nullptr;
}

} // namespace

// -- UCharacterMovementComponent -------------------------------------------------------------------

void UCharacterMovementComponent::SetMaxWalkSpeed(double NewSpeed) {
    sp::checkSetting(std::isfinite(NewSpeed) && NewSpeed >= 0.0, "UCharacterMovementComponent",
                     "MaxWalkSpeed", ">= 0", NewSpeed);
    MaxWalkSpeed = NewSpeed;
}
void UCharacterMovementComponent::SetJumpZVelocity(double NewVelocity) {
    sp::checkSetting(std::isfinite(NewVelocity) && NewVelocity >= 0.0, "UCharacterMovementComponent",
                     "JumpZVelocity", ">= 0", NewVelocity);
    JumpZVelocity = NewVelocity;
}
void UCharacterMovementComponent::SetMaxStepHeight(double NewHeight) {
    sp::checkSetting(std::isfinite(NewHeight) && NewHeight >= 0.0, "UCharacterMovementComponent",
                     "MaxStepHeight", ">= 0", NewHeight);
    MaxStepHeight = NewHeight;
}
void UCharacterMovementComponent::SetWalkableFloorAngle(double NewAngle) {
    sp::checkSetting(std::isfinite(NewAngle) && NewAngle > 0.0 && NewAngle < 90.0,
                     "UCharacterMovementComponent", "WalkableFloorAngle", "in (0, 90) degrees", NewAngle);
    WalkableFloorAngle = NewAngle;
}

FVector UCharacterMovementComponent::GetVelocity() const {
    const ACharacter* character = characterOf(*this);
    if (!character)
        return {};
    return FVector::fromEigen(
        physicsOf(*character).getCharacterVelocity(character->PhysicsCharacter("GetVelocity")));
}

bool UCharacterMovementComponent::IsMovingOnGround() const {
    const ACharacter* character = characterOf(*this);
    return character &&
           physicsOf(*character).isCharacterOnGround(character->PhysicsCharacter("IsMovingOnGround"));
}

// -- ACharacter --------------------------------------------------------------------------------------

ACharacter::ACharacter() : APawn(NoDefaultRoot{}) {
    CapsuleComponent = CreateDefaultSubobject<UCapsuleComponent>("CapsuleComponent");
    Mesh = CreateDefaultSubobject<USkeletalMeshComponent>("Mesh");
    // Named, not loaded: the file is read when play begins (a class default must not need the assets).
    Mesh->SkeletalMesh = "/Game/characters/humanoid.glb";
    Mesh->AnimationMode = EAnimationMode::AnimationBlendSpace;
    // The humanoid's clips at the speeds their feet move at (walk: two 0.69 m steps in 1.1 s).
    Mesh->BlendSpace = {{"idle", 0.0}, {"walk", 1.25}, {"run", 3.2}};
    Mesh->CollisionPrimitive = ECollisionPrimitive::NoCollision; // the capsule is the character's shape
    CharacterMovement = CreateDefaultSubobject<UCharacterMovementComponent>("CharacterMovement");
    InputComponent = CreateDefaultSubobject<UInputComponent>("InputComponent");
}

sp::physics::CharacterDesc ACharacter::describe() const {
    sp::physics::CharacterDesc desc;
    desc.radius = GetAgentRadius();
    desc.halfHeight = std::max(
        CapsuleComponent->CapsuleHalfHeight * std::abs(CapsuleComponent->GetComponentScale().Z), desc.radius);
    desc.position = GetActorLocation().toEigen();
    desc.stepHeight = CharacterMovement->MaxStepHeight;
    desc.maxSlopeDegrees = CharacterMovement->WalkableFloorAngle;
    desc.jumpSpeed = CharacterMovement->JumpZVelocity;
    return desc;
}

sp::physics::BodyId ACharacter::PhysicsCharacter(const char* function) const {
    SP_CHECK(HasBegunPlay() && GetWorld(), sp::InvalidState, "ACharacter.", function, "(): ", GetDebugName(),
             " is not in play");
    sp::physics::PhysicsWorld& physics = physicsOf(*this);
    const sp::physics::CharacterDesc desc = describe();
    if (character_.isSet() && physics.isValidCharacter(character_)) {
        const sp::physics::CharacterDesc& current = physics.getCharacterDesc(character_);
        if (current.radius != desc.radius || current.halfHeight != desc.halfHeight) {
            physics.removeCharacter(character_); // another capsule: a new character, where this one was
            character_ = {};
        } else if (current.stepHeight != desc.stepHeight || current.maxSlopeDegrees != desc.maxSlopeDegrees ||
                   current.jumpSpeed != desc.jumpSpeed) {
            physics.setCharacterDesc(character_, desc);
        }
    }
    if (!character_.isSet() || !physics.isValidCharacter(character_)) {
        character_ = physics.addCharacter(desc);
        placed_ = GetActorLocation();
    }
    if (!(GetActorLocation() == placed_)) { // moved by someone since the last step: teleport
        physics.setCharacterPosition(character_, GetActorLocation().toEigen());
        placed_ = GetActorLocation();
    }
    return character_;
}

double ACharacter::GetAgentRadius() const {
    const Eigen::Vector3d scale = CapsuleComponent->GetComponentScale().toEigen().cwiseAbs();
    return CapsuleComponent->CapsuleRadius * std::max(scale.x(), scale.y());
}

void ACharacter::Jump() {
    jumpPressed_ = true;
}

bool ACharacter::CanJump() const {
    return HasBegunPlay() && physicsOf(*this).isCharacterOnGround(PhysicsCharacter("CanJump"));
}

void ACharacter::BeginPlay() {
    APawn::BeginPlay();
    GetWorld()->GetSubsystem<sp::world::PhysicsHooks>().add(*this);
    PhysicsCharacter("BeginPlay");
    PostPhysicsTick();
}

void ACharacter::EndPlay() {
    if (auto* subsystem = GetWorld()->FindSubsystem<sp::world::PhysicsHooks>())
        subsystem->remove(*this);
    if (auto* physics = GetWorld()->FindSubsystem<sp::world::PhysicsSubsystem>())
        if (character_.isSet() && physics->GetPhysicsWorld().isValidCharacter(character_))
            physics->GetPhysicsWorld().removeCharacter(character_);
    character_ = {};
    APawn::EndPlay();
}

void ACharacter::Tick(double deltaSeconds) {
    APawn::Tick(deltaSeconds);
    const sp::physics::BodyId id = PhysicsCharacter("Tick");
    const auto axis = [this](const char* action) {
        return std::clamp(InputComponent->GetActionValue(action).X, -1.0, 1.0);
    };
    TurnControllerView(axis("Turn"), axis("LookUp"), 45.0, 45.0, deltaSeconds); // ADefaultPawn's rates
    // Walking follows the view's heading; the walk is horizontal whatever the pitch.
    const double yaw = GetControlRotation().Yaw * std::numbers::pi / 180.0;
    const Eigen::Vector3d forward(std::cos(yaw), std::sin(yaw), 0.0),
        right(std::sin(yaw), -std::cos(yaw), 0.0);
    Eigen::Vector3d input =
        forward * axis("MoveForward") + right * axis("MoveRight") + ConsumeMovementInput().toEigen();
    input.z() = 0.0;
    if (input.norm() > 1.0)
        input.normalize();
    sp::physics::PhysicsWorld& physics = physicsOf(*this);
    physics.setCharacterWalkVelocity(id, input * CharacterMovement->MaxWalkSpeed);
    if (jumpPressed_ || axis("Jump") > 0.0) {
        physics.jumpCharacter(id);
        jumpPressed_ = false;
    }
    animateBody(deltaSeconds);
}

void ACharacter::PrePhysicsTick() {
    PhysicsCharacter("PrePhysicsTick");
}

void ACharacter::PostPhysicsTick() {
    if (!character_.isSet() || !physicsOf(*this).isValidCharacter(character_))
        return;
    const FVector position = FVector::fromEigen(physicsOf(*this).getCharacterPosition(character_));
    if (!(position == GetActorLocation()))
        CapsuleComponent->SetWorldLocation(position);
    placed_ = GetActorLocation();
    // The body stands on the capsule's bottom.
    const double feet = -std::max(CapsuleComponent->CapsuleHalfHeight, CapsuleComponent->CapsuleRadius);
    if (Mesh->RelativeLocation.Z != feet || Mesh->RelativeLocation.X != 0.0 ||
        Mesh->RelativeLocation.Y != 0.0)
        Mesh->SetRelativeLocation(FVector{0.0, 0.0, feet});
}

namespace {
// Metres a second past which a move between two ticks is a teleport, not a walk (a sprinter does 12).
constexpr double kTeleportSpeed = 20.0;
} // namespace

void ACharacter::animateBody(double deltaSeconds) {
    const Eigen::Vector3d location = GetActorLocation().toEigen();
    const Eigen::Vector3d moved = location - lastLocation_;
    lastLocation_ = location;
    if (deltaSeconds <= 0.0 || !moved.allFinite())
        return; // the first tick: no speed yet
    // The horizontal speed, smoothed over about a tenth of a second: a step up or a stop does not snap the
    // legs.
    const Eigen::Vector3d velocity(moved.x() / deltaSeconds, moved.y() / deltaSeconds, 0.0);
    // Faster than anything walks (a teleport, SetActorLocation): no speed to animate, no heading to turn to.
    if (velocity.norm() > kTeleportSpeed)
        return;
    speed_ += (velocity.norm() - speed_) * std::min(1.0, deltaSeconds / 0.1);
    // Faces where it walks: the body turns (at up to 720 degrees a second) while the capsule, round, keeps
    // the controller's rotation.
    if (velocity.norm() > 0.2) {
        const double heading = std::atan2(velocity.y(), velocity.x()) * 180.0 / std::numbers::pi;
        const double relative =
            std::remainder(heading - GetActorRotation().Yaw - Mesh->RelativeRotation.Yaw, 360.0);
        const double turn = std::clamp(relative, -720.0 * deltaSeconds, 720.0 * deltaSeconds);
        if (turn != 0.0)
            Mesh->SetRelativeRotation(
                FRotator{0.0, std::remainder(Mesh->RelativeRotation.Yaw + turn, 360.0), 0.0});
    }
    if (Mesh->AnimationMode == EAnimationMode::AnimationBlendSpace && Mesh->blendSpaceReady())
        Mesh->SetBlendSpaceInput(speed_);
}
