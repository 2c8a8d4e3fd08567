"""The toolkit's own loop: how long after a header edit the typed API is usable.

For one engine header and one plugin header, adds a reflected property and a reflected function (what a
user adds most), then times, each from the edit: the stubs (the generator step), the in-process module and
spear-server rebuilt (the engine), or the plugin rebuilt, each against the same build's no-op time. After
each measurement the header is restored and the build brought back to where it was (not timed), so every
edit starts from an up-to-date build. A built engine is required (bash run.sh or the build of test.sh).

    /usr/bin/python3 bench/bench_regen.py [--build-dir build] [--jobs 2] [--write]

--write puts the results in BENCHMARKS.md.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
from markdown_section import replace_section, section  # noqa: E402

ENGINE_HEADER = ROOT / "core/gameplay/kinematic_vehicle.h"
ENGINE_CLASS = "AKinematicVehicle"
PLUGIN_HEADER = "point_filter.h"  # in examples/plugin
PLUGIN_CLASS = "APointFilter"
ADDED = """
  public:
    /// Added by bench/bench_regen.py.
    SPPROPERTY()
    double BenchRegenValue = 0.0;

    /// Added by bench/bench_regen.py.
    SPFUNCTION()
    double GetBenchRegenTwice() const { return 2.0 * BenchRegenValue; }
"""


def with_members(text: str, cls: str) -> str:
    """The header text with ADDED at the end of class `cls` (before its closing brace)."""
    start = re.search(rf"^class {cls}\b", text, re.M)
    if start is None:
        raise SystemExit(f"bench_regen: no 'class {cls}' in the header")
    end = text.index("\n};", start.end())
    return text[:end] + "\n" + ADDED.rstrip("\n") + text[end:]


def build(build_dir: Path, jobs: int, target: str | None = None) -> float:
    """Builds (one target, or everything); returns the wall time in seconds."""
    command = ["cmake", "--build", str(build_dir), "-j", str(jobs)] + (["--target", target] if target else [])
    start = time.perf_counter()
    result = subprocess.run(command, cwd=ROOT, capture_output=True, text=True, check=False)
    elapsed = time.perf_counter() - start
    if result.returncode != 0:
        raise SystemExit(f"bench_regen: {' '.join(command)} failed:\n{result.stdout[-3000:]}{result.stderr[-3000:]}")
    return elapsed


def after_edit(header: Path, cls: str, rebuild: Callable[[], float], restore: Callable[[], float]) -> float:
    """Edits `header`, times `rebuild`, then restores the header and runs `restore` (not timed)."""
    original = header.read_text()
    header.write_text(with_members(original, cls))
    try:
        return rebuild()
    finally:
        header.write_text(original)
        restore()


def check_engine_api(build_dir: Path) -> None:
    """The new members are in the stubs and in the built module, as a user would reach them."""
    stubs = (ROOT / "generated/engine/python/api.pyi").read_text()
    assert "def GetBenchRegenTwice(self) -> float" in stubs and "def BenchRegenValue(self) -> float" in stubs, "stubs"
    probe = (f"import spear._spear_engine as m; assert hasattr(m.{ENGINE_CLASS}, 'GetBenchRegenTwice'); "
             f"assert hasattr(m.{ENGINE_CLASS}, 'BenchRegenValue')")
    subprocess.run([sys.executable, "-c", probe], cwd=ROOT, check=True,
                   env={**os.environ, "PYTHONPATH": str(ROOT / "python"), "SPEAR_BUILD_DIR": str(build_dir)})


def engine_rows(build_dir: Path, jobs: int) -> list[tuple[str, float, float]]:
    rows = []
    for label, target, check in (("stubs (generator step)", "spear_codegen_engine", False),
                                 ("in-process module (_spear_engine)", "_spear_engine", True),
                                 ("spear-server", "spear-server", False)):
        build(build_dir, jobs)
        noop = min(build(build_dir, jobs, target) for _ in range(3))

        def rebuild(target: str = target, check: bool = check) -> float:
            elapsed = build(build_dir, jobs, target)
            if check:
                check_engine_api(build_dir)
            return elapsed

        edited = after_edit(ENGINE_HEADER, ENGINE_CLASS, rebuild, lambda: build(build_dir, jobs))
        rows.append((label, edited, noop))
        print(f"engine header {ENGINE_HEADER.relative_to(ROOT)} -> {label}: {edited:.1f} s "
              f"(no-op {noop:.2f} s)", flush=True)
    return rows


def plugin_rows(build_dir: Path, jobs: int) -> list[tuple[str, float, float]]:
    with tempfile.TemporaryDirectory() as scratch:
        source = Path(scratch) / "plugin"
        shutil.copytree(ROOT / "examples/plugin", source)
        plugin_build = Path(scratch) / "build"
        subprocess.run(["cmake", "-S", str(source), "-B", str(plugin_build), "-G", "Ninja",
                        "-DCMAKE_BUILD_TYPE=RelWithDebInfo", f"-Dspear_DIR={build_dir}"],
                       check=True, capture_output=True)
        print("plugin: first build of examples/plugin (not timed)", flush=True)
        build(plugin_build, jobs)
        noop = min(build(plugin_build, jobs) for _ in range(3))
        header = source / PLUGIN_HEADER
        stubs = after_edit(header, PLUGIN_CLASS, lambda: build(plugin_build, jobs, "spear_codegen_my_plugin"),
                           lambda: build(plugin_build, jobs))
        whole = after_edit(header, PLUGIN_CLASS, lambda: build(plugin_build, jobs), lambda: build(plugin_build, jobs))
    for label, value in (("stubs (generator step)", stubs), ("plugin library and module", whole)):
        print(f"plugin header examples/plugin/{PLUGIN_HEADER} -> {label}: {value:.1f} s (no-op {noop:.2f} s)",
              flush=True)
    return [("stubs (generator step)", stubs, noop), ("plugin library and module", whole, noop)]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", type=Path, default=ROOT / "build")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--write", action="store_true", help="put the results in BENCHMARKS.md")
    args = parser.parse_args()
    build_dir = args.build_dir.resolve()
    if not (build_dir / "CMakeCache.txt").is_file():
        raise SystemExit(f"bench_regen: no build in {build_dir}: run `bash run.sh` first")
    engine = engine_rows(build_dir, args.jobs)
    plugin = plugin_rows(build_dir, args.jobs)
    body = [f"`-j{args.jobs}`, {os.cpu_count()} hardware threads; each time from the header edit (one SPPROPERTY "
            "and one SPFUNCTION added) to the target built, with that target's no-op build beside it.", "",
            "| header edited | ready | after the edit | no-op build |", "|---|---|---:|---:|"]
    for where, rows in ((f"engine `{ENGINE_HEADER.relative_to(ROOT)}`", engine),
                        (f"plugin `examples/plugin/{PLUGIN_HEADER}`", plugin)):
        body += [f"| {where} | {label} | {edited:.1f} s | {noop:.2f} s |" for label, edited, noop in rows]
    if args.write:
        command = f"/usr/bin/python3 bench/bench_regen.py --build-dir build --jobs {args.jobs} --write"
        replace_section(ROOT / "BENCHMARKS.md", "regen", "Header edit to typed API (bench_regen.py)",
                        section("regen", command, body))
        print("BENCHMARKS.md: section 'regen' written")
    print("\n".join(body))


if __name__ == "__main__":
    main()
