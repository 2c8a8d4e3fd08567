"""Vectorised environments: environment steps per second for N environments (a cube pushed by a force, physics,
one 128 x 128 final-colour camera each), stepped as N worlds of one in-process engine, as worlds spread over one
spear-server per core, and over a Dask LocalCluster with one worker per core; each against the floor, N
independent single-world spear-server processes stepped one after another in the same run (what a user without
spear.vector writes).

    PYTHONPATH=python /usr/bin/python3 bench/bench_vector.py [--counts 1 4 16 64] [--steps 30] [--rounds 1]
                                                             [--size 128]

With --rounds K every column is measured K times, the columns taking turns, and a cell shows the median rate
and the median of the rounds' ratios to the same round's floor, with their range: the floor drifts with the
machine's state, so a ratio is only taken within a round.
"""

from __future__ import annotations

import argparse
import functools
import os
import statistics
import sys
import time
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402
from spear.vector import Box, CameraImage, StepResult, VectorEnv  # noqa: E402

SIZE = 128  # the camera's side in pixels (--size)


class Push:
    """A cube on a floor under a sun, pushed along X; an overhead SIZE x SIZE colour camera."""

    action_space = Box((1,), np.float32, -1.0, 1.0)

    def __init__(self, size: int = SIZE) -> None:
        self.size = size
        self.observation_space: Mapping[str, Box] = {"final_color": Box((size, size, 4), np.uint8, 0, 255)}
        self.cube: spear.AStaticMeshActor | None = None
        self.camera: spear.UCameraSensorComponent | None = None

    def reset(self, world: spear.UWorld, seed: int) -> None:
        if self.cube is None:
            sun = world.spawn_actor(uclass=spear.ADirectionalLight, rotation=spear.FRotator(Pitch=-60.0))
            sun.LightComponent.Intensity = 3.0
            floor = world.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(Z=-0.05))
            floor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
            floor.SetActorScale3D(NewScale3D=spear.FVector(8.0, 8.0, 0.1))
            floor.StaticMeshComponent.SetMobility(NewMobility=spear.EComponentMobility.Static)
            self.cube = world.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(Z=0.5))
            self.cube.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
            self.cube.StaticMeshComponent.SetSimulatePhysics(bSimulate=True)
            camera = world.spawn_actor(uclass=spear.ACameraSensorActor, location=spear.FVector(Z=6.0),
                                       rotation=spear.FRotator(Pitch=-90.0))
            self.camera = camera.CameraSensor
            self.camera.Width, self.camera.Height = self.size, self.size
            self.camera.Modalities = [spear.ECameraModality.FinalColor]

    def act(self, world: spear.UWorld, action: NDArray[np.float32]) -> None:
        assert self.cube is not None
        self.cube.StaticMeshComponent.AddForce(Force=spear.FVector(X=5.0 * float(action[0])))

    def observe(self, world: spear.UWorld) -> StepResult:
        assert self.camera is not None
        # Read by VectorEnv with the other environments' cameras of the same engine, in one call.
        return StepResult(observation={"final_color": CameraImage(self.camera)})


def rate(envs: list[VectorEnv[NDArray[np.float32]]], steps: int) -> float:
    """Environment steps per second of stepping `envs` one after another, after 3 warm-up steps."""
    actions = [[np.array([0.5], np.float32)] * e.num_envs for e in envs]
    for e in envs:
        e.reset(seed=0)
    for _ in range(3):
        for e, a in zip(envs, actions):
            e.step(a)
    start = time.perf_counter()
    for _ in range(steps):
        for e, a in zip(envs, actions):
            e.step(a)
    return sum(e.num_envs for e in envs) * steps / (time.perf_counter() - start)


def measured(make: Callable[[], list[VectorEnv[NDArray[np.float32]]]], steps: int) -> float:
    envs = make()
    try:
        return rate(envs, steps)
    finally:
        for e in envs:
            e.close()


def cell(rates: list[float], floors: list[float]) -> str:
    """A column's median rate and its ratio to the floor (the median of each round's ratio, and their range
    when there were several rounds); "-" for a column not measured."""
    if not rates:
        return "-"
    ratios = [rate / floor for rate, floor in zip(rates, floors)]
    spread = f"; {min(ratios):.1f}–{max(ratios):.1f}" if len(ratios) > 1 else ""
    return f"{statistics.median(rates):.0f} ({statistics.median(ratios):.1f}×{spread})"


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--counts", type=int, nargs="+", default=[1, 4, 16, 64])
    parser.add_argument("--steps", type=int, default=30)
    parser.add_argument("--no-dask", action="store_true", help="skip the Dask column (for a Python without Dask)")
    parser.add_argument("--rounds", type=int, default=1, help="measure every column this many times, in turns")
    parser.add_argument("--size", type=int, default=SIZE, help="each camera's width and height in pixels")
    args = parser.parse_args()
    if args.rounds < 1:
        parser.error(f"--rounds must be at least 1, got {args.rounds}")
    if args.size < 1:
        parser.error(f"--size must be at least 1, got {args.size}")
    make_env = functools.partial(Push, args.size)
    cores = os.cpu_count() or 1
    client: Any = None
    cluster: Any = None
    if not args.no_dask:
        import distributed  # Debian's python3-distributed

        import spear.distributed
        cluster = distributed.LocalCluster(n_workers=cores, threads_per_worker=1, processes=True,
                                           dashboard_address=None, silence_logs=40)
        client = distributed.Client(cluster)
    print(f"{cores} cores; environment steps per second (physics + one {args.size}x{args.size} colour camera each), "
          f"{args.steps} timed steps after 3 warm-up steps"
          + (f"; medians of {args.rounds} rounds, ratios to each round's floor with their range" if args.rounds > 1
             else ""))
    print("| N | floor: N single-world servers, one after another | worlds in one process | "
          f"one server per core ({cores}) | Dask LocalCluster ({cores} workers) |")
    print("|---:|---:|---:|---:|---:|")
    try:
        for n in args.counts:
            servers = min(cores, n)
            columns: dict[str, list[float]] = {"floor": [], "worlds": [], "servers": [], "dask": []}
            for _ in range(args.rounds):
                columns["floor"].append(measured(
                    lambda: [VectorEnv.on_servers(make_env, num_servers=1) for _ in range(n)], args.steps))
                columns["worlds"].append(measured(lambda: [VectorEnv.in_worlds(make_env, num_envs=n)], args.steps))
                columns["servers"].append(measured(lambda: [VectorEnv.on_servers(
                    make_env, num_servers=servers, worlds_per_server=n // servers)], args.steps))
                if client is not None:
                    with spear.distributed.Servers(client) as dask_servers:
                        columns["dask"].append(measured(lambda: [VectorEnv.on_servers(
                            make_env, num_servers=servers, worlds_per_server=n // servers,
                            servers=dask_servers.addresses[:servers], token=dask_servers.token)], args.steps))
            floors = columns["floor"]
            cells = [cell(columns[key], floors) for key in ("worlds", "servers", "dask")]
            print(f"| {n} | {statistics.median(floors):.0f} | {' | '.join(cells)} |", flush=True)
    finally:
        if client is not None:
            client.close()
            cluster.close()


if __name__ == "__main__":
    main()
