"""Streaming levels on both transports: a scene declares sub-scenes that UGameplayStatics.LoadStreamLevel
and UnloadStreamLevel add to and remove from the world inside a frame, leaving the rest of the world
bit-identical; handles into an unloaded level go stale naming it; bad levels change nothing."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

import pytest

import spear
from spear.errors import InvalidArgumentError, NotFoundError, StaleObjectError

Statics = spear.UGameplayStatics


def cube(game: spear.UWorld, name: str, x: float, z: float, *, simulate: bool = False) -> spear.AStaticMeshActor:
    actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name=name, location=spear.FVector(X=x, Z=z))
    actor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
    actor.StaticMeshComponent.SetSimulatePhysics(bSimulate=simulate)
    return actor


def write_files(instance: spear.Instance, folder: Path) -> Path:
    """levels/kitchen.json (a table and a crate that falls onto it, far from the rest), levels/garden.json
    (a bench), and main.json (a floor and a falling box) declaring both levels."""
    game = instance.get_game()
    (folder / "levels").mkdir()
    with instance.begin_frame():
        table = cube(game, "Table", 50.0, 0.5)
        crate = cube(game, "Crate", 50.0, 3.0, simulate=True)
        game.save_scene(path=str(folder / "levels" / "kitchen.json"))
        for actor in (table, crate):
            game.destroy_actor(actor=actor)
        bench = cube(game, "Bench", -50.0, 0.5)
        game.save_scene(path=str(folder / "levels" / "garden.json"))
        game.destroy_actor(actor=bench)
        floor = cube(game, "Floor", 0.0, -0.5)
        floor.SetActorScale3D(NewScale3D=spear.FVector(20.0, 20.0, 1.0))
        cube(game, "Box", 0.0, 4.0, simulate=True)
        game.save_scene(path=str(folder / "main.json"))
    with instance.end_frame():
        pass
    scene = json.loads((folder / "main.json").read_text())
    scene["levels"] = [{"name": "Kitchen", "path": "levels/kitchen.json", "loaded": False},
                       {"name": "Garden", "path": "levels/garden.json", "loaded": False}]
    (folder / "main.json").write_text(json.dumps(scene, indent=2) + "\n")
    return folder / "main.json"


def box_trajectory(instance: spear.Instance, main: Path, stream: bool) -> list[tuple[float, float, float]]:
    """The persistent box's fall over 90 frames, loading the Kitchen at frame 20 and unloading it at 60."""
    game = instance.get_game()
    with instance.begin_frame():
        game.load_scene(path=str(main))
        box = game.find_actor_by_name(name="Box")
        assert box is not None
    with instance.end_frame():
        pass
    samples = []
    for frame in range(90):
        with instance.begin_frame():
            if stream and frame == 20:
                Statics.LoadStreamLevel(WorldContextObject=game, LevelName="Kitchen")
            if stream and frame == 60:
                Statics.UnloadStreamLevel(WorldContextObject=game, LevelName="Kitchen")
            location = box.GetActorLocation()
            samples.append((location.X, location.Y, location.Z))
        with instance.end_frame():
            pass
    return samples


def test_levels_load_and_unload_inside_a_frame(instance: spear.Instance, tmp_path: Path) -> None:
    main = write_files(instance, tmp_path)
    game = instance.get_game()
    with instance.begin_frame():
        game.load_scene(path=str(main))
        assert Statics.GetStreamingLevelNames(WorldContextObject=game) == ["Kitchen", "Garden"]
        assert not Statics.IsStreamingLevelLoaded(WorldContextObject=game, LevelName="Kitchen")
        # Loading and unloading a level leaves the rest of the world as it was, to the byte.
        game.save_scene(path=str(tmp_path / "before.json"))
        Statics.LoadStreamLevel(WorldContextObject=game, LevelName="Garden")
        Statics.UnloadStreamLevel(WorldContextObject=game, LevelName="Garden")
        game.save_scene(path=str(tmp_path / "after.json"))
        assert (tmp_path / "after.json").read_bytes() == (tmp_path / "before.json").read_bytes()
        assert game.get_actor_count() == 2
        Statics.LoadStreamLevel(WorldContextObject=game, LevelName="Kitchen")
        Statics.LoadStreamLevel(WorldContextObject=game, LevelName="Kitchen")  # loaded: nothing happens
        assert game.get_actor_count() == 4
        crate = game.find_actor_by_name(name="Crate")
        assert crate is not None and crate.GetStreamingLevelName() == "Kitchen"
        assert Statics.IsStreamingLevelLoaded(WorldContextObject=game, LevelName="Kitchen")
        floor = game.find_actor_by_name(name="Floor")
        assert floor is not None and floor.GetStreamingLevelName() == ""
        # A scene saved now keeps the level in its file: it records that it is loaded, not its actors.
        game.save_scene(path=str(tmp_path / "during.json"))
        saved = json.loads((tmp_path / "during.json").read_text())
        assert [a["name"] for a in saved["actors"]] == ["Floor", "Box"]
        assert saved["levels"][0] == {"name": "Kitchen", "path": "levels/kitchen.json", "loaded": True}
    with instance.end_frame():
        pass
    instance.step(num_frames=60)
    with instance.begin_frame():
        assert crate.GetActorLocation().Z == pytest.approx(1.5, abs=1e-3)  # fell onto the level's table
        Statics.UnloadStreamLevel(WorldContextObject=game, LevelName="Kitchen")
        assert game.get_actor_count() == 2 and game.find_actor_by_name(name="Crate") is None
        with pytest.raises(StaleObjectError, match="AStaticMeshActor 'Crate' of streaming level 'Kitchen' "
                                                   r"\(handle .*\) was destroyed"):
            crate.GetActorLocation()
        # A scene that marks a level loaded loads it with the scene.
        game.load_scene(path=str(tmp_path / "during.json"))
        assert Statics.IsStreamingLevelLoaded(WorldContextObject=game, LevelName="Kitchen")
        assert game.get_actor_count() == 4
        # A level can be named by its file's path too.
        Statics.LoadStreamLevel(WorldContextObject=game, LevelName=str(tmp_path / "levels" / "garden.json"))
        bench = game.find_actor_by_name(name="Bench")
        assert bench is not None and bench.GetStreamingLevelName() == str(tmp_path / "levels" / "garden.json")
    with instance.end_frame():
        pass


