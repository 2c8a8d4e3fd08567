"""Assets named by a relative path are found from any working directory: the working directory first, then
SPEAR_ASSET_PATH's folders, then spear's built-in assets; UE's /Game/ names are assets/ names
(core/base/asset_path.h). Both transports, from a folder that is not the checkout."""

from __future__ import annotations

import json
import shutil
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

import spear
from test_camera import spawn_camera

ASSETS = Path(__file__).resolve().parents[2] / "assets"


@pytest.fixture(autouse=True)
def elsewhere(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """Every test runs from an empty folder outside the checkout, with no SPEAR_ASSET_PATH of its own."""
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    monkeypatch.delenv("SPEAR_ASSET_PATH", raising=False)
    return work


def _actor_names(instance: spear.Instance) -> set[str]:
    game = instance.get_game()
    with instance.begin_frame():
        pass
    with instance.end_frame():
        return {actor.GetName() for actor in game.find_actors_by_class(uclass=spear.AActor)}


def _first_actors(path: Path, count: int) -> None:
    """A scene of the apartment's first `count` actors."""
    document = json.loads((ASSETS / "scenes" / "apartment.json").read_text())
    document["actors"] = document["actors"][:count]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(document))


def test_the_built_in_scene_loads_by_its_relative_name(make_instance: Callable[..., spear.Instance]) -> None:
    names = _actor_names(make_instance(scene="assets/scenes/apartment.json"))
    assert names == _actor_names(make_instance(scene=str(ASSETS / "scenes" / "apartment.json")))
    assert len(names) > 10


def test_game_names_are_assets_names(make_instance: Callable[..., spear.Instance]) -> None:
    by_name = _actor_names(make_instance(scene="/Game/scenes/apartment"))
    assert by_name == _actor_names(make_instance(scene=str(ASSETS / "scenes" / "apartment.json")))


