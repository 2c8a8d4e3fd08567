#pragma once
// Controllers: the will behind a pawn. A controller possesses at most one pawn and a pawn has at most one
// controller; possessing a pawn takes it from its previous controller. The controller owns the control
// rotation (the view direction of a player, the facing an AI wants). APlayerController is a player's
// controller: it has a player index, a view target, and receives the player's input for its pawn.

#include "core/reflect/object_base.h"
#include "core/world/actor.h"

class APawn;

/// An actor that possesses and directs a pawn.
SPCLASS()
class AController : public AActor {
    SP_GENERATED_BODY()
  public:
    AController();

    /// Takes control of InPawn (releasing this controller's previous pawn, and taking InPawn from its
    /// previous controller); the control rotation becomes the pawn's rotation.
    SPFUNCTION()
    void Possess(APawn* InPawn);

    /// Releases the possessed pawn, if any.
    SPFUNCTION()
    void UnPossess();

    /// Returns the possessed pawn, or None.
    SPFUNCTION()
    APawn* K2_GetPawn() const;

    /// Returns the control rotation.
    SPFUNCTION()
    FRotator GetControlRotation() const { return controlRotation_; }

    /// Sets the control rotation (the possessed pawn follows it on the axes its bUseControllerRotation*
    /// flags name, from its next tick).
    SPFUNCTION()
    void SetControlRotation(const FRotator& NewRotation);

    /// Returns true for a player's controller.
    SPFUNCTION()
    virtual bool IsPlayerController() const { return false; }

    void EndPlay() override;

  protected:
    virtual void OnPossess(APawn* /*pawn*/) {}

  private:
    sp::reflect::ObjectHandle pawn_;
    FRotator controlRotation_;
};

/// A player's controller: a player index, a view target, and the player's input for its pawn.
SPCLASS()
class APlayerController : public AController {
    SP_GENERATED_BODY()
  public:
    bool IsPlayerController() const override { return true; }

    /// Returns the actor the player views the world from: the set view target, else the pawn, else this
    /// controller.
    SPFUNCTION()
    AActor* GetViewTarget() const;

    /// Makes NewViewTarget the player's view target (None: the pawn). BlendTime is accepted for UE
    /// compatibility; the view changes at once.
    SPFUNCTION()
    void SetViewTargetWithBlend(AActor* NewViewTarget, double BlendTime = 0.0);

    /// Returns the player's view point: the view target's location and the control rotation.
    SPFUNCTION()
    void GetPlayerViewPoint(FVector& Location, FRotator& Rotation) const;

    /// Adds Val degrees of yaw to the control rotation.
    SPFUNCTION()
    void AddYawInput(double Val);

    /// Adds Val degrees of pitch to the control rotation, keeping pitch within [-89, 89].
    SPFUNCTION()
    void AddPitchInput(double Val);

    /// Adds Val degrees of roll to the control rotation.
    SPFUNCTION()
    void AddRollInput(double Val);

    // The local player this controller serves (UGameplayStatics.GetPlayerControllerID), or -1 for none:
    // set by the game mode when the player logs in or is swapped to another controller.
    int GetPlayerIndex() const { return playerIndex_; }
    void SetPlayerIndex(int playerIndex) { playerIndex_ = playerIndex; }

  protected:
    void OnPossess(APawn* pawn) override;

  private:
    int playerIndex_ = -1;
    sp::reflect::ObjectHandle viewTarget_;
};

/// A controller for non-player pawns, directed from code.
SPCLASS()
class AAIController : public AController {
    SP_GENERATED_BODY()
  public:
};
