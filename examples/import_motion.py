"""A human-object motion sequence played back in the apartment, frame by frame in lock-step with the engine, and
rendered each frame: colour, body-part segmentation (one id per body part of the character) and depth.

The sequence (spear.motion's .npz format: the character's bone poses, its root's and each handled object's
trajectory) is the built-in /Game/motions/carry_case.npz, the humanoid walking with a case in its right hand
(made by scripts/make_motion.py); --motion plays another file of that format, such as a dataset converted to it,
or reads an animated glTF/FBX file straight (spear.motion.import_motion: its skinned character and the objects
its clip moves, each shown with the static mesh --object-mesh NAME=MESH names, sampled at --fps).
spear.motion.MotionPlayer spawns the character and the objects and, for each frame, poses the character
(SetBoneTransforms, one array) and moves the objects; the engine renders that frame's camera images with them.

    PYTHONPATH=python /usr/bin/python3 examples/import_motion.py [--motion FILE] [--out out/import_motion.png]
        [--server launch] [--animation CLIP --fps 30 --object-mesh NAME=MESH ...]
"""

# Debian 12's Pillow (9.4) has no annotations: strict pyright would flag every use of it.
# pyright: reportUnknownVariableType=false

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from PIL import Image, ImageDraw  # type: ignore[import]  # Debian ships no Pillow stubs

import spear
import spear.images
import spear.motion

WIDTH, HEIGHT = 320, 240
START, HEADING = (-1.0, 1.1), -60.0  # where in the apartment the sequence's origin goes, and which way it faces


def placement() -> NDArray[np.float64]:
    """The sequence's frame of reference in the apartment: its origin at START, its +X along HEADING."""
    yaw = math.radians(HEADING)
    matrix = np.eye(4)
    matrix[:2, :2] = [[math.cos(yaw), -math.sin(yaw)], [math.sin(yaw), math.cos(yaw)]]
    matrix[:2, 3] = START
    return matrix


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--motion", default="/Game/motions/carry_case.npz",
                        help="a motion sequence (.npz), or an animated glTF/FBX file, to play")
    parser.add_argument("--animation", default="", help="an animated file's clip (default: its only one)")
    parser.add_argument("--fps", type=float, default=30.0, help="an animated file's frames per second")
    parser.add_argument("--object-mesh", action="append", default=[], metavar="NAME=MESH",
                        help="the static mesh of an object an animated file moves (once per object)")
    parser.add_argument("--out", default="out/import_motion.png", help="where to write the sheet of frames")
    parser.add_argument("--server", default=None, help='"launch", "unix:PATH" or "tcp:HOST:PORT" (default: in-process)')
    args = parser.parse_args()

    animated = Path(args.motion).suffix.lower() in {".glb", ".gltf", ".fbx"}
    if animated:  # read through the engine: started first, at the rate asked for
        instance = spear.Instance(server=args.server, fixed_delta_seconds=1.0 / args.fps)
        meshes = dict(pair.split("=", 1) for pair in args.object_mesh)
        motion = spear.motion.import_motion(args.motion, animation=args.animation, fps=args.fps, object_meshes=meshes)
    else:
        motion = spear.motion.load_motion(args.motion)
        instance = spear.Instance(server=args.server, fixed_delta_seconds=1.0 / motion.fps)
    print(f"{args.motion}: {motion.frames} frames at {motion.fps:g} fps ({motion.duration:.2f} s), "
          f"{len(motion.bone_names)} bones of {motion.skeletal_mesh}, objects: {', '.join(motion.object_names) or 'none'}")

    game = instance.get_game()
    with instance.begin_frame():
        game.load_scene(path="/Game/scenes/apartment")
        player = spear.motion.MotionPlayer(game, motion, placement=placement())
        player.mesh.bBodyPartIds = True  # object ids per body part rather than per material
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera",
                                  location=spear.FVector(-2.7, -0.3, 1.9),
                                  rotation=spear.FRotator(Pitch=-22.0, Yaw=5.0)).CameraSensor
        camera.Width, camera.Height, camera.FOV = WIDTH, HEIGHT, 85.0
        camera.Modalities = [spear.ECameraModality.FinalColor, spear.ECameraModality.ObjectIds,
                             spear.ECameraModality.Depth]
        camera.AutoExposureMethod = spear.EAutoExposureMethod.AEM_Histogram
    with instance.end_frame():
        pass

    shown = sorted({int(round(i * (motion.frames - 1) / 3)) for i in range(4)})
    rows: list[tuple[int, NDArray[np.uint8], NDArray[np.uint8], NDArray[np.uint8]]] = []
    parts: set[str] = set()
    start = time.perf_counter()
    for frame in range(motion.frames):
        with instance.begin_frame():
            player.apply(frame)
        with instance.end_frame():
            pixels = camera.read_pixels()
        # Only the modalities a camera renders are in its pixels (a partial TypedDict).
        assert "final_color" in pixels and "object_ids" in pixels and "depth" in pixels
        if frame in shown:
            ids = pixels["object_ids"]
            with instance.begin_frame():  # which body part each id of the character is
                for object_id in np.unique(ids):
                    found, _, component, slot, _ = camera.GetObjectIdInfo(ObjectId=int(object_id))
                    if found and isinstance(component, spear.USkeletalMeshComponent):
                        parts.add(component.GetBodyPartOfSlot(MaterialSlot=slot))
            with instance.end_frame():
                pass
            depth = spear.images.depth_grey(pixels["depth"])
            rows.append((frame, pixels["final_color"][..., :3], spear.images.id_colours(ids), depth))
        if (frame + 1) % 15 == 0 or frame + 1 == motion.frames:
            print(f"frame {frame + 1}/{motion.frames} ({time.perf_counter() - start:.1f} s)", flush=True)
    instance.close()
    print(f"body parts seen: {', '.join(sorted(parts))}")

    sheet = Image.new("RGB", (3 * WIDTH, len(rows) * (HEIGHT + 16)), 0x101010)
    draw = ImageDraw.Draw(sheet)
    for row, (frame, colour, segmentation, depth) in enumerate(rows):
        y = row * (HEIGHT + 16)
        for column, (image, label) in enumerate(((colour, "colour"), (segmentation, "body parts"), (depth, "depth"))):
            sheet.paste(Image.fromarray(image), (column * WIDTH, y + 16))
            draw.text((column * WIDTH + 4, y + 2), f"frame {frame} ({frame / motion.fps:.2f} s): {label}",
                      fill=(230, 230, 230))
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(out)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
