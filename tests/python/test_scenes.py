"""Scene files: reflection-serialised worlds, byte-identical round trips, clear errors."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

import spear

ROOT = Path(__file__).resolve().parents[2]
APARTMENT = ROOT / "assets" / "scenes" / "apartment.json"


def test_the_default_scene_loads_and_saves_byte_identical(
        tmp_path: Path, make_instance: Callable[..., spear.Instance]) -> None:
    instance = make_instance(scene=APARTMENT)
    game = instance.get_game()
    with instance.begin_frame():
        assert game.find_actor_by_name(name="Floor") is not None
        lights = game.find_actors_by_tag(tag="light")
        assert {type(light).__name__ for light in lights} == {"ADirectionalLight", "APointLight"}
        sun = game.find_actor_by_class(uclass=spear.ADirectionalLight)
        assert sun is not None and sun.LightComponent.Intensity == 25.0
        meshes = game.find_actors_by_class(uclass=spear.AStaticMeshActor)
        materials = {m for a in meshes for c in game.get_components_by_class(actor=a, uclass=spear.UStaticMeshComponent)
                     for m in c.Materials}
        assert len(materials) >= 4
        legs = game.find_actor_by_name(name="TableLegs")
        assert legs is not None and len(legs.K2_GetComponents()) == 5  # an empty root and four legs
        out = tmp_path / "apartment.json"
        game.save_scene(path=str(out))
    instance.close()
    assert out.read_bytes() == APARTMENT.read_bytes()


def test_save_load_round_trip_keeps_every_property(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    first, second = tmp_path / "first.json", tmp_path / "second.json"
    with instance.begin_frame():
        cube = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Cube", location=spear.FVector(1.25, 2, 3),
                                rotation=spear.FRotator(Yaw=30.0), tags=["a", "b"])
        mesh = cube.StaticMeshComponent
        mesh.SetStaticMesh(NewMesh="/Engine/BasicShapes/Sphere")
        mesh.SetMaterial(ElementIndex=1, Material="/Game/M_Red")
        mesh.Friction = 0.8
        mesh.CollisionPrimitive = spear.ECollisionPrimitive.Box
        mesh.SetMobility(NewMobility=spear.EComponentMobility.Stationary)
        car = game.spawn_actor(uclass=spear.AKinematicVehicle, name="Car")
        car.MaxSpeed = 7.5
        game.save_scene(path=str(first))
        game.load_scene(path=str(first))
        assert not cube.is_valid()  # load replaces the world's actors
        loaded = game.find_actor_by_name(name="Cube")
        assert isinstance(loaded, spear.AStaticMeshActor)
        assert loaded.Tags == ["a", "b"] and loaded.GetActorLocation() == spear.FVector(1.25, 2, 3)
        lmesh = loaded.StaticMeshComponent
        assert lmesh.Materials == ["", "/Game/M_Red"] and lmesh.Friction == 0.8
        assert lmesh.CollisionPrimitive == spear.ECollisionPrimitive.Box
        assert lmesh.Mobility == spear.EComponentMobility.Stationary
        loaded_car = game.find_actor_by_name(name="Car")
        assert isinstance(loaded_car, spear.AKinematicVehicle) and loaded_car.MaxSpeed == 7.5
        game.save_scene(path=str(second))
    assert first.read_bytes() == second.read_bytes()
    doc = json.loads(first.read_text())
    component = doc["actors"][0]["components"][0]
    assert component["properties"]["Mobility"] == "Stationary"  # enums by name
    assert doc["actors"][0]["properties"]["RootComponent"] == "Cube.StaticMeshComponent"  # references by path


def test_missing_and_malformed_scenes_are_clear_errors(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    bad_json = tmp_path / "bad.json"
    bad_json.write_text("{ not json")
    bad_enum = tmp_path / "bad_enum.json"
    doc = json.loads(APARTMENT.read_text())
    doc["actors"][2]["components"][0]["properties"]["Mobility"] = "Sideways"
    bad_enum.write_text(json.dumps(doc))
    bad_class = tmp_path / "bad_class.json"
    bad_class.write_text(json.dumps({"format": "spear.scene", "version": 1,
                                     "actors": [{"name": "X", "class": "AFoo", "components": []}]}))
    bad_field = tmp_path / "bad_field.json"
    bad_field.write_text(json.dumps({"format": "spear.scene", "version": 1, "actors": [
        {"name": "X", "class": "AActor", "properties": {"Colour": 1}, "components": []}]}))
    with instance.begin_frame():
        game.spawn_actor(uclass=spear.AActor, name="Keep")
        with pytest.raises(spear.NotFoundError, match=r"UWorld.load_scene\(\): scene file '.*nowhere.json' not found"):
            game.load_scene(path=str(tmp_path / "nowhere.json"))
        with pytest.raises(spear.InvalidArgumentError, match=r"scene file '.*bad.json' is not valid JSON"):
            game.load_scene(path=str(bad_json))
        huge = tmp_path / "huge.json"
        huge.write_text('{"format": "spear.scene",\n "version": 1e400, "actors": []}')
        with pytest.raises(spear.InvalidArgumentError) as error:
            game.load_scene(path=str(huge))
        assert str(error.value) == (f"UWorld.load_scene(): scene file '{huge}' is not valid JSON: a number at line 2, "
                                    "column 12 is out of a double's range (at most about 1.8e308)")
        with pytest.raises(spear.InvalidArgumentError,
                           match=r"actors\[2\] 'Ceiling': component 'StaticMeshComponent': property 'Mobility': "
                                 r"'Sideways' is not an entry of EComponentMobility"):
            game.load_scene(path=str(bad_enum))
        with pytest.raises(spear.InvalidArgumentError, match=r"actors\[0\] 'X': class 'AFoo' is not registered"):
            game.load_scene(path=str(bad_class))
        with pytest.raises(spear.InvalidArgumentError, match=r"actors\[0\] 'X': AActor has no property 'Colour'"):
            game.load_scene(path=str(bad_field))
        # A failed load leaves the world as it was.
        assert [a.GetName() for a in game.find_actors()] == ["Keep"]
    with pytest.raises(spear.NotFoundError, match="scene file 'missing.json' not found"):
        spear.Instance(scene="missing.json", server="launch" if instance.transport == "rpc" else None)


def test_a_fifo_or_a_device_named_as_a_file_is_refused_at_once(instance: spear.Instance, tmp_path: Path) -> None:
    # A FIFO no one writes blocked the engine in open() for good (over RPC: every client of the server), and
    # /dev/zero was read until memory ran out. Only regular files are read or written.
    fifo = tmp_path / "BP_Fifo.json"
    os.mkfifo(fifo)
    not_regular = "is not a regular file (a FIFO, device or socket)"
    game = instance.get_game()
    with instance.begin_frame():
        kept = game.spawn_actor(uclass=spear.AActor, name="Kept")
        for path in (str(fifo), "/dev/zero"):
            with pytest.raises(spear.InvalidArgumentError,
                               match=re.escape(f"UWorld.load_scene(): scene file '{path}' {not_regular}")):
                game.load_scene(path=path)
            with pytest.raises(spear.InvalidArgumentError,
                               match=re.escape(f"UWorld.load_class(): blueprint '{path}' {not_regular}")):
                game.load_class(uclass=spear.AActor, name=path)
        with pytest.raises(spear.InvalidArgumentError,  # writing: a FIFO with no reader blocked the open
                           match=re.escape(f"UWorld.save_scene(): scene file '{fifo}' {not_regular}")):
            game.save_scene(path=str(fifo))
        with pytest.raises(spear.InvalidArgumentError,
                           match=re.escape(f"UWorld.save_scene(): scene file '/dev/null' {not_regular}")):
            game.save_scene(path="/dev/null")
        assert [a.GetName() for a in game.find_actors()] == ["Kept"] and kept.is_valid()
    with instance.end_frame():
        pass
    with instance.begin_frame():  # the engine works on
        game.spawn_actor(uclass=spear.AActor, name="Next")
        game.save_scene(path=str(tmp_path / "after.json"))
    with instance.end_frame():
        assert game.get_actor_count() == 2


def test_a_scene_that_fails_part_way_leaves_the_world_as_it_was(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    saved = tmp_path / "saved.json"
    with instance.begin_frame():
        cubes = [game.spawn_actor(uclass=spear.AStaticMeshActor, name=f"Cube{i}", location=spear.FVector(i, 0, 1))
                 for i in range(3)]
        for cube in cubes:
            cube.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        game.save_scene(path=str(saved))
        for i, cube in enumerate(cubes):  # the world moves on from what was saved
            cube.SetActorLocation(NewLocation=spear.FVector(i, 5, 1))
    with instance.end_frame():
        pass
    doc = json.loads(saved.read_text())
    # The last actor's friction is negative: refused when the loader sets it, after the first two actors of
    # the scene were built (before physics checked it only when the actor began play; either way the world
    # must stay as it was).
    properties = doc["actors"][-1]["components"][0]["properties"]
    properties["Friction"] = -1.0
    late_failure = tmp_path / "late_failure.json"
    late_failure.write_text(json.dumps(doc))
    properties["Friction"] = "slippery"  # and a value of the wrong type, refused before anything is built
    bad_value = tmp_path / "bad_value.json"
    bad_value.write_text(json.dumps(doc))
    with instance.begin_frame():
        with pytest.raises(spear.InvalidArgumentError,
                           match=re.escape(f"UWorld.load_scene(): scene '{late_failure}': actors[2] 'Cube2': component "
                                           "'StaticMeshComponent': property 'Friction': UPrimitiveComponent.Friction "
                                           "must be finite and >= 0, got -1")):
            game.load_scene(path=str(late_failure))
        with pytest.raises(spear.InvalidArgumentError, match=r"actors\[2\] 'Cube2': component 'StaticMeshComponent': "
                                                             r"property 'Friction': expected a number"):
            game.load_scene(path=str(bad_value))
        # The same actors, the same objects, where they were moved to, and usable.
        assert [a.GetName() for a in game.find_actors()] == ["Cube0", "Cube1", "Cube2"]
        for i, cube in enumerate(cubes):
            assert cube.is_valid() and cube.GetActorLocation() == spear.FVector(i, 5, 1)
            cube.SetActorLocation(NewLocation=spear.FVector(i, 0, 2))
        assert game.find_actor_by_name(name="Cube2") == cubes[2]
    with instance.end_frame():
        assert [cube.GetActorLocation().Z for cube in cubes] == [2, 2, 2]
    with instance.begin_frame():  # and the good scene still loads over them
        game.load_scene(path=str(saved))
        assert not cubes[0].is_valid() and game.get_actor_count() == 3
    with instance.end_frame():
        pass


def test_a_world_of_gameplay_actors_loads_and_saves_byte_identical(instance: spear.Instance, tmp_path: Path) -> None:
    """A car after it settled on its springs, a character, a trigger, a spline and an AI controller: what
    a scene saves of them loads back unchanged (begin-play does not move a car's wheel meshes)."""
    game = instance.get_game()
    with instance.begin_frame():
        floor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Floor", location=spear.FVector(Z=-0.5))
        floor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        floor.SetActorScale3D(NewScale3D=spear.FVector(40.0, 40.0, 1.0))
        car = game.spawn_actor(uclass=spear.AWheeledVehiclePawn, name="Car", location=spear.FVector(Z=1.0))
        car.MaxSteerAngle = 30.0
        walker = game.spawn_actor(uclass=spear.ACharacter, name="Walker", location=spear.FVector(X=5.0, Z=1.0))
        walker.CharacterMovement.MaxWalkSpeed = 2.0
        game.spawn_actor(uclass=spear.ATriggerSphere, name="Trigger", location=spear.FVector(Y=3.0))
        path = game.spawn_actor(uclass=spear.ASplineActor, name="Path").SplineComponent
        path.SetSplinePoints(Points=[spear.FVector(), spear.FVector(X=3.0, Y=1.0)],
                             CoordinateSpace=spear.ESplineCoordinateSpace.Local)
        game.spawn_actor(uclass=spear.AAIController, name="AI").Possess(InPawn=walker)
    with instance.end_frame():
        pass
    instance.step(num_frames=30)
    with instance.begin_frame():
        game.save_scene(path=str(tmp_path / "first.json"))
        game.load_scene(path=str(tmp_path / "first.json"))
        game.save_scene(path=str(tmp_path / "second.json"))
        assert (tmp_path / "first.json").read_bytes() == (tmp_path / "second.json").read_bytes()
        loaded = game.find_actor_by_name(name="Car")
        assert isinstance(loaded, spear.AWheeledVehiclePawn) and loaded.MaxSteerAngle == 30.0
    with instance.end_frame():
        pass


def test_the_default_scene_textures_are_what_their_script_makes() -> None:
    # The committed maps are generated, not edited: the script compares their pixels with what it makes now.
    script = ROOT / "scripts" / "make_apartment_textures.py"
    result = subprocess.run([sys.executable, str(script), "--check"], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
