"""Animated characters in the default apartment: three humanoids (idle, walking across the room, running in place),
a camera on the walker's head, and a sheet of frames (colour, object ids, the head camera's view).

The humanoid is the built-in skeletal mesh /Game/characters/humanoid.glb (made by scripts/make_humanoid.py: 18
bones named as Unreal's mannequin names them, clips idle, walk and run). Its clips play in place; the walker's
actor is moved each frame at its stride's speed. The head camera is attached to the walker's "head" bone
(USceneComponent.AttachToComponent's SocketName), so it bobs and turns with the head.

    PYTHONPATH=python /usr/bin/python3 examples/animated_characters.py [--frames 48] [--out out/animated_characters.png]
        [--server launch]
"""

# Debian 12's Pillow (9.4) has no annotations: strict pyright would flag every use of it.
# pyright: reportUnknownVariableType=false

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from PIL import Image, ImageDraw  # type: ignore[import]  # Debian ships no Pillow stubs

import spear
import spear.images

HUMANOID = "/Game/characters/humanoid.glb"
WIDTH, HEIGHT = 320, 240
WALK_SPEED = 1.25  # metres per second: the walk clip's stride (about 0.69 m per step, two steps in 1.1 s)


def spawn_character(game: spear.UWorld, name: str, location: tuple[float, float, float], yaw: float, clip: str
                    ) -> spear.ASkeletalMeshActor:
    actor = game.spawn_actor(uclass=spear.ASkeletalMeshActor, name=name, location=spear.FVector(*location),
                             rotation=spear.FRotator(Yaw=yaw))
    actor.SkeletalMeshComponent.SetSkeletalMesh(NewMesh=HUMANOID)
    actor.SkeletalMeshComponent.PlayAnimation(NewAnimToPlay=clip, bLoop=True)
    return actor


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--frames", type=int, default=48, help="frames to simulate at 1/60 s (default: %(default)s)")
    parser.add_argument("--out", default="out/animated_characters.png", help="where to write the sheet of frames")
    parser.add_argument("--server", default=None, help='"launch", "unix:PATH" or "tcp:HOST:PORT" (default: in-process)')
    args = parser.parse_args()
    if args.frames < 1:
        parser.error("--frames must be at least 1")

    instance = spear.Instance(server=args.server)
    game = instance.get_game()
    with instance.begin_frame():
        game.load_scene(path="/Game/scenes/apartment")
        spawn_character(game, "Idle", (1.9, -0.2, 0.0), 180.0, "idle")
        runner = spawn_character(game, "Runner", (0.4, -1.6, 0.0), 160.0, "run")
        walker = spawn_character(game, "Walker", (-0.9, 1.5, 0.0), -60.0, "walk")
        mesh = walker.SkeletalMeshComponent
        print(f"{mesh.GetNumBones()} bones: {', '.join(mesh.GetBoneName(BoneIndex=i) for i in range(mesh.GetNumBones()))}")
        print(f"clips: {', '.join(mesh.GetAnimationNames())}")

        overview = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Overview",
                                    location=spear.FVector(-2.7, -0.3, 1.9),
                                    rotation=spear.FRotator(Pitch=-22.0, Yaw=5.0)).CameraSensor
        overview.Width, overview.Height, overview.FOV = WIDTH, HEIGHT, 85.0
        overview.Modalities = [spear.ECameraModality.FinalColor, spear.ECameraModality.ObjectIds]
        overview.AutoExposureMethod = spear.EAutoExposureMethod.AEM_Histogram
        head = game.spawn_actor(uclass=spear.ACameraSensorActor, name="HeadCamera").CameraSensor
        head.AttachToComponent(Parent=mesh, SocketName="head")
        head.SetRelativeLocation(NewLocation=spear.FVector(0.12, 0.0, 0.08))  # at the eyes, looking ahead
        head.Width, head.Height, head.FOV = WIDTH, HEIGHT, 90.0
        head.Modalities = [spear.ECameraModality.FinalColor]
        head.AutoExposureMethod = spear.EAutoExposureMethod.AEM_Histogram
    with instance.end_frame():
        pass

    shown = sorted({int(round(i * (args.frames - 1) / 3)) for i in range(4)})
    rows: list[tuple[int, NDArray[np.uint8], NDArray[np.uint8], NDArray[np.uint8]]] = []
    start = time.perf_counter()
    heading = np.radians(-60.0)
    step = WALK_SPEED / 60.0
    for frame in range(args.frames):
        with instance.begin_frame():
            location = walker.GetActorLocation()
            walker.SetActorLocation(NewLocation=spear.FVector(location.X + step * np.cos(heading),
                                                              location.Y + step * np.sin(heading), 0.0))
        with instance.end_frame():
            if frame in shown:
                pixels = overview.read_pixels()
                seen = head.read_pixels()
                # Only the modalities a camera renders are in its pixels (a partial TypedDict).
                assert "final_color" in pixels and "object_ids" in pixels and "final_color" in seen
                rows.append((frame, pixels["final_color"][..., :3].copy(),
                             spear.images.id_colours(pixels["object_ids"]), seen["final_color"][..., :3].copy()))
        if frame % 12 == 11 or frame == args.frames - 1:
            print(f"frame {frame + 1}/{args.frames} ({(time.perf_counter() - start) / (frame + 1) * 1000:.0f} ms a frame)",
                  flush=True)

    with instance.begin_frame():
        foot = mesh.GetBoneTransform(BoneName="foot_l", Space=spear.EBoneSpaces.WorldSpace).Translation
        poses = runner.SkeletalMeshComponent.GetBoneTransforms(Space=spear.EBoneSpaces.ComponentSpace)
        print(f"walker at {mesh.GetPosition():.2f} s of 'walk', left foot at ({foot.X:.2f}, {foot.Y:.2f}, {foot.Z:.2f})")
        print(f"runner pose: {poses.shape[0]} bones x 4 x 4, head {poses[mesh.GetBoneIndex(BoneName='head'), 2, 3]:.2f} m up")
    with instance.end_frame():
        pass
    instance.close()

    label = 20
    sheet = Image.new("RGB", (3 * WIDTH, len(rows) * (HEIGHT + label)), 0x181818)
    draw: ImageDraw.ImageDraw = ImageDraw.Draw(sheet)
    for r, (frame, colour, ids, view) in enumerate(rows):
        y = r * (HEIGHT + label)
        for c, (image, name) in enumerate([(colour, "final_color"), (ids, "object_ids"), (view, "head camera")]):
            sheet.paste(Image.fromarray(image), (c * WIDTH, y + label))
            draw.text((c * WIDTH + 6, y + 4), f"frame {frame}: {name}", fill=(235, 235, 235))
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(out)
    print(f"wrote {out.resolve()}")


if __name__ == "__main__":
    main()
