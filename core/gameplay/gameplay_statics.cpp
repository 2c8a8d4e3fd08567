#include "core/gameplay/gameplay_statics.h"

#include "core/scene/streaming_levels.h"
#include "core/world/object_access.h"
#include "core/world/world.h"

AGameModeBase* UGameplayStatics::GetGameMode(UObject* WorldContextObject) {
    return sp::gameplay::startGameFramework(
        sp::world::worldOfContext(WorldContextObject, "UGameplayStatics.GetGameMode()"));
}

APlayerController* UGameplayStatics::GetPlayerController(UObject* WorldContextObject, int PlayerIndex) {
    UWorld& world = sp::world::worldOfContext(WorldContextObject, "UGameplayStatics.GetPlayerController()");
    sp::gameplay::startGameFramework(world);
    return sp::gameplay::findPlayerController(world, PlayerIndex);
}

APawn* UGameplayStatics::GetPlayerPawn(UObject* WorldContextObject, int PlayerIndex) {
    UWorld& world = sp::world::worldOfContext(WorldContextObject, "UGameplayStatics.GetPlayerPawn()");
    sp::gameplay::startGameFramework(world);
    APlayerController* controller = sp::gameplay::findPlayerController(world, PlayerIndex);
    return controller ? controller->K2_GetPawn() : nullptr;
}

int UGameplayStatics::GetPlayerControllerID(APlayerController* Player) {
    SP_CHECK(Player, sp::InvalidArgument, "UGameplayStatics.GetPlayerControllerID(): Player is None");
    sp::world::checkObjectAccess(*Player, "UGameplayStatics.GetPlayerControllerID()");
    return Player->GetPlayerIndex();
}

int UGameplayStatics::GetNumPlayerControllers(UObject* WorldContextObject) {
    AGameModeBase* mode = sp::gameplay::startGameFramework(
        sp::world::worldOfContext(WorldContextObject, "UGameplayStatics.GetNumPlayerControllers()"));
    return mode ? mode->GetNumPlayers() : 0;
}

APlayerController* UGameplayStatics::CreatePlayer(UObject* WorldContextObject, int ControllerId,
                                                  bool bSpawnPlayerController) {
    constexpr const char* kContext = "UGameplayStatics.CreatePlayer()";
    SP_CHECK(bSpawnPlayerController, sp::InvalidArgument, kContext,
             ": bSpawnPlayerController=False is not supported (a player always has a controller here)");
    SP_CHECK(ControllerId >= -1, sp::InvalidArgument, kContext, ": ControllerId ", ControllerId,
             " must be -1 (the next free index) or a player index");
    UWorld& world = sp::world::worldOfContext(WorldContextObject, kContext);
    AGameModeBase* mode = sp::gameplay::startGameFramework(world);
    SP_CHECK(mode, sp::InvalidState, kContext, ": an editor world has no players");
    int index = ControllerId;
    if (index < 0)
        for (index = 0; sp::gameplay::findPlayerController(world, index);)
            ++index;
    SP_CHECK(!sp::gameplay::findPlayerController(world, index), sp::InvalidArgument, kContext, ": player ",
             index, " exists already");
    APlayerController* controller = mode->Login(index);
    mode->RestartPlayer(controller);
    return controller;
}

std::vector<AActor*> UGameplayStatics::GetAllActorsOfClass(UObject* WorldContextObject,
                                                           TSubclassOf<AActor> ActorClass) {
    constexpr const char* kContext = "UGameplayStatics.GetAllActorsOfClass()";
    SP_CHECK(ActorClass, sp::InvalidArgument, kContext, ": ActorClass is None");
    return sp::world::worldOfContext(WorldContextObject, kContext).find_actors_by_class(ActorClass);
}

AActor* UGameplayStatics::GetActorOfClass(UObject* WorldContextObject, TSubclassOf<AActor> ActorClass) {
    constexpr const char* kContext = "UGameplayStatics.GetActorOfClass()";
    SP_CHECK(ActorClass, sp::InvalidArgument, kContext, ": ActorClass is None");
    return sp::world::worldOfContext(WorldContextObject, kContext).find_actor_by_class(ActorClass);
}

std::vector<AActor*> UGameplayStatics::GetAllActorsWithTag(UObject* WorldContextObject,
                                                           const std::string& Tag) {
    return sp::world::worldOfContext(WorldContextObject, "UGameplayStatics.GetAllActorsWithTag()")
        .find_actors_by_tag(Tag);
}

void UGameplayStatics::LoadStreamLevel(UObject* WorldContextObject, const std::string& LevelName,
                                       bool /*bMakeVisibleAfterLoad*/, bool /*bShouldBlockOnLoad*/) {
    constexpr const char* kContext = "UGameplayStatics.LoadStreamLevel()";
    sp::scene::loadStreamLevel(sp::world::worldOfContext(WorldContextObject, kContext), LevelName, kContext);
}

void UGameplayStatics::UnloadStreamLevel(UObject* WorldContextObject, const std::string& LevelName,
                                         bool /*bShouldBlockOnUnload*/) {
    constexpr const char* kContext = "UGameplayStatics.UnloadStreamLevel()";
    sp::scene::unloadStreamLevel(sp::world::worldOfContext(WorldContextObject, kContext), LevelName,
                                 kContext);
}

std::vector<std::string> UGameplayStatics::GetStreamingLevelNames(UObject* WorldContextObject) {
    std::vector<std::string> names;
    for (const UWorld::StreamingLevel& level :
         sp::world::worldOfContext(WorldContextObject, "UGameplayStatics.GetStreamingLevelNames()")
             .GetStreamingLevels())
        names.push_back(level.name);
    return names;
}

bool UGameplayStatics::IsStreamingLevelLoaded(UObject* WorldContextObject, const std::string& LevelName) {
    for (const UWorld::StreamingLevel& level :
         sp::world::worldOfContext(WorldContextObject, "UGameplayStatics.IsStreamingLevelLoaded()")
             .GetStreamingLevels())
        if (level.name == LevelName)
            return level.loaded;
    return false;
}
