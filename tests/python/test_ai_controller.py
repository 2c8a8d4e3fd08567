"""AAIController.MoveToLocation / MoveToActor on both transports: a flying pawn and a walking character
reach their goal in a straight line and stop within the acceptance radius; the request results and move
status follow UE's; StopMovement stops."""

from __future__ import annotations

import math

import pytest

import spear

Request = spear.EPathFollowingRequestResult
Status = spear.EPathFollowingStatus


def frames(instance: spear.Instance, count: int) -> None:
    instance.step(num_frames=count)


def test_a_flying_pawn_flies_straight_to_the_goal(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        pawn = game.spawn_actor(uclass=spear.ADefaultPawn, location=spear.FVector(Z=1.0))
        ai = game.spawn_actor(uclass=spear.AAIController)
        assert ai.MoveToLocation(Dest=spear.FVector(X=3.0)) == Request.Failed  # no pawn to move
        ai.Possess(InPawn=pawn)
        assert ai.MoveToLocation(Dest=spear.FVector(X=0.05, Z=1.0)) == Request.AlreadyAtGoal
        assert ai.MoveToLocation(Dest=spear.FVector(4.0, 3.0, 1.0)) == Request.RequestSuccessful
        assert ai.GetMoveStatus() == Status.Moving
        assert ai.GetImmediateMoveDestination() == spear.FVector(4.0, 3.0, 1.0)
    with instance.end_frame():
        pass
    samples = []
    for _ in range(40):  # 5 m at 12 m/s: 25 frames
        with instance.begin_frame():
            location = pawn.GetActorLocation()
            samples.append((location.X, location.Y))
        with instance.end_frame():
            pass
    assert all(y == pytest.approx(0.75 * x, abs=1e-9) for x, y in samples)  # on the straight line
    with instance.begin_frame():
        assert ai.GetMoveStatus() == Status.Idle
        arrived = pawn.GetActorLocation()
        assert math.dist((arrived.X, arrived.Y, arrived.Z), (4.0, 3.0, 1.0)) <= 0.1
        assert ai.GetControlRotation().Yaw == pytest.approx(math.degrees(math.atan2(3.0, 4.0)))  # faces its way
    with instance.end_frame():
        pass


def test_a_character_walks_to_an_actor_and_stops_when_told(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        floor = game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(Z=-0.5))
        floor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        floor.SetActorScale3D(NewScale3D=spear.FVector(40.0, 40.0, 1.0))
        walker = game.spawn_actor(uclass=spear.ACharacter, location=spear.FVector(Z=0.95))
        goal = game.spawn_actor(uclass=spear.APlayerStart, name="Goal", location=spear.FVector(X=-3.0, Y=-4.0, Z=5.0))
        ai = game.spawn_actor(uclass=spear.AAIController)
        ai.Possess(InPawn=walker)
        walker.CharacterMovement.MaxWalkSpeed = 2.0
        assert ai.MoveToActor(Goal=goal, AcceptanceRadius=0.2) == Request.RequestSuccessful
    with instance.end_frame():
        pass
    frames(instance, 240)  # 5 m at 2 m/s: 2.5 s
    with instance.begin_frame():
        assert ai.GetMoveStatus() == Status.Idle
        at = walker.GetActorLocation()
        # A walking pawn reaches the goal in the horizontal plane, stopping at the acceptance radius plus
        # its own radius (bStopOnOverlap); it stays on the floor.
        assert math.hypot(at.X + 3.0, at.Y + 4.0) <= 0.2 + 0.35 + 1e-6 and at.Z == pytest.approx(0.9, abs=0.02)
        assert ai.MoveToLocation(Dest=spear.FVector(X=20.0), bStopOnOverlap=False) == Request.RequestSuccessful
    with instance.end_frame():
        pass
    frames(instance, 30)
    with instance.begin_frame():
        ai.StopMovement()
        stopped = walker.GetActorLocation()
        assert ai.GetMoveStatus() == Status.Idle
    with instance.end_frame():
        pass
    frames(instance, 30)
    with instance.begin_frame():
        assert walker.GetActorLocation().X == pytest.approx(stopped.X, abs=0.05)  # it stopped (its last step)
        with pytest.raises(spear.InvalidArgumentError, match="AcceptanceRadius -1 must be >= 0"):
            ai.MoveToLocation(Dest=spear.FVector(), AcceptanceRadius=-1.0)
    with instance.end_frame():
        pass
