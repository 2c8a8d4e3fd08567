"""Assets named by a relative path are found from any working directory: the working directory first, then
SPEAR_ASSET_PATH's folders, then spear's built-in assets; UE's /Game/ names are assets/ names
(core/base/asset_path.h). Both transports, from a folder that is not the checkout."""

from __future__ import annotations

import json
import shutil
from collections.abc import Callable
from pathlib import Path

import pytest

import spear

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
