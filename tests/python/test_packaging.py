"""The package as a user installs it: a wheel built by pip (setup.py drives CMake), installed into a fresh
virtual environment, used from a folder outside the checkout with nothing on PYTHONPATH: the getting-started
example and the examples that load the built-in scene and blueprints run (copied alone out of the checkout)
and those assets load on both transports, spear-server is on the venv's PATH,
and mypy --strict sees the installed package's types with no stub path."""

from __future__ import annotations

import os
import subprocess
import sys
import venv
from collections.abc import Iterator
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

USE_INSTALLED = """
import spear

for server in (None, "launch"):
    instance = spear.Instance(server=server, scene="assets/scenes/apartment.json")
    game = instance.get_game()
    with instance.begin_frame():
        crate = game.spawn_actor(uclass=spear.BP_Crate, name="Crate")
    with instance.end_frame():
        actors = game.find_actors_by_class(uclass=spear.AActor)
        print(server, len(actors), crate.GetClassName(), spear.__file__)
    instance.close()
"""


def _clean_env(venv_dir: Path) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "SPEAR_SERVER", "SPEAR_ASSET_PATH")}
    env["PATH"] = f"{venv_dir / 'bin'}:{env.get('PATH', '')}"
    return env


@pytest.fixture(scope="module")
def installed(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[Path, Path]]:
    """(venv folder, a work folder outside the checkout) with the wheel installed."""
    base = tmp_path_factory.mktemp("packaging")
    wheels = base / "wheels"
    build_dir = os.environ.get("SPEAR_BUILD_DIR", str(ROOT / "build"))
    # As the README says: Debian's python3-build, without isolation (only Debian's packages are reachable).
    subprocess.run([sys.executable, "-m", "build", "--no-isolation", "--wheel", "--outdir", str(wheels), str(ROOT)],
                   check=True, cwd=base, env={**os.environ, "SPEAR_BUILD_DIR": build_dir}, stdout=subprocess.DEVNULL)
    (wheel,) = wheels.glob("spear-*.whl")
    venv_dir = base / "venv"
    venv.EnvBuilder(system_site_packages=True, with_pip=False).create(venv_dir)
    # Debian's pip (23) installs into another environment with --python; the venv itself has no pip.
    # Without PYTHONPATH: with the checkout's python/ on it, pip would take spear for installed already.
    subprocess.run([sys.executable, "-m", "pip", "--python", str(venv_dir / "bin" / "python"), "install", "--no-deps",
                    "-q", str(wheel)], check=True, cwd=base, env=_clean_env(venv_dir))
    work = base / "work"
    work.mkdir()
    yield venv_dir, work


