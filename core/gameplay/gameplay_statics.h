#pragma once
// UGameplayStatics: UE's function library for games, as static functions. Each takes a
// WorldContextObject (the world itself, or any object in it) that says which world it asks about; from
// Python they are called on the class:
//
//     pc = spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=0)
//
// The player functions start the world's game framework on first use (see core/gameplay/game_mode.h).

#include <string>
#include <vector>

#include "core/gameplay/game_mode.h"
#include "core/reflect/class_ref.h"

/// Static functions for games: the game mode, players, and actor queries.
SPCLASS(Abstract)
class UGameplayStatics : public UObject {
    SP_GENERATED_BODY()
  public:
    /// Returns the game mode of WorldContextObject's world (None in an editor world).
    SPFUNCTION()
    static AGameModeBase* GetGameMode(UObject* WorldContextObject);

    /// Returns the controller of player PlayerIndex, or None.
    SPFUNCTION()
    static APlayerController* GetPlayerController(UObject* WorldContextObject, int PlayerIndex);

    /// Returns the pawn of player PlayerIndex, or None.
    SPFUNCTION()
    static APawn* GetPlayerPawn(UObject* WorldContextObject, int PlayerIndex);

    /// Returns the player index that Player serves, or -1 when it serves none.
    SPFUNCTION()
    static int GetPlayerControllerID(APlayerController* Player);

    /// Returns the number of player controllers with a player.
    SPFUNCTION()
    static int GetNumPlayerControllers(UObject* WorldContextObject);

    /// Creates player ControllerId (-1: the next free index) with a new player controller, started with a
    /// pawn as the game mode starts players; returns its controller. bSpawnPlayerController is accepted for
    /// UE compatibility and must be true.
    SPFUNCTION()
    static APlayerController* CreatePlayer(UObject* WorldContextObject, int ControllerId = -1,
                                           bool bSpawnPlayerController = true);

    /// Returns every actor of class ActorClass or a subclass of it, in spawn order.
    SPFUNCTION(DeterminesOutputType = ActorClass)
    static std::vector<AActor*> GetAllActorsOfClass(UObject* WorldContextObject,
                                                    TSubclassOf<AActor> ActorClass);

    /// Returns the first actor of class ActorClass or a subclass of it, or None.
    SPFUNCTION(DeterminesOutputType = ActorClass)
    static AActor* GetActorOfClass(UObject* WorldContextObject, TSubclassOf<AActor> ActorClass);

    /// Returns every actor that has Tag, in spawn order.
    SPFUNCTION()
    static std::vector<AActor*> GetAllActorsWithTag(UObject* WorldContextObject, const std::string& Tag);

    /// Loads streaming level LevelName: one the world's scene file declares (its "levels"), or the scene
    /// file at that path. Its actors join the world at once, the rest untouched; its object references
    /// resolve within it and its actor names must be free. Nothing happens for a loaded level.
    /// bMakeVisibleAfterLoad and bShouldBlockOnLoad are accepted for UE compatibility: a level is loaded,
    /// visible, before the call returns.
    SPFUNCTION()
    static void LoadStreamLevel(UObject* WorldContextObject, const std::string& LevelName,
                                bool bMakeVisibleAfterLoad = true, bool bShouldBlockOnLoad = true);

    /// Unloads streaming level LevelName: destroys the actors it loaded (their handles go stale, naming
    /// the level). bShouldBlockOnUnload is accepted for UE compatibility.
    SPFUNCTION()
    static void UnloadStreamLevel(UObject* WorldContextObject, const std::string& LevelName,
                                  bool bShouldBlockOnUnload = true);

    /// Returns the names of the world's streaming levels, declared ones first, in order.
    SPFUNCTION()
    static std::vector<std::string> GetStreamingLevelNames(UObject* WorldContextObject);

    /// Returns true while streaming level LevelName is loaded.
    SPFUNCTION()
    static bool IsStreamingLevelLoaded(UObject* WorldContextObject, const std::string& LevelName);
};
