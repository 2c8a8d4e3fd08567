"""MuJoCo steps the dynamics and spear renders (the SPEAR paper's mujoco_interop application), through the
mujoco_interop plugin: a small MJCF model of falling shapes is loaded, its bodies appear as spear actors,
and every frame MuJoCo advances 1/60 s and the actors take their new poses. A camera renders the last frame
into a PNG.

    bash run.sh        # builds spear, and the plugin into build/python/mujoco_interop when MuJoCo is installed
    PYTHONPATH=python /usr/bin/python3 examples/mujoco_interop/mujoco_interop.py [--server launch] [--out PNG]

SPEAR_PLUGIN_DIR=<dir> uses the plugin package in <dir>/mujoco_interop instead (an out-of-tree build's
<build>/python); mypy and pyright read its stubs with MYPYPATH / PYTHONPATH set to that directory.
"""

# Without the plugin's stubs on the path (spear's own type check of the examples) its names are unknown;
# with them (tests/python/test_mujoco_interop.py) everything is checked. Debian's Pillow has no annotations.
# mypy: warn-unused-ignores=False
# pyright: reportMissingImports=false, reportUnknownVariableType=false, reportUnknownArgumentType=false

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

import numpy as np

import spear

ROOT = Path(__file__).resolve().parents[2]
PLUGIN_DIR = Path(os.environ.get("SPEAR_PLUGIN_DIR", ROOT / "build/python"))
# First on the path: this script's own folder (also called mujoco_interop) must not hide the package.
sys.path.insert(0, str(PLUGIN_DIR))

from mujoco_interop.api import AMujocoScene  # type: ignore[import]  # noqa: E402
from PIL import Image  # type: ignore[import]  # noqa: E402

FRAME_SECONDS = 1.0 / 60.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--server", choices=["launch"], help="run the engine in a spear-server process")
    parser.add_argument("--mjcf", type=Path, default=Path(__file__).resolve().parent / "falling_shapes.xml")
    parser.add_argument("--seconds", type=float, default=1.5, help="simulated time")
    parser.add_argument("--out", type=Path, default=ROOT / "out/mujoco_interop.png")
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=480)
    args = parser.parse_args()
    if not (PLUGIN_DIR / "mujoco_interop").is_dir():
        sys.exit(f"no mujoco_interop plugin in {PLUGIN_DIR}: build spear with libmujoco-dev installed (bash run.sh), "
                 "or set SPEAR_PLUGIN_DIR to an out-of-tree build's python directory")

    instance = spear.Instance(server=args.server)
    instance.load_plugin("mujoco_interop")
    game = instance.get_game()
    with instance.begin_frame():
        scene = game.spawn_actor(uclass=AMujocoScene, name="Mujoco")
        scene.LoadMjcf(Path=str(args.mjcf))
        names = scene.GetBodyNames()
        moving = [actor for actor in scene.GetBodyActors() if not actor.bStaticBody]
        steps = max(1, round(FRAME_SECONDS / scene.GetTimestep()))
        print(f"loaded {args.mjcf.name}: {scene.NumBodies} bodies ({len(moving)} moving), {scene.NumGeoms} geoms; "
              f"{steps} MuJoCo steps per frame ({instance.transport})")

        sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun",
                               rotation=spear.FRotator(Pitch=-55.0, Yaw=-30.0))
        sun.LightComponent.Intensity = 2.0
        sky = game.spawn_actor(uclass=spear.ASkyLight, name="Sky")
        sky.SkyLightComponent.Intensity = 0.3
        sky.SkyLightComponent.BackgroundColor = spear.FLinearColor(0.35, 0.5, 0.8, 1.0)
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera",
                                  location=spear.FVector(-1.9, -1.5, 1.3),
                                  rotation=spear.FRotator(Pitch=-25.0, Yaw=35.0)).CameraSensor
        camera.Width, camera.Height, camera.FOV = args.width, args.height, 60.0
        camera.Modalities = [spear.ECameraModality.FinalColor]
    with instance.end_frame():
        pass

    frames = max(1, round(args.seconds / FRAME_SECONDS))
    pixels: spear.FCameraPixels = {}
    for frame in range(frames):
        with instance.begin_frame():
            scene.Step(NumSteps=steps)  # MuJoCo steps; the bodies' actors move in the same call
        with instance.end_frame():
            if frame == frames - 1:
                pixels = camera.read_pixels()
            if frame % 30 == 0 or frame == frames - 1:
                poses = scene.GetBodyPoses()
                heights = ", ".join(f"{names[actor.BodyId]} {poses['Positions'][actor.BodyId, 2]:.2f}"
                                    for actor in moving)
                print(f"t = {scene.GetSimTime():.3f} s: heights {heights} m")

    if "final_color" not in pixels:
        sys.exit("the camera returned no image")
    image = np.ascontiguousarray(pixels["final_color"][:, :, :3])
    args.out.parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(image).save(args.out)
    print(f"wrote {args.out} ({image.shape[1]}x{image.shape[0]})")

    with instance.begin_frame():
        scene.Clear()  # the bodies' actors go with the model
        game.destroy_actor(actor=scene)
    with instance.end_frame():
        pass
    instance.unload_plugin("mujoco_interop")
    instance.close()


if __name__ == "__main__":
    main()
