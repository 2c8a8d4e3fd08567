"""Editor and game worlds: a persistent editor world, an ephemeral game world copied from it by play()."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

import spear

ROOT = Path(__file__).resolve().parents[2]
APARTMENT = ROOT / "assets" / "scenes" / "apartment.json"


def test_standalone_instance_has_no_editor(instance: spear.Instance) -> None:
    with pytest.raises(spear.InvalidStateError, match=r"get_editor\(\): this instance runs standalone"):
        instance.get_editor()
    with instance.begin_frame():
        with pytest.raises(spear.InvalidStateError, match=r"UWorld.play\(\): .* is not an editor world"):
            instance.get_game().play()


def test_play_copies_the_editor_world_and_stop_destroys_the_copy(
        tmp_path: Path, make_instance: Callable[..., spear.Instance]) -> None:
    instance = make_instance(mode="editor", scene=APARTMENT)
    editor = instance.get_editor()
    with pytest.raises(spear.InvalidStateError, match=r"get_game\(\): the editor is not playing"):
        instance.get_game()
    with instance.begin_frame():
        assert editor.is_editor_world() and not editor.is_playing()
        count = editor.get_actor_count()
        # Static furniture can be placed in the editor world.
        shelf = editor.find_actor_by_name(name="Shelf")
        assert shelf is not None
        shelf.SetActorLocation(NewLocation=spear.FVector(2.5, -1.5, 0.9))
        editor.play()
        assert editor.is_playing()
    with instance.end_frame():
        pass
    game = instance.get_game()
    assert game != editor
    instance.step(num_frames=30)
    with instance.begin_frame():
        assert game.is_game_world() and not game.is_editor_world()
        assert game.get_actor_count() == count
        game_shelf = game.find_actor_by_name(name="Shelf")
        assert game_shelf is not None and game_shelf != shelf
        assert game_shelf.GetActorLocation().X == pytest.approx(2.5)
        with pytest.raises(spear.InvalidStateError, match="is static"):  # static while playing
            game_shelf.SetActorLocation(NewLocation=spear.FVector())
        game.destroy_actor(actor=game_shelf)
        game.spawn_actor(uclass=spear.AActor, name="OnlyInGame")
        assert game.get_frame_count() == 31 and editor.get_frame_count() == 0  # the editor world never ticks
    with instance.end_frame():
        assert editor.find_actor_by_name(name="OnlyInGame") is None and shelf.is_valid()
        editor.stop()
        assert not game.is_valid()
    with pytest.raises(spear.InvalidStateError):
        instance.get_game()
    with instance.begin_frame():
        with pytest.raises(spear.InvalidStateError, match=r"UWorld.stop\(\): the editor is not playing"):
            editor.stop()
        saved = tmp_path / "edited.json"
        editor.save_scene(path=str(saved))
        editor.load_scene(path=str(saved))
        assert editor.get_actor_count() == count
        moved = editor.find_actor_by_name(name="Shelf")
        assert moved is not None and moved.GetActorLocation().X == pytest.approx(2.5)
        editor.play()  # play again from the edited world
    with instance.end_frame():
        assert instance.get_game().get_actor_count() == count
    instance.close()


def test_bad_instance_mode_is_rejected() -> None:
    with pytest.raises(spear.InvalidArgumentError, match="mode 'server' must be 'game' or 'editor'"):
        spear.Instance(mode="server")  # type: ignore[arg-type]
