"""Input injection: continuous actions routed to one actor's UInputComponent, read in its Tick."""

from __future__ import annotations

import math

import pytest

import spear


def test_injected_input_moves_only_the_targeted_actor(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        a = game.spawn_actor(uclass=spear.AKinematicVehicle, name="A", location=spear.FVector(0, 0, 0.2))
        b = game.spawn_actor(uclass=spear.AKinematicVehicle, name="B", location=spear.FVector(0, 5, 0.2))
        assert isinstance(a.InputComponent, spear.UInputComponent) and a.MaxSpeed == 2.0
    with instance.end_frame():
        pass
    for _ in range(30):  # 0.5 s at full throttle: 1 m along +X
        with instance.begin_frame():
            game.inject_input_for_actor(actor=a, input_action_name="Throttle", value=spear.FVector(X=1.0))
        with instance.end_frame():
            pass
    with instance.begin_frame():
        assert a.GetActorLocation().X == pytest.approx(1.0, abs=1e-9)
        assert b.GetActorLocation() == spear.FVector(0, 5, 0.2)
        # Steering yaws the vehicle; the action holds for one tick only.
        game.inject_input_for_actor(actor=a, input_action_name="Steer", value=spear.FVector(X=1.0))
    with instance.end_frame():
        assert a.GetActorRotation().Yaw == pytest.approx(90.0 / 60.0)
        assert not a.InputComponent.IsActionTriggered(ActionName="Steer")
    instance.step(num_frames=5)
    with instance.begin_frame():
        assert a.GetActorRotation().Yaw == pytest.approx(90.0 / 60.0)
        assert b.GetActorRotation().Yaw == 0.0


def test_move_action_drives_in_the_vehicle_frame(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        car = game.spawn_actor(uclass=spear.AKinematicVehicle, name="Car", rotation=spear.FRotator(Yaw=90.0))
        car.MaxSpeed = 6.0
        game.inject_input_for_actor(actor=car, input_action_name="Move", value=spear.FVector(X=1.0))
    with instance.end_frame():
        location = car.GetActorLocation()  # forward is +Y after a 90 degree yaw
        assert location.X == pytest.approx(0.0, abs=1e-12) and location.Y == pytest.approx(0.1)


def test_input_errors_are_clear(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        plain = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Plain")
        with pytest.raises(spear.InvalidArgumentError,
                           match=r"inject_input_for_actor\(\): AStaticMeshActor 'Plain' has no UInputComponent"):
            game.inject_input_for_actor(actor=plain, input_action_name="Throttle", value=spear.FVector(X=1))
        car = game.spawn_actor(uclass=spear.AKinematicVehicle, name="Car")
        with pytest.raises(spear.InvalidArgumentError, match="input_action_name is empty"):
            game.inject_input_for_actor(actor=car, input_action_name="", value=spear.FVector())
        # Refused when injected, not in the next tick (where a pawn would fail to move by it).
        with pytest.raises(spear.InvalidArgumentError,
                           match=r"inject_input_for_actor\(\): value \(nan, 0, 0\) of action 'Throttle' is not finite"):
            game.inject_input_for_actor(actor=car, input_action_name="Throttle", value=spear.FVector(X=math.nan))
