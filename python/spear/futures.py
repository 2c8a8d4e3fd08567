"""Futures for asynchronous calls: obj.call_async.Function(...) returns a Future[T].

Over RPC, asynchronous calls are queued and travel together in one message when the frame block ends
(or when a result is needed first), so a frame's worth of calls costs one round trip. In-process they
run at once and the future is already resolved. Either way, call get() in the end_frame block.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from typing import Any, Generic, TypeVar

T = TypeVar("T")

_PENDING = object()


class Future(Generic[T]):
    """The result of an asynchronous call."""

    __slots__ = ("_value", "_error", "_flush")

    def __init__(self, flush: Callable[[], None] | None = None) -> None:
        self._value: Any = _PENDING
        self._error: BaseException | None = None
        self._flush = flush

    @staticmethod
    def resolved(value: T) -> Future[T]:
        future: Future[T] = Future()
        future._value = value
        return future

    @staticmethod
    def failed(error: BaseException) -> Future[Any]:
        future: Future[Any] = Future()
        future._error = error
        future._value = None
        return future

    def done(self) -> bool:
        """True once the result (or error) has arrived."""
        return self._value is not _PENDING

    def get(self) -> T:
        """The result; raises the call's error. Sends queued calls first if they have not gone yet."""
        if self._value is _PENDING and self._flush is not None:
            self._flush()
        if self._error is not None:
            raise self._error
        if self._value is _PENDING:
            raise RuntimeError("Future.get(): the call was never sent")
        return self._value  # type: ignore[no-any-return]

    def _set(self, value: Any = None, error: BaseException | None = None) -> None:
        self._value, self._error = value, error


def warn_send_failed(error: BaseException, stacklevel: int) -> None:
    """Reports the error of a send_async call, which nobody waits for: a warning on both transports."""
    warnings.warn(f"send_async call failed: {error}", RuntimeWarning, stacklevel=stacklevel + 1)


class ImmediateCaller:
    """obj.call_async in-process: runs the call now and returns a resolved future."""

    __slots__ = ("_target", "_discard")

    def __init__(self, target: Any, discard: bool = False) -> None:
        self._target = target
        self._discard = discard

    # __getattribute__ rather than __getattr__: every name is a function of the object, and the failed normal
    # lookup that precedes __getattr__ costs a quarter of a queued call.
    def __getattribute__(self, name: str) -> Any:
        if name.startswith("__"):
            return object.__getattribute__(self, name)
        method = getattr(_target(self), name)
        if _discard(self):
            def send(**kwargs: Any) -> None:
                try:
                    method(**kwargs)
                except Exception as error:  # noqa: BLE001 - nobody waits for it: a warning, as over RPC
                    warn_send_failed(error, stacklevel=2)

            return send

        def call(**kwargs: Any) -> Any:
            try:
                return Future.resolved(method(**kwargs))
            except Exception as error:  # noqa: BLE001 - delivered through the future, as over RPC
                return Future.failed(error)

        return call


# The slots' descriptors, read without going through __getattribute__.
_target: Callable[[ImmediateCaller], Any] = vars(ImmediateCaller)["_target"].__get__
_discard: Callable[[ImmediateCaller], bool] = vars(ImmediateCaller)["_discard"].__get__
