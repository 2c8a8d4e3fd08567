"""SpFuncs from Python: functions that C++ code registers at run time on a USpFuncComponent (the SPEAR
paper's Fig. 8), called with named numpy arrays of any dtype and shape.

Both transports share this module: the in-process engine and the RPC proxies differ only in how they
carry the bundle (`_sp_call_sp_func`); here the bundle is checked and its objects turned into JSON and
back, so that the same call gives the same result, or the same error, either way.
"""

from __future__ import annotations

import dataclasses
import enum
import functools
import json
from collections.abc import Mapping
from typing import Any, TypedDict

import numpy as np
from numpy.typing import NDArray

from spear import _blueprint, errors


class SpFuncResult(TypedDict):
    """What an SpFunc returns: named arrays, named objects (decoded from JSON), and an info string."""

    arrays: dict[str, NDArray[Any]]
    unreal_objs: dict[str, Any]
    info: str


def _json_default(value: Any) -> Any:
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: getattr(value, f.name) for f in dataclasses.fields(value)}
    if isinstance(value, enum.Enum):
        return value.value
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"a {type(value).__name__} has no JSON form")


def _encode_objects(context: str, unreal_objs: Mapping[str, object] | None) -> dict[str, str]:
    encoded: dict[str, str] = {}
    for name, value in (unreal_objs or {}).items():
        try:
            encoded[str(name)] = json.dumps(value, default=_json_default, sort_keys=True)
        except (TypeError, ValueError) as error:
            raise errors.InvalidArgumentError(f"{context}: unreal_objs[{name!r}] cannot be sent: {error}") from None
    return encoded


# numpy kinds and sizes that cross (bool, integers, float16/32/64), as in core/reflect/value.h's DType.
_SUPPORTED = {("b", 1)} | {(k, n) for k in "ui" for n in (1, 2, 4, 8)} | {("f", n) for n in (2, 4, 8)}


def _check_arrays(context: str, arrays: Mapping[str, NDArray[Any]] | None) -> dict[str, NDArray[Any]]:
    checked: dict[str, NDArray[Any]] = {}
    for name, array in (arrays or {}).items():
        if not isinstance(array, np.ndarray):
            raise errors.InvalidArgumentError(
                f"{context}: arrays[{name!r}] must be a numpy array, got {type(array).__name__}")
        if (array.dtype.kind, array.dtype.itemsize) not in _SUPPORTED:
            raise errors.InvalidArgumentError(
                f"{context}: arrays[{name!r}] has dtype {array.dtype}, which cannot cross (use bool, an integer "
                "or a float dtype)")
        checked[str(name)] = array
    return checked


def call_sp_func(self: Any, name: str, *, arrays: Mapping[str, NDArray[Any]] | None = None,
                 unreal_objs: Mapping[str, object] | None = None, info: str = "") -> SpFuncResult:
    """Calls the SpFunc `name` of this object (or of its USpFuncComponents, for an actor)."""
    context = f"{type(self).__name__}.{name}()"
    if not isinstance(info, str):
        raise errors.InvalidArgumentError(f"{context}: info must be a str, got {type(info).__name__}")
    # The transport calls finish() on the raw bundle: at once, or when a queued call's reply arrives.
    return self._sp_call_sp_func(  # type: ignore[no-any-return]
        name, _check_arrays(context, arrays), _encode_objects(context, unreal_objs), info, finish_result, context)


def finish_result(raw: Mapping[str, Any]) -> SpFuncResult:
    """The typed result from the bundle a transport carried back (objects arrive as JSON text)."""
    return {
        "arrays": dict(raw["arrays"]),
        "unreal_objs": {key: json.loads(text) for key, text in raw["unreal_objs"].items()},
        "info": raw["info"],
    }


def get_sp_func_names(self: Any) -> list[str]:
    """The names of the SpFuncs this object answers to now, sorted."""
    return list(self._sp_get_sp_func_names(f"{type(self).__name__}.get_sp_func_names()"))


def sp_func_getattr(self: Any, name: str) -> Any:
    """Attribute fallback: a function the object's blueprint declares (spear._blueprint), else an SpFunc by name,
    as in Fig. 8 (`my_actor.my_sp_func(arrays=...)`)."""
    if name.startswith("_"):
        raise AttributeError(f"'{type(self).__name__}' object has no attribute '{name}'")
    try:
        caller = _blueprint.function_caller(self, name)  # a function its blueprint declares, if any
    except errors.SpearError as error:
        raise AttributeError(f"'{type(self).__name__}' object has no attribute '{name}', and its blueprint's "
                             f"functions cannot be looked up now: {error}") from error
    if caller is not None:
        return caller
    try:
        names = self._sp_get_sp_func_names(f"{type(self).__name__}.{name}()")
    except errors.SpearError as error:
        # Attribute lookups must fail with AttributeError (hasattr, getattr with a default); the reason
        # (outside a frame, a destroyed object) goes in the message.
        raise AttributeError(f"'{type(self).__name__}' object has no attribute '{name}', and its SpFuncs "
                             f"cannot be listed now: {error}") from error
    if name in names:
        return functools.partial(call_sp_func, self, name)
    raise AttributeError(f"'{type(self).__name__}' object has no attribute or SpFunc '{name}'")
