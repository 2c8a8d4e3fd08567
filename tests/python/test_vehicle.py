"""AWheeledVehiclePawn: a car on Bullet's raycast vehicle, driven by input on both transports. It rests on
its springs at the analytic height, drives, steers, brakes, is stopped by a wall, pushes what it hits, and
a scripted drive is bit-identical between runs."""

from __future__ import annotations

import re
from collections.abc import Callable

import pytest

import spear
from spear.errors import InvalidArgumentError

GRAVITY = 9.81
X = spear.FVector(X=1.0)


def ground(game: spear.UWorld) -> None:
    plane = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground")
    plane.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Plane")
    plane.SetActorScale3D(NewScale3D=spear.FVector(200.0, 200.0, 1.0))


def spawn_car(instance: spear.Instance, location: spear.FVector) -> spear.AWheeledVehiclePawn:
    game = instance.get_game()
    with instance.begin_frame():
        ground(game)
        car = game.spawn_actor(uclass=spear.AWheeledVehiclePawn, name="Car", location=location)
    with instance.end_frame():
        pass
    return car


def drive(instance: spear.Instance, actor: spear.AActor, frames: int, **actions: float) -> None:
    game = instance.get_game()
    for _ in range(frames):
        with instance.begin_frame():
            for action, value in actions.items():
                game.inject_input_for_actor(actor=actor, input_action_name=action, value=spear.FVector(X=value))
        with instance.end_frame():
            pass


def test_it_rests_on_its_springs_at_the_analytic_height(instance: spear.Instance) -> None:
    car = spawn_car(instance, location=spear.FVector(Z=1.0))
    instance.step(num_frames=180)
    with instance.begin_frame():
        assert car.GetNumWheels() == 4
        # Each spring carries a quarter of the weight: SuspensionStiffness * mass * compression = mass * g / 4.
        suspension = 0.3 - GRAVITY / (4 * car.SuspensionStiffness)
        # The chassis (0.6 m tall) hangs its wheels from 0.05 m above its bottom face.
        assert car.GetActorLocation().Z == pytest.approx(0.25 + suspension + car.WheelRadius, abs=1e-3)
        assert car.GetForwardSpeed() == pytest.approx(0.0, abs=1e-6)
        for index in range(4):
            wheel = car.GetWheelState(WheelIndex=index)
            assert wheel.bInContact and wheel.SuspensionLength == pytest.approx(suspension, abs=1e-3)
            assert wheel.Location.Z == pytest.approx(car.WheelRadius, abs=1e-3)
            assert wheel.ContactPoint.Z == pytest.approx(0.0, abs=1e-9)
    with instance.end_frame():
        pass


def test_a_controller_drives_it_forward_left_and_to_a_stop(instance: spear.Instance) -> None:
    car = spawn_car(instance, location=spear.FVector(Z=0.9))
    with instance.begin_frame():
        player = spear.UGameplayStatics.GetPlayerController(WorldContextObject=instance.get_game(), PlayerIndex=0)
        assert player is not None
        player.Possess(InPawn=car)  # input for the player now drives the car
    with instance.end_frame():
        pass
    instance.step(num_frames=60)
    drive(instance, player, 120, Throttle=1.0)
    with instance.begin_frame():
        speed, location = car.GetForwardSpeed(), car.GetActorLocation()
        # 6000 N on 1500 kg for 2 s: 8 m/s, less what the tyres lose.
        assert 6.5 < speed < 8.0 and location.X > 6.0 and location.Y == pytest.approx(0.0, abs=1e-6)
        assert car.GetWheelState(WheelIndex=2).RotationInDegrees > 1000.0  # the wheels roll
    with instance.end_frame():
        pass
    drive(instance, player, 60, Throttle=0.5, Steer=1.0)
    with instance.begin_frame():
        assert car.GetActorRotation().Yaw > 20.0 and car.GetActorLocation().Y > 1.0  # positive steer: left
        assert car.GetWheelState(WheelIndex=0).SteerAngleInDegrees == pytest.approx(car.MaxSteerAngle)
        assert car.GetWheelState(WheelIndex=2).SteerAngleInDegrees == 0.0  # only the front wheels steer
    with instance.end_frame():
        pass
    drive(instance, player, 180, Brake=1.0)
    with instance.begin_frame():
        assert abs(car.GetForwardSpeed()) < 0.05
    with instance.end_frame():
        pass


