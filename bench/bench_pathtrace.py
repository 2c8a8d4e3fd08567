"""The path tracer's throughput: rays against Embree's own rtcIntersect1 loop (spear_pathtrace_bench, in
the same run), and samples per second on the default scene at 640x480 through the public API, in-process
and over RPC (a frame's path tracing and its readback included).

    PYTHONPATH=python /usr/bin/python3 bench/bench_pathtrace.py --build-dir build [--frames 8] [--write]

--write replaces the path tracer section of BENCHMARKS.md (between its pathtrace markers).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

import spear
from markdown_section import replace_section, section  # beside this script

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "assets" / "scenes" / "apartment.json"


def default_scene_samples_per_second(server: str | None, frames: int, spp: int) -> float:
    """Samples per second of a 640x480 path-traced camera on the default scene (physics frozen)."""
    instance = spear.Instance(server=server)
    game = instance.get_game()
    with instance.begin_frame():
        game.load_scene(path=str(SCENE))
        for actor in game.find_actors_by_class(uclass=spear.AStaticMeshActor):
            if actor.StaticMeshComponent.bSimulatePhysics:
                actor.StaticMeshComponent.SetSimulatePhysics(bSimulate=False)
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera",
                                  location=spear.FVector(-2.6, -1.6, 1.7),
                                  rotation=spear.FRotator(Pitch=-18.0, Yaw=22.0)).CameraSensor
        camera.Width, camera.Height, camera.FOV = 640, 480, 75.0
        camera.Renderer = spear.ECameraRenderer.PathTraced
        camera.SamplesPerPixel = spp
    with instance.end_frame():
        camera.read_pixels()
    start = time.perf_counter()
    for frame in range(frames):
        with instance.begin_frame():
            pass
        with instance.end_frame():
            camera.read_pixels()
            accumulated = camera.GetAccumulatedSamples()
        print(f"  {'rpc' if server else 'in-process'}: frame {frame + 1}/{frames}, {accumulated} spp", file=sys.stderr)
    elapsed = time.perf_counter() - start
    instance.close()
    assert accumulated == (frames + 1) * spp, "the default scene must stay still for the accumulation to grow"
    return 640 * 480 * spp * frames / elapsed


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--build-dir", default="build")
    parser.add_argument("--frames", type=int, default=8)
    parser.add_argument("--spp", type=int, default=4, help="samples per pixel per frame")
    parser.add_argument("--write", action="store_true", help="update the path tracer section of BENCHMARKS.md")
    args = parser.parse_args()

    bench = ROOT / args.build_dir / "core" / "pathtrace" / "bench" / "spear_pathtrace_bench"
    rays = subprocess.run([str(bench)], capture_output=True, text=True, check=True).stdout.rstrip()
    rates = {name: default_scene_samples_per_second(server, args.frames, args.spp)
             for name, server in (("in-process", None), ("RPC", "launch"))}
    command = "PYTHONPATH=python /usr/bin/python3 bench/bench_pathtrace.py --build-dir build --write"
    text = section("pathtrace", command, [
        "```",
        rays,
        "```",
        "",
        "| default scene, 640x480, path traced | Msamples/s | ms per sample per pixel |",
        "|---|---:|---:|",
        *[f"| {name} | {rate / 1e6:.2f} | {640 * 480 / rate * 1e3:.0f} |" for name, rate in rates.items()],
    ])
    print(text)
    if args.write:
        replace_section(ROOT / "BENCHMARKS.md", "pathtrace", "Path tracer throughput", text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
