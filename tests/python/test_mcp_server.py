"""examples/mcp_server.py as an MCP client sees it: JSON-RPC over the server's stdin and stdout, the
engine in-process or in a spear-server. Code with a type error is refused before it runs; code that
passes runs in a persistent namespace; failures come back as error results and the server keeps going."""

from __future__ import annotations

import base64
import json
import os
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[2]


class Client:
    def __init__(self, process: subprocess.Popen[str]) -> None:
        self.process = process
        self.next_id = 0

    def send(self, message: dict[str, Any] | str) -> None:
        assert self.process.stdin is not None
        self.process.stdin.write((message if isinstance(message, str) else json.dumps(message)) + "\n")
        self.process.stdin.flush()

    def receive(self) -> dict[str, Any]:
        assert self.process.stdout is not None
        line = self.process.stdout.readline()
        if not line:
            stderr = self.process.stderr.read() if self.process.stderr else ""
            pytest.fail(f"the server closed its output; stderr:\n{stderr}")
        reply: dict[str, Any] = json.loads(line)
        return reply

    def request(self, method: str, params: dict[str, Any] | None = None) -> dict[str, Any]:
        self.next_id += 1
        self.send({"jsonrpc": "2.0", "id": self.next_id, "method": method, **({"params": params} if params else {})})
        reply = self.receive()
        assert reply["id"] == self.next_id
        return reply

    def tool(self, name: str, **arguments: Any) -> dict[str, Any]:
        reply = self.request("tools/call", {"name": name, "arguments": arguments})
        result: dict[str, Any] = reply["result"]
        return result


def text(result: dict[str, Any]) -> str:
    return "\n".join(c["text"] for c in result["content"] if c["type"] == "text")


@pytest.fixture(params=["inprocess", "rpc"])
def client(request: pytest.FixtureRequest) -> Iterator[Client]:
    flags = ["--server", "launch"] if request.param == "rpc" else []
    process = subprocess.Popen(
        [sys.executable, str(ROOT / "examples/mcp_server.py"), *flags], stdin=subprocess.PIPE,
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT,
        env={**os.environ, "PYTHONPATH": str(ROOT / "python")})
    client = Client(process)
    reply = client.request("initialize", {"protocolVersion": "2025-06-18", "capabilities": {},
                                          "clientInfo": {"name": "test", "version": "0"}})
    assert reply["result"]["protocolVersion"] == "2025-06-18"
    assert reply["result"]["serverInfo"]["name"] == "spear" and "tools" in reply["result"]["capabilities"]
    client.send({"jsonrpc": "2.0", "method": "notifications/initialized"})  # no reply
    yield client
    assert process.stdin is not None
    process.stdin.close()
    assert process.wait(timeout=60) == 0
    if process.stdout:
        process.stdout.close()
    if process.stderr:
        process.stderr.close()


def test_tools_are_listed_with_schemas(client: Client) -> None:
    tools = {t["name"]: t for t in client.request("tools/list")["result"]["tools"]}
    assert sorted(tools) == ["check_code", "execute_code", "get_status", "render_view"]
    assert tools["execute_code"]["inputSchema"]["required"] == ["code"]


def test_code_with_a_type_error_is_refused_before_it_runs(client: Client) -> None:
    code = ("with instance.begin_frame():\n"
            "    cube = game.spawn_actor(uclass=spear.AStaticMeshActor, name='Cube')\n"
            "    cube.SetActorLocation(NewLocation='up')\n")
    result = client.tool("execute_code", code=code)
    assert result["isError"]
    assert ('line 3: error: Argument "NewLocation" to "SetActorLocation" of "AActor" has incompatible type "str"; '
            'expected "FVector"  [arg-type]') in text(result)
    assert "nothing was run" in text(result)
    assert "Cube" not in text(client.tool("get_status"))  # the engine was never touched


def test_code_runs_in_a_persistent_typed_namespace(client: Client) -> None:
    first = client.tool("execute_code", code=(
        "with instance.begin_frame():\n"
        "    cube = game.spawn_actor(uclass=spear.AStaticMeshActor, name='Cube', location=spear.FVector(Z=1.0))\n"
        "    cube.StaticMeshComponent.SetStaticMesh(NewMesh='/Engine/BasicShapes/Cube')\n"
        "with instance.end_frame():\n"
        "    print('spawned', cube.GetName())\n"))
    assert not first["isError"], text(first)
    assert text(first) == "spawned Cube\n"
    # `cube` is known to the type checker as an AStaticMeshActor from the earlier call.
    refused = client.tool("check_code", code="\ncube.StaticMeshComponent.Mobility = 3\n")
    assert refused["isError"]
    assert ('line 2: error: Incompatible types in assignment (expression has type "int", variable has type '
            '"EComponentMobility")  [assignment]') in text(refused)
    second = client.tool("execute_code", code=(
        "with instance.begin_frame():\n"
        "    print(cube.GetActorLocation().Z)\n"))  # no end_frame: the server closes the frame
    assert not second["isError"], text(second)
    assert text(second).startswith("1.0\n") and "left a frame open" in text(second)
    assert "Cube (AStaticMeshActor)" in text(client.tool("get_status"))


