"""The in-process transport: the pybind11 engine module, loaded on first use.

Loading registers every pybind11 class as a virtual subclass of its class in the typed API, so that
isinstance() and uclass= treat in-process objects like any other implementation.
"""

from __future__ import annotations

import importlib
from types import ModuleType
from typing import Any

from spear._engine import api

_module: ModuleType | None = None


def module() -> Any:
    global _module
    if _module is None:
        loaded = importlib.import_module("spear._spear_engine")
        for name in api.__all__:
            public = getattr(api, name)
            native = getattr(loaded, name, None)
            if native is not None and isinstance(public, type) and hasattr(public, "register"):
                public.register(native)
        _module = loaded
    return _module


def new_engine(fixed_delta_seconds: float) -> Any:
    return module().Engine(fixed_delta_seconds=fixed_delta_seconds)
