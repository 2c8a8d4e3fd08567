"""Overlap events delivered to Python callbacks, UE's OnComponentBeginOverlap/OnComponentEndOverlap:

    def entered(trigger: spear.UPrimitiveComponent, other: spear.UPrimitiveComponent) -> None: ...
    subscription = instance.on_overlap(trigger.CollisionComponent, begin=entered, end=left)
    ...
    subscription.cancel()

At the start of every end_frame block, before the block's own code, each subscription's callbacks run for the
components that began and stopped overlapping its component in the frame that just ticked (begins first, in the
order the engine reports them; subscriptions in the order they were made). It is the polled API
(GetBeginOverlaps/GetEndOverlaps) read for you, so both transports deliver the same events. A subscription
whose component is destroyed ends by itself; an exception in a callback propagates from the end_frame block
once every other event of the frame has been delivered (the frame still ends).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from spear.errors import StaleObjectError
from spear.futures import Future

if TYPE_CHECKING:
    from spear._engine import api

OverlapCallback = Callable[["api.UPrimitiveComponent", "api.UPrimitiveComponent"], object]


class OverlapSubscription:
    """Begin and end overlap callbacks of one component; cancel() stops them."""

    def __init__(self, component: api.UPrimitiveComponent, begin: OverlapCallback | None,
                 end: OverlapCallback | None, subscriptions: list[OverlapSubscription]) -> None:
        self.component = component
        self.begin = begin
        self.end = end
        self._subscriptions = subscriptions

    @property
    def active(self) -> bool:
        """False once cancelled, or once its component was destroyed."""
        return any(s is self for s in self._subscriptions)

    def cancel(self) -> None:
        """Stops the callbacks (doing nothing when already stopped)."""
        self._subscriptions[:] = [s for s in self._subscriptions if s is not self]

    def poll(self) -> tuple[Future[list[api.UPrimitiveComponent]] | None, Future[list[api.UPrimitiveComponent]] | None]:
        """Queues the reads of the last tick's events (over RPC, all subscriptions' reads travel together)."""
        queued = self.component.call_async
        return (queued.GetBeginOverlaps() if self.begin is not None else None,
                queued.GetEndOverlaps() if self.end is not None else None)

    def deliver(self, begins: Future[list[api.UPrimitiveComponent]] | None,
                ends: Future[list[api.UPrimitiveComponent]] | None) -> list[BaseException]:
        """Calls the callbacks for the events poll() read (see the module notes); returns what they raised,
        having called the rest (a callback that cancels its subscription stops the calls that follow)."""
        try:
            events = ((self.begin, begins.get() if begins is not None else []),
                      (self.end, ends.get() if ends is not None else []))
        except StaleObjectError:
            self.cancel()  # the component is gone, and so are its events
            return []
        failures: list[BaseException] = []
        for callback, others in events:
            for other in others:
                if callback is None or not self.active:
                    break
                try:
                    callback(self.component, other)
                except Exception as error:  # the other events are delivered first
                    failures.append(error)
        return failures


def deliver_all(subscriptions: list[OverlapSubscription]) -> None:
    """Delivers every subscription's events, in subscription order (a callback may cancel or add ones), then
    raises the first exception a callback raised: the polled events are read once, so none may be dropped."""
    polled = []
    for subscription in list(subscriptions):
        try:
            polled.append((subscription, *subscription.poll()))
        except StaleObjectError:  # in-process, a destroyed component fails at once
            subscription.cancel()
    failures: list[BaseException] = []
    for subscription, begins, ends in polled:
        if subscription.active:
            failures += subscription.deliver(begins, ends)
    if failures:
        raise failures[0]