def test_output_to_the_stdout_file_descriptor_cannot_corrupt_the_protocol(client: Client) -> None:
    # os.write(1, ...) bypasses Python's sys.stdout, as C++ code's printf would.
    result = client.tool("execute_code", code="import os\nos.write(1, b'raw bytes\\n')\nprint('printed')\n")
    assert not result["isError"], text(result)
    assert text(result) == "printed\n"
    assert client.request("ping")["result"] == {}


def test_syntax_errors_name_the_agents_line(client: Client) -> None:
    result = client.tool("execute_code", code="x = 1\nprint(x +)\n")
    assert result["isError"] and text(result).startswith("type check failed (nothing was run):\nline 2: syntax error:")


def test_code_cannot_stop_the_server_or_read_its_messages(client: Client) -> None:
    stopped = client.tool("execute_code", code="import sys\nsys.exit(3)\n")
    assert stopped["isError"] and text(stopped) == "SystemExit (line 2): 3"
    reading = client.tool("execute_code", code="answer = input()\n")
    assert reading["isError"] and text(reading).startswith("EOFError (line 1)")
    assert client.request("ping")["result"] == {}


def test_names_from_code_that_failed_partway_stay_known(client: Client) -> None:
    failed = client.tool("execute_code", code="count = 5\nraise ValueError('late')\n")
    assert failed["isError"] and text(failed) == "ValueError (line 2): late"
    later = client.tool("execute_code", code="print(count + 1)\n")
    assert not later["isError"], text(later)
    assert text(later) == "6\n"


def test_engine_errors_are_reported_and_the_session_goes_on(client: Client) -> None:
    failed = client.tool("execute_code", code=(
        "with instance.begin_frame():\n"
        "    game.spawn_actor(uclass='ANoSuchClass')\n"))
    assert failed["isError"]
    assert text(failed) == ("NotFoundError (line 2): UWorld.spawn_actor(): argument 'uclass': "
                            "class 'ANoSuchClass' is not registered")
    ok = client.tool("execute_code", code="instance.step()\n")
    assert not ok["isError"], text(ok)


def test_render_view_returns_png_images(client: Client) -> None:
    setup = client.tool("execute_code", code=(
        "with instance.begin_frame():\n"
        "    box = game.spawn_actor(uclass=spear.AStaticMeshActor, name='Box', location=spear.FVector(Z=0.5))\n"
        "    box.StaticMeshComponent.SetStaticMesh(NewMesh='/Engine/BasicShapes/Cube')\n"
        "with instance.end_frame():\n"
        "    pass\n"))
    assert not setup["isError"], text(setup)
    result = client.tool("render_view", location=[-4.0, 0.0, 1.5], rotation=[-10.0, 0.0, 0.0], width=64, height=48)
    assert not result["isError"], text(result)
    images = [c for c in result["content"] if c["type"] == "image"]
    assert len(images) == 3 and all(c["mimeType"] == "image/png" for c in images)
    assert all(base64.b64decode(c["data"]).startswith(b"\x89PNG\r\n\x1a\n") for c in images)
    assert "64x48" in text(result) and "visible: Box" in text(result)
    assert "ACameraSensorActor" not in text(client.tool("get_status"))  # the temporary camera is gone


def test_bad_messages_get_protocol_errors(client: Client) -> None:
    client.send("{not json")
    assert client.receive()["error"]["code"] == -32700
    client.send({"jsonrpc": "2.0", "id": 99, "params": {}})
    assert client.receive()["error"]["code"] == -32600
    assert client.request("no/such/method")["error"]["code"] == -32601
    unknown = client.request("tools/call", {"name": "no_such_tool", "arguments": {}})["error"]
    assert unknown["code"] == -32602 and unknown["message"].startswith("unknown tool 'no_such_tool'")
    wrong = client.request("tools/call", {"name": "render_view", "arguments": {"width": 5}})["error"]
    assert wrong == {"code": -32602, "message": "render_view: argument 'width' must be an integer in 16..1024, got 5"}
    assert client.request("ping")["result"] == {}
