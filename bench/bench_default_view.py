"""What a frame of the default scene costs: the textured apartment (assets/scenes/apartment.json) from the view
of the image-quality bench, final_color at 1920x1080 by default, the camera moving a millimetre a frame so
that nothing is reused.

A frame is `with instance.begin_frame(): <move>` + `with instance.end_frame(): camera.read_pixels()`, timed
over a loop of --frames frames (wall time a frame, what a user's loop gets), twice, and the renderer's own
surface-pass time a frame over the loops (GetRenderStats().SurfaceMs over Frames). The renderer's switches come from the
environment, so one command compares them, e.g.:

    PYTHONPATH=python /usr/bin/python3 bench/bench_default_view.py
    SPEAR_TEXTURE_FILTER=anisotropic PYTHONPATH=python /usr/bin/python3 bench/bench_default_view.py
    SPEAR_LIGHTING=compute SPEAR_IRRADIANCE_BLEND=pixel SPEAR_TARGET_FORMATS=float \\
        PYTHONPATH=python /usr/bin/python3 bench/bench_default_view.py
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402
from bench_image_quality import apartment  # noqa: E402  (the scene and its pose)

SWITCHES = ("SPEAR_LIGHTING", "SPEAR_IRRADIANCE_BLEND", "SPEAR_TARGET_FORMATS", "SPEAR_TEXTURE_FILTER")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--width", type=int, default=1920)
    parser.add_argument("--height", type=int, default=1080)
    parser.add_argument("--frames", type=int, default=10, help="frames a timed loop (two loops run)")
    args = parser.parse_args()
    switches = ", ".join(f"{name}={os.environ[name]}" for name in SWITCHES if name in os.environ) or "defaults"
    instance = spear.Instance()
    game = instance.get_game()
    with instance.begin_frame():
        location, rotation = apartment(game)
        actor = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera", location=location, rotation=rotation)
        camera = actor.CameraSensor
        camera.Width, camera.Height, camera.FOV = args.width, args.height, 75.0
        camera.Modalities = [spear.ECameraModality.FinalColor]
        camera.Exposure = 0.076
        device = camera.get_render_device_info().Renderer
    with instance.end_frame():
        camera.read_pixels()  # the first frame builds the programs and lights the probes: not timed
    print(f"default scene, {args.width}x{args.height} final_color ({switches}), "
          f"{device}:", flush=True)
    with instance.begin_frame():
        before = camera.GetRenderStats()
    with instance.end_frame():
        pass
    frame = 0
    for loop in range(2):
        start = time.perf_counter()
        for _ in range(args.frames):
            frame += 1
            with instance.begin_frame():
                actor.SetActorLocation(NewLocation=spear.FVector(location.X + 0.001 * frame, location.Y, location.Z))
            with instance.end_frame():
                camera.read_pixels()
        print(f"  loop {loop + 1}: {(time.perf_counter() - start) * 1e3 / args.frames:.1f} ms a frame", flush=True)
    with instance.begin_frame():
        stats = camera.GetRenderStats()
    with instance.end_frame():
        pass
    frames = max(stats.Frames - before.Frames, 1)
    print(f"  surface pass: {(stats.SurfaceMs - before.SurfaceMs) / frames:.1f} ms a frame")
    instance.close()


if __name__ == "__main__":
    main()
