"""The inspector's server side, on both transports (instance.inspect() in-process and on a launched spear-server):
the page and its token, the WebSocket and its hello, requests between frames, and bad input. The browser itself is
tests/python/test_inspector_browser.py."""

from __future__ import annotations

import struct
from collections.abc import Callable, Iterator
from typing import Any

import msgpack
import pytest

import spear
from spear.errors import InvalidArgumentError, InvalidStateError

from inspector_client import WebSocketClient, frame, http_get, served, split_url

@pytest.fixture
def inspected(make_instance: Callable[..., spear.Instance]) -> Iterator[tuple[spear.Instance, str]]:
    instance = make_instance()
    yield instance, instance.inspect(port=0)


def test_the_page_needs_the_token(inspected: tuple[spear.Instance, str]) -> None:
    instance, url = inspected
    base = url.split("?")[0]
    status, body = served(instance, lambda: http_get(base))
    assert status == 403
    assert body.decode() == ("spear-server: inspector: wrong or missing token; open the address spear-server "
                             "printed (http://.../?token=...)")
    assert served(instance, lambda: http_get(base + "?token=guess"))[0] == 403
    status, body = served(instance, lambda: http_get(url))
    assert status == 200 and b"<title>spear inspector</title>" in body
    # The scripts are the same for everyone; files outside the page's folder are not served.
    status, body = served(instance, lambda: http_get(base + "inspector/src/main.js"))
    assert status == 200 and b"Connection.open" in body
    assert served(instance, lambda: http_get(base + "../../../etc/passwd"))[0] == 404
    assert served(instance, lambda: http_get(base + "inspector/%2e%2e/%2e%2e/index.html"))[0] == 404
    assert served(instance, lambda: http_get(url, method="POST"))[0] == 405


def test_a_websocket_says_hello_with_the_token(inspected: tuple[spear.Instance, str]) -> None:
    instance, url = inspected

    def wrong() -> tuple[dict[str, Any], bool]:
        client = WebSocketClient(url)
        reply = client.hello(token="guess")
        return reply, client.closed_by_server()

    reply, closed = served(instance, wrong)
    assert reply["error"] == ["InvalidArgumentError", "hello(): wrong or missing token"] and closed

    def right() -> dict[str, Any]:
        client = WebSocketClient(url)
        hello = client.hello()
        assert "ok" in hello and "shm_probe" not in hello["ok"]  # a browser maps no shared memory
        return client.request("echo", value=[1, "two", 3.5])

    assert served(instance, right)["ok"] == [1, "two", 3.5]


def test_another_sites_page_cannot_open_a_websocket(inspected: tuple[spear.Instance, str]) -> None:
    instance, url = inspected
    host, port, _ = split_url(url)
    assert served(instance, lambda: WebSocketClient(url, origin="http://evil.example").status) == 403
    assert served(instance, lambda: WebSocketClient(url, origin=f"http://{host}:{port}").status) == 101


def test_between_frames_requests_look_without_ticking(inspected: tuple[spear.Instance, str]) -> None:
    instance, url = inspected
    game = instance.get_game()
    with instance.begin_frame():
        game.spawn_actor(uclass=spear.AStaticMeshActor, name="Looked", location=spear.FVector(1.0, 2.0, 3.0))
    with instance.end_frame():
        pass
    frames = instance.frame_count

    def look() -> tuple[dict[str, Any], dict[str, Any]]:
        client = WebSocketClient(url)
        client.hello()
        world = client.request("world", kind="game")["ok"]
        outside = client.request("call", object=world, function="get_actor_count", args={})
        batch = client.request("batch", between_frames=True,
                               calls=[{"op": "call", "object": world, "function": "get_actor_count", "args": {}}])
        return outside, batch

    outside, batch = served(instance, look)
    assert outside["error"][0] == "InvalidStateError"
    assert "called outside a frame" in outside["error"][1]
    assert batch["ok"][0]["ok"] == 1
    assert instance.frame_count == frames  # looking ran no frame


