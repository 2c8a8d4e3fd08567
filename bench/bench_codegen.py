"""Generator wall time: a full regeneration of the engine headers, and a no-op rebuild.

    /usr/bin/python3 bench/bench_codegen.py [--build-dir build]
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def timed(cmd: list[str]) -> float:
    start = time.perf_counter()
    subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--build-dir", type=Path, default=ROOT / "build")
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    headers = [h for h in (ROOT / "core/engine/reflected_headers.txt").read_text().splitlines()
               if h and not h.startswith("#")]
    with tempfile.TemporaryDirectory() as out:
        gen = [sys.executable, "-m", "codegen", "generate", "--module", "engine", "--root", str(ROOT), "--out", out,
               "--include-dir", "/usr/include/eigen3", *headers]
        timed(gen)  # the first run writes every file; later runs parse and render but write nothing
        full = [timed(gen) for _ in range(args.runs)]
    with tempfile.TemporaryDirectory() as out:
        fresh = []
        for i in range(args.runs):
            gen[gen.index("--out") + 1] = f"{out}/{i}"
            fresh.append(timed(gen))
    noop = [timed(["cmake", "--build", str(args.build_dir)]) for _ in range(args.runs)]
    print(f"engine headers: {len(headers)}")
    print(f"full regeneration into an empty folder: best {min(fresh):.2f} s, median {sorted(fresh)[len(fresh) // 2]:.2f} s")
    print(f"regeneration with unchanged output:     best {min(full):.2f} s")
    print(f"no-op build (ninja, nothing changed):   best {min(noop) * 1000:.0f} ms")


if __name__ == "__main__":
    main()
