"""Bad values are refused when they are set, on both transports, naming the property and its range; the
engine keeps running and the old value stays (before, they were accepted and failed every later frame)."""

from __future__ import annotations

import math
import re
from typing import Any

import pytest

import spear


def spawn_simulated_box(game: spear.UWorld, location: spear.FVector) -> spear.AStaticMeshActor:
    """A cube at location that physics simulates."""
    box = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Box", location=location)
    box.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
    box.StaticMeshComponent.SetSimulatePhysics(bSimulate=True)
    return box


def assert_still_steps(instance: spear.Instance, box: spear.AActor) -> None:
    """Physics steps on after a refused value, and the box's location stays finite."""
    instance.step(num_frames=2)
    with instance.begin_frame():
        location = box.GetActorLocation()
        assert all(math.isfinite(c) for c in (location.X, location.Y, location.Z))
    with instance.end_frame():
        pass


CAMERA_CASES = [
    ("Width", 100000, 640, "UCameraSensorComponent.Width must be in [1, 16384], got 100000"),
    ("Width", -5, 640, "UCameraSensorComponent.Width must be in [1, 16384], got -5"),
    ("Height", 0, 480, "UCameraSensorComponent.Height must be in [1, 16384], got 0"),
    ("FOV", 180.0, 90.0, "UCameraSensorComponent.FOV must be in (0, 180) degrees, got 180"),
    ("NearClip", 0.0, 0.05, "UCameraSensorComponent.NearClip must be > 0 and finite, got 0"),
    ("FarClip", math.inf, 1000.0, "UCameraSensorComponent.FarClip must be > 0 and finite, got inf"),
    ("Exposure", math.nan, 1.0, "UCameraSensorComponent.Exposure must be > 0 and finite, got nan"),
    ("ShadowResolution", 8, 0, "UCameraSensorComponent.ShadowResolution must be 0 or in [16, 8192], got 8"),
    ("Latency", 3, 0, "UCameraSensorComponent.Latency must be 0, 1 or 2, got 3"),
    ("AutoExposureBias", 16.0, 0.0, "UCameraSensorComponent.AutoExposureBias must be in [-15, 15] f-stops, got 16"),
    ("AutoExposureMinBrightness", math.nan, -10.0,
     "UCameraSensorComponent.AutoExposureMinBrightness must be in [-20, 40] EV100, got nan"),
    ("AutoExposureMaxBrightness", 41.0, 20.0,
     "UCameraSensorComponent.AutoExposureMaxBrightness must be in [-20, 40] EV100, got 41"),
    ("AutoExposureSpeedUp", 0.0, 3.0, "UCameraSensorComponent.AutoExposureSpeedUp must be in (0, 100] f-stops per second, got 0"),
    ("AutoExposureSpeedDown", math.inf, 1.0,
     "UCameraSensorComponent.AutoExposureSpeedDown must be in (0, 100] f-stops per second, got inf"),
    ("AutoExposureLowPercent", 100.0, 10.0, "UCameraSensorComponent.AutoExposureLowPercent must be in [0, 100), got 100"),
    ("AutoExposureHighPercent", -1.0, 90.0, "UCameraSensorComponent.AutoExposureHighPercent must be in (0, 100], got -1"),
]


@pytest.mark.parametrize("name, value, default, message", CAMERA_CASES, ids=[f"{c[0]}={c[1]}" for c in CAMERA_CASES])
def test_camera_settings_are_checked_when_set(instance: spear.Instance, name: str, value: Any, default: Any,
                                              message: str) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera").CameraSensor
        camera.Width, camera.Height = 32, 24
        with pytest.raises(spear.InvalidArgumentError, match=re.escape(message)):
            setattr(camera, name, value)
        expected = 32 if name == "Width" else 24 if name == "Height" else default
        assert getattr(camera, name) == expected
    with instance.end_frame():
        assert "final_color" in camera.read_pixels()  # the camera still renders


