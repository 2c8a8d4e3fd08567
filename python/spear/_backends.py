"""The two transports behind spear.Instance. Both run the same engine code; they differ only in where
it runs. Instance talks to either through this small interface."""

from __future__ import annotations

import importlib
from typing import Any, Protocol

from spear import errors
from spear._plugins import PluginPackage
from spear._protocol import FrameAction, WorldKind, WorldsAction
from spear._type_code import TypeCode

_WORLD = TypeCode("object", "UWorld")



class Backend(Protocol):
    def world(self, kind: WorldKind) -> Any: ...

    # action: "create" (name), "destroy" (world) or "list".
    def worlds(self, action: WorldsAction, *, name: str = "", world: Any = None) -> Any: ...

    def frame(self, action: FrameAction) -> None: ...

    def frame_count(self) -> int: ...

    def frame_state(self) -> str: ...

    def call_function(self, uobject: Any, function: str, args: dict[str, Any]) -> Any: ...

    def get_property(self, uobject: Any, path: str) -> Any: ...

    def set_property(self, uobject: Any, path: str, value: Any) -> None: ...

    def load_plugin(self, plugin: PluginPackage) -> list[str]: ...

    def unload_plugin(self, name: str) -> None: ...

    # The browser inspector: started on a port (0: a free one) if it does not run; returns its address with the
    # token. serve_inspector() answers it while the script waits (in-process it is otherwise answered between
    # frames).
    def inspect(self, port: int) -> str: ...

    def serve_inspector(self, seconds: float) -> None: ...

    def close(self) -> None: ...


class InProcessBackend:
    """The engine in this process, through the pybind11 module."""

    def __init__(self, fixed_delta_seconds: float, *, editor: bool = False, scene: str = "") -> None:
        from spear import _inprocess
        from spear._segments import remove_orphaned_segments

        # No shared memory in-process, but a program that ran over RPC before may have been killed along with
        # its server: every client start removes what such processes left under /dev/shm.
        remove_orphaned_segments()
        self._module = _inprocess.module()
        self._engine: Any = self._module.Engine(fixed_delta_seconds=fixed_delta_seconds, editor=editor, scene=scene)
        self._inspector: Any = None

    def world(self, kind: WorldKind) -> Any:
        if kind == "editor":
            world = self._engine.get_editor_world()
            if world is None:
                raise errors.InvalidStateError(
                    "get_editor(): this instance runs standalone and has no editor world; "
                    "start it with spear.Instance(mode='editor')")
            return world
        return self._engine.get_game_world()

    def worlds(self, action: WorldsAction, *, name: str = "", world: Any = None) -> Any:
        if action == "create":
            return self._engine.create_world(name=name)
        if action == "destroy":
            return self._engine.destroy_world(world=world)
        return self._engine.get_worlds()

    def frame(self, action: FrameAction) -> None:
        if action == "begin" and self._inspector is not None:
            # Between frames, on the engine's own thread: what the inspector's browsers asked for since the last
            # frame (a poll() when they asked nothing).
            self._inspector.pump()
        getattr(self._engine, {"begin": "begin_frame", "execute": "execute_frame", "begin_end": "begin_end_frame",
                               "end": "end_frame", "abort": "abort_frame"}[action])()

    def frame_count(self) -> int:
        return int(self._engine.frame_count)

    def frame_state(self) -> str:
        return str(self._engine.frame_state)

    def call_function(self, uobject: Any, function: str, args: dict[str, Any]) -> Any:
        return self._module.call_function(uobject=uobject, function=function, args=args)

    def get_property(self, uobject: Any, path: str) -> Any:
        return self._module.get_property(uobject=uobject, path=path)

    def set_property(self, uobject: Any, path: str, value: Any) -> None:
        self._module.set_property(uobject=uobject, path=path, value=value)

    def load_plugin(self, plugin: PluginPackage) -> list[str]:
        from spear import _inprocess

        # The bindings first: importing them maps the plugin's library, which the loader then registers.
        native = importlib.import_module(f"{plugin.name}._{plugin.name}")
        _inprocess.register_classes(importlib.import_module(f"{plugin.name}.api"), native)
        _, classes = self._module._load_plugin(str(plugin.library), plugin.api_hash)
        return list(classes)

    def unload_plugin(self, name: str) -> None:
        # The classes leave the registry; the bindings' code stays mapped (CPython cannot unload a module).
        self._module._unload_plugin(name)

    def inspect(self, port: int) -> str:
        from pathlib import Path

        from spear._engine import API_HASH

        if self._inspector is None:
            root = Path(__file__).resolve().parent / "inspector"
            self._inspector = self._module.InspectorServer(self._engine, port=port, root=str(root), api_hash=API_HASH)
            return str(self._inspector.url)
        return str(self._inspector.open(port))

    def serve_inspector(self, seconds: float) -> None:
        import time

        deadline = time.monotonic() + seconds
        if self._inspector is None:  # nobody to answer: waits, as over RPC
            time.sleep(seconds)
            return
        while (left := deadline - time.monotonic()) > 0:
            # Waiting releases the GIL (other threads run); answering holds it, as any engine call does.
            if self._inspector.wait_ready(int(min(left, 0.1) * 1000)):
                self._inspector.pump()

    def close(self) -> None:
        self._inspector = None  # before the engine it serves
        del self._engine


