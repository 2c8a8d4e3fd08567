"""The root of spear's Python class hierarchy for engine objects.

The generated classes in spear._engine.api derive from SpObject. Implementations (the in-process
pybind11 classes and the RPC proxies) are registered as, or derive from, those classes, so that
isinstance(x, spear.AActor) and spawn_actor(uclass=spear.AActor) mean the same with either transport.
"""

from __future__ import annotations

import abc
from typing import ClassVar


class SpObject(metaclass=abc.ABCMeta):
    """Base of every engine object class in the typed API."""

    __slots__ = ()
    __sp_class__: ClassVar[str] = "UObject"

    def is_valid(self) -> bool:
        """True while the engine object exists; False once it was destroyed."""
        raise NotImplementedError
