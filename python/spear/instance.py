"""Instance: one engine and the frame loop around the user's work, as in SPEAR.

    instance = spear.Instance()
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor)   # typed: AStaticMeshActor
    with instance.end_frame():
        print(actor.GetActorLocation())

Engine objects may only be used inside the two blocks; outside, calls raise InvalidStateError.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from typing import Any

from spear import _inprocess
from spear._engine import api
from spear.errors import InvalidStateError


class Instance:
    """A running engine, in this process."""

    def __init__(self, *, fixed_delta_seconds: float = 1.0 / 60.0) -> None:
        self._engine = _inprocess.new_engine(fixed_delta_seconds)
        self._closed = False

    # -- worlds --------------------------------------------------------------------------------

    def get_game(self) -> api.UWorld:
        """The game world."""
        world = self._require_open("get_game").get_game_world()
        assert isinstance(world, api.UWorld)
        return world

    def get_editor(self) -> api.UWorld:
        """The editor world; only an editor instance has one."""
        self._require_open("get_editor")
        raise InvalidStateError(
            "get_editor(): this instance runs standalone and has no editor world; start it in editor mode"
        )

    # -- frames --------------------------------------------------------------------------------

    @contextlib.contextmanager
    def begin_frame(self) -> Iterator[None]:
        """Runs the block at the start of a frame; the engine ticks once when the block ends."""
        engine = self._require_open("begin_frame")
        engine.begin_frame()
        try:
            yield
        except BaseException:
            engine.abort_frame()  # the frame still ends, so the engine stays usable
            raise
        engine.execute_frame()

    @contextlib.contextmanager
    def end_frame(self) -> Iterator[None]:
        """Runs the block at the end of the frame that begin_frame started, reading its results."""
        engine = self._require_open("end_frame")
        engine.begin_end_frame()
        try:
            yield
        finally:
            engine.end_frame()

    def step(self, *, num_frames: int = 1) -> None:
        """Runs num_frames frames with no user work."""
        for _ in range(num_frames):
            with self.begin_frame():
                pass
            with self.end_frame():
                pass

    @property
    def frame_count(self) -> int:
        """Frames run so far."""
        return int(self._require_open("frame_count").frame_count)

    # -- dynamic access ------------------------------------------------------------------------

    def call_function(self, *, uobject: api.UObject, function: str, args: dict[str, Any] | None = None) -> Any:
        """Calls a reflected function by name (the typed call is uobject.Function(...))."""
        self._require_open("call_function")
        return _inprocess.module().call_function(uobject=uobject, function=function, args=args or {})

    def get_property(self, *, uobject: api.UObject, path: str) -> Any:
        """Reads a reflected property by name or dotted path ("RelativeLocation.Z")."""
        self._require_open("get_property")
        return _inprocess.module().get_property(uobject=uobject, path=path)

    def set_property(self, *, uobject: api.UObject, path: str, value: Any) -> None:
        """Writes a reflected property by name or dotted path."""
        self._require_open("set_property")
        _inprocess.module().set_property(uobject=uobject, path=path, value=value)

    # -- lifetime ------------------------------------------------------------------------------

    def close(self) -> None:
        """Destroys the engine and every object in it; their handles become stale."""
        if not self._closed:
            self._closed = True
            del self._engine

    def __enter__(self) -> Instance:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _require_open(self, function: str) -> Any:
        if self._closed:
            raise InvalidStateError(f"{function}(): the instance is closed")
        return self._engine