class RpcBackend:
    """An engine in a spear-server process: launched for this instance, or already running."""

    def __init__(self, server: str, token: str | None, fixed_delta_seconds: float, *, editor: bool = False,
                 scene: str = "") -> None:
        from spear._engine import rpc  # noqa: F401  (registers the proxy classes)
        from spear._rpc_client import LaunchedServer, RpcConnection

        self._launched = (
            LaunchedServer(fixed_delta_seconds=fixed_delta_seconds, mode="editor" if editor else "game", scene=scene)
            if server == "launch" else None
        )
        address = self._launched.address if self._launched else server
        try:
            self.connection = RpcConnection(address, token=token)
        except BaseException:
            if self._launched:
                self._launched.close()
            raise

    def world(self, kind: WorldKind) -> Any:
        from spear._rpc_types import convert

        return convert(self.connection.request("world", kind=kind), _WORLD, self.connection)

    def worlds(self, action: WorldsAction, *, name: str = "", world: Any = None) -> Any:
        from spear._rpc_types import convert

        if action == "create":
            return convert(self.connection.request("worlds", action="create", name=name), _WORLD, self.connection)
        if action == "destroy":
            return self.connection.request("worlds", action="destroy", object=world, context="destroy_world()")
        handles = self.connection.request("worlds", action="list")
        return [convert(handle, _WORLD, self.connection) for handle in handles]

    def frame(self, action: FrameAction) -> None:
        # A frame's begin travels with the first message of its block, and the calls queued in a block travel
        # with the operation that closes it: a frame whose blocks only queue calls (send_async) and read
        # results costs three messages (begin + calls + execute, begin_end + the first read, end), and the
        # client waits for two: the end's reply is read before the next request (its error raised there).
        self.connection.queue_frame(action)
        if action == "end":
            self.connection.post()
        elif action not in ("begin", "begin_end"):
            self.connection.flush()

    def frame_count(self) -> int:
        return int(self.connection.request("frame", action="state")["frame_count"])

    def frame_state(self) -> str:
        return str(self.connection.request("frame", action="state")["state"])

    def call_function(self, uobject: Any, function: str, args: dict[str, Any]) -> Any:
        from spear._rpc_types import convert

        typed = self.connection.request("call_typed", object=uobject, function=function, args=args)
        if typed["out_types"]:
            types = {k: TypeCode.from_wire(t) for k, t in typed["out_types"].items()}
            return {k: convert(v, types.get(k), self.connection) for k, v in typed["value"].items()}
        return convert(typed["value"], TypeCode.from_wire(typed["type"]), self.connection)

    def get_property(self, uobject: Any, path: str) -> Any:
        from spear._rpc_types import convert

        # The server walks the path (core/reflect/property_path.h), as the in-process engine does.
        typed = self.connection.request("get_typed", object=uobject, property=path)
        return convert(typed["value"], TypeCode.from_wire(typed["type"]), self.connection)

    def set_property(self, uobject: Any, path: str, value: Any) -> None:
        self.connection.request("set", object=uobject, property=path, value=value)

    def load_plugin(self, plugin: PluginPackage) -> list[str]:
        from spear._rpc_types import add_api_module

        importlib.import_module(f"{plugin.name}.rpc")  # registers the plugin's proxy classes
        add_api_module(importlib.import_module(f"{plugin.name}.api"))
        reply = self.connection.request("load_plugin", path=str(plugin.library.resolve()), api_hash=plugin.api_hash)
        return list(reply["classes"])

    def unload_plugin(self, name: str) -> None:
        self.connection.request("unload_plugin", name=name)

    def inspect(self, port: int) -> str:
        return str(self.connection.request("inspect", port=port))

    def serve_inspector(self, seconds: float) -> None:
        import time

        time.sleep(seconds)  # the server answers its browsers by itself

    def close(self) -> None:
        self.connection.close()
        if self._launched:
            self._launched.close()
