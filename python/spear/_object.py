"""The root of spear's Python class hierarchy for engine objects.

The generated classes in spear._engine.api derive from SpObject. Implementations (the in-process
pybind11 classes and the RPC proxies) are registered as, or derive from, those classes, so that
isinstance(x, spear.AActor) and spawn_actor(uclass=spear.AActor) mean the same with either transport.
"""

from __future__ import annotations

import abc
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, ClassVar

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from spear._spfunc import SpFuncResult


class SpObject(metaclass=abc.ABCMeta):
    """Base of every engine object class in the typed API."""

    __slots__ = ()
    __sp_class__: ClassVar[str] = "UObject"

    def is_valid(self) -> bool:
        """True while the engine object exists; False once it was destroyed."""
        raise NotImplementedError

    def call_sp_func(self, name: str, *, arrays: Mapping[str, NDArray[Any]] | None = None,
                     unreal_objs: Mapping[str, object] | None = None, info: str = "") -> SpFuncResult:
        """Calls the SpFunc `name` registered in C++ on this object (for an actor: on its USpFuncComponents).

        `arrays` travel without copying (through shared memory over RPC when large); `unreal_objs` values
        travel as JSON. The attribute form `obj.name(arrays=...)` does the same, untyped.
        """
        raise NotImplementedError

    def get_sp_func_names(self) -> list[str]:
        """The names of the SpFuncs this object answers to now, sorted."""
        raise NotImplementedError
