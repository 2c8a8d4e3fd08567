#pragma once
// Controllers: the will behind a pawn. A controller possesses at most one pawn and a pawn has at most one
// controller; possessing a pawn takes it from its previous controller. The controller owns the control
// rotation (the view direction of a player, the facing an AI wants). APlayerController is a player's
// controller: it has a player index, a view target, and receives the player's input for its pawn.

#include <vector>

#include "core/reflect/object_base.h"
#include "core/world/actor.h"

class APawn;
class ARecastNavMesh;

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
    // True for a controller that sets its pawn's controls itself each frame (a vehicle it possesses then
    // ignores its input actions).
    virtual bool DrivesPawnDirectly() const { return false; }
    // Input injected into a controller moves its pawn.
    std::optional<const AActor*> GetInputForwardTarget() const override;

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

/// What a move request did (UE's EPathFollowingRequestResult).
SPENUM()
enum class EPathFollowingRequestResult : uint8_t {
    /// Not started: the controller has no pawn, or the goal is None.
    Failed = 0,
    /// The pawn is within the acceptance radius already.
    AlreadyAtGoal = 1,
    /// The pawn is on its way.
    RequestSuccessful = 2,
};

/// What an AI controller's movement is doing (UE's EPathFollowingStatus).
SPENUM()
enum class EPathFollowingStatus : uint8_t {
    /// No move in progress.
    Idle = 0,
    /// Waiting (not used yet: moves start at once).
    Waiting = 1,
    /// Paused (not used yet).
    Paused = 2,
    /// Moving to its goal.
    Moving = 3,
};

/// A controller for non-player pawns, directed from code. MoveToLocation / MoveToActor walk (ACharacter)
/// or fly (ADefaultPawn) the pawn to a goal through its movement input, turning the control rotation to
/// face where it goes. A walking pawn with bUsePathfinding follows a path on the world's default navigation
/// data when the world has navigation (an ARecastNavMesh or an ANavMeshBoundsVolume), corner by corner,
/// and the move fails when its start or goal is off the navigation mesh; an unreachable goal is walked to as
/// close as the mesh allows. Otherwise (flying, no navigation, or bUsePathfinding false) it goes straight.
SPCLASS()
class AAIController : public AController {
    SP_GENERATED_BODY()
  public:
    /// Starts moving the pawn to Dest; it stops within AcceptanceRadius metres of it (in the horizontal
    /// plane for a walking pawn), plus its own radius when bStopOnOverlap.
    SPFUNCTION()
    EPathFollowingRequestResult MoveToLocation(const FVector& Dest, double AcceptanceRadius = 0.1,
                                               bool bStopOnOverlap = true, bool bUsePathfinding = true);

    /// Starts moving the pawn to Goal, following it if it moves.
    SPFUNCTION()
    EPathFollowingRequestResult MoveToActor(AActor* Goal, double AcceptanceRadius = 0.1,
                                            bool bStopOnOverlap = true, bool bUsePathfinding = true);

    /// Stops the move in progress.
    SPFUNCTION()
    void StopMovement();

    /// Returns whether a move is in progress.
    SPFUNCTION()
    EPathFollowingStatus GetMoveStatus() const {
        return moving_ ? EPathFollowingStatus::Moving : EPathFollowingStatus::Idle;
    }

    /// Returns the point the pawn is moving to now: the next corner of its path, else the goal (its location
    /// when no move is in progress).
    SPFUNCTION()
    FVector GetImmediateMoveDestination() const;

    void Tick(double deltaSeconds) override;

  private:
    // Where the goal is now: the goal actor's location, else the destination.
    FVector goalLocation() const;
    // The remaining offset from the pawn to the goal, horizontal for a walking pawn, and how close counts.
    bool arrived(const APawn& pawn, Eigen::Vector3d& offset) const;
    // How close to the goal counts as there: the acceptance radius, plus the pawn's radius when
    // bStopOnOverlap.
    double stopDistance(const APawn& pawn) const;
    static void checkAcceptanceRadius(double radius, const char* function);
    EPathFollowingRequestResult start(bool usePathfinding);
    // Plans the path to the goal on `navigation`; false when the start or goal is off it.
    bool planPath(const APawn& pawn, ARecastNavMesh& navigation);
    // Advances nextCorner_ past the corners reached (re-planning for a goal actor that moved); false once the
    // pawn is at the path's end.
    bool advanceOnPath(const APawn& pawn);

    bool moving_ = false;
    bool followingPath_ = false;
    std::vector<Eigen::Vector3d> path_; // corners after the start
    size_t nextCorner_ = 0;
    FVector plannedGoal_; // the goal's location when the path was planned
    FVector destination_;
    sp::reflect::ObjectHandle goalActor_;
    double acceptanceRadius_ = 0.1;
    bool stopOnOverlap_ = true;
};