def test_built_in_blueprints_spawn_from_anywhere(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        crate = game.spawn_actor(uclass=spear.BP_Crate, name="Crate")
        axes = game.load_class(uclass=spear.AActor, name="/Game/blueprints/BP_Axes")
        assert axes.__sp_class__ == "BP_Axes"
    with instance.end_frame():
        assert crate.GetClassName() == "BP_Crate"


def test_spear_asset_path_folders_are_searched(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                               make_instance: Callable[..., spear.Instance]) -> None:
    library = tmp_path / "library"
    _first_actors(library / "rooms" / "my_room.json", 3)
    monkeypatch.setenv("SPEAR_ASSET_PATH", f"{tmp_path / 'nothing-here'}:{library}")
    assert len(_actor_names(make_instance(scene="rooms/my_room.json"))) == 3


def test_streaming_levels_are_relative_to_the_scene_file_found(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                               elsewhere: Path,
                                                               make_instance: Callable[..., spear.Instance]) -> None:
    # A scene found on SPEAR_ASSET_PATH names its level relative to its own folder: a file of the same
    # relative name in the working directory (two actors) is not the level (one actor).
    _first_actors(elsewhere / "rooms" / "extra.json", 2)
    library = tmp_path / "library"
    _first_actors(library / "rooms" / "extra.json", 1)
    room = library / "rooms" / "my_room.json"
    _first_actors(room, 0)
    document = json.loads(room.read_text())
    document["levels"] = [{"name": "Extra", "path": "extra.json", "loaded": True}]
    room.write_text(json.dumps(document))
    monkeypatch.setenv("SPEAR_ASSET_PATH", str(library))
    assert len(_actor_names(make_instance(scene="rooms/my_room.json"))) == 1


def test_a_file_in_the_working_directory_comes_first(elsewhere: Path,
                                                     make_instance: Callable[..., spear.Instance]) -> None:
    # The user's own assets/scenes/apartment.json (two actors) shadows the built-in one.
    _first_actors(elsewhere / "assets" / "scenes" / "apartment.json", 2)
    assert len(_actor_names(make_instance(scene="assets/scenes/apartment.json"))) == 2


def test_a_missing_asset_is_named(make_instance: Callable[..., spear.Instance]) -> None:
    with pytest.raises(spear.NotFoundError, match="no_such_room"):
        make_instance(scene="/Game/scenes/no_such_room")


def _box_obj(half: tuple[float, float, float]) -> str:
    """An OBJ box of the given half extents, centred on the origin."""
    hx, hy, hz = half
    corners = [(x, y, z) for x in (-hx, hx) for y in (-hy, hy) for z in (-hz, hz)]
    faces = [(1, 2, 4, 3), (5, 7, 8, 6), (1, 5, 6, 2), (3, 4, 8, 7), (1, 3, 7, 5), (2, 6, 8, 4)]
    return "".join(f"v {x} {y} {z}\n" for x, y, z in corners) + "".join(
        f"f {a} {b} {c}\nf {a} {c} {d}\n" for a, b, c, d in faces
    )


def _mesh_scene(path: Path, mesh: str) -> None:
    """A scene of one static mesh actor named Box showing `mesh`."""
    path.parent.mkdir(parents=True, exist_ok=True)
    component = {"name": "StaticMeshComponent", "class": "UStaticMeshComponent", "attach_parent": None,
                 "properties": {"StaticMesh": mesh}}
    actor = {"name": "Box", "class": "AStaticMeshActor", "components": [component]}
    path.write_text(json.dumps({"format": "spear.scene", "version": 1, "actors": [actor]}))


@pytest.mark.parametrize("levels", [False, True], ids=["scene", "streaming-level"])
def test_meshes_are_relative_to_the_scene_file_that_names_them(
    tmp_path: Path, elsewhere: Path, levels: bool, make_instance: Callable[..., spear.Instance]
) -> None:
    # A scene travels with its meshes: "meshes/box.obj" is the one beside the scene file (half extents
    # 0.25, 0.5, 1), not a file of the same relative name in the working directory (a unit box), both for
    # the engine's bounds and physics and for the renderer.
    (elsewhere / "meshes").mkdir()
    (elsewhere / "meshes" / "box.obj").write_text(_box_obj((0.5, 0.5, 0.5)))
    bundle = tmp_path / "bundle"
    (bundle / "meshes").mkdir(parents=True)
    (bundle / "meshes" / "box.obj").write_text(_box_obj((0.25, 0.5, 1.0)))
    _mesh_scene(bundle / "scene.json", "meshes/box.obj")
    if levels:  # the level's file is in a folder of its own, and its mesh is relative to that folder
        room = tmp_path / "room.json"
        _first_actors(room, 0)
        document = json.loads(room.read_text())
        document["levels"] = [{"name": "Bundle", "path": "bundle/scene.json", "loaded": True}]
        room.write_text(json.dumps(document))
    instance = make_instance(scene=str(tmp_path / "room.json" if levels else bundle / "scene.json"))
    game = instance.get_game()
    with instance.begin_frame():
        box = game.find_actor_by_name(name="Box")
        assert isinstance(box, spear.AStaticMeshActor)
        # What the scene says is kept as written, so that saving it keeps the bundle relocatable.
        assert box.StaticMeshComponent.StaticMesh == "meshes/box.obj"
        extent = box.GetActorBounds(bOnlyCollidingComponents=False).BoxExtent
        camera = spawn_camera(game, [spear.ECameraModality.ObjectIds], 32, 32, 90.0)
        camera.GetOwner().SetActorLocation(NewLocation=spear.FVector(X=-4.0))  # type: ignore[union-attr]
    with instance.end_frame():
        assert (extent.X, extent.Y, extent.Z) == pytest.approx((0.25, 0.5, 1.0))
        ids = camera.read_pixels()["object_ids"]
        box_id = camera.GetObjectId(Component=box.StaticMeshComponent)
        # Its face 3.75 m away, 1 m wide and 2 m high, covers 1 / 7.5 and 2 / 7.5 of a 90 degree view of
        # 32 pixels (the unit box would be as wide, and half as high).
        rows, columns = np.nonzero(ids == box_id)
        assert columns.max() - columns.min() + 1 == pytest.approx(4.3, abs=1)
        assert rows.max() - rows.min() + 1 == pytest.approx(8.5, abs=1)


def test_a_missing_mesh_set_as_the_property_is_refused_and_the_mesh_kept(instance: spear.Instance) -> None:
    # Assigning StaticMesh is SetStaticMesh(): a file that is nowhere is NotFoundError naming it and the
    # folders searched, and the component keeps the mesh it had.
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Crate")
        mesh = actor.StaticMeshComponent
        mesh.StaticMesh = "/Engine/BasicShapes/Sphere"
        with pytest.raises(spear.NotFoundError, match=(
                r"UStaticMeshComponent\.SetStaticMesh\(\): mesh file 'meshes/misspelt\.ply' not found "
                r"\(looked for in the working directory, .*\)")):
            mesh.StaticMesh = "meshes/misspelt.ply"
        with pytest.raises(spear.NotFoundError, match=r"'/Engine/BasicShapes/Cone' is not a built-in shape"):
            mesh.StaticMesh = "/Engine/BasicShapes/Cone"
        assert mesh.StaticMesh == "/Engine/BasicShapes/Sphere"


def test_a_scene_naming_a_missing_mesh_is_refused_and_leaves_the_world_as_it_was(
        tmp_path: Path, make_instance: Callable[..., spear.Instance]) -> None:
    _mesh_scene(tmp_path / "bundle" / "scene.json", "meshes/chair.obj")  # no such file beside it or anywhere
    instance = make_instance()
    before = _actor_names(instance)
    game = instance.get_game()
    with instance.begin_frame():
        with pytest.raises(spear.NotFoundError, match=(
                r"scene\.json': actors\[0\] 'Box': component 'StaticMeshComponent': property 'StaticMesh': .*"
                r"mesh file 'meshes/chair\.obj' not found \(looked for in the scene's folder .*bundle, "
                r"the working directory")):
            game.load_scene(path=str(tmp_path / "bundle" / "scene.json"))
    with instance.end_frame():
        pass
    assert _actor_names(instance) == before
