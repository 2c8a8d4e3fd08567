"""Editor and game worlds: edit a persistent editor world, play a copy of it, stop, save the edit.

    PYTHONPATH=python /usr/bin/python3 examples/editor_play.py [out.json]
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import spear

APARTMENT = Path(__file__).resolve().parent.parent / "assets" / "scenes" / "apartment.json"


def main() -> None:
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(tempfile.gettempdir()) / "apartment_edited.json"
    instance = spear.Instance(mode="editor", scene=APARTMENT)
    editor = instance.get_editor()

    with instance.begin_frame():
        # Static furniture can be placed in the editor world (in a game world it would be an error).
        shelf = editor.find_actor_by_name(name="Shelf")
        assert shelf is not None
        shelf.SetActorLocation(NewLocation=spear.FVector(2.5, -1.5, 0.9))
        editor.play()  # the game world is a reflection copy of the editor world
    with instance.end_frame():
        pass

    game = instance.get_game()
    instance.step(num_frames=60)
    with instance.begin_frame():
        ball = game.find_actor_by_name(name="Ball")
        assert ball is not None
        print(f"playing: {game.get_actor_count()} actors, {game.get_frame_count()} frames, "
              f"ball at z = {ball.GetActorLocation().Z:.3f} m")
        game.destroy_actor(actor=ball)  # only the game copy loses it
    with instance.end_frame():
        editor.stop()
        print(f"stopped: the editor world still has {editor.get_actor_count()} actors, "
              f"ball present: {editor.find_actor_by_name(name='Ball') is not None}")
        editor.save_scene(path=str(out))
        print(f"saved the edited scene to {out}")
    instance.close()


if __name__ == "__main__":
    main()
