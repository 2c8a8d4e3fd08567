"""Nearest-lane queries through the engine against a brute-force scan of the same lanes: a street grid of
N x N blocks laid as road splines, its lanes queried one call a point (FindNearestLaneLocationByName) and in one
call for many points (FindNearestLanes), in-process and over RPC, against the C++ scan of every lane segment
(LaneGraph::nearestByScan, from build/core/zonegraph/spear_zonegraph_bench on the same grid). Goal: batched >= 20x
the scan at 10,000 lanes (issue #52).

    PYTHONPATH=python /usr/bin/python3 bench/bench_lanes.py [--build-dir build] [--blocks 20] [--points 200000]
        [--single 2000] [--no-rpc]

Points are uniform over the city and 20 m beyond, at 0.5 m, each asking for the nearest lane within 50 m.
"""

from __future__ import annotations

import argparse
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402

BLOCK = 60.0  # metres, as the C++ benchmark's grid
REACH = 50.0


def lay_grid(game: spear.UWorld, blocks: int) -> None:
    """Every street between two neighbouring intersections is its own road, in the C++ benchmark's order."""
    for i in range(blocks + 1):
        for j in range(blocks):
            for name, a, b in ((f"x{i}_{j}", (j * BLOCK, i * BLOCK), ((j + 1) * BLOCK, i * BLOCK)),
                               (f"y{i}_{j}", (i * BLOCK, j * BLOCK), (i * BLOCK, (j + 1) * BLOCK))):
                road = game.spawn_actor(uclass=spear.ASplineActor, name=name, tags=["Road"])
                road.SplineComponent.SetSplinePoints(
                    Points=[spear.FVector(*a, 0.0), spear.FVector(*b, 0.0)],
                    CoordinateSpace=spear.ESplineCoordinateSpace.World)


def measure(server: str | None, blocks: int, points: NDArray[np.float64], single: int) -> tuple[int, float, float, float]:
    """(lanes, build seconds, single queries/s, batched queries/s) on one transport."""
    instance = spear.Instance(server=server)
    game = instance.get_game()
    with instance.begin_frame():
        lay_grid(game, blocks)
        lanes = spear.UZoneGraphSubsystem.GetZoneGraphSubsystem(WorldContextObject=game)
        start = time.perf_counter()
        count = lanes.GetNumLanes()
        build = time.perf_counter() - start
        start = time.perf_counter()
        for p in points[:single]:
            lanes.FindNearestLaneLocationByName(Location=spear.FVector(*map(float, p)), TagName="", MaxDistance=REACH)
        one_by_one = single / (time.perf_counter() - start)
        start = time.perf_counter()
        indices, _, _ = lanes.FindNearestLanes(Locations=points, MaxDistance=REACH, Tag="")
        batched = len(points) / (time.perf_counter() - start)
        assert (indices >= 0).all()
    with instance.end_frame():
        pass
    instance.close()
    return count, build, one_by_one, batched


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--build-dir", default="build", help="the CMake build folder (for the C++ scan)")
    parser.add_argument("--blocks", type=int, default=20, help="blocks a side (20: 12,952 lanes)")
    parser.add_argument("--points", type=int, default=200_000, help="points in the batched call")
    parser.add_argument("--single", type=int, default=2000, help="points queried one call each")
    parser.add_argument("--no-rpc", action="store_true", help="in-process only")
    args = parser.parse_args()

    bench = Path(args.build_dir) / "core" / "zonegraph" / "spear_zonegraph_bench"
    scan_output = subprocess.run([str(bench), "--blocks", str(args.blocks), "--queries", "20000"], check=True,
                                 capture_output=True, text=True).stdout
    print(scan_output.strip().replace("\n", "\n  C++: ").join(("  C++: ", "")))
    scan = float(re.search(r"scan_queries_per_second=([\d.]+)", scan_output).group(1))  # type: ignore[union-attr]

    rng = np.random.default_rng(7)
    points = np.column_stack([rng.uniform(-20.0, args.blocks * BLOCK + 20.0, (args.points, 2)),
                              np.full(args.points, 0.5)])
    for name, server in [("in-process", None)] + ([] if args.no_rpc else [("rpc", "launch")]):
        lanes, build, single, batched = measure(server, args.blocks, points, args.single)
        print(f"{name}: {lanes} lanes built in {build:.2f} s; one call a point {single:,.0f} queries/s "
              f"({single / scan:.0f}x the scan), batched {batched:,.0f} queries/s ({batched / scan:.0f}x the scan; "
              f"goal >= 20x)", flush=True)


if __name__ == "__main__":
    main()