def test_a_wall_stops_it_and_a_box_is_pushed(instance: spear.Instance) -> None:
    game = instance.get_game()
    car = spawn_car(instance, location=spear.FVector(Z=0.9))
    with instance.begin_frame():
        wall = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Wall", location=spear.FVector(X=12.0, Z=1.5))
        wall.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        wall.SetActorScale3D(NewScale3D=spear.FVector(0.4, 10.0, 3.0))
        wall.StaticMeshComponent.Mobility = spear.EComponentMobility.Static
        box = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Box", location=spear.FVector(X=6.0, Y=3.0, Z=0.5))
        box.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        box.StaticMeshComponent.SetSimulatePhysics(bSimulate=True)
        box.StaticMeshComponent.SetMassOverrideInKg(MassInKg=20.0)
    with instance.end_frame():
        pass
    drive(instance, car, 300, Throttle=1.0)
    with instance.begin_frame():
        # The chassis' front (X + 2.1) stays at the wall's face (X = 11.8), give or take contact slop.
        front = car.GetActorLocation().X + 2.1
        assert 10.0 < front < 11.85
        assert box.GetActorLocation().X == pytest.approx(6.0, abs=1e-3)  # beside the car's path: untouched
    with instance.end_frame():
        pass
    with instance.begin_frame():
        car.K2_SetActorLocationAndRotation(NewLocation=spear.FVector(X=0.0, Y=3.0, Z=0.9), NewRotation=spear.FRotator())
    with instance.end_frame():
        pass
    drive(instance, car, 120, Throttle=0.6)
    with instance.begin_frame():
        assert box.GetActorLocation().X > 6.5  # hit and pushed ahead of the car
    with instance.end_frame():
        pass


def test_a_scripted_drive_is_bit_identical_between_runs(make_instance: Callable[..., spear.Instance]) -> None:
    def trajectory() -> list[tuple[float, ...]]:
        instance = make_instance()
        car = spawn_car(instance, location=spear.FVector(Z=0.9))
        samples: list[tuple[float, ...]] = []
        for frame in range(150):
            drive(instance, car, 1, Throttle=1.0 if frame < 100 else -0.5, Steer=0.6 if 40 <= frame < 90 else 0.0)
            with instance.begin_frame():
                location, rotation = car.GetActorLocation(), car.GetActorRotation()
                samples.append((location.X, location.Y, location.Z, rotation.Yaw, car.GetForwardSpeed()))
            with instance.end_frame():
                pass
        instance.close()
        return samples

    first, second = trajectory(), trajectory()
    assert first == second
    assert first[-1][0] > 5.0 and first[-1][3] > 5.0  # it went somewhere and turned


@pytest.mark.parametrize("name, value, message", [
    ("MaxSteerAngle", 95.0, "AWheeledVehiclePawn.MaxSteerAngle must be in [0, 80] degrees, got 95"),
    ("WheelRadius", 0.0, "AWheeledVehiclePawn.WheelRadius must be > 0, got 0"),
    ("MaxEngineForce", -1.0, "AWheeledVehiclePawn.MaxEngineForce must be >= 0, got -1"),
    ("SuspensionStiffness", float("nan"), "AWheeledVehiclePawn.SuspensionStiffness must be > 0, got nan"),
])
def test_bad_settings_are_refused_when_set(instance: spear.Instance, name: str, value: float, message: str) -> None:
    car = spawn_car(instance, location=spear.FVector(Z=0.9))
    with instance.begin_frame():
        before = getattr(car, name)
        with pytest.raises(InvalidArgumentError, match=f"^{re.escape(message)}$"):
            setattr(car, name, value)
        assert getattr(car, name) == before
        with pytest.raises(InvalidArgumentError, match=r"WheelIndex 4 is out of range \[0, 4\)"):
            car.GetWheelState(WheelIndex=4)
    with instance.end_frame():
        pass
    instance.step(num_frames=2)  # the engine keeps running
