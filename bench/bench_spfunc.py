"""SpFunc call overhead (the example plugin's AArrayTools "echo", which returns its arrays unchanged) with a
3-element float64 array and a 1920x1080x4 uint8 image, in-process and over RPC, as ratios to the floors
measured in the same run: a bare pybind11 call (in-process, small), a raw Unix-socket ping-pong of the same
request size (RPC, small), and one memcpy of the image (large).

    cmake -S examples/plugin -B build/plugin -G Ninja -Dspear_DIR=$PWD/build && cmake --build build/plugin
    PYTHONPATH=python /usr/bin/python3 bench/bench_spfunc.py [--build-dir build] [--plugin-dir build/plugin/python]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import timeit
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))
sys.path.insert(0, str(ROOT / "bench"))

import spear  # noqa: E402
from bench_rpc import raw_ping_pong_us  # noqa: E402


def best_s(fn: Callable[[], object], number: int, repeat: int = 7) -> float:
    """Best-of-repeat seconds per call (the least disturbed run)."""
    return min(timeit.repeat(fn, number=number, repeat=repeat)) / number


def request_bytes(arrays: dict[str, Any]) -> int:
    """The size of an sp_func request carrying `arrays`, for the raw ping-pong floor."""
    from spear._rpc_client import _HandleRef
    from spear._wire import OutgoingSegments, encode, pack_frame

    segments = OutgoingSegments()
    try:
        frame = pack_frame({"id": 1, "op": "sp_func", "object": encode(_HandleRef((1, 0)), segments),
                            "name": "echo", "arrays": encode(arrays, segments), "unreal_objs": {}, "info": ""})
    finally:
        segments.release()
    return sum(len(part) for part in frame) - 4


def measure(instance: spear.Instance, small: np.ndarray, image: np.ndarray) -> dict[str, float]:
    from my_plugin.api import AArrayTools, AMyActor, APointFilter

    game = instance.get_game()
    rpc = instance.transport == "rpc"
    results: dict[str, float] = {}
    with instance.begin_frame():
        tools = game.spawn_actor(uclass=AArrayTools)
        fig8 = game.spawn_actor(uclass=AMyActor)
        fig8.Initialize()
        echo = tools.echo  # the attribute form, looked up once (each lookup asks for the SpFunc names)
        results["small typed"] = best_s(lambda: tools.call_sp_func("echo", arrays={"x": small}),
                                        number=500 if rpc else 20_000)
        results["small attribute"] = best_s(lambda: echo(arrays={"x": small}), number=500 if rpc else 20_000)
        points_filter = game.spawn_actor(uclass=APointFilter)
        point = small.astype(np.float32).reshape(1, 3)
        center = spear.FVector()
        results["small typed SPFUNCTION"] = best_s(
            lambda: points_filter.Filter(Points=point, Center=center, Radius=10.0), number=500 if rpc else 20_000)
        results["large typed"] = best_s(lambda: tools.call_sp_func("echo", arrays={"image": image}),
                                        number=5 if rpc else 2_000)
        back = tools.call_sp_func("echo", arrays={"image": image})["arrays"]["image"]
        assert np.array_equal(back, image)
        game.destroy_actor(actor=tools)
        game.destroy_actor(actor=points_filter)
        fig8.Terminate()
        game.destroy_actor(actor=fig8)
    with instance.end_frame():
        pass
    return results


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", type=Path, default=ROOT / "build")
    parser.add_argument("--plugin-dir", type=Path, default=ROOT / "build/plugin/python")
    args = parser.parse_args()
    if not (args.plugin_dir / "my_plugin" / "libmy_plugin.so").is_file():
        sys.exit(f"bench_spfunc: no example plugin in {args.plugin_dir}; build it first (see the docstring)")
    sys.path.insert(0, str(args.plugin_dir))
    sys.path.insert(0, str(args.build_dir / "bench"))
    import _spear_bench_floor as floor  # type: ignore[import-not-found]

    small = np.array([1.0, 2.0, 3.0])
    image = np.random.default_rng(0).integers(0, 256, size=(1080, 1920, 4), dtype=np.uint8)
    empty = floor.Empty()
    pybind_s = best_s(lambda: empty.noop_kw(value=1.0), number=200_000)
    target = np.empty_like(image)
    memcpy_s = best_s(lambda: np.copyto(target, image), number=50)

    timings: dict[str, dict[str, float]] = {}
    for transport in ("inprocess", "rpc"):
        with spear.Instance(server=None if transport == "inprocess" else "launch") as instance:
            instance.load_plugin("my_plugin")
            timings[transport] = measure(instance, small, image)
    with tempfile.TemporaryDirectory() as tmp:
        socket_s = raw_ping_pong_us(request_bytes({"x": small}), 2000, tmp) * 1e-6

    inp, rpc = timings["inprocess"], timings["rpc"]
    print("floors: bare pybind11 call (one kw-only arg) "
          f"{pybind_s * 1e9:.0f} ns; raw Unix-socket ping-pong {socket_s * 1e6:.1f} us; "
          f"memcpy of 1920x1080x4 uint8 (8.3 MB) {memcpy_s * 1e3:.2f} ms")
    rows = [
        ("in-process  echo, 3 x float64, call_sp_func", inp["small typed"], pybind_s, "pybind11 call"),
        ("in-process  echo, 3 x float64, attribute form", inp["small attribute"], pybind_s, "pybind11 call"),
        ("in-process  Filter(Points=1x3 float32) (typed SPFUNCTION)", inp["small typed SPFUNCTION"], pybind_s, "pybind11 call"),
        ("in-process  echo, 1920x1080x4 uint8", inp["large typed"], memcpy_s, "memcpy"),
        ("RPC         echo, 3 x float64, call_sp_func", rpc["small typed"], socket_s, "socket round trip"),
        ("RPC         echo, 3 x float64, attribute form", rpc["small attribute"], socket_s, "socket round trip"),
        ("RPC         Filter(Points=1x3 float32) (typed SPFUNCTION)", rpc["small typed SPFUNCTION"], socket_s,
         "socket round trip"),
        ("RPC         echo, 1920x1080x4 uint8 (shared memory)", rpc["large typed"], memcpy_s, "memcpy"),
    ]
    print(f"{'call':58} {'time':>11} {'ratio':>8}  floor")
    for name, seconds, base, floor_name in rows:
        shown = f"{seconds * 1e6:8.1f} us" if seconds < 1e-3 else f"{seconds * 1e3:8.2f} ms"
        print(f"{name:58} {shown:>11} {seconds / base:7.3g}x  {floor_name}")


if __name__ == "__main__":
    main()
