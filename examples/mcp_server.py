"""An MCP server (Model Context Protocol, stdio) through which an agent drives spear by writing Python.

Code an agent sends is type-checked with mypy --strict against spear's stubs *before* it runs: a misspelt
function, a wrong argument type or an unknown modality comes back as the checker's message, with the line
number in the agent's code, and the engine is never touched. Code that passes runs in one persistent
namespace (`instance`, `game`, `spear`, `np`, and whatever earlier calls defined, with the types they had:
as in a typed module, a name keeps the type it was first given), so an agent builds a scene step by step.
Tools:

- get_status: the world's frame, time and actors.
- check_code(code): the type check alone.
- execute_code(code): check, then run; returns what the code printed, or its error. A frame the code
  leaves open (a begin_frame block without its end_frame) is closed, so the next call starts clean.
- render_view(...): renders the world from a temporary camera and returns images (colour, depth, objects).

Engine calls happen inside frames, and a frame advances the simulation by one step: get_status runs one
frame, render_view two (one to render, one to remove its camera).

The code runs with this process's rights, as code typed into a Python prompt would: serve trusted agents.

    PYTHONPATH=python /usr/bin/python3 examples/mcp_server.py [--server launch] [--scene FILE]

A client registers it as a stdio server, e.g. {"command": "/usr/bin/python3", "args":
["examples/mcp_server.py"], "env": {"PYTHONPATH": "python"}}. Logs go to stderr.
"""

from __future__ import annotations

import __future__
import argparse
import base64
import contextlib
import io
import json
import os
import re
import subprocess
import sys
import tempfile
import traceback
from collections.abc import Callable
from pathlib import Path
from typing import Any, TextIO, cast

import numpy as np
from numpy.typing import NDArray
from PIL import Image  # type: ignore[import]  # Debian ships no Pillow stubs

import spear
import spear.images

PROTOCOL_VERSIONS = ("2025-06-18", "2025-03-26", "2024-11-05")  # newest first
ROOT = Path(__file__).resolve().parent.parent
JsonObject = dict[str, Any]

# What the type checker is told about the namespace code runs in; earlier code follows it.
PREAMBLE = """\
import numpy as np
import spear
instance: spear.Instance
game: spear.UWorld
"""

TOOLS: list[JsonObject] = [
    {"name": "get_status", "description": "The game world's frame count, simulated time and actors.",
     "inputSchema": {"type": "object", "properties": {}}},
    {"name": "check_code",
     "description": "Type-check Python code against spear's typed API (mypy --strict) without running it. "
                    "Names defined by earlier execute_code calls are known.",
     "inputSchema": {"type": "object", "properties": {"code": {"type": "string"}}, "required": ["code"]}},
    {"name": "execute_code",
     "description": "Type-check, then run Python code in a persistent namespace holding instance "
                    "(spear.Instance), game (spear.UWorld), spear and np. Engine calls go inside "
                    "`with instance.begin_frame():` or `with instance.end_frame():`. Returns what it printed.",
     "inputSchema": {"type": "object", "properties": {"code": {"type": "string"}}, "required": ["code"]}},
    {"name": "render_view",
     "description": "Render the game world from a temporary camera: final colour, depth and object ids.",
     "inputSchema": {"type": "object", "properties": {
         "location": {"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3,
                      "description": "camera position in metres (X forward, Y left, Z up)"},
         "rotation": {"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3,
                      "description": "Pitch, Yaw, Roll in degrees"},
         "width": {"type": "integer", "minimum": 16, "maximum": 1024},
         "height": {"type": "integer", "minimum": 16, "maximum": 1024}}}},
]


class ToolError(Exception):
    """A tool call that failed; its message goes back to the agent as an error result."""


class InvalidParams(Exception):
    """A call the tool cannot take (unknown tool, arguments against its schema): a JSON-RPC error -32602."""


class TypeCheckFailed(ToolError):
    pass