def test_streaming_leaves_the_rest_of_the_world_bit_identical(make_instance: Callable[..., spear.Instance],
                                                              tmp_path: Path) -> None:
    first = make_instance()
    main = write_files(first, tmp_path)
    with_streaming = box_trajectory(first, main, stream=True)
    without = box_trajectory(make_instance(), main, stream=False)
    assert with_streaming == without
    assert with_streaming[-1][2] == pytest.approx(0.5, abs=1e-3)  # the box landed on the floor


def test_bad_levels_change_nothing(instance: spear.Instance, tmp_path: Path) -> None:
    main = write_files(instance, tmp_path)
    game = instance.get_game()
    with instance.begin_frame():
        game.load_scene(path=str(main))
        # A level whose actor names are in use is refused before the world changes.
        clash = json.loads((tmp_path / "levels" / "kitchen.json").read_text())
        clash["actors"][0]["name"] = "Floor"
        (tmp_path / "clash.json").write_text(json.dumps(clash))
        with pytest.raises(InvalidArgumentError, match="actors\\[0\\] 'Floor': the name is used by an actor of "
                                                       "the world"):
            Statics.LoadStreamLevel(WorldContextObject=game, LevelName=str(tmp_path / "clash.json"))
        assert game.get_actor_count() == 2 and game.find_actor_by_name(name="Crate") is None
        with pytest.raises(NotFoundError):
            Statics.LoadStreamLevel(WorldContextObject=game, LevelName=str(tmp_path / "missing.json"))
        # Neither failed path stays behind as a level.
        assert Statics.GetStreamingLevelNames(WorldContextObject=game) == ["Kitchen", "Garden"]
        with pytest.raises(InvalidArgumentError, match="no streaming level 'Attic' in this world \\(levels: "
                                                       "'Kitchen', 'Garden'\\)"):
            Statics.UnloadStreamLevel(WorldContextObject=game, LevelName="Attic")
        # A scene whose level marked loaded cannot be read is refused as a whole: the world stays as it was.
        broken = json.loads(main.read_text())
        broken["levels"][1] = {"name": "Garden", "path": "levels/missing.json", "loaded": True}
        (tmp_path / "broken.json").write_text(json.dumps(broken))
        Statics.LoadStreamLevel(WorldContextObject=game, LevelName="Kitchen")
        with pytest.raises(NotFoundError, match="streaming level 'Garden'"):
            game.load_scene(path=str(tmp_path / "broken.json"))
        assert game.get_actor_count() == 4 and game.find_actor_by_name(name="Crate") is not None
        assert Statics.IsStreamingLevelLoaded(WorldContextObject=game, LevelName="Kitchen")
        assert Statics.GetStreamingLevelNames(WorldContextObject=game) == ["Kitchen", "Garden"]
    with instance.end_frame():
        pass


def test_play_starts_with_the_levels_the_editor_loaded(make_instance: Callable[..., spear.Instance],
                                                       tmp_path: Path) -> None:
    main = write_files(make_instance(), tmp_path)
    instance = make_instance(mode="editor", scene=main)
    editor = instance.get_editor()
    with instance.begin_frame():
        Statics.LoadStreamLevel(WorldContextObject=editor, LevelName="Garden")
        editor.play()
    with instance.end_frame():
        pass
    game = instance.get_game()
    with instance.begin_frame():
        assert Statics.GetStreamingLevelNames(WorldContextObject=game) == ["Kitchen", "Garden"]
        assert Statics.IsStreamingLevelLoaded(WorldContextObject=game, LevelName="Garden")
        assert not Statics.IsStreamingLevelLoaded(WorldContextObject=game, LevelName="Kitchen")
        bench = game.find_actor_by_name(name="Bench")
        assert bench is not None and bench.GetStreamingLevelName() == "Garden"
        # Read from the scene's folder although the game world was copied, not loaded from the file.
        Statics.LoadStreamLevel(WorldContextObject=game, LevelName="Kitchen")
        assert game.find_actor_by_name(name="Crate") is not None
    with instance.end_frame():
        pass
