#include "core/gameplay/game_mode.h"

#include "core/world/world.h"

AGameModeBase::AGameModeBase() {
    CreateDefaultSubobject<USceneComponent>("RootComponent");
}

APlayerStart::APlayerStart() {
    CreateDefaultSubobject<USceneComponent>("RootComponent");
}

AActor* AGameModeBase::FindPlayerStart(AController* Player, const std::string& IncomingName) const {
    (void)Player; // every player may use every start; kept for UE's signature
    const std::vector<AActor*> starts = GetWorld()->find_actors_by_class(&APlayerStart::StaticClass());
    for (AActor* start : starts)
        if (IncomingName.empty() || static_cast<APlayerStart*>(start)->PlayerStartTag == IncomingName)
            return start;
    return nullptr;
}

void AGameModeBase::RestartPlayer(AController* NewPlayer) {
    constexpr const char* kContext = "AGameModeBase.RestartPlayer()";
    SP_CHECK(NewPlayer, sp::InvalidArgument, kContext, ": NewPlayer is None");
    SP_CHECK(NewPlayer->GetWorld() == GetWorld(), sp::InvalidArgument, kContext, ": ",
             NewPlayer->GetDebugName(), " is in another world than ", GetDebugName());
    const AActor* start = FindPlayerStart(NewPlayer);
    const FVector location = start ? start->GetActorLocation() : FVector{};
    const FRotator rotation = start ? FRotator{0.0, start->GetActorRotation().Yaw, 0.0} : FRotator{};
    APawn* pawn = NewPlayer->K2_GetPawn();
    if (!pawn) {
        SP_CHECK(DefaultPawnClass, sp::InvalidArgument, kContext, ": DefaultPawnClass of ", GetDebugName(),
                 " is None");
        pawn = static_cast<APawn*>(GetWorld()->spawn_actor(DefaultPawnClass.Get(), location, rotation));
    } else {
        pawn->K2_SetActorLocationAndRotation(location, rotation);
    }
    NewPlayer->Possess(pawn);
}

int AGameModeBase::GetNumPlayers() const {
    int players = 0;
    for (AActor* actor : GetWorld()->find_actors_by_class(&APlayerController::StaticClass()))
        players += static_cast<APlayerController*>(actor)->GetPlayerIndex() >= 0;
    return players;
}

void AGameModeBase::SwapPlayerControllers(APlayerController* OldPC, APlayerController* NewPC) {
    constexpr const char* kContext = "AGameModeBase.SwapPlayerControllers()";
    SP_CHECK(OldPC && NewPC, sp::InvalidArgument, kContext, ": ", OldPC ? "NewPC" : "OldPC", " is None");
    SP_CHECK(OldPC != NewPC, sp::InvalidArgument, kContext, ": OldPC and NewPC are the same controller");
    SP_CHECK(OldPC->GetWorld() == GetWorld() && NewPC->GetWorld() == GetWorld(), sp::InvalidArgument,
             kContext, ": both controllers must be in the world of ", GetDebugName());
    SP_CHECK(OldPC->GetPlayerIndex() >= 0, sp::InvalidArgument, kContext, ": OldPC ", OldPC->GetDebugName(),
             " has no player to move");
    SP_CHECK(NewPC->GetPlayerIndex() < 0, sp::InvalidArgument, kContext, ": NewPC ", NewPC->GetDebugName(),
             " already serves player ", NewPC->GetPlayerIndex());
    AActor* viewTarget = OldPC->GetViewTarget();
    APawn* pawn = OldPC->K2_GetPawn();
    const FRotator control = OldPC->GetControlRotation();
    NewPC->SetPlayerIndex(OldPC->GetPlayerIndex());
    OldPC->SetPlayerIndex(-1);
    if (pawn)
        NewPC->Possess(pawn); // takes it from OldPC
    NewPC->SetControlRotation(control);
    NewPC->SetViewTargetWithBlend(viewTarget == OldPC || viewTarget == pawn ? nullptr : viewTarget);
}

APlayerController* AGameModeBase::Login(int playerIndex) {
    SP_CHECK(PlayerControllerClass, sp::InvalidArgument, "AGameModeBase.Login(): PlayerControllerClass of ",
             GetDebugName(), " is None");
    auto* controller = static_cast<APlayerController*>(GetWorld()->spawn_actor(PlayerControllerClass.Get()));
    controller->SetPlayerIndex(playerIndex);
    return controller;
}

namespace sp::gameplay {

AGameModeBase* startGameFramework(UWorld& world) {
    if (world.is_editor_world())
        return nullptr;
    auto* mode = static_cast<AGameModeBase*>(world.find_actor_by_class(&AGameModeBase::StaticClass()));
    if (!mode)
        mode = static_cast<AGameModeBase*>(world.spawn_actor(&AGameModeBase::StaticClass()));
    if (!findPlayerController(world, 0)) {
        APlayerController* player = mode->Login(0);
        mode->RestartPlayer(player);
    }
    return mode;
}

APlayerController* findPlayerController(const UWorld& world, int playerIndex) {
    for (AActor* actor : world.find_actors_by_class(&APlayerController::StaticClass()))
        if (static_cast<APlayerController*>(actor)->GetPlayerIndex() == playerIndex)
            return static_cast<APlayerController*>(actor);
    return nullptr;
}

} // namespace sp::gameplay