class Session:
    """The engine, the persistent namespace and the code that built it."""

    def __init__(self, instance: spear.Instance) -> None:
        self.instance = instance
        self.game = instance.get_game()
        self.namespace: dict[str, Any] = {"instance": instance, "game": self.game, "spear": spear, "np": np}
        self.history: list[str] = []  # code that ran, in order: the type checker's context for new code
        self.mypy_cache = tempfile.TemporaryDirectory(prefix="spear-mcp-mypy-")  # warm after the first check

    def check(self, code: str) -> str:
        """mypy --strict on `code` after the preamble and earlier code; errors are reported in `code`'s lines."""
        try:  # a syntax error first, by itself (mypy would stop there, counting lines from the preamble)
            compile(code, "<agent code>", "exec", flags=__future__.annotations.compiler_flag, dont_inherit=True)
        except SyntaxError as e:
            raise TypeCheckFailed(
                f"type check failed (nothing was run):\nline {e.lineno}: syntax error: {e.msg}") from None
        context = PREAMBLE + "".join(block + "\n" for block in self.history)
        offset = context.count("\n")
        search_path = os.pathsep.join([str(ROOT / "python"), os.environ.get("PYTHONPATH", "")])
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / "agent_code.py"
            path.write_text(context + code + "\n")
            # spear is found as an installed, typed package (on PYTHONPATH), so only the agent's code is
            # checked; no configuration file of the user's or the project's applies.
            result = subprocess.run(
                [sys.executable, "-m", "mypy", "--config-file", os.devnull, "--strict", "--no-error-summary",
                 "--show-error-codes", "--hide-error-context", "--no-pretty", "--cache-dir", self.mypy_cache.name,
                 str(path)],
                capture_output=True, text=True, check=False, cwd=tmp, stdin=subprocess.DEVNULL,
                env={**os.environ, "PYTHONPATH": search_path})
        messages: list[str] = []  # errors, with the notes that explain them
        for line in result.stdout.splitlines():
            m = re.match(r".*agent_code\.py:(\d+): (error|note): (.*)$", line)
            if m and int(m.group(1)) > offset:
                messages.append(f"line {int(m.group(1)) - offset}: {m.group(2)}: {m.group(3)}")
        errors = [m for m in messages if ": error: " in m]
        if errors:
            raise TypeCheckFailed("type check failed (nothing was run):\n" + "\n".join(messages))
        if result.returncode != 0:  # an error outside the agent's lines: the checker itself failed
            raise ToolError(f"the type checker failed: {result.stderr.strip() or result.stdout.strip()}")
        return "type check passed"

    def execute(self, code: str) -> str:
        self.check(code)
        # Names the code defines stay in the namespace even if it fails partway, so the checker keeps
        # seeing it too: later code may use what it defined before the failure.
        self.history.append(code)
        output = io.StringIO()
        stdin, sys.stdin = sys.stdin, io.StringIO()  # input() must not read the protocol's messages
        try:
            with contextlib.redirect_stdout(output):
                exec(compile(code, "<agent code>", "exec"), self.namespace)  # the tool's purpose
        except (Exception, SystemExit) as e:  # the code failed (or called exit()): the server goes on
            frames = [f for f in traceback.extract_tb(e.__traceback__) if f.filename == "<agent code>"]
            where = f" (line {frames[-1].lineno})" if frames else ""
            raise ToolError(f"{output.getvalue()}{type(e).__name__}{where}: {e}{self.close_open_frame()}") from None
        finally:
            sys.stdin = stdin
        return (output.getvalue() or "(no output)") + self.close_open_frame()

    def close_open_frame(self) -> str:
        if self.instance.frame_state != "between begin_frame and end_frame":
            return ""  # a with-block that raised has already ended its frame
        with self.instance.end_frame():
            pass
        return "\n(the code left a frame open: it was closed with an empty end_frame block)"

    def status(self) -> str:
        with self.instance.begin_frame():
            pass
        with self.instance.end_frame():
            actors = self.game.find_actors_by_class(uclass=spear.AActor)
            lines = [f"frame {self.game.get_frame_count()}, {self.game.get_time_seconds():.3f} s simulated, "
                     f"{len(actors)} actors:"]
            lines += [f"  {a.GetName()} ({a.GetClassName()}) at {a.GetActorLocation()}" for a in actors]
        return "\n".join(lines)

    def render(self, location: list[float], rotation: list[float], width: int, height: int) -> list[JsonObject]:
        self.close_open_frame()
        actor: spear.ACameraSensorActor | None = None
        try:
            with self.instance.begin_frame():
                actor = self.game.spawn_actor(uclass=spear.ACameraSensorActor, location=spear.FVector(*location),
                                              rotation=spear.FRotator(*rotation))
                camera = actor.CameraSensor
                camera.Width, camera.Height = width, height
                camera.Modalities = [spear.ECameraModality.FinalColor, spear.ECameraModality.Depth,
                                     spear.ECameraModality.ObjectIds]
            with self.instance.end_frame():
                pixels = camera.read_pixels()
                assert "final_color" in pixels and "depth" in pixels and "object_ids" in pixels
                ids = pixels["object_ids"]
                names = {int(i): info.Actor.GetName() for i in np.unique(ids) if i != 0
                         for info in [camera.GetObjectIdInfo(ObjectId=int(i))] if info.Actor is not None}
        finally:  # the camera goes whatever happened, so that the next render_view can make its own
            self.close_open_frame()
            if actor is not None:
                with self.instance.begin_frame():
                    self.game.destroy_actor(actor=actor)
                with self.instance.end_frame():
                    pass
        depth = pixels["depth"]
        visible = sorted(set(names.values()))
        summary = (f"{width}x{height} view from {location} (pitch, yaw, roll {rotation}); depth "
                   f"{float(depth[depth > 0].min()) if (depth > 0).any() else 0:.2f}..{float(depth.max()):.2f} m; "
                   f"visible: {', '.join(visible) or 'nothing'}")
        return [{"type": "text", "text": summary},
                png_content(pixels["final_color"][..., :3]),
                png_content(spear.images.depth_grey(depth)),
                png_content(spear.images.id_colours(ids))]


