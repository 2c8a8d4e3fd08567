"""Python classes for blueprints: engine classes defined by data at run time (core/world/blueprint.h).

A blueprint has no generated Python class, so UWorld.load_class() returns one made here: a subclass of its
native class's API class (so it types and checks as, e.g., type[AActor]) whose __sp_class__ is the
blueprint's name, which makes it work as uclass= on both transports. One class per blueprint name.
"""

from __future__ import annotations

from pathlib import Path

from spear._object import SpObject

_CLASSES: dict[str, type[SpObject]] = {}


def declare(name: str, parent: type[SpObject], asset: str, doc: str) -> type[SpObject]:
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
    return cls


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
