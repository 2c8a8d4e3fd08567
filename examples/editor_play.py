"""Editor and game worlds: edit a persistent editor world, play a copy of it, stop, save the edit.

    PYTHONPATH=python /usr/bin/python3 examples/editor_play.py [out.json] [--server launch]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import spear

APARTMENT = "/Game/scenes/apartment"  # assets/scenes/apartment.json, found wherever spear is installed


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("out", nargs="?", type=Path, default=Path(tempfile.gettempdir()) / "apartment_edited.json",
                        help="where to save the edited scene (default: %(default)s)")
    parser.add_argument("--server", default=None, help='"launch", "unix:PATH" or "tcp:HOST:PORT" (default: in-process)')
    args = parser.parse_args()
    out: Path = args.out
    instance = spear.Instance(mode="editor", scene=APARTMENT, server=args.server)
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