def png_content(rgb: NDArray[np.uint8]) -> JsonObject:
    buffer = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(rgb)).save(buffer, format="PNG")
    return {"type": "image", "data": base64.b64encode(buffer.getvalue()).decode(), "mimeType": "image/png"}


def call_tool(session: Session, name: str, arguments: JsonObject) -> list[JsonObject]:
    def text(value: str) -> list[JsonObject]:
        return [{"type": "text", "text": value}]

    def code() -> str:
        value = arguments.get("code")
        if not isinstance(value, str):
            raise InvalidParams(f"{name}: argument 'code' must be a string, got {type(value).__name__}")
        return value

    def vector(key: str, default: list[float]) -> list[float]:
        value: object = arguments.get(key, default)
        items = cast("list[object]", value) if isinstance(value, list) else []
        numbers = [float(v) for v in items if isinstance(v, int | float) and not isinstance(v, bool)]
        if len(numbers) != 3 or len(items) != 3:
            raise InvalidParams(f"render_view: argument '{key}' must be 3 numbers, got {value!r}")
        return numbers

    def size(key: str, default: int) -> int:
        value: object = arguments.get(key, default)
        if not (isinstance(value, int) and 16 <= value <= 1024):
            raise InvalidParams(f"render_view: argument '{key}' must be an integer in 16..1024, got {value!r}")
        return value

    tools: dict[str, Callable[[], list[JsonObject]]] = {
        "get_status": lambda: text(session.status()),
        "check_code": lambda: text(session.check(code())),
        "execute_code": lambda: text(session.execute(code())),
        "render_view": lambda: session.render(vector("location", [-4.0, 0.0, 2.0]),
                                              vector("rotation", [-15.0, 0.0, 0.0]),
                                              size("width", 320), size("height", 240)),
    }
    if name not in tools:
        raise InvalidParams(f"unknown tool '{name}' (tools: {', '.join(tools)})")
    return tools[name]()


