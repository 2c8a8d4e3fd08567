"""Call overhead of the typed in-process API, as ratios to bare pybind11 calls measured in the same run.

    PYTHONPATH=python /usr/bin/python3 bench/bench_calls.py [--build-dir build]
"""

from __future__ import annotations

import argparse
import sys
import timeit
from pathlib import Path
from typing import Callable

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402


def best_ns(fn: Callable[[], object], number: int = 200_000, repeat: int = 7) -> float:
    """Best-of-repeat time per call in nanoseconds (the least disturbed run)."""
    return min(timeit.repeat(fn, number=number, repeat=repeat)) / number * 1e9


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--build-dir", type=Path, default=ROOT / "build")
    args = parser.parse_args()
    sys.path.insert(0, str(args.build_dir / "bench"))
    import _spear_bench_floor as floor  # type: ignore[import-not-found]

    empty = floor.Empty()
    instance = spear.Instance()
    game = instance.get_game()
    rows: list[tuple[str, float, float]] = []
    floor_call = best_ns(empty.noop)
    floor_kw = best_ns(lambda: empty.noop_kw(value=1.0))
    floor_attr = best_ns(lambda: empty.value)
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor)
        comp = actor.StaticMeshComponent
        location = spear.FVector(X=1.0)
        rows.append(("GetName() -> str", best_ns(actor.GetName), floor_call))
        rows.append(("ActorHasTag(Tag=str) -> bool", best_ns(lambda: actor.ActorHasTag(Tag="x")), floor_kw))
        rows.append(("bVisible (bool property read)", best_ns(lambda: comp.bVisible), floor_attr))
        rows.append(("Mobility (enum property read)", best_ns(lambda: comp.Mobility), floor_attr))
        rows.append(("GetActorLocation() -> FVector", best_ns(actor.GetActorLocation, number=50_000), floor_call))
        rows.append(("SetActorLocation(NewLocation=FVector)",
                     best_ns(lambda: actor.SetActorLocation(NewLocation=location), number=50_000), floor_kw))
        rows.append(("call_function('GetName') (dynamic)",
                     best_ns(lambda: instance.call_function(uobject=actor, function="GetName"), number=50_000),
                     floor_call))
    with instance.end_frame():
        pass
    print(f"floor: bare pybind11 method {floor_call:.0f} ns, with one kw-only float {floor_kw:.0f} ns, "
          f"def_readwrite read {floor_attr:.0f} ns")
    print(f"{'call':42} {'ns/call':>9} {'floor ns':>9} {'ratio':>7}")
    for name, ns, base in rows:
        print(f"{name:42} {ns:9.0f} {base:9.0f} {ns / base:7.2f}")


if __name__ == "__main__":
    main()
