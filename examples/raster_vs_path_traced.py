"""The default scene rendered by the rasteriser and by the reference path tracer, side by side in one PNG.

Two cameras at one pose: one rasterises (direct light, shadow maps, and indirect light from the world's
irradiance probes: GlobalIlluminationQuality, --global-illumination Off for the constant sky term alone), the other
path traces (ECameraRenderer.PathTraced: global illumination, accumulated over frames while nothing moves).
The scene's simulated objects are frozen first (a moving object restarts the accumulation, as it should),
then frames are stepped until the path-traced camera has --samples samples per pixel; progress is printed
as they accumulate.

    PYTHONPATH=python /usr/bin/python3 examples/raster_vs_path_traced.py [--out out/raster_vs_path_traced.png]
        [--samples 64] [--global-illumination Medium] [--server launch]
"""

# Debian 12's Pillow (9.4) has no annotations: strict pyright would flag every use of it.
# pyright: reportUnknownVariableType=false

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from PIL import Image, ImageDraw  # type: ignore[import]  # Debian ships no Pillow stubs

import spear

# By asset name: found in the working directory, SPEAR_ASSET_PATH or spear's own assets (a checkout or the
# installed package), so the example runs from anywhere.
DEFAULT_SCENE = "/Game/scenes/apartment"


def spawn_camera(game: spear.UWorld, name: str, width: int, height: int) -> spear.UCameraSensorComponent:
    actor = game.spawn_actor(uclass=spear.ACameraSensorActor, name=name, location=spear.FVector(-2.6, -1.6, 1.7),
                             rotation=spear.FRotator(Pitch=-18.0, Yaw=22.0))
    camera = actor.CameraSensor
    camera.Width, camera.Height, camera.FOV = width, height, 75.0
    camera.Modalities = [spear.ECameraModality.FinalColor]
    camera.ShadowResolution = 2048
    # One exposure for both halves, so that they compare: what automatic exposure meters for this view.
    camera.Exposure = 0.07
    return camera


def final_color(camera: spear.UCameraSensorComponent) -> NDArray[np.uint8]:
    pixels = camera.read_pixels()
    assert "final_color" in pixels  # the one modality the cameras render
    return pixels["final_color"]


def freeze(game: spear.UWorld) -> list[str]:
    """Stops simulating physics on every static mesh actor that simulates; returns their names."""
    frozen = []
    for actor in game.find_actors_by_class(uclass=spear.AStaticMeshActor):
        if actor.StaticMeshComponent.bSimulatePhysics:
            actor.StaticMeshComponent.SetSimulatePhysics(bSimulate=False)
            frozen.append(actor.GetName())
    return frozen


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--out", default="out/raster_vs_path_traced.png")
    parser.add_argument("--scene", default=DEFAULT_SCENE)
    parser.add_argument("--width", type=int, default=480)
    parser.add_argument("--height", type=int, default=360)
    parser.add_argument("--samples", type=int, default=64, help="path-traced samples per pixel in all")
    parser.add_argument("--per-frame", type=int, default=8, help="samples per pixel added each frame")
    parser.add_argument("--bounces", type=int, default=4, help="indirect bounces")
    parser.add_argument("--global-illumination", default="Medium",
                        choices=[q.name for q in spear.EGlobalIlluminationQuality],
                        help="the raster camera's GlobalIlluminationQuality")
    parser.add_argument("--server", default=None, help='None: in-process; "launch", "unix:PATH" or "tcp:HOST:PORT"')
    args = parser.parse_args()

    instance = spear.Instance(server=args.server)
    game = instance.get_game()
    with instance.begin_frame():
        game.load_scene(path=args.scene)
        frozen = freeze(game)
        raster = spawn_camera(game, "Raster", args.width, args.height)
        raster.GlobalIlluminationQuality = spear.EGlobalIlluminationQuality[args.global_illumination]
        traced = spawn_camera(game, "PathTraced", args.width, args.height)
        traced.MaxBounces = args.bounces
    with instance.end_frame():
        pass
    print(f"froze {', '.join(frozen) or 'nothing'} for the still view path tracing needs")

    start = time.monotonic()
    samples = 0
    raster_image = traced_image = np.zeros((args.height, args.width, 4), np.uint8)
    while samples < args.samples:
        with instance.begin_frame():
            traced.Renderer = spear.ECameraRenderer.PathTraced
            traced.SamplesPerPixel = min(args.per_frame, args.samples - samples)
        with instance.end_frame():
            raster_image, traced_image = final_color(raster), final_color(traced)
            previous, samples = samples, traced.GetAccumulatedSamples()
        elapsed = time.monotonic() - start
        print(f"path traced: {samples}/{args.samples} samples per pixel, {elapsed:.1f} s", file=sys.stderr)
        if samples <= previous:
            sys.exit("raster_vs_path_traced.py: the scene keeps changing, so the path tracer keeps restarting")

    label = 22
    sheet = Image.new("RGB", (2 * args.width, args.height + label), 0x181818)
    draw = ImageDraw.Draw(sheet)
    for i, (name, image) in enumerate([("raster", raster_image), (f"path traced, {samples} spp", traced_image)]):
        sheet.paste(Image.fromarray(np.ascontiguousarray(image[..., :3])), (i * args.width, label))
        draw.text((i * args.width + 6, 5), name, fill=(235, 235, 235))
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(out)
    mean = [float(image[..., :3].mean()) for image in (raster_image, traced_image)]
    print(f"mean final_color: raster {mean[0]:.1f}, path traced {mean[1]:.1f}")
    print(f"wrote {out.resolve()}")
    instance.close()


if __name__ == "__main__":
    main()
