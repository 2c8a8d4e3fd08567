#pragma once
// APawn: an actor that a controller (a player's or an AI's) can possess. The controller owns the control
// rotation (where the player looks); the pawn follows it on the axes its bUseControllerRotation* flags
// name, each tick. ADefaultPawn: a pawn that flies where its input says, like UE's DefaultPawn.
//
// Pawn and controller refer to each other by handle, not pointer: either may be destroyed first, and a
// stale link simply reads as "none".

#include "core/reflect/object_base.h"
#include "core/world/actor.h"
#include "core/world/input_component.h"

class AController;

/// An actor that a controller can possess.
SPCLASS()
class APawn : public AActor {
    SP_GENERATED_BODY()
  public:
    APawn();

    /// Whether the pawn's pitch follows its controller's control rotation each tick.
    SPPROPERTY()
    bool bUseControllerRotationPitch = false;

    /// Whether the pawn's yaw follows its controller's control rotation each tick.
    SPPROPERTY()
    bool bUseControllerRotationYaw = true;

    /// Whether the pawn's roll follows its controller's control rotation each tick.
    SPPROPERTY()
    bool bUseControllerRotationRoll = false;

    /// Returns the controller that possesses this pawn, or None.
    SPFUNCTION()
    AController* GetController() const;

    /// Returns true while a controller possesses this pawn.
    SPFUNCTION()
    bool IsControlled() const { return GetController() != nullptr; }

    /// Returns true while a player controller possesses this pawn.
    SPFUNCTION()
    bool IsPlayerControlled() const;

    /// Returns the controller's control rotation, or the pawn's own rotation when it has no controller.
    SPFUNCTION()
    FRotator GetControlRotation() const;

    /// Adds movement along WorldDirection, scaled by ScaleValue, for the pawn's next tick (the inputs of one
    /// tick add up; a pawn that moves itself, such as ADefaultPawn, consumes them).
    SPFUNCTION()
    void AddMovementInput(const FVector& WorldDirection, double ScaleValue = 1.0);

    /// Returns the movement input added since the pawn last moved.
    SPFUNCTION()
    FVector GetPendingMovementInputVector() const { return pendingMovement_; }

    void Tick(double deltaSeconds) override;
    void EndPlay() override;

    // For controllers that steer the pawn through its movement input: the speed in m/s that a full unit
    // of input moves it at (0: it does not move from input), whether it walks (moves in the horizontal
    // plane only), and its radius in the horizontal plane.
    virtual double GetMovementSpeed() const { return 0.0; }
    virtual bool IsWalking() const { return false; }
    virtual double GetAgentRadius() const { return 0.0; }

    // Called by AController::Possess and UnPossess only.
    void SetControllerHandle(sp::reflect::ObjectHandle controller) { controller_ = controller; }

  protected:
    // For pawns whose root is a component of their own (a vehicle's chassis): no default root.
    struct NoDefaultRoot {};
    explicit APawn(NoDefaultRoot) {}

    // Turns the possessing controller's view: yaw by yawAxis * yawRate and pitch (kept within [-89, 89]) by
    // pitchAxis * pitchRate degrees per second, for deltaSeconds (the "Turn" and "LookUp" actions).
    void TurnControllerView(double yawAxis, double pitchAxis, double yawRate, double pitchRate,
                            double deltaSeconds);

    // The movement input added since the last call, cleared.
    FVector ConsumeMovementInput();

  private:
    sp::reflect::ObjectHandle controller_;
    FVector pendingMovement_;
};

/// A pawn that flies along its control rotation from the "MoveForward", "MoveRight" and "MoveUp" input
/// actions (X in [-1, 1]) and AddMovementInput, and turns its controller's view with "Turn" and "LookUp".
/// It has no collision body: it passes through geometry, like UE's DefaultPawn with collision off.
SPCLASS()
class ADefaultPawn : public APawn {
    SP_GENERATED_BODY()
  public:
    ADefaultPawn();

    /// Receives the injected actions (from inject_input_for_actor on the pawn or its controller).
    SPPROPERTY(ReadOnly, NotNull)
    UInputComponent* InputComponent = nullptr;

    /// Speed in metres per second at full input.
    SPPROPERTY()
    double MaxSpeed = 12.0;

    /// Degrees per second of yaw at "Turn" = 1.
    SPPROPERTY()
    double BaseTurnRate = 45.0;

    /// Degrees per second of pitch at "LookUp" = 1.
    SPPROPERTY()
    double BaseLookUpRate = 45.0;

    void Tick(double deltaSeconds) override;
    double GetMovementSpeed() const override { return MaxSpeed; }
};
