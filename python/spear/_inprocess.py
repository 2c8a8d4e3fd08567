"""The in-process transport: the pybind11 engine module, loaded on first use.

Loading registers every pybind11 class as a virtual subclass of its class in the typed API, so that
isinstance() and uclass= treat in-process objects like any other implementation.
"""

from __future__ import annotations

import importlib
from types import ModuleType
from typing import Any

from spear import _spfunc
from spear._engine import api

_module: ModuleType | None = None
_natives: dict[str, Any] = {}  # engine class name -> its pybind11 class (engine and loaded plugins)


def native_class(class_name: str) -> Any:
    """The pybind11 class of an engine class, or None if no in-process module has it."""
    if _module is None and class_name not in _natives:
        module()
    return _natives.get(class_name)


def module() -> Any:
    global _module
    if _module is None:
        loaded = importlib.import_module("spear._spear_engine")
        register_classes(api, loaded)
        _install_sp_funcs(loaded)
        _module = loaded
    return _module


def _install_sp_funcs(loaded: Any) -> None:
    """SpFuncs on the root pybind11 class: the typed call, the names, and Fig. 8's attribute form."""
    root = loaded.UObject

    def call_raw(self: Any, name: str, arrays: dict[str, Any], unreal_objs: dict[str, str], info: str,
                 finish: Any, context: str) -> Any:
        return finish(loaded._call_sp_func(self, name, arrays, unreal_objs, info, context))

    root._sp_call_sp_func = call_raw
    root._sp_get_sp_func_names = lambda self, context: loaded._get_sp_func_names(self, context)
    root.call_sp_func = _spfunc.call_sp_func
    root.get_sp_func_names = _spfunc.get_sp_func_names
    root.__getattr__ = _spfunc.sp_func_getattr


def register_classes(api_module: ModuleType, native_module: Any) -> None:
    """Makes each pybind11 class of `native_module` a virtual subclass of its class in `api_module`."""
    for name in api_module.__all__:
        public = getattr(api_module, name)
        native = getattr(native_module, name, None)
        if native is not None and isinstance(public, type) and hasattr(public, "register"):
            public.register(native)
            _natives[name] = native


def new_engine(fixed_delta_seconds: float) -> Any:
    return module().Engine(fixed_delta_seconds=fixed_delta_seconds)
