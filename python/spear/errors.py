"""Exceptions raised by spear, in-process and over RPC alike.

Each engine error type maps to one class here; messages name the function and the bad value, e.g.
"UWorld.spawn_actor(): class 'AFoo' is not registered".
"""

from __future__ import annotations


class SpearError(Exception):
    """Base class of every error the engine reports."""


class InvalidArgumentError(SpearError, TypeError):
    """A value of the wrong type, out of range, or an unexpected or missing argument."""


class NotFoundError(SpearError, LookupError):
    """An unknown class, property, function, asset or name."""


class StaleObjectError(SpearError, ReferenceError):
    """A handle whose engine object was destroyed."""


class InvalidStateError(SpearError, RuntimeError):
    """A call not allowed in the engine's current state (outside a frame, moving a static component, ...)."""


class ConnectionLostError(SpearError, ConnectionError):
    """The spear server of an instance over RPC closed the connection or went away (the process died, the
    machine became unreachable)."""
