"""Instance: one engine and the frame loop around the user's work, as in SPEAR.

    instance = spear.Instance()                     # the engine in this process
    instance = spear.Instance(server="launch")      # the engine in its own spear-server process
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor)   # typed: AStaticMeshActor
    with instance.end_frame():
        print(actor.GetActorLocation())

Both transports give the same typed API and the same behaviour. Engine objects may only be used
inside the two blocks; outside, calls raise InvalidStateError.
"""

from __future__ import annotations

import contextlib
import os
import weakref
from collections.abc import Iterator
from types import ModuleType
from typing import Any, Literal, cast

from spear import _events, _plugins
from spear._backends import Backend, InProcessBackend, RpcBackend
from spear._engine import api
from spear.errors import InvalidArgumentError, InvalidStateError

_OPEN: weakref.WeakSet[Instance] = weakref.WeakSet()  # instances not yet closed (see only_open_instance)

FrameState = Literal["idle", "inside begin_frame", "between begin_frame and end_frame", "inside end_frame"]


class Instance:
    """A running engine.

    server: None runs the engine in this process; "launch" starts a spear-server process for this
    instance (stopped by close()); "unix:PATH" or "tcp:HOST:PORT" connects to a running server
    (token: the server's TCP token).

    In this process, the first engine sets glibc's mmap and trim thresholds to 32 and 128 MiB, as spear-server
    does for its own, so that a frame's freed memory is kept for the next one; MALLOC_MMAP_THRESHOLD_ or
    MALLOC_TRIM_THRESHOLD_ in the environment, when set, win (README, "The camera sensor").
    """

    def __init__(self, *, server: str | None = None, token: str | None = None,
                 fixed_delta_seconds: float = 1.0 / 60.0, mode: Literal["game", "editor"] = "game",
                 scene: str | os.PathLike[str] | None = None) -> None:
        # mode="editor": a persistent editor world (get_editor()) and a game world only between its play()
        # and stop(). scene: a scene file loaded into the editor world, or else into the game world.
        if mode not in ("game", "editor"):
            raise InvalidArgumentError(f"Instance(): mode {mode!r} must be 'game' or 'editor'")
        if server not in (None, "launch") and (mode != "game" or scene is not None):
            raise InvalidArgumentError("Instance(): mode= and scene= are chosen by the server you connect to; "
                                       "pass them when starting it (spear-server --mode --scene) or use server='launch'")
        scene_path = "" if scene is None else os.fspath(scene)
        self._backend: Backend
        if server is None:
            self._backend = InProcessBackend(fixed_delta_seconds, editor=mode == "editor", scene=scene_path)
        else:
            self._backend = RpcBackend(server, token, fixed_delta_seconds, editor=mode == "editor", scene=scene_path)
        self.transport = "inprocess" if server is None else "rpc"
        self._closed = False
        self._overlap_subscriptions: list[_events.OverlapSubscription] = []
        _OPEN.add(self)

    # -- worlds --------------------------------------------------------------------------------

    def get_game(self) -> api.UWorld:
        """The game world; in an editor instance, the world that the editor's play() created."""
        world = self._open("get_game").world("game")
        assert isinstance(world, api.UWorld)
        return world

    def get_editor(self) -> api.UWorld:
        """The editor world (save_scene, load_scene, play, stop); only an editor instance has one."""
        world = self._open("get_editor").world("editor")
        assert isinstance(world, api.UWorld)
        return world

    def create_world(self, *, name: str) -> api.UWorld:
        """A new world beside the game world, with its own actors, physics and render scene, ticked in the
        same frames (after the game world, in creation order): many small environments in one engine.
        name: unique among this instance's worlds."""
        if not isinstance(name, str):  # the same words on both transports
            raise InvalidArgumentError(f"create_world(): name must be a str, got {type(name).__name__}")
        world = self._open("create_world").worlds("create", name=name)
        assert isinstance(world, api.UWorld)
        return world

    def destroy_world(self, *, world: api.UWorld) -> None:
        """Destroys a world create_world() made (inside or outside a frame); its objects' handles become stale."""
        if not isinstance(world, api.UWorld):  # the same words on both transports
            raise InvalidArgumentError(f"destroy_world(): world must be a UWorld, got {type(world).__name__}")
        self._open("destroy_world").worlds("destroy", world=world)

    def get_worlds(self) -> list[api.UWorld]:
        """The worlds that tick each frame: the game world (when there is one), then the created ones."""
        worlds = self._open("get_worlds").worlds("list")
        assert all(isinstance(world, api.UWorld) for world in worlds)
        return list(worlds)

    # -- frames --------------------------------------------------------------------------------

    @contextlib.contextmanager
    def begin_frame(self) -> Iterator[None]:
        """Runs the block at the start of a frame; the engine ticks once when the block ends."""
        backend = self._open("begin_frame")
        backend.frame("begin")
        try:
            yield
        except BaseException:
            backend.frame("abort")  # the frame still ends, so the engine stays usable
            raise
        backend.frame("execute")

    @contextlib.contextmanager
    def end_frame(self) -> Iterator[None]:
        """Runs the block at the end of the frame that begin_frame started, reading its results."""
        backend = self._open("end_frame")
        backend.frame("begin_end")
        try:
            _events.deliver_all(self._overlap_subscriptions)  # the events of the frame that just ticked
            yield
        finally:
            backend.frame("end")

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
        return self._open("frame_count").frame_count()

    @property
    def frame_state(self) -> FrameState:
        """Where the engine is in the frame protocol: "idle", "inside begin_frame", "between begin_frame and
        end_frame" (a frame ran; end_frame comes next) or "inside end_frame"."""
        return cast(FrameState, self._open("frame_state").frame_state())

    # -- events --------------------------------------------------------------------------------

    def on_overlap(self, component: api.UPrimitiveComponent, *, begin: _events.OverlapCallback | None = None,
                   end: _events.OverlapCallback | None = None) -> _events.OverlapSubscription:
        """Calls begin(component, other) and end(component, other) at the start of each end_frame block, for
        the components that began or stopped overlapping `component` in the frame that ticked (UE's
        OnComponentBeginOverlap/EndOverlap). Returns the subscription; cancel() stops it, and it ends by
        itself with its component. A callback's exception propagates from the end_frame block."""
        self._open("on_overlap")
        if begin is None and end is None:
            raise InvalidArgumentError("on_overlap(): give begin=, end= or both")
        if not isinstance(component, api.UPrimitiveComponent):
            raise InvalidArgumentError(
                f"on_overlap(): component must be a UPrimitiveComponent, got {type(component).__name__}")
        from spear._wire import of_engine  # the RPC wire format, loaded only when needed

        if not of_engine(component, self._rpc_connection()):
            raise InvalidArgumentError(f"on_overlap(): {type(component).__name__} belongs to another engine "
                                       "(a different spear.Instance)")
        subscription = _events.OverlapSubscription(component, begin, end, self._overlap_subscriptions)
        self._overlap_subscriptions.append(subscription)
        return subscription

    # -- dynamic access ------------------------------------------------------------------------

    def call_function(self, *, uobject: api.UObject, function: str, args: dict[str, Any] | None = None) -> Any:
        """Calls a reflected function by name (the typed call is uobject.Function(...))."""
        return self._open("call_function").call_function(uobject, function, args or {})

    def get_property(self, *, uobject: api.UObject, path: str) -> Any:
        """Reads a reflected property by name or dotted path ("RelativeLocation.Z")."""
        return self._open("get_property").get_property(uobject, path)

    def set_property(self, *, uobject: api.UObject, path: str, value: Any) -> None:
        """Writes a reflected property by name or dotted path."""
        self._open("set_property").set_property(uobject, path, value)

    # -- plugins -------------------------------------------------------------------------------

    def load_plugin(self, plugin: str | os.PathLike[str]) -> ModuleType:
        """Loads a plugin built by spear_add_plugin(): its classes spawn by uclass= like engine classes.

        plugin: the plugin package's name (on sys.path) or the path of its directory. Returns the package,
        whose typed API is its `api` module. Loading a loaded plugin again does nothing.
        """
        backend = self._open("load_plugin")
        found = _plugins.find(plugin)
        backend.load_plugin(found)
        return found.package

    def unload_plugin(self, name: str) -> None:
        """Unloads a plugin's classes; refused while objects of them are alive (destroy them first)."""
        self._open("unload_plugin").unload_plugin(name)

    # -- the browser inspector -----------------------------------------------------------------

    def inspect(self, *, port: int = 0) -> str:
        """Serves the browser inspector of this engine on a TCP port of loopback (0: a free one) and returns the
        address to open, with its token ("http://127.0.0.1:PORT/?token=..."): an outliner, the properties of
        any object (editable), any camera's modalities and frame controls, on the engine this script drives.
        Calling it again returns the same address. Over RPC the server answers the browser by itself; in-process
        the engine answers it between frames (at each begin_frame) and during serve_inspector()."""
        if not isinstance(port, int) or isinstance(port, bool) or not 0 <= port <= 65535:
            raise InvalidArgumentError(f"inspect(): port must be an int in [0, 65535], got {port!r}")
        return self._open("inspect").inspect(port)

    def serve_inspector(self, *, seconds: float) -> None:
        """Answers the inspector's browsers for `seconds` while the script has nothing else to do (at its end,
        say, to leave the scene open for a look); in-process they are otherwise answered only between frames."""
        if isinstance(seconds, bool) or not isinstance(seconds, (int, float)) or not seconds >= 0:
            raise InvalidArgumentError(f"serve_inspector(): seconds must be a number >= 0, got {seconds!r}")
        self._open("serve_inspector").serve_inspector(float(seconds))

    # -- lifetime ------------------------------------------------------------------------------

    def close(self) -> None:
        """Destroys the engine (or disconnects, stopping a launched server); handles become stale."""
        if not self._closed:
            self._closed = True
            _OPEN.discard(self)
            self._overlap_subscriptions.clear()
            self._backend.close()

    def __enter__(self) -> Instance:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    @property
    def server_pid(self) -> int | None:
        """The process id of the spear server this instance talks to over RPC (on its machine); None
        in-process."""
        connection = self._rpc_connection()
        return None if connection is None else int(connection.server_pid)

    def _rpc_connection(self) -> Any:
        """The RPC connection of an instance over RPC; None in-process."""
        return getattr(self._open("_rpc_connection"), "connection", None)

    def _open(self, function: str) -> Backend:
        if self._closed:
            raise InvalidStateError(f"{function}(): the instance is closed")
        return self._backend


def only_open_instance(context: str) -> Instance:
    """The one open instance, for a call that names no engine object (a static function without one)."""
    open_now = list(_OPEN)
    if len(open_now) == 1:
        return open_now[0]
    found = "no spear.Instance is open" if not open_now else f"{len(open_now)} spear.Instances are open"
    raise InvalidStateError(f"{context}: {found}, so the engine to run it is not known; pass an engine object "
                            "among its arguments (WorldContextObject=world)")