def _run(installed: tuple[Path, Path], *command: str) -> str:
    venv_dir, work = installed
    result = subprocess.run(command, cwd=work, env=_clean_env(venv_dir), capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, f"{command} failed:\n{result.stdout}\n{result.stderr}"
    return result.stdout


def test_getting_started_runs_from_the_installed_package(installed: tuple[Path, Path]) -> None:
    venv_dir, work = installed
    (work / "getting_started.py").write_text((ROOT / "examples" / "getting_started.py").read_text())
    out = _run(installed, str(venv_dir / "bin" / "python"), "getting_started.py")
    assert "using the destroyed actor raises StaleObjectError" in out


# Examples that load the built-in scene or blueprints, each copied alone into a folder outside the checkout and
# run against the installed package, with small arguments, and what its output must say.
INSTALLED_EXAMPLES = [
    ("render_image.py", ["--out", "out/render_image.png"], "out/render_image.png"),
    ("movie_render_queue.py", ["--frames", "3", "--width", "48", "--height", "32", "--out", "out/queue"],
     "final_color.mp4"),
    ("raster_vs_path_traced.py", ["--width", "64", "--height", "48", "--samples", "8", "--out", "out/side.png"],
     "out/side.png"),
    ("blueprints.py", [], "came to rest"),
    ("control_pawn.py", ["--frames", "8", "--out", "out/pawn.png"], "out/pawn.png"),
    # The built-in humanoid (/Game/characters/humanoid.glb), its skeleton and clips.
    ("animated_characters.py", ["--frames", "4", "--out", "out/characters.png"], "clips: idle, walk, run"),
    # The built-in motion sequence (/Game/motions/carry_case.npz), found by spear.motion in the package.
    ("import_motion.py", ["--out", "out/motion.png"], "objects: Case"),
]


@pytest.mark.parametrize("server", [[], ["--server", "launch"]], ids=["inprocess", "rpc"])
@pytest.mark.parametrize("example,args,says", INSTALLED_EXAMPLES, ids=[e[0] for e in INSTALLED_EXAMPLES])
def test_examples_run_out_of_the_checkout_against_the_installed_package(
        installed: tuple[Path, Path], example: str, args: list[str], says: str, server: list[str]) -> None:
    # They name the built-in assets by asset name (/Game/...), which the package finds wherever it is run.
    venv_dir, work = installed
    folder = work / f"{Path(example).stem}_{len(server)}"
    folder.mkdir()
    (folder / example).write_text((ROOT / "examples" / example).read_text())
    result = subprocess.run([str(venv_dir / "bin" / "python"), example, *args, *server], cwd=folder,
                            env=_clean_env(venv_dir), capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, f"{example} failed:\n{result.stdout}\n{result.stderr}"
    assert says in result.stdout, result.stdout


def test_built_in_assets_load_on_both_transports(installed: tuple[Path, Path]) -> None:
    venv_dir, work = installed
    (work / "use_installed.py").write_text(USE_INSTALLED)
    lines = _run(installed, str(venv_dir / "bin" / "python"), "use_installed.py").splitlines()
    assert len(lines) == 2
    for line in lines:
        _, count, class_name, package_file = line.split()
        assert int(count) > 10 and class_name == "BP_Crate"
        assert package_file.startswith(str(venv_dir)), f"spear imported from {package_file}, not the venv"


def test_spear_server_is_on_path(installed: tuple[Path, Path]) -> None:
    venv_dir, _ = installed
    result = subprocess.run(["spear-server"], env=_clean_env(venv_dir), capture_output=True, text=True, timeout=60)
    assert result.returncode == 2 and "usage: spear-server" in result.stderr


def test_mypy_sees_the_installed_types(installed: tuple[Path, Path]) -> None:
    venv_dir, work = installed
    (work / "getting_started.py").write_text((ROOT / "examples" / "getting_started.py").read_text())
    (work / "misuse.py").write_text("import spear\n\nspear.FVector(X='far')\n")
    ok = subprocess.run([str(venv_dir / "bin" / "python"), "-m", "mypy", "--strict", "--no-incremental",
                         "getting_started.py"], cwd=work, env=_clean_env(venv_dir), capture_output=True, text=True)
    assert ok.returncode == 0, ok.stdout
    bad = subprocess.run([str(venv_dir / "bin" / "python"), "-m", "mypy", "--strict", "--no-incremental", "misuse.py"],
                         cwd=work, env=_clean_env(venv_dir), capture_output=True, text=True)
    assert 'Argument "X" to "FVector" has incompatible type "str"; expected "float"' in bad.stdout


def test_a_plugin_builds_against_the_installed_package(installed: tuple[Path, Path]) -> None:
    # The CMake package ships inside the Python package (spear.get_cmake_dir()): the example plugin builds
    # against its headers, generator and libraries, and loads into the installed spear on both transports.
    venv_dir, work = installed
    python = str(venv_dir / "bin" / "python")
    cmake_dir = _run(installed, python, "-c", "import spear; print(spear.get_cmake_dir())").strip()
    assert cmake_dir.startswith(str(venv_dir)), cmake_dir
    build = work / "plugin-build"
    _run(installed, "cmake", "-S", str(ROOT / "examples" / "plugin"), "-B", str(build), "-G", "Ninja",
         "-DCMAKE_BUILD_TYPE=RelWithDebInfo", f"-Dspear_DIR={cmake_dir}")
    _run(installed, "cmake", "--build", str(build), "-j", os.environ.get("SPEAR_JOBS", "2"))
    env = {**_clean_env(venv_dir), "SPEAR_PLUGIN_DIR": str(build / "python")}
    for transport in ([], ["--rpc"]):
        result = subprocess.run([python, str(ROOT / "examples" / "plugin" / "use_plugin.py"), *transport], cwd=work,
                                env=env, capture_output=True, text=True, timeout=300)
        assert result.returncode == 0, result.stdout + result.stderr
        assert "unloaded plugin 'my_plugin'" in result.stdout
    typed = subprocess.run([python, "-m", "mypy", "--strict", "--no-incremental",
                            str(ROOT / "examples" / "plugin" / "use_plugin.py")], cwd=work,
                           env={**env, "MYPYPATH": str(build / "python")}, capture_output=True, text=True)
    assert typed.returncode == 0, typed.stdout


SERVE_INSPECTOR = """
import concurrent.futures, sys, urllib.request
import spear
for server in (None, "launch"):
    instance = spear.Instance(server=server)
    url = instance.inspect(port=0)
    def fetch(path: str) -> bytes:
        return urllib.request.urlopen(url.split("?")[0] + path if path else url, timeout=30).read()
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        page, script, client = (pool.submit(fetch, p) for p in ("", "inspector/src/main.js",
                                                                  "generated/engine/ts/api.gen.js"))
        while not (page.done() and script.done() and client.done()):
            instance.serve_inspector(seconds=0.02)  # in-process the engine answers between frames, or here
    print(instance.transport, b"<title>spear inspector</title>" in page.result(), len(script.result()) > 1000,
          b"API_HASH" in client.result())
    instance.close()
"""


def test_the_installed_package_serves_the_inspector(installed: tuple[Path, Path]) -> None:
    venv_dir, work = installed
    (work / "serve_inspector.py").write_text(SERVE_INSPECTOR)
    lines = _run(installed, str(venv_dir / "bin" / "python"), "serve_inspector.py").splitlines()
    assert lines == ["inprocess True True True", "rpc True True True"]