def handle(session: Session, message: object) -> JsonObject | None:
    """The reply to one JSON-RPC message (None for a notification)."""
    request = cast(JsonObject, message) if isinstance(message, dict) else {}
    method: object = request.get("method")
    params: object = request.get("params") or {}
    if request.get("jsonrpc") != "2.0" or not isinstance(method, str) or not isinstance(params, dict):
        return error_reply(request.get("id"), -32600, "invalid JSON-RPC request")
    if "id" not in request:
        return None  # notifications (initialized, cancelled) need no answer
    request_id: object = request["id"]
    arguments = cast(JsonObject, params)
    if method == "initialize":
        asked = arguments.get("protocolVersion")
        return {"jsonrpc": "2.0", "id": request_id, "result": {
            "protocolVersion": asked if asked in PROTOCOL_VERSIONS else PROTOCOL_VERSIONS[0],
            "capabilities": {"tools": {}},
            "serverInfo": {"name": "spear", "version": "0.1.0"},
            "instructions": "Drive the spear simulator by writing typed Python: see the execute_code tool."}}
    if method == "ping":
        return {"jsonrpc": "2.0", "id": request_id, "result": {}}
    if method == "tools/list":
        return {"jsonrpc": "2.0", "id": request_id, "result": {"tools": TOOLS}}
    if method == "tools/call":
        name: object = arguments.get("name")
        tool_arguments: object = arguments.get("arguments") or {}
        if not isinstance(name, str) or not isinstance(tool_arguments, dict):
            return error_reply(request_id, -32602, "tools/call needs a tool name and an arguments object")
        try:
            content, is_error = call_tool(session, name, cast(JsonObject, tool_arguments)), False
        except InvalidParams as e:
            return error_reply(request_id, -32602, str(e))
        except ToolError as e:
            content, is_error = [{"type": "text", "text": str(e)}], True
        except spear.SpearError as e:  # an engine error outside the agent's code (render_view)
            content, is_error = [{"type": "text", "text": f"{type(e).__name__}: {e}"}], True
        except Exception as e:  # a fault of this server's: reported, and the server goes on
            log(f"tools/call {name} failed:\n{traceback.format_exc()}")
            return error_reply(request_id, -32603, f"internal error in {name}: {type(e).__name__}: {e}")
        return {"jsonrpc": "2.0", "id": request_id, "result": {"content": content, "isError": is_error}}
    return error_reply(request_id, -32601, f"method '{method}' is not supported")


def log(text: str) -> None:
    print(text, file=sys.stderr, flush=True)


def error_reply(request_id: object, code: int, text: str) -> JsonObject:
    return {"jsonrpc": "2.0", "id": request_id, "error": {"code": code, "message": text}}


def serve(session: Session, protocol: TextIO) -> None:
    for line in sys.stdin:
        if not line.strip():
            continue
        try:
            message = json.loads(line)
        except json.JSONDecodeError as e:
            reply: JsonObject | None = error_reply(None, -32700, f"parse error: {e}")
        else:
            reply = handle(session, message)
        if reply is not None:
            protocol.write(json.dumps(reply) + "\n")
            protocol.flush()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--server", default=None, help="run the engine in a spear-server ('launch' or an address)")
    parser.add_argument("--scene", default=None, help="a scene file to load (default: an empty world)")
    args = parser.parse_args()
    # The protocol gets its own copy of stdout, and file descriptor 1 becomes stderr: output written to
    # stdout by anything else (C++ code, a child process) cannot corrupt the message stream. What the
    # agent's code prints is captured per call and returned as the tool's result.
    protocol = os.fdopen(os.dup(sys.stdout.fileno()), "w", buffering=1)
    sys.stdout.flush()
    os.dup2(sys.stderr.fileno(), sys.stdout.fileno())
    instance = spear.Instance(server=args.server, scene=args.scene)
    print(f"spear MCP server ready ({'in-process' if args.server is None else args.server})", file=sys.stderr)
    try:
        serve(Session(instance), protocol)
    finally:
        instance.close()


if __name__ == "__main__":
    main()
