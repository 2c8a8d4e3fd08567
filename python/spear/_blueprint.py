"""Python classes for blueprints: engine classes defined by data at run time (core/scene/blueprint.h).

A blueprint has no generated Python class, so UWorld.load_class() returns one made here: a subclass of its
native class's API class (so it types and checks as, e.g., type[AActor]) whose __sp_class__ is the
blueprint's name, which makes it work as uclass= on both transports. One class per blueprint name.

The functions a blueprint declares (core/scene/blueprint_functions.h) are called by attribute on its objects,
`crate.Launch(Speed=3.0)`, on either transport: the objects are of the native class, so the attribute
fallback (spear._spfunc.sp_func_getattr) asks function_caller() first. The generator types them in the
blueprint's stub class.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from spear._object import SpObject
from spear._type_code import TypeCode

# A function's result type and its parameters, each (name, required), in order.
Signature = tuple[TypeCode, tuple[tuple[str, bool], ...]]

_CLASSES: dict[str, type[SpObject]] = {}
_FUNCTIONS: dict[str, dict[str, Signature]] = {}  # blueprint name -> its functions


def declare(name: str, parent: type[SpObject], asset: str, doc: str,
            functions: Mapping[str, Signature] | None = None) -> type[SpObject]:
    """A blueprint class the generator found an asset for (api.py): typed as its parent's class, and
    loaded from `asset` (relative to the project root) the first time it is used as uclass=. In a checkout
    that is a file of the checkout; in an installed package the engine finds it on its asset search path
    (the package's own assets/, see core/base/asset_path.h)."""
    here = Path(__file__).resolve().parent
    # The checkout's file, or the installed package's own copy (spear/assets/...): never a file of the same
    # name that happens to be in the working directory.
    found = [p for p in (here.parents[1] / asset, here / asset) if p.is_file()]
    path = str(found[0]) if found else asset
    cls = type(name, (parent,), {"__sp_class__": name, "__sp_asset__": path, "__slots__": (),
                                 "__module__": "spear", "__doc__": doc})
    _CLASSES[name] = cls
    if functions:
        _FUNCTIONS[name] = dict(functions)
    return cls


def function_caller(obj: Any, name: str) -> Callable[..., Any] | None:
    """`obj.name` when `name` is a function of the blueprint `obj` was spawned from, called by name (its
    arguments checked and converted by the engine, as for any reflected call); None otherwise. Over RPC it
    goes through the proxy's typed call, so call_async and send_async queue it like any other call."""
    if not any(name in functions for functions in _FUNCTIONS.values()):
        return None  # no blueprint declares it: no need to ask the object for its class
    client = getattr(obj, "_sp_client", None)
    # Asked at each lookup, as the engine answers it (outside a frame it refuses, on either transport); over
    # RPC by a direct request rather than a typed call, so that call_async never queues the question.
    class_name = obj.GetClassName() if client is None else client.request(
        "call", object=obj, function="GetClassName", args={})
    signature = _FUNCTIONS.get(class_name, {}).get(name)
    if signature is None:
        return None
    result_type, params = signature
    function = f"{class_name}.{name}()"
    if client is None:
        from spear import _inprocess

        native = _inprocess.module()

        def call_in_process(*args: Any, **kwargs: Any) -> Any:
            check_call(function, args, kwargs, params)
            return native.call_function(uobject=obj, function=name, args=kwargs)

        return call_in_process

    def call_over_rpc(*args: Any, **kwargs: Any) -> Any:
        check_call(function, args, kwargs, params)
        return obj._sp_call(class_name, name, kwargs, result_type)

    return call_over_rpc


def _plural(count: int, word: str) -> str:
    return f"{count} {word}" if count == 1 else f"{count} {word}s"


def check_call(function: str, args: tuple[Any, ...], kwargs: Mapping[str, Any],
               params: tuple[tuple[str, bool], ...], method: bool = True) -> None:
    """Refuses a call that does not fit the function's keyword-only parameters with Python's TypeError, in
    the words the generated bindings use for a C++ function (core/pybind/bridge.cpp, checkCall), in the
    order CPython checks: an unexpected keyword, then positional arguments, then missing ones. A method
    counts its object as a positional argument, as Python does; a static function has none."""
    names = [param for param, _ in params]
    for key in kwargs:
        if key not in names:
            raise TypeError(f"{function} got an unexpected keyword argument '{key}'")
    given = sum(1 for param in names if param in kwargs)
    if args:
        takes = 1 if method else 0  # the object itself
        count = len(args) + takes
        message = f"{function} takes {_plural(takes, 'positional argument')} but {count}"
        if given:
            message += (f" positional argument{'' if count == 1 else 's'} "
                        f"(and {_plural(given, 'keyword-only argument')})")
        raise TypeError(message + (" was given" if count == 1 and not given else " were given"))
    missing = [f"'{param}'" for param, required in params if required and param not in kwargs]
    if missing:
        names_text = missing[0]
        for i in range(1, len(missing)):
            names_text += (", " if len(missing) > 2 else " ") + ("and " if i + 1 == len(missing) else "")
            names_text += missing[i]
        raise TypeError(f"{function} missing {_plural(len(missing), 'required keyword-only argument')}: {names_text}")


def blueprint_class(name: str, native: str) -> type[SpObject]:
    """The Python class of blueprint `name`, whose objects are made by native class `native`."""
    cls = _CLASSES.get(name)
    if cls is None:
        from spear._engine import api

        base = getattr(api, native, None)
        if not (isinstance(base, type) and issubclass(base, SpObject)):
            base = api.UObject
        doc = f"Blueprint {name}: a class defined by data, made from {native}."
        cls = type(name, (base,), {"__sp_class__": name, "__slots__": (), "__module__": "spear", "__doc__": doc})
        _CLASSES[name] = cls
    return cls
