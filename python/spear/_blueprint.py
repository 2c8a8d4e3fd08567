"""Python classes for blueprints: engine classes defined by data at run time (core/world/blueprint.h).

A blueprint has no generated Python class, so UWorld.load_class() returns one made here: a subclass of its
native class's API class (so it types and checks as, e.g., type[AActor]) whose __sp_class__ is the
blueprint's name, which makes it work as uclass= on both transports. One class per blueprint name.

The functions a blueprint declares (core/world/blueprint_functions.h) are called by attribute on its objects,
`crate.Launch(Speed=3.0)`, on either transport: the objects are of the native class, so the attribute
fallback (spear._spfunc.sp_func_getattr) asks function_caller() first. The generator types them in the
blueprint's stub class.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from spear._object import SpObject

if TYPE_CHECKING:
    from spear._rpc_client import RpcConnection

_CLASSES: dict[str, type[SpObject]] = {}
_FUNCTIONS: dict[str, frozenset[str]] = {}  # blueprint name -> the functions it declares


def declare(name: str, parent: type[SpObject], asset: str, doc: str, functions: Sequence[str] = ()) -> type[SpObject]:
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
        _FUNCTIONS[name] = frozenset(functions)
    return cls


def function_caller(obj: Any, name: str) -> Callable[..., Any] | None:
    """`obj.name` when `name` is a function of the blueprint `obj` was spawned from, called by name through
    the engine's dynamic call path (its arguments checked and converted there); None otherwise."""
    if not any(name in functions for functions in _FUNCTIONS.values()):
        return None  # no blueprint declares it: no need to ask the object for its class
    if name not in _FUNCTIONS.get(obj.GetClassName(), ()):
        return None
    client = getattr(obj, "_sp_client", None)
    if client is None:  # in-process
        from spear import _inprocess

        native = _inprocess.module()
        return lambda **kwargs: native.call_function(uobject=obj, function=name, args=kwargs)

    connection: RpcConnection = client

    def call(**kwargs: Any) -> Any:
        from spear._rpc_types import convert
        from spear._type_code import TypeCode

        typed = connection.request("call_typed", object=obj, function=name, args=kwargs)
        return convert(typed["value"], TypeCode.from_wire(typed["type"]), connection)

    return call


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
