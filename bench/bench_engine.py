"""Engine benchmarks: physics frames, spawn+destroy throughput and default scene load time.

Each number is printed beside a floor measured in the same run: the physics frame beside an empty
frame (the frame protocol alone), spawning a mesh with a body beside spawning a plain AActor, and the
scene load beside parsing the same file with Python's json module.

    PYTHONPATH=python /usr/bin/python3 bench/bench_engine.py
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402

CUBE = "/Engine/BasicShapes/Cube"
APARTMENT = ROOT / "assets" / "scenes" / "apartment.json"


def frame_ms(instance: spear.Instance, frames: int) -> float:
    start = time.perf_counter()
    instance.step(num_frames=frames)
    return (time.perf_counter() - start) / frames * 1e3


def physics_frames(bodies: int, frames: int = 120) -> tuple[float, float]:
    """Mean frame time with `bodies` falling cubes on a floor, and with none (the floor)."""
    instance = spear.Instance()
    game = instance.get_game()
    with instance.begin_frame():
        floor = game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(Z=-0.5))
        floor.StaticMeshComponent.SetStaticMesh(NewMesh=CUBE)
        floor.StaticMeshComponent.SetRelativeScale3D(NewScale3D=spear.FVector(100, 100, 1))
        floor.StaticMeshComponent.SetMobility(NewMobility=spear.EComponentMobility.Static)
    with instance.end_frame():
        pass
    empty = frame_ms(instance, frames)
    side = max(1, round(bodies ** 0.5))
    with instance.begin_frame():
        for i in range(bodies):
            cube = game.spawn_actor(uclass=spear.AStaticMeshActor,
                                    location=spear.FVector(1.5 * (i % side), 1.5 * (i // side), 1.0 + 0.01 * i))
            cube.StaticMeshComponent.SetStaticMesh(NewMesh=CUBE)
            cube.StaticMeshComponent.SetSimulatePhysics(bSimulate=True)
    with instance.end_frame():
        pass
    busy = frame_ms(instance, frames)  # falling and landing: the bodies are awake throughout
    instance.close()
    return busy, empty


def spawn_destroy_per_s(uclass: type[spear.AActor], with_mesh: bool, count: int = 2000) -> float:
    instance = spear.Instance()
    game = instance.get_game()
    with instance.begin_frame():
        start = time.perf_counter()
        for _ in range(count):
            actor = game.spawn_actor(uclass=uclass)
            if with_mesh and isinstance(actor, spear.AStaticMeshActor):
                actor.StaticMeshComponent.SetStaticMesh(NewMesh=CUBE)
                actor.StaticMeshComponent.IsSimulatingPhysics()  # forces the body to be built now
            game.destroy_actor(actor=actor)
        elapsed = time.perf_counter() - start
    instance.close()
    return count / elapsed


def scene_load_ms(repeat: int = 20) -> tuple[float, float]:
    instance = spear.Instance()
    game = instance.get_game()
    best = float("inf")
    with instance.begin_frame():
        for _ in range(repeat):
            start = time.perf_counter()
            game.load_scene(path=str(APARTMENT))
            best = min(best, time.perf_counter() - start)
    instance.close()
    parse = min(_timed(lambda: json.loads(APARTMENT.read_text())) for _ in range(repeat))
    return best * 1e3, parse * 1e3


def _timed(fn: object) -> float:
    assert callable(fn)
    start = time.perf_counter()
    fn()
    return time.perf_counter() - start


def main() -> None:
    print("physics frame (1/60 s = 4 substeps of 1/240 s), falling cubes on a static floor")
    print(f"{'bodies':>8} {'frame ms':>10} {'empty frame ms':>15} {'ratio':>7}")
    for bodies in (4, 16, 64, 256):
        busy, empty = physics_frames(bodies)
        print(f"{bodies:>8} {busy:>10.3f} {empty:>15.3f} {busy / empty:>7.1f}")
    mesh = spawn_destroy_per_s(spear.AStaticMeshActor, with_mesh=True)
    plain = spawn_destroy_per_s(spear.AActor, with_mesh=False)
    print(f"spawn+destroy: {mesh:,.0f}/s AStaticMeshActor with a body, {plain:,.0f}/s plain AActor "
          f"(ratio {plain / mesh:.1f})")
    load, parse = scene_load_ms()
    print(f"default scene load ({APARTMENT.name}): {load:.2f} ms (best of 20); "
          f"Python json.loads of the same file: {parse:.2f} ms (ratio {load / parse:.1f})")


if __name__ == "__main__":
    main()
