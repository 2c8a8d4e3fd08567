"""Positive typing case: the gameplay framework, and static functions called on their class."""

from __future__ import annotations

from typing import assert_type

import spear


def players(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        pc = spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=0)
        assert_type(pc, spear.APlayerController | None)
        assert pc is not None
        pawn = pc.K2_GetPawn()
        assert_type(pawn, spear.APawn | None)
        assert_type(pc.GetControlRotation(), spear.FRotator)
        pc.SetControlRotation(NewRotation=spear.FRotator(Yaw=90.0))
        view = pc.GetPlayerViewPoint()
        assert_type(view, spear.APlayerController.GetPlayerViewPointResult)
        assert_type(view.Location, spear.FVector)
        mode = spear.UGameplayStatics.GetGameMode(WorldContextObject=pc)
        assert_type(mode, spear.AGameModeBase | None)
        ai = game.spawn_actor(uclass=spear.AAIController)
        if pawn is not None:
            ai.Possess(InPawn=pawn)
            assert_type(pawn.GetController(), spear.AController | None)
        assert_type(spear.UGameplayStatics.GetAllActorsOfClass(WorldContextObject=game, ActorClass=spear.APawn),
                    list[spear.APawn])
        assert_type(spear.UGameplayStatics.GetActorOfClass(WorldContextObject=game, ActorClass="APawn"),
                    spear.AActor | None)
        assert_type(spear.UGameplayStatics.GetPlayerControllerID(Player=pc), int)
        if mode is not None:
            mode.DefaultPawnClass = spear.ADefaultPawn
            new_pc = game.spawn_actor(uclass=spear.APlayerController)
            mode.SwapPlayerControllers(OldPC=pc, NewPC=new_pc)
        # A static function is also reachable from an object of its class, as in C++.
        statics: type[spear.UGameplayStatics] = spear.UGameplayStatics
        assert_type(statics.GetNumPlayerControllers(WorldContextObject=game), int)


def levels(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        spear.UGameplayStatics.LoadStreamLevel(WorldContextObject=game, LevelName="Kitchen")
        assert_type(spear.UGameplayStatics.GetStreamingLevelNames(WorldContextObject=game), list[str])
        assert_type(spear.UGameplayStatics.IsStreamingLevelLoaded(WorldContextObject=game, LevelName="Kitchen"), bool)
        spear.UGameplayStatics.UnloadStreamLevel(WorldContextObject=game, LevelName="Kitchen",
                                                 bShouldBlockOnUnload=False)
        actor = game.find_actor_by_name(name="Crate")
        if actor is not None:
            assert_type(actor.GetStreamingLevelName(), str)
    with instance.end_frame():
        pass


def characters(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        character = game.spawn_actor(uclass=spear.ACharacter, location=spear.FVector(Z=1.0))
        assert_type(character.CapsuleComponent, spear.UCapsuleComponent)
        movement = character.GetCharacterMovement()
        assert_type(movement, spear.UCharacterMovementComponent | None)
        character.CharacterMovement.MaxWalkSpeed = 3.0
        assert_type(character.CharacterMovement.GetVelocity(), spear.FVector)
        assert_type(character.CanJump(), bool)
        character.Jump()
    with instance.end_frame():
        pass


def ai(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        controller = game.spawn_actor(uclass=spear.AAIController)
        result = controller.MoveToLocation(Dest=spear.FVector(X=3.0), AcceptanceRadius=0.5)
        assert_type(result, spear.EPathFollowingRequestResult)
        assert_type(controller.GetMoveStatus(), spear.EPathFollowingStatus)
        if result == spear.EPathFollowingRequestResult.RequestSuccessful:
            controller.StopMovement()
    with instance.end_frame():
        pass
