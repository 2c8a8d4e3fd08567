"""The gameplay framework: game mode, players, possession, control rotation, input through a controller,
and UGameplayStatics' static functions called on the class; on both transports."""

from __future__ import annotations

import gc
import math

import pytest

import spear
from spear.errors import InvalidArgumentError, InvalidStateError

FORWARD = spear.FVector(X=1.0)


def player0(game: spear.UWorld) -> spear.APlayerController:
    pc = spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=0)
    assert pc is not None
    return pc


def test_a_game_world_starts_player_0_on_first_use(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        assert game.get_actor_count() == 0  # nobody asked for players yet: the world is as its scene made it
        start = game.spawn_actor(uclass=spear.APlayerStart, location=spear.FVector(X=3.0, Y=-2.0, Z=1.5),
                                 rotation=spear.FRotator(Yaw=30.0))
        pc = player0(game)
        assert isinstance(pc, spear.APlayerController) and pc.IsPlayerController()
        mode = spear.UGameplayStatics.GetGameMode(WorldContextObject=game)
        assert isinstance(mode, spear.AGameModeBase)
        assert mode.GetNumPlayers() == 1 and spear.UGameplayStatics.GetNumPlayerControllers(WorldContextObject=pc) == 1
        assert mode.FindPlayerStart(Player=pc) == start
        pawn = pc.K2_GetPawn()
        assert isinstance(pawn, spear.ADefaultPawn)
        assert spear.UGameplayStatics.GetPlayerPawn(WorldContextObject=game, PlayerIndex=0) == pawn
        assert pawn.GetActorLocation() == spear.FVector(X=3.0, Y=-2.0, Z=1.5)
        assert pawn.GetController() == pc and pawn.IsPlayerControlled()
        assert pc.GetControlRotation().Yaw == pytest.approx(30.0)
        assert spear.UGameplayStatics.GetPlayerControllerID(Player=pc) == 0
        assert spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=1) is None
        # Asking again finds the same framework.
        assert player0(game) == pc and game.get_actor_count() == 4