def test_valid_camera_settings_are_taken(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera").CameraSensor
        camera.Width, camera.Height, camera.FOV, camera.Latency, camera.ShadowResolution = 16, 8, 179.5, 2, 16
        assert (camera.Width, camera.Height, camera.FOV, camera.Latency, camera.ShadowResolution) == (16, 8, 179.5, 2, 16)
    with instance.end_frame():
        pass


@pytest.mark.parametrize("call, message", [
    ("location", "USceneComponent.SetRelativeTransform(): the location must be finite, got (nan, 0.000000, 0.000000)"),
    ("relative", "USceneComponent.SetRelativeLocation(): the location must be finite, got (inf, 0.000000, 0.000000)"),
    ("rotation", "USceneComponent.SetRelativeRotation(): the rotation must be finite"),
    ("scale", "USceneComponent.SetRelativeTransform(): the scale must have no zero component, got (0.000000, 1.000000, 1.000000)"),
])
def test_transforms_are_checked_when_set(instance: spear.Instance, call: str, message: str) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        box = spawn_simulated_box(game, spear.FVector(1.0, 2.0, 3.0))
        mesh = box.StaticMeshComponent
        with pytest.raises(spear.InvalidArgumentError, match=re.escape(message)):
            if call == "location":
                box.SetActorLocation(NewLocation=spear.FVector(math.nan, 0.0, 0.0))
            elif call == "relative":
                mesh.SetRelativeLocation(NewLocation=spear.FVector(math.inf, 0.0, 0.0))
            elif call == "rotation":
                mesh.RelativeRotation = spear.FRotator(Pitch=math.nan, Yaw=0.0, Roll=0.0)
            else:
                box.SetActorScale3D(NewScale3D=spear.FVector(0.0, 1.0, 1.0))
        assert box.GetActorLocation() == spear.FVector(1.0, 2.0, 3.0)
    with instance.end_frame():
        pass
    assert_still_steps(instance, box)  # with the old, valid transform


PHYSICS_CASES = [
    ("Friction", math.nan, 0.5, "UPrimitiveComponent.Friction must be finite and >= 0, got nan"),
    ("Friction", -0.1, 0.5, "UPrimitiveComponent.Friction must be finite and >= 0, got -0.1"),
    ("Restitution", 1.5, 0.0, "UPrimitiveComponent.Restitution must be in [0, 1], got 1.5"),
    ("LinearDamping", math.inf, 0.0, "UPrimitiveComponent.LinearDamping must be in [0, 1], got inf"),
    ("AngularDamping", -1.0, 0.0, "UPrimitiveComponent.AngularDamping must be in [0, 1], got -1"),
]


@pytest.mark.parametrize("name, value, default, message", PHYSICS_CASES, ids=[f"{c[0]}={c[1]}" for c in PHYSICS_CASES])
def test_physics_properties_are_checked_when_set(instance: spear.Instance, name: str, value: float, default: float,
                                                 message: str) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        box = spawn_simulated_box(game, spear.FVector(0.0, 0.0, 1.0))
        mesh = box.StaticMeshComponent
        with pytest.raises(spear.InvalidArgumentError, match=re.escape(message)):
            setattr(mesh, name, value)
        assert getattr(mesh, name) == default
        setattr(mesh, name, 0.25)  # a valid value is taken
        assert getattr(mesh, name) == 0.25
    with instance.end_frame():
        pass
    assert_still_steps(instance, box)  # with the old, valid values


MISTYPED_CASES = [
    ("Width", True, "UCameraSensorComponent.Width must be an int, got bool True"),
    ("Width", 1.5, "UCameraSensorComponent.Width must be an int, got float 1.5"),
    ("Width", "64", "UCameraSensorComponent.Width must be an int, got str '64'"),
    ("Width", 2**40, "UCameraSensorComponent.Width is out of range: 1099511627776"),
    ("bShadows", 0, "UCameraSensorComponent.bShadows must be a bool, got int 0"),
]


@pytest.mark.parametrize("name, value, message", MISTYPED_CASES, ids=[f"{c[0]}={c[1]!r}" for c in MISTYPED_CASES])
def test_mistyped_values_give_the_same_error_on_both_transports(instance: spear.Instance, name: str, value: Any,
                                                                message: str) -> None:
    # Python's bool is an int: without its own check, True would have become Width 1 in-process.
    game = instance.get_game()
    with instance.begin_frame():
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera").CameraSensor
        with pytest.raises(spear.InvalidArgumentError) as error:
            setattr(camera, name, value)
        assert str(error.value) == message
        box = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Box").StaticMeshComponent
        box.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        with pytest.raises(spear.InvalidArgumentError) as error:
            box.SetSimulatePhysics(bSimulate=1)  # type: ignore[arg-type]  # the misuse under test
        assert str(error.value) == ("UPrimitiveComponent.SetSimulatePhysics(): argument 'bSimulate' must be a bool, "
                                    "got int 1")
    with instance.end_frame():
        pass


def test_numpy_scalars_pass_for_python_numbers_on_both_transports(instance: spear.Instance) -> None:
    import numpy as np

    game = instance.get_game()
    with instance.begin_frame():
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera").CameraSensor
        camera.Width, camera.bShadows, camera.FOV = np.int64(48), np.bool_(False), np.float32(75.0)
        assert (camera.Width, camera.bShadows, camera.FOV) == (48, False, 75.0)
    with instance.end_frame():
        pass
