"""The same misuse gives the same error, word for word, in-process and over RPC.

Each case runs on both transports inside a frame; the error type and message must equal the pinned ones
on both (None: the call is accepted on both). In-process, arguments pybind11 would not take are decoded as
the server decodes them (core/pybind/bridge.h), and a call that does not fit the signature raises the
TypeError Python raises for the RPC proxy's signature.
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np
import pytest

import spear


@dataclasses.dataclass
class Scene:
    instance: spear.Instance
    game: spear.UWorld
    cube: spear.AStaticMeshActor
    gone: spear.AActor
    camera: spear.UCameraSensorComponent
    library: spear.AMaterialLibrary
    navmesh: spear.ARecastNavMesh
    rig: spear.AMultiViewCameraRig


def _scene(instance: spear.Instance) -> Scene:
    game = instance.get_game()
    with instance.begin_frame():
        cube = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Cube")
        gone = game.spawn_actor(uclass=spear.AActor, name="Gone")
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera").CameraSensor
        library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Library")
        navmesh = game.spawn_actor(uclass=spear.ARecastNavMesh, name="NavMesh")
        rig = game.spawn_actor(uclass=spear.AMultiViewCameraRig, name="Rig")
    with instance.end_frame():
        pass
    with instance.begin_frame():
        game.destroy_actor(actor=gone)
    with instance.end_frame():
        pass
    return Scene(instance, game, cube, gone, camera, library, navmesh, rig)


@pytest.fixture(scope="module")
def scenes() -> Iterator[dict[str, Scene]]:
    inprocess = spear.Instance()
    rpc = spear.Instance(server="launch")
    try:
        yield {"inprocess": _scene(inprocess), "rpc": _scene(rpc)}
    finally:
        inprocess.close()
        rpc.close()


def _deep(levels: int) -> list[Any]:
    value: list[Any] = []
    for _ in range(levels):
        value = [value]
    return value


# (name, misuse, expected error type name or None for accepted, expected message)
def _unset(value: spear.FVector, field: str) -> spear.FVector:
    """`value` with its slot `field` emptied (as `del value.Y` leaves it)."""
    delattr(value, field)
    return value


class _Vector(spear.FVector):
    """A user's subclass of a struct's class: still that struct."""
    __slots__ = ()


CASES: list[tuple[str, Callable[[Scene], object], str | None, str]] = [
    # enums: only a value of the parameter's own enum
    ("enum given int", lambda s: setattr(s.cube.StaticMeshComponent, "Mobility", 2),
     "InvalidArgumentError", "USceneComponent.Mobility must be EComponentMobility, got int 2"),
    ("enum given another enum", lambda s: setattr(s.cube.StaticMeshComponent, "Mobility",
                                                   spear.ESplineCoordinateSpace.World),
     "InvalidArgumentError",
     "USceneComponent.Mobility must be EComponentMobility, got ESplineCoordinateSpace ESplineCoordinateSpace.World"),
    ("enum given str", lambda s: setattr(s.cube.StaticMeshComponent, "Mobility", "Movable"),
     "InvalidArgumentError", "USceneComponent.Mobility must be EComponentMobility, got str 'Movable'"),
    ("enum list element given int", lambda s: s.rig.ConfigureCameras(Width=8, Height=8, Modalities=[0]),  # type: ignore[list-item]
     "InvalidArgumentError",
     "AMultiViewCameraRig.ConfigureCameras(): argument 'Modalities'[0] must be ECameraModality, got int 0"),
    ("enum accepted", lambda s: setattr(s.cube.StaticMeshComponent, "Mobility", spear.EComponentMobility.Movable),
     None, ""),
    # structs
    ("struct given tuple", lambda s: s.cube.SetActorScale3D(NewScale3D=(1.0, 1.0, 1.0)),  # type: ignore[arg-type]
     "InvalidArgumentError", "AActor.SetActorScale3D(): argument 'NewScale3D' must be FVector, got list [... 3 items]"),
    ("struct field given str", lambda s: s.cube.SetActorScale3D(NewScale3D=spear.FVector(X="a")),  # type: ignore[arg-type]
     "InvalidArgumentError",
     "AActor.SetActorScale3D(): argument 'NewScale3D': FVector.X must be a float, got str 'a'"),
    ("struct given another struct", lambda s: s.cube.SetActorScale3D(NewScale3D=spear.FRotator()),  # type: ignore[arg-type]
     "InvalidArgumentError", "AActor.SetActorScale3D(): argument 'NewScale3D': FVector has no field 'Pitch'"),
    ("struct with an emptied field", lambda s: s.cube.SetActorScale3D(NewScale3D=_unset(spear.FVector(), "Y")),
     "AttributeError", "'FVector' object has no attribute 'Y'"),
    ("struct given a subclass of its class", lambda s: s.cube.SetActorScale3D(NewScale3D=_Vector(1.0, 2.0, 3.0)),
     None, ""),
    ("struct value refuses an unknown field", lambda s: setattr(s.cube.GetActorLocation(), "x", 5.0),
     "AttributeError", "'FVector' object has no attribute 'x'"),
    ("struct value within a struct refuses an unknown field",
     lambda s: setattr(s.cube.GetActorTransform().Translation, "Translation", 5.0),
     "AttributeError", "'FVector' object has no attribute 'Translation'"),
    # numbers, bools, strings
    ("int given bool", lambda s: setattr(s.camera, "Width", True),
     "InvalidArgumentError", "UCameraSensorComponent.Width must be an int, got bool True"),
    ("int given float", lambda s: setattr(s.camera, "Width", 64.0),
     "InvalidArgumentError", "UCameraSensorComponent.Width must be an int, got float 64"),
    ("float given bool", lambda s: setattr(s.camera, "FOV", True),
     "InvalidArgumentError", "UCameraSensorComponent.FOV must be a float, got bool True"),
    ("float given str", lambda s: setattr(s.camera, "FOV", "wide"),
     "InvalidArgumentError", "UCameraSensorComponent.FOV must be a float, got str 'wide'"),
    ("float given int", lambda s: setattr(s.camera, "FOV", 90), None, ""),
    ("float given numpy float32", lambda s: setattr(s.camera, "FOV", np.float32(80.0)), None, ""),
    ("int given numpy int64", lambda s: setattr(s.camera, "Width", np.int64(64)), None, ""),
    ("int given an IntEnum", lambda s: setattr(s.camera, "Width", spear.EComponentMobility.Movable), None, ""),
    ("float given an IntEnum", lambda s: setattr(s.camera, "FOV", spear.EComponentMobility.Movable), None, ""),
    ("int given an array", lambda s: setattr(s.camera, "Width", np.array([64, 65])),
     "InvalidArgumentError", "UCameraSensorComponent.Width must be an int, got ndarray <ndarray int64 (2)>"),
    ("int too large for 64 bits", lambda s: setattr(s.camera, "Width", 2**70),
     "InvalidArgumentError", "UCameraSensorComponent.Width: integer 1180591620717411303424 is too large"),
    ("float given a huge int", lambda s: setattr(s.camera, "FOV", -(2**64)),
     "InvalidArgumentError", "UCameraSensorComponent.FOV: integer -18446744073709551616 is too large"),
    ("bool given int", lambda s: s.cube.GetActorBounds(bOnlyCollidingComponents=1),  # type: ignore[arg-type]
     "InvalidArgumentError",
     "AActor.GetActorBounds(): argument 'bOnlyCollidingComponents' must be a bool, got int 1"),
    ("str given bytes", lambda s: s.cube.ActorHasTag(Tag=b"props"),  # type: ignore[arg-type]
     "InvalidArgumentError", "AActor.ActorHasTag(): argument 'Tag': cannot pass a value of type 'bytes'"),
    ("unsendable value", lambda s: setattr(s.camera, "FOV", object()),
     "InvalidArgumentError", "UCameraSensorComponent.FOV: cannot pass a value of type 'object'"),
    # containers
    ("list given str", lambda s: setattr(s.cube, "Tags", "props"),
     "InvalidArgumentError", "AActor.Tags must be a list, got str 'props'"),
    ("list element given int", lambda s: setattr(s.cube, "Tags", ["a", 1]),
     "InvalidArgumentError", "AActor.Tags[1] must be a str, got int 1"),
    ("dict with an int key", lambda s: setattr(s.library, "Materials", {1: spear.FMaterialDesc()}),
     "InvalidArgumentError", "AMaterialLibrary.Materials: dict keys must be str"),
    ("nested too deep", lambda s: setattr(s.cube, "Tags", _deep(100)),
     "InvalidArgumentError", "AActor.Tags: a value has lists or dicts nested deeper than 64 levels"),
    # arrays
    ("array given list", lambda s: s.navmesh.FindPaths(StartPoints=[[0.0, 0.0, 0.0]],  # type: ignore[arg-type]
                                                       EndPoints=np.zeros((1, 3))),
     "InvalidArgumentError",
     "ARecastNavMesh.FindPaths(): argument 'StartPoints' must be an ndarray of float64, got list [... 1 items]"),
    ("array of the wrong dtype", lambda s: s.navmesh.FindPaths(StartPoints=np.zeros((1, 3), np.float32),
                                                               EndPoints=np.zeros((1, 3))),
     "InvalidArgumentError", "ARecastNavMesh.FindPaths(): argument 'StartPoints' must have dtype float64, got float32"),
    # objects and classes
    ("object of another class", lambda s: s.game.destroy_actor(actor=s.camera),  # type: ignore[arg-type]
     "InvalidArgumentError",
     "UWorld.destroy_actor(): argument 'actor' must be AActor, got UCameraSensorComponent 'CameraSensor'"),
    ("object given str", lambda s: s.game.destroy_actor(actor="Cube"),  # type: ignore[arg-type]
     "InvalidArgumentError", "UWorld.destroy_actor(): argument 'actor' must be AActor, got str 'Cube'"),
    ("object given None", lambda s: s.game.destroy_actor(actor=None),  # type: ignore[arg-type]
     "InvalidArgumentError", "UWorld.destroy_actor(): argument 'actor' must not be None"),
    ("destroyed object as argument", lambda s: s.game.destroy_actor(actor=s.gone),
     "StaleObjectError", "UWorld.destroy_actor(): argument 'actor': AActor 'Gone' (handle H) was destroyed"),
    ("class given int", lambda s: s.game.spawn_actor(uclass=3),  # type: ignore[call-overload]
     "InvalidArgumentError", "UWorld.spawn_actor(): argument 'uclass' must be a class, got int 3"),
    ("unknown class name", lambda s: s.game.spawn_actor(uclass="ANoSuchActor"),
     "NotFoundError", "UWorld.spawn_actor(): argument 'uclass': class 'ANoSuchActor' is not registered"),
    # calls that do not fit the signature: Python's own TypeError
    ("unexpected keyword", lambda s: s.cube.GetActorBounds(bOnly=True),  # type: ignore[call-arg]
     "TypeError", "AActor.GetActorBounds() got an unexpected keyword argument 'bOnly'"),
    ("missing keyword", lambda s: s.cube.SetActorScale3D(),  # type: ignore[call-arg]
     "TypeError", "AActor.SetActorScale3D() missing 1 required keyword-only argument: 'NewScale3D'"),
    ("two missing keywords", lambda s: s.cube.K2_SetActorLocationAndRotation(),  # type: ignore[call-arg]
     "TypeError",
     "AActor.K2_SetActorLocationAndRotation() missing 2 required keyword-only arguments: 'NewLocation' and "
     "'NewRotation'"),
    ("positional argument", lambda s: s.cube.GetActorBounds(True),  # type: ignore[misc]
     "TypeError", "AActor.GetActorBounds() takes 1 positional argument but 2 were given"),
    ("positional and keyword", lambda s: s.cube.SetActorScale3D(1, NewScale3D=spear.FVector()),  # type: ignore[misc]
     "TypeError",
     "AActor.SetActorScale3D() takes 1 positional argument but 2 positional arguments (and 1 keyword-only argument) "
     "were given"),
    ("argument to a function without parameters", lambda s: s.cube.GetName(Full=True),  # type: ignore[call-arg]
     "TypeError", "UObject.GetName() got an unexpected keyword argument 'Full'"),
    # attributes
    ("unknown property", lambda s: setattr(s.cube, "CustomTimeDilation", 2.0),
     "AttributeError", "'AStaticMeshActor' object has no attribute 'CustomTimeDilation'"),
    ("read-only property", lambda s: setattr(s.cube, "RootComponent", None),
     "AttributeError", "property 'RootComponent' of 'AStaticMeshActor' object has no setter"),
    # the images of a frame: a key that is no modality (a modality not rendered: test_camera.py)
    ("misspelt modality key", lambda s: s.camera.read_pixels()["normals"],  # type: ignore[typeddict-item]
     "KeyError", "\"'normals' is not a field of FCameraPixels (its fields: final_color, hdr_color, depth, position, "
     "normal, object_ids, material_ids, base_color, roughness, metallic, material_ao, diffuse_illumination, "
     "diffuse_only, specular_residual)\""),
    # property paths (core/reflect/property_path.h) and checked writes
    ("property path through a reference to a missing property",
     lambda s: s.instance.get_property(uobject=s.cube, path="RootComponent.Colour"),
     "NotFoundError",
     "get_property('RootComponent.Colour'): class 'UStaticMeshComponent' has no property 'Colour' (at 'RootComponent')"),
    ("property path past a list's end", lambda s: s.instance.set_property(uobject=s.cube, path="Tags[5]", value="x"),
     "NotFoundError", "set_property('Tags[5]'): 'Tags' has 0 items, no [5]"),
    ("property path that does not parse", lambda s: s.instance.get_property(uobject=s.cube, path="Tags[0"),
     "InvalidArgumentError", "get_property('Tags[0'): property path 'Tags[0' expects ']' at character 7"),
    ("material written through a path, out of range",
     lambda s: s.instance.set_property(uobject=s.library, path="Materials[Bad]", value=spear.FMaterialDesc(Metallic=2.0)),
     "InvalidArgumentError", "AMaterialLibrary.SetMaterials(): material 'Bad': Metallic must be in [0, 1], got 2"),
    ("mesh property naming no shape", lambda s: setattr(s.cube.StaticMeshComponent, "StaticMesh", "/Engine/BasicShapes/Cone"),
     "NotFoundError", "UStaticMeshComponent.SetStaticMesh(): '/Engine/BasicShapes/Cone' is not a built-in shape "
     "(/Engine/BasicShapes/Cube, /Engine/BasicShapes/Sphere, /Engine/BasicShapes/Cylinder, /Engine/BasicShapes/Plane)"),
    ("component added under a parent that is not there",
     lambda s: s.cube.AddComponentByClass(ComponentClass=spear.USceneComponent, AttachParent="Arm"),
     "InvalidArgumentError",
     "AActor.AddComponentByClass(): AttachParent 'Arm' is not a scene component of AStaticMeshActor 'Cube'"),
]


def _outcome(scene: Scene, misuse: Callable[[Scene], object]) -> tuple[str | None, str]:
    with scene.instance.begin_frame():
        try:
            misuse(scene)
            outcome: tuple[str | None, str] = (None, "")
        except Exception as error:  # noqa: BLE001 - the type is what is compared
            # Handles are numbered per engine: the two engines' objects have different ones.
            outcome = (type(error).__name__, re.sub(r"\(handle \d+:\d+\)", "(handle H)", str(error)))
    with scene.instance.end_frame():
        pass
    return outcome


@pytest.mark.parametrize("name, misuse, error, message", CASES, ids=[case[0] for case in CASES])
def test_same_error_on_both_transports(scenes: dict[str, Scene], name: str, misuse: Callable[[Scene], object],
                                       error: str | None, message: str) -> None:
    inprocess = _outcome(scenes["inprocess"], misuse)
    rpc = _outcome(scenes["rpc"], misuse)
    assert inprocess == rpc, f"{name}: in-process {inprocess} but over RPC {rpc}"
    assert inprocess == (error, message)
