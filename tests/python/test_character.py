"""ACharacter on both transports: it stands on the floor at its capsule's half height, walks where its
controller looks, climbs a step no higher than MaxStepHeight and stops at a higher one and at a wall,
jumps to JumpZVelocity^2 / 2g, is seen by triggers, and bad settings are refused when set."""

from __future__ import annotations

import pytest

import spear
from spear.errors import InvalidArgumentError

GRAVITY = 9.81
FULL = spear.FVector(X=1.0)


def block(game: spear.UWorld, name: str, centre: spear.FVector, size: spear.FVector) -> spear.AStaticMeshActor:
    actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name=name, location=centre)
    actor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
    actor.SetActorScale3D(NewScale3D=size)
    return actor


def course(instance: spear.Instance, step_height: float) -> tuple[spear.ACharacter, spear.APlayerController]:
    """A floor, a step of step_height from x = 2 to 6, a wall with its face at x = 7.8, and player 0
    possessing a character standing at the origin."""
    game = instance.get_game()
    with instance.begin_frame():
        block(game, "Floor", spear.FVector(Z=-0.5), spear.FVector(40.0, 40.0, 1.0))
        block(game, "Step", spear.FVector(X=4.0, Z=step_height / 2), spear.FVector(4.0, 6.0, step_height))
        block(game, "Wall", spear.FVector(X=8.0, Z=1.5), spear.FVector(0.4, 6.0, 3.0))
        character = game.spawn_actor(uclass=spear.ACharacter, name="Walker", location=spear.FVector(Z=0.95))
        player = spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=0)
        assert player is not None
        player.Possess(InPawn=character)
    with instance.end_frame():
        pass
    instance.step(num_frames=30)
    return character, player


def walk(instance: spear.Instance, player: spear.APlayerController, frames: int) -> None:
    for _ in range(frames):
        with instance.begin_frame():
            instance.get_game().inject_input_for_actor(actor=player, input_action_name="MoveForward", value=FULL)
        with instance.end_frame():
            pass


def test_it_climbs_a_low_step_and_stops_at_the_wall(instance: spear.Instance) -> None:
    character, player = course(instance, 0.3)
    with instance.begin_frame():
        assert character.CharacterMovement.IsMovingOnGround()
        assert character.GetActorLocation().Z == pytest.approx(0.9, abs=0.02)  # CapsuleHalfHeight above the floor
        character.CharacterMovement.MaxWalkSpeed = 3.0
    with instance.end_frame():
        pass
    walk(instance, player, 60)  # 1 s at 3 m/s along the view (+X): onto the step at x = 3
    with instance.begin_frame():
        location = character.GetActorLocation()
        assert location.X == pytest.approx(3.0, abs=1e-6) and location.Z == pytest.approx(1.2, abs=0.03)
        assert character.CharacterMovement.GetVelocity().X == pytest.approx(3.0, abs=1e-6)
    with instance.end_frame():
        pass
    walk(instance, player, 120)  # would reach x = 9: the wall's face (7.8) stops the capsule (radius 0.35)
    with instance.begin_frame():
        assert 7.8 - 0.1 < character.GetActorLocation().X + 0.35 <= 7.8 + 0.01
        assert character.CharacterMovement.GetVelocity().X == pytest.approx(0.0, abs=0.05)
    with instance.end_frame():
        pass


def test_a_step_above_max_step_height_stops_it(instance: spear.Instance) -> None:
    character, player = course(instance, 0.6)
    walk(instance, player, 120)
    with instance.begin_frame():
        location = character.GetActorLocation()
        assert location.Z == pytest.approx(0.9, abs=0.02) and location.X + 0.35 <= 2.0 + 0.01
        character.CharacterMovement.MaxStepHeight = 0.65  # now it climbs
    with instance.end_frame():
        pass
    walk(instance, player, 30)
    with instance.begin_frame():
        assert character.GetActorLocation().Z == pytest.approx(1.5, abs=0.03)
    with instance.end_frame():
        pass


def test_it_jumps_to_the_height_its_jump_speed_gives(instance: spear.Instance) -> None:
    character, _ = course(instance, 0.3)
    with instance.begin_frame():
        ground = character.GetActorLocation().Z
        assert character.CanJump()
        character.Jump()
    with instance.end_frame():
        pass
    apex = ground
    for _ in range(60):
        with instance.begin_frame():
            apex = max(apex, character.GetActorLocation().Z)
        with instance.end_frame():
            pass
    # Sampled once a frame: the apex lies within a frame's rise of v^2 / 2g.
    assert apex - ground == pytest.approx(4.2 ** 2 / (2 * GRAVITY), abs=0.03)
    with instance.begin_frame():
        assert character.CharacterMovement.IsMovingOnGround()
        assert character.GetActorLocation().Z == pytest.approx(ground, abs=0.01)
    with instance.end_frame():
        pass


def test_a_trigger_sees_it_and_settings_are_checked(instance: spear.Instance) -> None:
    character, player = course(instance, 0.3)
    game = instance.get_game()
    with instance.begin_frame():
        trigger = game.spawn_actor(uclass=spear.ATriggerBox, location=spear.FVector(X=1.5, Z=1.0))
        assert trigger.GetOverlappingActors(ClassFilter=spear.ACharacter) == []
        with pytest.raises(InvalidArgumentError, match=r"^UCharacterMovementComponent\.WalkableFloorAngle must be "
                                                       r"in \(0, 90\) degrees, got 90$"):
            character.CharacterMovement.WalkableFloorAngle = 90.0
        with pytest.raises(InvalidArgumentError, match=r"^UCapsuleComponent\.CapsuleRadius must be > 0, got 0$"):
            character.CapsuleComponent.CapsuleRadius = 0.0
    with instance.end_frame():
        pass
    # Walking at 6 m/s towards the trigger (x in [1, 2]): the frame its capsule first reaches in is the
    # frame the trigger reports the begin-overlap event (not one later).
    entered = began = -1
    for frame in range(20):
        walk(instance, player, 1)
        with instance.begin_frame():
            if entered < 0 and trigger.IsOverlappingActor(Other=character):
                entered = frame
            if began < 0 and trigger.CollisionComponent.GetBeginOverlaps() == [character.CapsuleComponent]:
                began = frame
        with instance.end_frame():
            pass
    assert entered >= 0 and began == entered
    with instance.begin_frame():
        assert trigger.GetOverlappingActors(ClassFilter=spear.ACharacter) == [character]
        # Moving it by hand teleports it; physics carries on from there.
        character.SetActorLocation(NewLocation=spear.FVector(X=-5.0, Z=2.0))
    with instance.end_frame():
        pass
    with instance.begin_frame():
        assert character.GetActorLocation().X == pytest.approx(-5.0)
    with instance.end_frame():
        pass
    instance.step(num_frames=60)
    with instance.begin_frame():
        location = character.GetActorLocation()
        assert location.X == pytest.approx(-5.0) and location.Z == pytest.approx(0.9, abs=0.02)
    with instance.end_frame():
        pass
