"""Builds spear plugins out of tree for the tests, as a plugin author would: find_package(spear) against
the engine's build directory, then spear_add_plugin() (see examples/plugin/CMakeLists.txt)."""

from __future__ import annotations

import contextlib
import os
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

import spear

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples/plugin"


def spear_build_dir() -> Path:
    build = Path(os.environ.get("SPEAR_BUILD_DIR", ROOT / "build"))
    if not (build / "spearConfig.cmake").is_file():
        pytest.fail(f"no spear build in {build} (spearConfig.cmake missing): run `bash test.sh`, or set "
                    "SPEAR_BUILD_DIR to the build directory", pytrace=False)
    return build


def run(command: list[str], cwd: Path | None = None) -> str:
    result = subprocess.run(command, cwd=cwd, capture_output=True, text=True, check=False)
    if result.returncode != 0:
        pytest.fail(f"{' '.join(command)} failed:\n{result.stdout[-4000:]}\n{result.stderr[-4000:]}", pytrace=False)
    return result.stdout


def configure(source: Path, build: Path) -> None:
    run(["cmake", "-S", str(source), "-B", str(build), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=RelWithDebInfo",
         f"-Dspear_DIR={spear_build_dir()}"])


def build(build_dir: Path) -> str:
    """Builds; returns the build's output (which says when the generator ran)."""
    return run(["cmake", "--build", str(build_dir), "-j", os.environ.get("SPEAR_JOBS", "2")])


def build_plugin(source: Path, build_dir: Path) -> Path:
    """Configures and builds the plugin at `source`; returns the directory holding its Python package."""
    configure(source, build_dir)
    build(build_dir)
    return build_dir / "python"


def build_importable_plugin(source: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """build_plugin() in a fresh temporary directory, with the package directory put on sys.path (as
    PYTHONPATH would) so that the plugin's typed API imports; returns that directory."""
    python_dir = build_plugin(source, tmp_path_factory.mktemp(source.name) / "build")
    if str(python_dir) not in sys.path:
        sys.path.insert(0, str(python_dir))
    return python_dir


@contextlib.contextmanager
def whole_frame(instance: spear.Instance) -> Iterator[None]:
    """A whole frame, for tests that do everything in begin_frame (end_frame runs even after an error)."""
    try:
        with instance.begin_frame():
            yield
    finally:
        with instance.end_frame():
            pass
