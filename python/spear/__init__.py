"""spear: a simulator for embodied-AI and synthetic-data research, typed end to end.

Every engine class, struct and enum is importable from here with its full typed API (generated from
the engine's reflected C++ headers): spear.AActor, spear.FVector, spear.EComponentMobility, ...
"""

from spear._engine.api import *  # noqa: F403
from spear._engine import api as _api
from spear.errors import (ConnectionLostError, InvalidArgumentError, InvalidStateError, NotFoundError, SpearError,
                          StaleObjectError)
from spear._events import OverlapSubscription
from spear._spfunc import SpFuncResult
from spear.instance import Instance



def get_cmake_dir() -> str:
    """The folder of spear's CMake package, for plugins: ``cmake -Dspear_DIR=<this>``. In an installed
    package it is spear/sdk/cmake (the engine's headers, libraries and generator ship with the package); in a
    checkout, the build directory (SPEAR_BUILD_DIR, default build/)."""
    import os
    from pathlib import Path

    package = Path(__file__).resolve().parent
    if (package / "sdk" / "cmake" / "spearConfig.cmake").is_file():
        return str(package / "sdk" / "cmake")
    return os.environ.get("SPEAR_BUILD_DIR", str(package.parents[1] / "build"))


__all__ = [
    "get_cmake_dir",
    "Instance",
    "SpFuncResult",
    "OverlapSubscription",
    "SpearError",
    "ConnectionLostError",
    "InvalidArgumentError",
    "InvalidStateError",
    "NotFoundError",
    "StaleObjectError",
]
__all__ += _api.__all__  # the form type checkers follow (pyright does not expand *_api.__all__)