def test_possession_moves_a_pawn_between_controllers(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        pc = player0(game)
        first = pc.K2_GetPawn()
        assert first is not None
        second = game.spawn_actor(uclass=spear.ADefaultPawn, location=spear.FVector(Y=5.0),
                                  rotation=spear.FRotator(Yaw=-90.0))
        ai = game.spawn_actor(uclass=spear.AAIController)
        assert not ai.IsPlayerController() and ai.K2_GetPawn() is None and not second.IsControlled()
        ai.Possess(InPawn=first)  # taken from the player
        assert first.GetController() == ai and not first.IsPlayerControlled()
        assert pc.K2_GetPawn() is None
        pc.Possess(InPawn=second)
        assert pc.K2_GetPawn() == second and second.GetController() == pc
        assert pc.GetControlRotation().Yaw == pytest.approx(-90.0)  # a new pawn: the view starts along it
        assert pc.GetViewTarget() == second
        ai.UnPossess()
        assert ai.K2_GetPawn() is None and first.GetController() is None and not first.IsControlled()
        game.destroy_actor(actor=second)
        assert pc.K2_GetPawn() is None  # a destroyed pawn leaves no dangling link
        assert pc.GetViewTarget() == pc


def test_control_rotation_turns_the_pawn_on_its_flagged_axes(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        pc = player0(game)
        pawn = pc.K2_GetPawn()
        assert isinstance(pawn, spear.ADefaultPawn)
        assert pawn.bUseControllerRotationYaw and not pawn.bUseControllerRotationPitch
        pc.SetControlRotation(NewRotation=spear.FRotator(Pitch=20.0, Yaw=45.0, Roll=5.0))
        pc.AddYawInput(Val=15.0)
        pc.AddPitchInput(Val=100.0)  # clamped to 89
        assert pc.GetControlRotation() == spear.FRotator(Pitch=89.0, Yaw=60.0, Roll=5.0)
        assert pawn.GetControlRotation() == pc.GetControlRotation()
    with instance.end_frame():
        rotation = pawn.GetActorRotation()
        assert rotation.Yaw == pytest.approx(60.0) and rotation.Pitch == pytest.approx(0.0, abs=1e-9)
        view = pc.GetPlayerViewPoint()
        assert view.Location == pawn.GetActorLocation() and view.Rotation == pc.GetControlRotation()


def test_input_injected_for_a_controller_moves_its_pawn(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        pc = player0(game)
        pawn = pc.K2_GetPawn()
        assert isinstance(pawn, spear.ADefaultPawn)
        pawn.MaxSpeed = 6.0
        pc.SetControlRotation(NewRotation=spear.FRotator(Yaw=90.0))
    with instance.end_frame():
        pass
    for _ in range(10):  # 10 ticks at 6 m/s along the view (+Y after 90 degrees of yaw): 1 m
        with instance.begin_frame():
            game.inject_input_for_actor(actor=pc, input_action_name="MoveForward", value=FORWARD)
        with instance.end_frame():
            pass
    with instance.begin_frame():
        location = pawn.GetActorLocation()
        assert location.X == pytest.approx(0.0, abs=1e-9) and location.Y == pytest.approx(1.0)
        game.inject_input_for_actor(actor=pc, input_action_name="MoveRight", value=FORWARD)
        game.inject_input_for_actor(actor=pc, input_action_name="Turn", value=FORWARD)
        pawn.AddMovementInput(WorldDirection=spear.FVector(Z=1.0), ScaleValue=0.5)
        assert pawn.GetPendingMovementInputVector() == spear.FVector(Z=0.5)
    with instance.end_frame():
        # The turn comes first (45 deg/s for one tick), then the move: right of the new view, plus half a
        # unit up, scaled to one unit of input, at 6 m/s for 1/60 s.
        yaw = math.radians(90.0 + 45.0 / 60.0)
        assert pc.GetControlRotation().Yaw == pytest.approx(math.degrees(yaw))
        direction = (math.sin(yaw), -math.cos(yaw), 0.5)
        length = math.hypot(*direction)
        moved = pawn.GetActorLocation()
        step = (moved.X - location.X, moved.Y - location.Y, moved.Z - location.Z)
        assert step == pytest.approx(tuple(0.1 * d / length for d in direction), abs=1e-12)
        assert pawn.GetPendingMovementInputVector() == spear.FVector()


def test_swapping_player_controllers_hands_over_the_player(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        old = player0(game)
        pawn = old.K2_GetPawn()
        camera = game.spawn_actor(uclass=spear.AActor)
        old.SetViewTargetWithBlend(NewViewTarget=camera, BlendTime=0.5)
        old.SetControlRotation(NewRotation=spear.FRotator(Yaw=12.0))
        mode = spear.UGameplayStatics.GetGameMode(WorldContextObject=game)
        assert mode is not None
        new = game.spawn_actor(uclass=spear.APlayerController)
        assert spear.UGameplayStatics.GetPlayerControllerID(Player=new) == -1
        mode.SwapPlayerControllers(OldPC=old, NewPC=new)
        assert player0(game) == new and spear.UGameplayStatics.GetPlayerControllerID(Player=old) == -1
        assert new.K2_GetPawn() == pawn and old.K2_GetPawn() is None
        assert new.GetViewTarget() == camera and new.GetControlRotation().Yaw == pytest.approx(12.0)
        assert mode.GetNumPlayers() == 1
        with pytest.raises(InvalidArgumentError, match=r"SwapPlayerControllers\(\): OldPC .* has no player"):
            mode.SwapPlayerControllers(OldPC=old, NewPC=game.spawn_actor(uclass=spear.APlayerController))


def test_create_player_and_game_mode_classes(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        mode = game.spawn_actor(uclass=spear.AGameModeBase)  # a world's own game mode is the one used
        # A class reference reads back as the API's class itself, on both transports.
        assert mode.DefaultPawnClass is spear.ADefaultPawn
        assert instance.get_property(uobject=mode, path="DefaultPawnClass") is spear.ADefaultPawn
        mode.DefaultPawnClass = spear.APawn
        assert mode.DefaultPawnClass is spear.APawn
        game.spawn_actor(uclass=spear.APlayerStart, location=spear.FVector(Z=1.0))
        game.spawn_actor(uclass=spear.APlayerStart, location=spear.FVector(Z=9.0)).PlayerStartTag = "high"
        assert spear.UGameplayStatics.GetGameMode(WorldContextObject=game) == mode
        first = player0(game).K2_GetPawn()
        assert first is not None and first.GetClassName() == "APawn"
        second = spear.UGameplayStatics.CreatePlayer(WorldContextObject=game)
        assert second is not None and spear.UGameplayStatics.GetPlayerControllerID(Player=second) == 1
        assert mode.GetNumPlayers() == 2
        tall = mode.FindPlayerStart(Player=second, IncomingName="high")
        assert tall is not None and tall.GetActorLocation().Z == 9.0
        assert mode.FindPlayerStart(Player=second, IncomingName="nowhere") is None
        pawns = spear.UGameplayStatics.GetAllActorsOfClass(WorldContextObject=game, ActorClass=spear.APawn)
        assert [p.GetClassName() for p in pawns] == ["APawn", "APawn"]
        assert spear.UGameplayStatics.GetActorOfClass(WorldContextObject=game, ActorClass="APlayerStart") is not None
        with pytest.raises(InvalidArgumentError, match=r"CreatePlayer\(\): player 1 exists already"):
            spear.UGameplayStatics.CreatePlayer(WorldContextObject=game, ControllerId=1)


def test_static_functions_are_called_on_the_class_or_an_object(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        game.spawn_actor(uclass=spear.AActor, tags=["t"])
        tagged = spear.UGameplayStatics.GetAllActorsWithTag(WorldContextObject=game, Tag="t")
        assert len(tagged) == 1
        # With no engine object among the arguments, the call goes to the only open instance.
        assert spear.UGameplayStatics.GetPlayerControllerID(Player=player0(game)) == 0


def test_gameplay_misuse_is_refused_clearly(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        pc = player0(game)
        with pytest.raises(InvalidArgumentError, match=r"UGameplayStatics.GetGameMode\(\).*WorldContextObject"):
            spear.UGameplayStatics.GetGameMode(WorldContextObject=None)  # type: ignore[arg-type]
        with pytest.raises(InvalidArgumentError, match=r"AController.Possess\(\).*InPawn"):
            pc.Possess(InPawn=None)  # type: ignore[arg-type]
        with pytest.raises(InvalidArgumentError, match=r"AController.SetControlRotation\(\): .* must be finite"):
            pc.SetControlRotation(NewRotation=spear.FRotator(Yaw=float("nan")))
        with pytest.raises(InvalidArgumentError, match=r"CreatePlayer\(\): bSpawnPlayerController=False"):
            spear.UGameplayStatics.CreatePlayer(WorldContextObject=game, bSpawnPlayerController=False)
        ai = game.spawn_actor(uclass=spear.AAIController)
        with pytest.raises(InvalidArgumentError, match=r"inject_input_for_actor\(\): .* possesses no pawn"):
            game.inject_input_for_actor(actor=ai, input_action_name="MoveForward", value=FORWARD)
    with instance.end_frame():
        pass
    with pytest.raises(InvalidStateError, match="outside a frame"):
        spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=0)
    with instance.begin_frame():
        assert player0(game) == pc  # the engine kept running


def test_an_editor_world_has_no_game_framework() -> None:
    with spear.Instance(mode="editor") as inst:
        editor = inst.get_editor()
        with inst.begin_frame():
            assert spear.UGameplayStatics.GetGameMode(WorldContextObject=editor) is None
            assert spear.UGameplayStatics.GetPlayerController(WorldContextObject=editor, PlayerIndex=0) is None
            assert editor.get_actor_count() == 0
            with pytest.raises(InvalidStateError, match=r"CreatePlayer\(\): an editor world has no players"):
                spear.UGameplayStatics.CreatePlayer(WorldContextObject=editor)
        with inst.end_frame():
            pass


def test_a_static_call_without_an_engine_object_needs_exactly_one_instance() -> None:
    gc.collect()  # instances other tests dropped without closing
    statics = spear.UGameplayStatics
    with pytest.raises(InvalidStateError, match=r"GetPlayerControllerID\(\): no spear.Instance is open"):
        statics.GetPlayerControllerID(Player=None)  # type: ignore[arg-type]
    with spear.Instance() as a, spear.Instance(server="launch") as b:
        with pytest.raises(InvalidStateError, match=r"2 spear.Instances are open, so the engine to run it"):
            statics.GetPlayerControllerID(Player=None)  # type: ignore[arg-type]
        for inst in (a, b):
            with inst.begin_frame():
                assert statics.GetPlayerControllerID(Player=player0(inst.get_game())) == 0
            with inst.end_frame():
                pass


def test_the_server_refuses_a_static_call_it_cannot_make() -> None:
    from spear.errors import NotFoundError

    with spear.Instance(server="launch") as inst:
        connection = inst._rpc_connection()
        with inst.begin_frame():
            with pytest.raises(InvalidArgumentError, match=r"'AActor.GetName' is not static; call it on an object"):
                connection.request("call", **{"class": "AActor", "function": "GetName", "args": {}})
            with pytest.raises(NotFoundError, match=r"class 'ANope' is not registered"):
                connection.request("call", **{"class": "ANope", "function": "GetName", "args": {}})
            with pytest.raises(NotFoundError, match=r"class 'UGameplayStatics' has no function 'Nope'"):
                connection.request("call", **{"class": "UGameplayStatics", "function": "Nope", "args": {}})
        with inst.end_frame():
            pass
        with inst.begin_frame():  # the server kept running
            assert player0(inst.get_game()).IsPlayerController()
        with inst.end_frame():
            pass
