"""Builds the spear package for pip: CMake builds the engine (the pybind11 module, its libraries,
spear-server and the generated bindings), then the package is assembled from python/spear, the generated
API (python/spear/_engine, a link into generated/ in the checkout, real files in the wheel) and the built-in
assets. Only Debian's packages are reachable, so build without isolation:

    /usr/bin/python3 -m pip install --no-build-isolation .
    /usr/bin/python3 -m build --no-isolation --wheel

The CMake build folder is SPEAR_BUILD_DIR (default build/, shared with bash run.sh and bash test.sh).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

ROOT = Path(__file__).resolve().parent


class PlatformDistribution(Distribution):
    """The package holds compiled code (the module, its libraries, spear-server): the wheel is tagged for
    this Python and platform, not pure."""

    def has_ext_modules(self) -> bool:
        return True


class BuildWithCMake(build_py):
    """Builds the engine with CMake before collecting the package's files, then adds the built-in assets."""

    def run(self) -> None:
        # The module is built for Debian's /usr/bin/python3 (the interpreter that sees the apt-installed
        # packages); a wheel built by another Python would be tagged for it and hold a module it cannot load.
        if os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3"):
            raise SystemExit(f"spear: build the package with /usr/bin/python3 (or a venv made from it), not "
                             f"{sys.executable}")
        build_dir = Path(os.environ.get("SPEAR_BUILD_DIR", ROOT / "build"))
        print(f"spear: building the engine with CMake in {build_dir}", flush=True)
        # A build folder configured before (by hand, with CMake's default generator) keeps its generator:
        # CMake refuses to switch one.
        generator = [] if (build_dir / "CMakeCache.txt").exists() else ["-G", "Ninja"]
        subprocess.check_call(["cmake", "-S", str(ROOT), "-B", str(build_dir), *generator,
                               "-DCMAKE_BUILD_TYPE=RelWithDebInfo", "-DPython3_EXECUTABLE=/usr/bin/python3"],
                              stdout=subprocess.DEVNULL)
        subprocess.check_call(["cmake", "--build", str(build_dir), "-j", os.environ.get("SPEAR_JOBS", "2"),
                               "--target", "_spear_engine", "spear-server"])
        super().run()
        # Without debug information: the build's RelWithDebInfo libraries are ten times the size.
        package = Path(self.build_lib) / "spear"
        for binary in [*package.glob("_spear_engine*.so"), *package.glob("lib/*.so"), package / "bin" / "spear-server"]:
            subprocess.check_call(["strip", "--strip-debug", str(binary)])
        # The built-in assets (default scene, blueprints) travel as package data: the engine looks for them
        # beside an installed package (core/base/asset_path.h).
        assets = package / "assets"
        shutil.rmtree(assets, ignore_errors=True)
        shutil.copytree(ROOT / "assets", assets)
        self._copy_sdk(build_dir, package / "sdk")

    @staticmethod
    def _copy_sdk(build_dir: Path, sdk: Path) -> None:
        """What a plugin author builds against (spear.get_cmake_dir()): the CMake package, the engine's headers
        (generated ones included), and the generator with its templates, laid out as in the checkout."""
        shutil.rmtree(sdk, ignore_errors=True)
        files = [*ROOT.glob("core/**/*.h"), *ROOT.glob("generated/engine/cpp/*.h"),
                 ROOT / "generated/engine/reflection.json", *ROOT.glob("codegen/*.py"),
                 *ROOT.glob("templates/*.j2"), *ROOT.glob("cmake/Spear*.cmake"), ROOT / "cmake/plugin_module.cpp.in"]
        for file in files:
            target = sdk / file.relative_to(ROOT)
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(file, target)
        for name in ("spearConfig.cmake", "spearTargets.cmake"):
            shutil.copy2(build_dir / "sdk" / name, sdk / "cmake" / name)


(ROOT / "build" / "setuptools").mkdir(parents=True, exist_ok=True)
setup(
    distclass=PlatformDistribution,
    # Beside CMake's files in build/, not among them, and no spear.egg-info in python/ (with python/ on
    # PYTHONPATH, pip would take that for an installed spear).
    options={"build": {"build_base": "build/setuptools"}, "egg_info": {"egg_base": "build/setuptools"}},
    cmdclass={"build_py": BuildWithCMake},
    package_dir={"": "python"},
    packages=["spear", "spear._engine"],
    package_data={
        "spear": ["py.typed", "*.pyi", "_spear_engine*.so", "bin/spear-server", "lib/*.so",
                  "inspector/*.html", "inspector/*.css", "inspector/**/*.js"],
        "spear._engine": ["*.pyi"],
    },
    entry_points={"console_scripts": ["spear-server = spear._server_command:main"]},
)
