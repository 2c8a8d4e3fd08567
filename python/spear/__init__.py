"""spear: a simulator for embodied-AI and synthetic-data research, typed end to end.

Every engine class, struct and enum is importable from here with its full typed API (generated from
the engine's reflected C++ headers): spear.AActor, spear.FVector, spear.EComponentMobility, ...
"""

from spear._engine.api import *  # noqa: F403
from spear._engine import api as _api
from spear.errors import InvalidArgumentError, InvalidStateError, NotFoundError, SpearError, StaleObjectError
from spear._spfunc import SpFuncResult
from spear.instance import Instance

__all__ = [
    "Instance",
    "SpFuncResult",
    "SpearError",
    "InvalidArgumentError",
    "InvalidStateError",
    "NotFoundError",
    "StaleObjectError",
]
__all__ += _api.__all__  # the form type checkers follow (pyright does not expand *_api.__all__)
