"""Table 3 side by side: spear's co-simulation benchmark (examples/cosim_benchmark.py, in-process and over
RPC) and MuJoCo running the same workload alone (bench/mujoco_cosim_peer.cpp: mj_step + mjr_render +
mjr_readPixels), one cell after the other in the same run, on the same device.

    PYTHONPATH=python /usr/bin/python3 bench/bench_cosim.py --build-dir build [--frames 1000] [--write]
    PYTHONPATH=python /usr/bin/python3 bench/bench_cosim.py --objects 256 --views 1 --sizes 3840x2160 640x480
    PYTHONPATH=python /usr/bin/python3 bench/bench_cosim.py --no-shadows    # the sun casts none, on both sides

The cells are every --views x --objects at each of --sizes (default: Table 3's 1920x1080), then Table 3's
256x256 cell (N = 64, one view) unless --sizes already holds that size.

--write replaces the Table 3 section of BENCHMARKS.md (between its cosim markers) with the results.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import platform
import subprocess
import sys
from pathlib import Path
from types import ModuleType
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402
from markdown_section import replace_section, section  # noqa: E402  (beside this script)


def load_example() -> ModuleType:
    spec = importlib.util.spec_from_file_location("cosim_benchmark", ROOT / "examples" / "cosim_benchmark.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up while the class is built
    spec.loader.exec_module(module)
    return module


def mujoco(peer: Path, objects: int, views: int, width: int, height: int, frames: int,
           shadows: bool) -> dict[str, Any]:
    completed = subprocess.run([str(peer), "--objects", str(objects), "--views", str(views), "--width", str(width),
                                "--height", str(height), "--frames", str(frames), "--shadows", str(int(shadows))],
                               check=True, capture_output=True, text=True)
    result: dict[str, Any] = json.loads(completed.stdout.strip().splitlines()[-1])
    return result


def spear_cell(example: ModuleType, server: str | None, objects: int, views: int, width: int, height: int,
               frames: int, png: Path | None, shadows: bool) -> float:
    instance = spear.Instance(server=server, fixed_delta_seconds=example.FRAME_DT)
    try:
        result = example.run(instance, objects=objects, views=views, width=width, height=height, frames=frames,
                             physics="bullet", png=png, shadows=shadows)
    finally:
        instance.close()
    return float(result.ms_per_frame)


def size(text: str) -> tuple[int, int]:
    """WxH, as --sizes takes it."""
    try:
        width, height = (int(part) for part in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"a size is WIDTHxHEIGHT, like 1920x1080; got '{text}'") from None
    if width < 1 or height < 1:
        raise argparse.ArgumentTypeError(f"a size must be at least 1x1; got '{text}'")
    return width, height


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", type=Path, default=ROOT / "build")
    parser.add_argument("--frames", type=int, default=1000)
    parser.add_argument("--objects", type=int, nargs="+", default=[4, 16, 64])
    parser.add_argument("--views", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--sizes", type=size, nargs="+", default=[(1920, 1080)], metavar="WxH",
                        help="image sizes of the grid of cells (default: 1920x1080)")
    parser.add_argument("--no-rpc", action="store_true", help="in-process only")
    parser.add_argument("--no-inprocess", action="store_true",
                        help="over RPC only: for a Python that cannot load the in-process module (another "
                        "version than the build's, as on a host running the portable kit, bench/portable_kit.sh)")
    parser.add_argument("--peer-dir", type=Path, default=None,
                        help="folder holding spear_mujoco_cosim_peer (default: BUILD_DIR/bench)")
    parser.add_argument("--png-dir", type=Path, default=None,
                        help="write view 0 of each cell's last frame here "
                        "(cosim_N<objects>_<views>v_<size>_<transport>.png)")
    parser.add_argument("--no-shadows", action="store_true", help="the sun casts no shadows, on both sides")
    parser.add_argument("--write", action="store_true", help="update the Table 3 section of BENCHMARKS.md")
    args = parser.parse_args()

    if args.no_rpc and args.no_inprocess:
        parser.error("--no-rpc and --no-inprocess leave nothing to measure")
    if args.write and args.no_shadows:
        parser.error("--write records Table 3's workload, which has shadows: leave out --no-shadows")
    peer = (args.peer_dir or args.build_dir / "bench") / "spear_mujoco_cosim_peer"
    if not peer.exists():
        parser.error(f"{peer} is missing: build it with `cmake --build {args.build_dir} --target "
                     "spear_mujoco_cosim_peer` (needs Debian's libmujoco-dev)")
    example = load_example()
    cells = [(n, v, w, h) for w, h in args.sizes for v in args.views for n in args.objects]
    if (256, 256) not in args.sizes:
        cells.append((64, 1, 256, 256))
    rows = []
    device = ""
    for objects, views, width, height in cells:
        print(f"cell: N={objects}, {views} view(s), {width}x{height}", file=sys.stderr, flush=True)
        peer_result = mujoco(peer, objects, views, width, height, args.frames, not args.no_shadows)
        def png(transport: str) -> Path | None:
            stem = f"cosim_N{objects}_{views}v_{width}x{height}_{transport}"
            return None if args.png_dir is None else args.png_dir / f"{stem}.png"

        inprocess = None if args.no_inprocess else spear_cell(example, None, objects, views, width, height,
                                                              args.frames, png("inprocess"), not args.no_shadows)
        rpc = None if args.no_rpc else spear_cell(example, "launch", objects, views, width, height, args.frames,
                                                  png("rpc"), not args.no_shadows)
        device = str(peer_result.get("device", ""))
        rows.append((objects, views, width, height, inprocess, rpc, float(peer_result["ms_per_frame"])))

    paper = example.PAPER_TABLE3
    lines = [
        "| cell | spear in-process ms | spear RPC ms | MuJoCo alone ms | spear / MuJoCo | RPC / in-process "
        "| paper: SPEAR / UnrealCV+ ms |",
        "|---|---:|---:|---:|---:|---:|---:|",
    ]

    def ms(value: float | None) -> str:
        return "-" if value is None else f"{value:.1f}"

    def ratio(numerator: float | None, denominator: float | None) -> str:
        return "-" if numerator is None or denominator is None else f"{numerator / denominator:.2f}"

    for objects, views, width, height, inprocess, rpc, peer_ms in rows:
        key = (objects, views)
        reference = (f"{paper['SPEAR'][key]:.1f} / {paper['UnrealCV+'][key]:.1f}"
                     if width == 1920 and key in paper["SPEAR"] else "-")
        # Without an in-process run the RPC frame time is compared with MuJoCo's (marked so).
        versus = ratio(inprocess, peer_ms) if inprocess is not None else f"{ratio(rpc, peer_ms)} (RPC)"
        lines.append(
            f"| N={objects}, {views} view{'s' if views > 1 else ''}, {width}x{height} | {ms(inprocess)} | "
            f"{ms(rpc)} | {peer_ms:.1f} | {versus} | {ratio(rpc, inprocess)} | {reference} |")
    # The command that reproduces this table: the options that choose its cells included where not the default.
    grid = "".join(f" --{name} {' '.join(values)}" for name, values, default in (
        ("objects", [str(n) for n in args.objects], ["4", "16", "64"]),
        ("views", [str(v) for v in args.views], ["1", "2"]),
        ("sizes", [f"{w}x{h}" for w, h in args.sizes], ["1920x1080"])) if values != default)
    command = ("PYTHONPATH=python /usr/bin/python3 bench/bench_cosim.py --build-dir build "
               f"--frames {args.frames}{grid}{' --no-rpc' if args.no_rpc else ''}"
               f"{' --no-inprocess' if args.no_inprocess else ''}"
               f"{' --no-shadows' if args.no_shadows else ' --write'}")
    lighting = ("the sun casts no shadows on either side" if args.no_shadows
                else "MuJoCo renders RGB with its own shadows")
    text = section("cosim", command, [
        f"Device: {device} ({platform.machine()}, {args.frames} timed frames per cell after 10 warm-up frames; "
        f"{lighting}, no MSAA).",
        "",
        *lines,
    ])
    print(text)
    if args.write:
        replace_section(ROOT / "BENCHMARKS.md", "cosim", "Table 3: the co-simulation benchmark beside MuJoCo", text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