def test_a_browser_steps_frames_that_python_sees(inspected: tuple[spear.Instance, str]) -> None:
    instance, url = inspected
    before = instance.frame_count

    def step() -> list[dict[str, Any]]:
        client = WebSocketClient(url)
        client.hello()
        return list(client.request("batch", critical=[0, 1, 2, 3], calls=[
            {"op": "frame", "action": a} for a in ("begin", "execute", "begin_end", "end")])["ok"])

    replies = served(instance, step)
    assert all("ok" in r for r in replies)
    assert instance.frame_count == before + 1


def test_bad_frames_drop_only_their_connection(inspected: tuple[spear.Instance, str]) -> None:
    instance, url = inspected

    def abuse() -> bool:
        unmasked = WebSocketClient(url)
        unmasked.send_raw(frame(b"\x00\x00\x00\x00", masked=False))
        text = WebSocketClient(url)
        text.send_raw(frame(b"hello", opcode=1))
        huge = WebSocketClient(url)  # before its hello: 64 KiB at most
        huge.send_raw(frame(b"\x00" * 70000))
        return all(c.closed_by_server() for c in (unmasked, text, huge))

    assert served(instance, abuse)
    # The engine and its inspector go on.
    assert served(instance, lambda: WebSocketClient(url).hello())["ok"]["api_hash"]
    instance.step()


def test_inspect_and_serve_refuse_bad_arguments(make_instance: Callable[..., spear.Instance]) -> None:
    instance = make_instance()
    with pytest.raises(InvalidArgumentError, match=r"inspect\(\): port must be an int in \[0, 65535\], got -1"):
        instance.inspect(port=-1)
    with pytest.raises(InvalidArgumentError, match=r"inspect\(\): port must be an int in \[0, 65535\], got 'x'"):
        instance.inspect(port="x")  # type: ignore[arg-type]
    url = instance.inspect(port=0)
    assert instance.inspect(port=0) == url  # one inspector an engine
    port = split_url(url)[1]
    assert instance.inspect(port=port) == url
    with pytest.raises(InvalidStateError, match=r"inspect\(\): the inspector already listens on http://127\.0\.0\.1:"):
        instance.inspect(port=1 if port != 1 else 2)
    with pytest.raises(InvalidArgumentError, match=r"serve_inspector\(\): seconds must be a number >= 0, got -1"):
        instance.serve_inspector(seconds=-1)


def test_a_browser_hears_the_engines_log(make_instance: Callable[..., spear.Instance]) -> None:
    instance = make_instance(scene="/Game/scenes/apartment")
    url = instance.inspect(port=0)
    client = served(instance, lambda: WebSocketClient(url))
    served(instance, client.hello)
    with instance.begin_frame():
        instance.get_game().spawn_actor(uclass=spear.ACameraSensorActor, name="Cam")
    with instance.end_frame():  # its first render lights the scene's irradiance probes, and says so
        pass
    served(instance, lambda: client.request("echo", value=0))
    lines = [push["log"] for push in client.pushes if "log" in push]
    assert any(file == "irradiance_probes.cpp" and message.startswith("irradiance probes: ")
               for file, _, message in lines), lines
    client.close()


def test_a_browser_that_stops_reading_is_dropped_and_the_engine_goes_on(inspected: tuple[spear.Instance, str]) -> None:
    instance, url = inspected

    def flood() -> bool:
        client = WebSocketClient(url)
        client.hello()
        # 100 echoes of 1 MB, none of their replies read: past the 64 MiB a client may leave unread.
        message = msgpack.packb({"id": 1, "op": "echo", "value": "x" * (1 << 20)}, use_bin_type=True)
        request = frame(struct.pack("<I", len(message)) + message)
        try:
            for _ in range(100):
                client.send_raw(request)
        except OSError:
            pass  # dropped while still sending
        return client.closed_by_server()

    assert served(instance, flood)
    instance.step()  # the engine goes on
    assert served(instance, lambda: WebSocketClient(url).hello())["ok"]["api_hash"]
