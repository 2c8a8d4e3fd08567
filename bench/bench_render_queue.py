"""The render queue's cost per frame against the renderer alone, in one run: the same camera move through the
default scene, rendered (a) by moving the camera each frame and reading read_pixels() into numpy arrays,
(b) by a render queue job writing the same images to PNG + EXR files with their camera JSON. The difference
is what writing files costs (encoding PNG and ZIP-compressed EXR, and writing whole files).

    PYTHONPATH=python /usr/bin/python3 bench/bench_render_queue.py [--frames 30] [--write]

--write replaces the render queue section of BENCHMARKS.md (between its render-queue markers).
"""

from __future__ import annotations

import argparse
import math
import shutil
import sys
import tempfile
import time
from pathlib import Path

import spear
from markdown_section import replace_section, section  # beside this script

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "assets" / "scenes" / "apartment.json"
M = spear.ECameraModality
SETS = {"final_color": [M.FinalColor], "final_color, depth, normal, object_ids": [M.FinalColor, M.Depth, M.Normal,
                                                                                  M.ObjectIds]}


def poses(frames: int) -> tuple[list[spear.FVector], list[spear.FRotator]]:
    t = [0.5 - 0.5 * math.cos(math.pi * i / max(frames - 1, 1)) for i in range(frames)]
    return ([spear.FVector(X=-2.6 + 0.5 * e, Y=-1.8 + e, Z=1.7) for e in t],
            [spear.FRotator(Pitch=-18.0, Yaw=15.0 + 20.0 * e) for e in t])


def ms_per_frame(queue_job: bool, modalities: list[spear.ECameraModality], width: int, height: int,
                 frames: int) -> tuple[float, str]:
    """Milliseconds per frame of the camera move, and the renderer's GL_RENDERER."""
    instance = spear.Instance()
    game = instance.get_game()
    locations, rotations = poses(frames)
    out = Path(tempfile.mkdtemp(prefix="spear_bench_queue_"))
    with instance.begin_frame():
        game.load_scene(path=str(SCENE))
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera").CameraSensor
        camera.Width, camera.Height, camera.FOV, camera.Modalities = width, height, 75.0, modalities
        queue = spear.UMoviePipelineQueueEngineSubsystem.GetMoviePipelineQueueEngineSubsystem(WorldContextObject=game)
    with instance.end_frame():
        camera.read_pixels()  # warm: GL context, programs, shadow maps
        device = camera.get_render_device_info().Renderer
    start = time.perf_counter()
    if queue_job:
        with instance.begin_frame():
            job = queue.AllocateJob(Camera=camera)
            job.SetConfiguration(Configuration=spear.FMoviePipelineConfiguration(
                OutputDirectory=str(out), CameraLocations=locations, CameraRotations=rotations))
            queue.RenderJob(Job=job)
        with instance.end_frame():
            pass
        while True:
            with instance.begin_frame():
                pass
            with instance.end_frame():
                frames_done = job.GetProgress().FramesRendered
                if not queue.IsRendering():
                    break
    else:
        for location, rotation in zip(locations, rotations):
            with instance.begin_frame():
                camera.SetWorldLocation(NewLocation=location)
                camera.SetWorldRotation(NewRotation=rotation)
            with instance.end_frame():
                camera.read_pixels()
        frames_done = frames
    elapsed = time.perf_counter() - start
    instance.close()
    shutil.rmtree(out)
    assert frames_done == frames, frames_done
    return 1000.0 * elapsed / frames, device


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--frames", type=int, default=30)
    parser.add_argument("--write", action="store_true", help="replace the section in BENCHMARKS.md")
    args = parser.parse_args()

    rows = ["| resolution | modalities | renderer alone (read_pixels) ms/frame | render queue (files) ms/frame | "
            "queue / alone |", "|---|---|---:|---:|---:|"]
    device = ""
    for width, height in [(640, 480), (1280, 720)]:
        for name, modalities in SETS.items():
            # Alternating runs, the better of two each, so that the VM's drift does not favour one side.
            alone, queued = [], []
            for _ in range(2):
                ms, device = ms_per_frame(False, modalities, width, height, args.frames)
                alone.append(ms)
                queued.append(ms_per_frame(True, modalities, width, height, args.frames)[0])
            a, q = min(alone), min(queued)
            print(f"{width}x{height} {name}: alone {a:.1f} ms, queue {q:.1f} ms", file=sys.stderr)
            rows.append(f"| {width}x{height} | {name} | {a:.1f} | {q:.1f} | {q / a:.2f} |")
    body = [f"{args.frames} frames of a camera move through the default scene per cell, in-process, on {device}; "
            "each cell the better of two alternating runs.", "", *rows]
    text = section("render-queue", "PYTHONPATH=python /usr/bin/python3 bench/bench_render_queue.py --write", body)
    print(text)
    if args.write:
        replace_section(ROOT / "BENCHMARKS.md", "render-queue", "Render queue: writing files against the renderer alone",
                        text)


if __name__ == "__main__":
    main()
