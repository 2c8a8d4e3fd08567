"""Navigation: first spear_navigation_bench (build and rebuild times, and paths and random points through
sp::navigation against Detour called directly on the same tiles, the floor), then from Python: the default
scene's (the apartment's) build time and path queries one by one and batched (FindPaths), in-process and
over RPC (the per-call cost of each transport: compare with the RPC section's round trip).

    PYTHONPATH=python /usr/bin/python3 bench/bench_navigation.py [--build-dir build] [--queries 500]
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402


def measure(server: str | None, queries: int) -> dict[str, float]:
    instance = spear.Instance(server=server, scene=str(ROOT / "assets/scenes/apartment.json"))
    game = instance.get_game()
    with instance.begin_frame():
        nav = spear.UNavigationSystemV1.GetNavigationSystem(WorldContextObject=game).GetDefaultNavDataInstance()
        start = time.perf_counter()
        nav.RebuildNavigation()
        build_ms = (time.perf_counter() - start) * 1e3
        tiles, area = nav.GetNumTiles(), nav.GetNavigableArea()
        nav.SetRandomSeed(Seed=3)
        a, b = nav.GetRandomPoints(NumPoints=queries), nav.GetRandomPoints(NumPoints=queries)
        start = time.perf_counter()
        for i in range(queries):
            nav.FindPath(Start=spear.FVector(*a[i]), End=spear.FVector(*b[i]))
        single_us = (time.perf_counter() - start) / queries * 1e6
        start = time.perf_counter()
        batch = nav.FindPaths(StartPoints=a, EndPoints=b)
        batch_us = (time.perf_counter() - start) / queries * 1e6
        mean_m = float(np.mean(batch.Lengths))
    with instance.end_frame():
        pass
    instance.close()
    return {"build_ms": build_ms, "tiles": tiles, "area": area, "single_us": single_us, "batch_us": batch_us,
            "mean_m": mean_m}


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--build-dir", default="build")
    parser.add_argument("--queries", type=int, default=500)
    args = parser.parse_args()
    native = subprocess.run([str(Path(args.build_dir) / "core/navigation/spear_navigation_bench"), "--queries", "2000"],
                            capture_output=True, text=True, check=True).stdout
    print(native, end="")
    print("| transport | apartment build | tiles | walkable | mean path | FindPath one by one | FindPaths batched |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for name, server in (("in-process", None), ("RPC", "launch")):
        r = measure(server, args.queries)
        print(f"| {name} | {r['build_ms']:.1f} ms | {r['tiles']:.0f} | {r['area']:.1f} m² | {r['mean_m']:.1f} m "
              f"| {r['single_us']:.1f} µs | {r['batch_us']:.1f} µs |")


if __name__ == "__main__":
    main()
