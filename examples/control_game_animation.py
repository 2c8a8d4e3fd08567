"""A possessed character walking and running through the apartment with its legs moving, seen by a chase camera.

Player 0 possesses an ACharacter, whose body (ACharacter.Mesh) is the built-in humanoid: its idle, walk and run
clips blend by the speed the character moves at (a blend space), and the body turns to where it walks. The
script drives it with input actions as a game would (MoveForward, MoveRight, Turn): it walks, turns, runs and
stops. A camera attached to the capsule behind it follows; frames of it, and of the walk, go into a sheet.

    PYTHONPATH=python /usr/bin/python3 examples/control_game_animation.py [--frames 150] [--out out/game_animation.png]
        [--server launch]
"""

# Debian 12's Pillow (9.4) has no annotations: strict pyright would flag every use of it.
# pyright: reportUnknownVariableType=false

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from PIL import Image, ImageDraw  # type: ignore[import]  # Debian ships no Pillow stubs

import spear

WIDTH, HEIGHT = 320, 240
WALK_SPEED, RUN_SPEED = 1.25, 3.2  # the humanoid's walk and run clips' own speeds (ACharacter's blend space)


def phase(frame: int, frames: int) -> tuple[str, float, float, float]:
    """(what, MoveForward, Turn, MaxWalkSpeed) at `frame`: walk, walk turning right, run, stop."""
    t = frame / frames
    if t < 0.3:
        return "walk", 1.0, 0.0, WALK_SPEED
    if t < 0.5:
        return "turn", 1.0, -1.0, WALK_SPEED
    if t < 0.75:
        return "run", 1.0, 0.0, RUN_SPEED
    return "stop", 0.0, 0.0, WALK_SPEED


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--frames", type=int, default=150, help="frames to simulate at 1/60 s (default: %(default)s)")
    parser.add_argument("--out", default="out/game_animation.png", help="where to write the sheet of frames")
    parser.add_argument("--server", default=None, help='"launch", "unix:PATH" or "tcp:HOST:PORT" (default: in-process)')
    args = parser.parse_args()
    if args.frames < 8:
        parser.error("--frames must be at least 8")

    instance = spear.Instance(server=args.server)
    game = instance.get_game()
    with instance.begin_frame():
        game.load_scene(path="/Game/scenes/apartment")
        character = game.spawn_actor(uclass=spear.ACharacter, name="Player", location=spear.FVector(-1.1, -0.2, 0.95))
        player = spear.UGameplayStatics.GetPlayerController(WorldContextObject=game, PlayerIndex=0)
        assert player is not None
        player.Possess(InPawn=character)
        # The chase camera: on the capsule, 1.6 m behind and 0.7 m above its centre, looking a little down.
        chase = game.spawn_actor(uclass=spear.ACameraSensorActor, name="ChaseCamera").CameraSensor
        chase.AttachToComponent(Parent=character.CapsuleComponent)
        chase.SetRelativeLocation(NewLocation=spear.FVector(-1.6, 0.0, 0.7))
        chase.SetRelativeRotation(NewRotation=spear.FRotator(Pitch=-12.0))
        chase.Width, chase.Height, chase.FOV = WIDTH, HEIGHT, 80.0
        chase.Modalities = [spear.ECameraModality.FinalColor]
        chase.AutoExposureMethod = spear.EAutoExposureMethod.AEM_Histogram
        body = character.Mesh
        clips = [sample.Animation for sample in body.BlendSpace]
        print(f"player 0 possesses {character.GetName()}; its body: {body.SkeletalMesh} "
              f"({body.GetNumBones()} bones), blend space "
              + ", ".join(f"{s.Animation} at {s.SampleValue:g} m/s" for s in body.BlendSpace))
    with instance.end_frame():
        pass

    shown = {int(round(f * (args.frames - 1) / 7)) for f in range(8)}
    frames: list[tuple[int, str, NDArray[np.uint8]]] = []
    last = ""
    for frame in range(args.frames):
        what, forward, turn, speed = phase(frame, args.frames)
        with instance.begin_frame():
            character.CharacterMovement.MaxWalkSpeed = speed
            game.inject_input_for_actor(actor=player, input_action_name="MoveForward", value=spear.FVector(X=forward))
            game.inject_input_for_actor(actor=player, input_action_name="Turn", value=spear.FVector(X=turn))
        with instance.end_frame():
            if frame in shown:
                pixels = chase.read_pixels()
                assert "final_color" in pixels  # a partial TypedDict: only the camera's modalities
                frames.append((frame, what, pixels["final_color"][..., :3].copy()))
        if what != last or frame == args.frames - 1:
            with instance.begin_frame():
                weights = body.GetBlendSpaceWeights()
                velocity = character.CharacterMovement.GetVelocity()
                location = character.GetActorLocation()
            with instance.end_frame():
                pass
            blend = ", ".join(f"{clip} {w:.2f}" for clip, w in zip(clips, weights) if w > 0.005)
            print(f"frame {frame + 1}/{args.frames} {what}: at ({location.X:.2f}, {location.Y:.2f}), "
                  f"{np.hypot(velocity.X, velocity.Y):.2f} m/s, pose {blend}", flush=True)
            last = what
    instance.close()

    label = 20
    columns = 4
    rows = (len(frames) + columns - 1) // columns
    sheet = Image.new("RGB", (columns * WIDTH, rows * (HEIGHT + label)), 0x181818)
    draw: ImageDraw.ImageDraw = ImageDraw.Draw(sheet)
    for i, (frame, what, image) in enumerate(frames):
        x, y = (i % columns) * WIDTH, (i // columns) * (HEIGHT + label)
        sheet.paste(Image.fromarray(image), (x, y + label))
        draw.text((x + 6, y + 4), f"frame {frame}: {what}", fill=(235, 235, 235))
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(out)
    print(f"wrote {out.resolve()}")


if __name__ == "__main__":
    main()
