"""Runs the generator as a user would (python3 -m codegen ...), for the codegen tests."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
EIGEN = "/usr/include/eigen3"


def engine_headers() -> list[str]:
    lines = (ROOT / "core/engine/reflected_headers.txt").read_text().splitlines()
    return [line for line in lines if line and not line.startswith("#")]


def run_codegen(command: str, module: str, out: Path, headers: list[str], hash_seed: str = "0",
                extra: list[str] | None = None) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, PYTHONHASHSEED=hash_seed)
    # The engine module also types the blueprint assets, as the build does.
    blueprints = ["--blueprint-dir", "assets/blueprints"] if module == "engine" else []
    return subprocess.run(
        [sys.executable, "-m", "codegen", command, "--module", module, "--root", str(ROOT), "--out", str(out),
         "--include-dir", EIGEN, *blueprints, *(extra or []), *headers],
        cwd=ROOT, env=env, capture_output=True, text=True, check=False,
    )


def tree(root: Path) -> dict[str, bytes]:
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}
