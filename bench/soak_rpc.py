"""Soak: a million mixed typed calls against one launched spear-server, sampling the server's resident memory,
to show that nothing leaks per call (objects spawned and destroyed, properties set and read, functions with
struct and array arguments, asynchronous batches, small camera reads, errors).

    PYTHONPATH=python /usr/bin/python3 bench/soak_rpc.py [--calls 1000000] [--write]

Prints progress every 10% and the server's RSS at each sample; --write records the result in
RELIABILITY.md between its soak markers. Memory is judged after a warm-up (allocator pools and caches
fill first): the growth from the first sample after warm-up to the last is what a leak would show.
"""

from __future__ import annotations

import argparse
import math
import re
import sys
import time
from pathlib import Path

import numpy as np

import spear

ROOT = Path(__file__).resolve().parent.parent


def rss_kib(pid: int) -> int:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1])
    raise RuntimeError(f"soak_rpc: no VmRSS for process {pid}")


def one_round(game: spear.UWorld, camera: spear.UCameraSensorComponent, i: int) -> int:
    """About 40 calls of many kinds; returns how many were made."""
    calls = 0
    actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name=f"Soak{i}",
                             location=spear.FVector(float(i % 7), 0.0, 1.0))
    mesh = actor.StaticMeshComponent
    mesh.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
    mesh.Friction = 0.25 + (i % 3) * 0.1
    actor.Tags = ["soak", str(i)]
    calls += 5
    for k in range(8):
        actor.SetActorLocation(NewLocation=spear.FVector(float(k), float(i % 5), 1.0))
        actor.GetActorLocation()
        calls += 2
    for k in range(16):
        actor.send_async.K2_SetActorLocationAndRotation(
            NewLocation=spear.FVector(0.0, float(k), 1.0), NewRotation=spear.FRotator(Pitch=0.0, Yaw=float(k), Roll=0.0))
        calls += 1
    assert game.find_actor_by_name(name=f"Soak{i}") is not None
    try:
        camera.Width = 0  # refused: the error path allocates and frees too
    except spear.InvalidArgumentError:
        pass
    camera.Exposure = 1.0 + (i % 4) * 0.25
    game.destroy_actor(actor=actor)
    calls += 4
    return calls


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--calls", type=int, default=1_000_000)
    parser.add_argument("--write", action="store_true", help="record the result in RELIABILITY.md")
    args = parser.parse_args(argv)

    instance = spear.Instance(server="launch")
    backend = instance._backend
    launched = getattr(backend, "_launched", None)
    if launched is None:
        raise spear.InvalidStateError("soak_rpc: needs a launched server")
    pid = launched.process.pid
    game = instance.get_game()
    with instance.begin_frame():
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera").CameraSensor
        camera.Width, camera.Height = 64, 48
    with instance.end_frame():
        pass

    samples: list[tuple[int, int]] = []
    made, rounds, frames = 0, 0, 0
    started = time.perf_counter()
    next_report = args.calls // 10
    warmup = args.calls // 10
    while made < args.calls:
        with instance.begin_frame():
            for _ in range(5):
                made += one_round(game, camera, rounds)
                rounds += 1
        with instance.end_frame():
            pixels = camera.read_pixels()
            assert pixels["final_color"].shape == (48, 64, 4)
            made += 1
        frames += 1
        if made >= next_report or made >= args.calls:
            samples.append((made, rss_kib(pid)))
            elapsed = time.perf_counter() - started
            print(f"  {made}/{args.calls} calls, {frames} frames, {made / elapsed:.0f} calls/s, "
                  f"server RSS {samples[-1][1] / 1024:.1f} MiB", file=sys.stderr, flush=True)
            next_report += args.calls // 10
    elapsed = time.perf_counter() - started
    instance.close()

    after_warmup = [s for s in samples if s[0] >= warmup] or samples
    first, last = after_warmup[0], after_warmup[-1]
    per_call = (last[1] - first[1]) * 1024 / max(1, last[0] - first[0])
    peak = max(s[1] for s in samples)
    lines = [
        "```bash",
        "PYTHONPATH=python /usr/bin/python3 bench/soak_rpc.py --calls " + str(args.calls) + " --write",
        "```",
        "",
        f"{made} typed calls over RPC ({frames} frames, {rounds} actors spawned and destroyed, a 64x48 camera "
        f"read each frame) in {elapsed:.0f} s ({made / elapsed:.0f} calls/s). Server RSS after the warm-up "
        f"({first[0]} calls): {first[1] / 1024:.1f} MiB; at the end: {last[1] / 1024:.1f} MiB; peak "
        f"{peak / 1024:.1f} MiB; {per_call:+.3f} bytes per call.",
        "",
        "| calls | server RSS MiB |",
        "|---:|---:|",
        *[f"| {calls} | {kib / 1024:.1f} |" for calls, kib in samples],
    ]
    text = "\n".join(lines)
    print(text)
    if args.write:
        path = ROOT / "RELIABILITY.md"
        content = path.read_text()
        begin, end = "<!-- soak:begin -->", "<!-- soak:end -->"
        if begin not in content or end not in content:
            raise spear.InvalidStateError(f"soak_rpc: {path} has no {begin} ... {end} markers")
        content = re.sub(re.escape(begin) + ".*?" + re.escape(end), lambda _: f"{begin}\n{text}\n{end}", content,
                         flags=re.S)
        path.write_text(content)
    return 0 if math.isfinite(per_call) else 1


if __name__ == "__main__":
    sys.exit(main())
