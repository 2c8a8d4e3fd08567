#pragma once
// AGameModeBase: the rules of a game world. It logs players in (a player controller of
// PlayerControllerClass each) and starts them (a DefaultPawnClass pawn at a player start, possessed).
// APlayerStart: where players start.
//
// A game world's framework starts on first use (sp::gameplay::startGameFramework, called by the
// UGameplayStatics functions): the world's game mode, spawned if the world has none, logs in player 0 and
// restarts it. A world nobody asks for players stays exactly as its scene made it. Editor worlds have no
// game framework.

#include <string>

#include "core/gameplay/controller.h"
#include "core/gameplay/pawn.h"
#include "core/reflect/class_ref.h"
#include "core/world/actor.h"

class APlayerStart;

/// The rules of a game world: which classes its players get, and where they start.
SPCLASS()
class AGameModeBase : public AActor {
    SP_GENERATED_BODY()
  public:
    AGameModeBase();

    /// The class of the pawn each player starts with.
    SPPROPERTY()
    TSubclassOf<APawn> DefaultPawnClass = &ADefaultPawn::StaticClass();

    /// The class of each player's controller.
    SPPROPERTY()
    TSubclassOf<APlayerController> PlayerControllerClass = &APlayerController::StaticClass();

    /// Returns the player start for Player: the first whose PlayerStartTag is IncomingName when that is not
    /// empty, else the first in the world, or None when the world has none.
    SPFUNCTION()
    AActor* FindPlayerStart(AController* Player, const std::string& IncomingName = "") const;

    /// Starts NewPlayer: spawns a DefaultPawnClass pawn for it when it has none, moves the pawn to its player
    /// start (the world origin when there is none) and possesses it.
    SPFUNCTION()
    void RestartPlayer(AController* NewPlayer);

    /// Returns the number of players (player controllers with a player index).
    SPFUNCTION()
    int GetNumPlayers() const;

    /// Moves OldPC's player to NewPC: NewPC takes OldPC's player index, pawn and view target, and OldPC is
    /// left without a player (destroy it, or keep it as a spectator controller).
    SPFUNCTION()
    void SwapPlayerControllers(APlayerController* OldPC, APlayerController* NewPC);

    // Logs a player in: spawns a PlayerControllerClass controller with player index `playerIndex`.
    APlayerController* Login(int playerIndex);
};

/// Where a player starts.
SPCLASS()
class APlayerStart : public AActor {
    SP_GENERATED_BODY()
  public:
    APlayerStart();

    /// Chooses this start by name (AGameModeBase.FindPlayerStart's IncomingName).
    SPPROPERTY()
    std::string PlayerStartTag;
};

namespace sp::gameplay {

// The world's game mode, with player 0 logged in and started; spawns them when missing. nullptr in an
// editor world.
AGameModeBase* startGameFramework(UWorld& world);
// The player controller with `playerIndex` in `world`, or nullptr (does not start the framework).
APlayerController* findPlayerController(const UWorld& world, int playerIndex);

} // namespace sp::gameplay
