"""Lane-following cars against idle ones: a street grid of N x N blocks (every street between two crossings a road
spline), C cars placed on its driving lanes, stepped F frames (60 per simulated second, no camera) with an
ALaneFollowingController driving each (through Bullet's raycast vehicle) and then, in a fresh engine, with the
same cars standing idle (no controllers: the physics of C cars and nothing else). Goal: driving frames per second
>= 0.7x idle (issue #52). Also prints where a driving frame's time goes (the world's frame timings: actors,
physics, and the rest, which is the traffic's step) and how the traffic flowed.

    PYTHONPATH=python /usr/bin/python3 bench/bench_traffic.py [--blocks 4] [--cars 100] [--frames 1800] [--server launch]
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402

BLOCK = 60.0


def build(game: spear.UWorld, blocks: int, cars: int, drive: bool) -> tuple[list[spear.AWheeledVehiclePawn], int]:
    """The grid, a ground under it, and the cars on driving lanes 16 m apart (three slots a street lane)."""
    ground = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground",
                              location=spear.FVector(blocks * BLOCK / 2, blocks * BLOCK / 2, 0.0))
    ground.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Plane")
    ground.SetActorScale3D(NewScale3D=spear.FVector(blocks * BLOCK + 100.0, blocks * BLOCK + 100.0, 1.0))
    for i in range(blocks + 1):
        for j in range(blocks):
            for name, a, b in ((f"x{i}_{j}", (j * BLOCK, i * BLOCK), ((j + 1) * BLOCK, i * BLOCK)),
                               (f"y{i}_{j}", (i * BLOCK, j * BLOCK), (i * BLOCK, (j + 1) * BLOCK))):
                road = game.spawn_actor(uclass=spear.ASplineActor, name=name, tags=["Road"])
                road.SplineComponent.SetSplinePoints(Points=[spear.FVector(*a, 0.0), spear.FVector(*b, 0.0)],
                                                     CoordinateSpace=spear.ESplineCoordinateSpace.World)
    lanes = spear.UZoneGraphSubsystem.GetZoneGraphSubsystem(WorldContextObject=game)
    lanes.GetZoneGraphData().bDrawRoads = False  # nothing renders here
    streets = [lane for lane in range(lanes.GetNumLanes())
               if lanes.GetLaneTag(LaneIndex=lane) == "Driving" and lanes.GetLaneRoad(LaneIndex=lane) is not None]
    slots = [(lane, d) for lane in streets for d in (6.0, 22.0, 38.0)]
    if cars > len(slots):
        raise SystemExit(f"bench_traffic: {cars} cars do not fit {len(slots)} places; use more --blocks")
    picks = np.random.default_rng(3).choice(len(slots), size=cars, replace=False)
    placed = []
    for k, s in enumerate(picks):
        lane, distance = slots[int(s)]
        at = lanes.CalculateLocationAlongLane(LaneIndex=lane, Distance=distance)
        car = game.spawn_actor(uclass=spear.AWheeledVehiclePawn, name=f"Car{k}",
                               location=spear.FVector(at.Position.X, at.Position.Y, 0.9),
                               rotation=spear.FRotator(Yaw=math.degrees(math.atan2(at.Direction.Y, at.Direction.X))))
        if drive:
            driver = game.spawn_actor(uclass=spear.ALaneFollowingController, name=f"Driver{k}")
            driver.Possess(InPawn=car)
        placed.append(car)
    return placed, len(streets)


def run(server: str | None, blocks: int, cars: int, frames: int, drive: bool) -> dict[str, float]:
    instance = spear.Instance(server=server)
    game = instance.get_game()
    with instance.begin_frame():
        placed, streets = build(game, blocks, cars, drive)
    with instance.end_frame():
        pass
    instance.step(num_frames=60)  # settle on the springs, the drivers find their lanes
    with instance.begin_frame():
        before = game.get_frame_timings()
        start_positions = [car.GetActorLocation() for car in placed]
    with instance.end_frame():
        pass
    start = time.perf_counter()
    done = 0
    while done < frames:
        chunk = min(300, frames - done)
        instance.step(num_frames=chunk)
        done += chunk
        print(f"  {'driving' if drive else 'idle'}: frame {done}/{frames}", end="\r", flush=True)
    seconds = time.perf_counter() - start
    with instance.begin_frame():
        after = game.get_frame_timings()
        moved = [math.hypot(car.GetActorLocation().X - p.X, car.GetActorLocation().Y - p.Y)
                 for car, p in zip(placed, start_positions)]
        upright = sum(abs(car.GetActorRotation().Roll) < 30.0 and abs(car.GetActorRotation().Pitch) < 30.0 for car in placed)
    with instance.end_frame():
        pass
    instance.close()
    n = after.Frames - before.Frames
    return {"fps": frames / seconds, "actors": (after.ActorsMs - before.ActorsMs) / n,
            "physics": (after.PhysicsMs - before.PhysicsMs) / n, "other": (after.OtherMs - before.OtherMs) / n,
            "moved": float(np.mean(moved)), "upright": float(upright), "streets": float(streets)}


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--blocks", type=int, default=4, help="blocks along each side of the grid")
    parser.add_argument("--cars", type=int, default=100)
    parser.add_argument("--frames", type=int, default=1800, help="frames timed (after 60 to settle)")
    parser.add_argument("--server", default=None, help='"launch" etc. (default: in-process)')
    args = parser.parse_args()

    driving = run(args.server, args.blocks, args.cars, args.frames, drive=True)
    idle = run(args.server, args.blocks, args.cars, args.frames, drive=False)
    print(f"{args.cars} cars on a {args.blocks} x {args.blocks} grid ({int(driving['streets'])} street lanes), "
          f"{args.frames} frames ({args.frames / 60:.0f} simulated s):" + " " * 20)
    for name, r in (("idle", idle), ("driving", driving)):
        print(f"  {name:8s} {r['fps']:7.0f} frames/s   per frame: actors {r['actors']:.3f} ms, physics "
              f"{r['physics']:.3f} ms, other (traffic) {r['other']:.3f} ms")
    print(f"  driving / idle: {driving['fps'] / idle['fps']:.2f}x (goal >= 0.7x)")
    print(f"  traffic: cars moved {driving['moved']:.0f} m on average (idle: {idle['moved']:.2f} m), "
          f"{int(driving['upright'])}/{args.cars} upright")


if __name__ == "__main__":
    main()
