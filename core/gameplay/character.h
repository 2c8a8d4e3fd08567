#pragma once
// ACharacter: a pawn that walks (UE's Character). Its root is a UCapsuleComponent; its
// UCharacterMovementComponent walks it on Bullet's kinematic character controller (core/physics/
// character.h): along the floor at MaxWalkSpeed, up steps to MaxStepHeight and slopes to
// WalkableFloorAngle, stopped by walls, falling with gravity, jumping at JumpZVelocity.
// Input actions (X component, for the character or the controller that possesses it): "MoveForward" and
// "MoveRight" in [-1, 1] along the control rotation's yaw, "Turn" and "LookUp" turn the controller's view,
// "Jump" > 0 jumps; AddMovementInput adds to the walk.

#include <limits>

#include "core/animation/skeletal_mesh_component.h"
#include "core/gameplay/pawn.h"
#include "core/physics/body_id.h"
#include "core/physics/character.h"
#include "core/world/actor_component.h"
#include "core/world/input_component.h"
#include "core/world/shape_components.h"

/// How a character walks, and how it is moving.
SPCLASS()
class UCharacterMovementComponent : public UActorComponent {
    SP_GENERATED_BODY()
  public:
    /// Walking speed in m/s at full input (>= 0).
    SPPROPERTY(Setter = SetMaxWalkSpeed)
    double MaxWalkSpeed = 6.0;

    /// Upward speed of a jump in m/s (>= 0): a jump rises JumpZVelocity^2 / 2g.
    SPPROPERTY(Setter = SetJumpZVelocity)
    double JumpZVelocity = 4.2;

    /// The highest step the character walks up, in metres (>= 0).
    SPPROPERTY(Setter = SetMaxStepHeight)
    double MaxStepHeight = 0.45;

    /// The steepest floor the character walks up, in degrees (in (0, 90)).
    SPPROPERTY(Setter = SetWalkableFloorAngle)
    double WalkableFloorAngle = 44.765;

    /// Sets MaxWalkSpeed (m/s, >= 0).
    SPFUNCTION()
    void SetMaxWalkSpeed(double NewSpeed);
    /// Sets JumpZVelocity (m/s, >= 0).
    SPFUNCTION()
    void SetJumpZVelocity(double NewVelocity);
    /// Sets MaxStepHeight (metres, >= 0).
    SPFUNCTION()
    void SetMaxStepHeight(double NewHeight);
    /// Sets WalkableFloorAngle (degrees, in (0, 90)).
    SPFUNCTION()
    void SetWalkableFloorAngle(double NewAngle);

    /// Returns the velocity over the last physics step, m/s (walking and falling).
    SPFUNCTION()
    FVector GetVelocity() const;

    /// Returns true while the character stands on the ground.
    SPFUNCTION()
    bool IsMovingOnGround() const;

    /// Returns true while the character is in the air (jumping or falling).
    SPFUNCTION()
    bool IsFalling() const { return !IsMovingOnGround(); }
};

/// A pawn that walks, climbs steps, jumps and falls, with UE's Character names.
SPCLASS()
class ACharacter : public APawn {
    SP_GENERATED_BODY()
  public:
    ACharacter();

    /// The collision capsule (the root component); its size is the character's.
    SPPROPERTY(ReadOnly, NotNull)
    UCapsuleComponent* CapsuleComponent = nullptr;

    /// The character's visible body (no collision of its own): by default the built-in humanoid
    /// (/Game/characters/humanoid.glb) with its feet at the capsule's bottom, playing a blend space of its
    /// idle, walk and run clips by the speed it moves at, its body turned to where it walks.
    SPPROPERTY(ReadOnly, NotNull)
    USkeletalMeshComponent* Mesh = nullptr;

    /// How the character walks.
    SPPROPERTY(ReadOnly, NotNull)
    UCharacterMovementComponent* CharacterMovement = nullptr;

    /// Receives the injected actions.
    SPPROPERTY(ReadOnly, NotNull)
    UInputComponent* InputComponent = nullptr;

    /// Jumps at the next physics step if the character stands on the ground.
    SPFUNCTION()
    void Jump();

    /// Ends a jump request that has not started yet.
    SPFUNCTION()
    void StopJumping() { jumpPressed_ = false; }

    /// Returns true when the character could jump now (it stands on the ground).
    SPFUNCTION()
    bool CanJump() const;

    /// Returns the character's movement component (UE's GetCharacterMovement).
    SPFUNCTION()
    UCharacterMovementComponent* GetCharacterMovement() const { return CharacterMovement; }

    void BeginPlay() override;
    void Tick(double deltaSeconds) override;
    void EndPlay() override;
    double GetMovementSpeed() const override { return CharacterMovement->MaxWalkSpeed; }
    bool IsWalking() const override { return true; }
    double GetAgentRadius() const override;
    // Brings the physics character in line with the actor just before the step (a teleport by anyone this
    // frame, changed settings).
    void PrePhysicsTick() override;
    // Moves the capsule to where the physics step left the character.
    void PostPhysicsTick() override;

    // The physics character, made on first use and remade when the capsule's size changed; unset while
    // the character is not in play.
    sp::physics::BodyId PhysicsCharacter(const char* function) const;

  private:
    sp::physics::CharacterDesc describe() const;
    // The body's animation from how the character moved since the last tick: the blend space's input (its
    // horizontal speed) and the body's heading.
    void animateBody(double deltaSeconds);

    mutable sp::physics::BodyId character_;
    // Where the capsule was put after the last step: a different location means someone moved it.
    mutable FVector placed_;
    bool jumpPressed_ = false;
    // For the body's animation: where the character was at the last tick, and its smoothed horizontal speed.
    Eigen::Vector3d lastLocation_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    double speed_ = 0.0;
};
