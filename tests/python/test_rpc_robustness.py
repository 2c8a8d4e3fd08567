"""A server no client can crash, hang, wedge or misuse: hostile nesting, counts, shapes, shared memory and
frames left open. Raw-socket tests speak the wire format by hand (core/rpc/dispatcher.h) to send what
spear's own client never would."""

from __future__ import annotations

import contextlib
import os
import re
import select
import signal
import socket
import struct
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import msgpack
import numpy as np
import pytest

import spear
import spear._engine
from spear._rpc_client import LaunchedServer, RpcConnection, find_server_binary

DEPTH_ERROR = "a value has lists or dicts nested deeper than 64 levels"


@pytest.fixture
def server() -> Iterator[LaunchedServer]:
    launched = LaunchedServer(fixed_delta_seconds=1 / 60)
    yield launched
    launched.close()


class RawClient:
    """Length-prefixed msgpack frames over the server's Unix socket, built by hand."""

    def __init__(self, server: LaunchedServer, *, hello: bool = True) -> None:
        self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.sock.connect(server.address.removeprefix("unix:"))
        self.sock.settimeout(30)
        if hello:
            greeting = self.request({"op": "hello", "api_hash": spear._engine.API_HASH})
            assert "ok" in greeting
            # As spear's client does: it shows it maps the server's memory, so large replies travel through it.
            probe = greeting["ok"].get("shm_probe")
            if probe:
                fd = os.open("/dev/shm" + probe, os.O_RDONLY)
                nonce = os.read(fd, 32).decode()
                os.close(fd)
                os.unlink("/dev/shm" + probe)
                assert self.request({"op": "shm_proof", "nonce": nonce})["ok"] is True

    def send(self, body: bytes) -> dict[str, Any]:
        self.sock.sendall(struct.pack("<I", len(body)) + body)
        (length,) = struct.unpack("<I", self._receive(4))
        reply: dict[str, Any] = msgpack.unpackb(self._receive(length), raw=False, strict_map_key=False)
        return reply

    def request(self, message: dict[str, Any]) -> dict[str, Any]:
        return self.send(msgpack.packb(message, use_bin_type=True))

    def closed_by_server(self) -> bool:
        return self.sock.recv(1) == b""

    def _receive(self, size: int) -> bytes:
        data = b""
        while len(data) < size:
            chunk = self.sock.recv(size - len(data))
            assert chunk, "the server closed the connection"
            data += chunk
        return data


def raw_map(**fields: bytes) -> bytes:
    """A msgpack map whose values are already-encoded bytes (fewer than 16 fields)."""
    return bytes([0x80 | len(fields)]) + b"".join(msgpack.packb(k) + v for k, v in fields.items())


def nested(depth: int) -> bytes:
    """`depth` one-element lists, each holding the next, around nil: a value of `depth` + 1 bytes."""
    return b"\x91" * depth + b"\xc0"


def array_ext(dtype: str, shape: list[int], payload: Any) -> msgpack.ExtType:
    """An array value (extension 3): [dtype, shape, payload bytes or {"shm": name, "size": n}]."""
    return msgpack.ExtType(3, msgpack.packb([dtype, shape, payload], use_bin_type=True))


def still_serves(server: LaunchedServer) -> None:
    connection = RpcConnection(server.address)
    assert connection.request("echo", value=[1, "two", 3.0]) == [1, "two", 3.0]
    connection.close()


def deep_list(depth: int) -> list[Any]:
    value: list[Any] = []
    for _ in range(depth - 1):
        value = [value]
    return value


# -- nesting -----------------------------------------------------------------------------------------

def test_deep_values_are_refused_naming_the_function(instance: spear.Instance) -> None:
    # In-process this recursed 100,000 C++ frames deep and took Python down; over RPC the client refuses it
    # with the same message before sending.
    game = instance.get_game()
    with instance.begin_frame():
        with pytest.raises(spear.InvalidArgumentError, match=rf"^call_function\('spawn_actor'\): {DEPTH_ERROR}$"):
            instance.call_function(uobject=game, function="spawn_actor",
                                   args={"uclass": spear.AActor, "location": deep_list(100_000)})
        # The limit counts `args` as the first level, on both transports: 63 more levels are still a value.
        with pytest.raises(spear.InvalidArgumentError, match=DEPTH_ERROR):
            instance.call_function(uobject=game, function="spawn_actor",
                                   args={"uclass": spear.AActor, "location": deep_list(64)})
        with pytest.raises(spear.InvalidArgumentError, match="argument 'location' must be FVector, got list"):
            instance.call_function(uobject=game, function="spawn_actor",
                                   args={"uclass": spear.AActor, "location": deep_list(63)})
        actor = game.spawn_actor(uclass=spear.AActor)
        with pytest.raises(spear.InvalidArgumentError, match=rf"^set_property\('Tags'\): {DEPTH_ERROR}$"):
            instance.set_property(uobject=actor, path="Tags", value=deep_list(100_000))
    with instance.end_frame():
        assert game.get_actor_count() == 1


def test_a_deeply_nested_message_is_refused_and_the_server_answers_on(server: LaunchedServer) -> None:
    client = RawClient(server)
    # 20 KB of nesting overflowed the server's stack in the recursive decoder (SIGSEGV).
    reply = client.send(raw_map(id=msgpack.packb(1), op=msgpack.packb("echo"), value=nested(20_000)))
    assert reply == {"id": 1, "error": ["InvalidArgumentError", f"echo(): {DEPTH_ERROR}"]}
    world = client.request({"id": 2, "op": "world", "kind": "game"})["ok"]
    assert "ok" in client.request({"op": "frame", "action": "begin"})  # objects are used inside a frame
    reply = client.send(raw_map(id=msgpack.packb(3), op=msgpack.packb("call"), object=msgpack.packb(world),
                                function=msgpack.packb("get_actor_count"),
                                args=b"\x81" + msgpack.packb("x") + nested(20_000)))
    assert reply["error"] == ["InvalidArgumentError", f"call_function('get_actor_count'): {DEPTH_ERROR}"]
    # Nested batches and a nested id recursed too.
    batches = raw_map(op=msgpack.packb("batch"), calls=b"\x91") * 20_000  # each holds the next
    reply = client.send(batches + msgpack.packb({"op": "echo", "value": 1}))
    assert reply["ok"][0]["error"] == ["InvalidArgumentError", "batch(): a batch may not contain a batch"]
    assert client.send(raw_map(id=nested(20_000), op=msgpack.packb("echo"))) == {"id": None, "ok": None}
    assert client.request({"id": 4, "op": "echo", "value": [[1]]}) == {"id": 4, "ok": [[1]]}
    still_serves(server)


def test_counts_beyond_the_message_are_refused_before_allocating(server: LaunchedServer) -> None:
    # A 5-byte array32 header announcing 2^32 - 1 elements, before hello: msgpack-c allocated 64 GiB of
    # objects for them.
    client = RawClient(server, hello=False)
    reply = client.send(b"\xdd\xff\xff\xff\xff")
    assert reply["error"][0] == "InvalidArgumentError"
    assert reply["error"][1] == ("request: malformed message (array size overflow: a list, map, string or binary "
                                 "announces more than the message's 5 bytes can hold)")
    assert client.closed_by_server()  # it never said hello
    # The same inside an array value, after hello.
    client = RawClient(server)
    reply = client.request({"id": 1, "op": "echo", "value": msgpack.ExtType(3, b"\xdf\xff\xff\xff\xff")})
    assert reply["error"][1].startswith("request: malformed message (map size overflow")
    still_serves(server)


# -- arrays in a request's tail (TAIL_FLAG) -----------------------------------------------------------

def tailed_frame(message: dict[str, Any], tail: bytes, *, claimed_message_length: int | None = None) -> bytes:
    """[length | TAIL_FLAG][message length][message][padding][tail], as a client without shared memory sends."""
    body = msgpack.packb(message, use_bin_type=True)
    start = -(-(4 + len(body)) // 64) * 64
    length = start + len(tail)
    told = len(body) if claimed_message_length is None else claimed_message_length
    return struct.pack("<II", length | 0x80000000, told) + body + bytes(start - 4 - len(body)) + tail


def test_arrays_in_a_requests_tail_are_checked_against_it(server: LaunchedServer) -> None:
    client = RawClient(server)
    tail = bytes(range(256)) * 4

    def echo(payload: dict[str, int], with_tail: bool = True) -> dict[str, Any]:
        message = {"id": 1, "op": "echo", "value": array_ext("uint8", [payload["size"]], payload)}
        if not with_tail:
            return client.request(message)
        client.sock.sendall(tailed_frame(message, tail))
        (length,) = struct.unpack("<I", client._receive(4))
        reply: dict[str, Any] = msgpack.unpackb(client._receive(length), raw=False, strict_map_key=False)
        return reply

    def refused(reply: dict[str, Any]) -> str:
        assert reply["error"][0] == "InvalidArgumentError", reply
        return str(reply["error"][1])

    # Small enough to come back in the message: the bytes it names, copied out of the tail.
    assert echo({"tail": 64, "size": 16})["ok"] == msgpack.ExtType(3, msgpack.packb(
        ["uint8", [16], tail[64:80]], use_bin_type=True))
    assert refused(echo({"tail": 1020, "size": 8})) == (
        "echo(): an array of 8 bytes at 1020 runs past the message's 1024-byte tail")
    assert refused(echo({"tail": 2**64 - 1, "size": 8})).endswith("runs past the message's 1024-byte tail")
    assert refused(echo({"tail": 0, "size": 8}, with_tail=False)) == (
        "echo(): an array in the message's tail, but the message has none")
    still_serves(server)


def test_a_tailed_frame_whose_message_runs_past_it_drops_only_that_client(server: LaunchedServer) -> None:
    client = RawClient(server)
    client.sock.sendall(tailed_frame({"id": 1, "op": "echo"}, b"x" * 100, claimed_message_length=10_000))
    assert client.closed_by_server()
    still_serves(server)


# -- array shapes ------------------------------------------------------------------------------------

def test_array_shapes_whose_size_wraps_around_are_refused(server: LaunchedServer) -> None:
    client = RawClient(server)
    # 1537228672809129302 * 3 * 4 bytes is 2^64 + 8: unchecked, 8 bytes of data passed for it.
    reply = client.request({"id": 1, "op": "echo", "value": array_ext("float32", [1537228672809129302, 3], b"\0" * 8)})
    assert reply["error"] == ["InvalidArgumentError", "echo(): array shape (1537228672809129302, 3) of float32 "
                                                      "holds more bytes than fit in 64 bits"]
    reply = client.request({"id": 2, "op": "echo", "value": array_ext("float64", [-1, -1], b"\0" * 8)})
    assert reply["error"] == ["InvalidArgumentError", "echo(): array shape (-1, -1) has a negative extent -1"]
    reply = client.request({"id": 3, "op": "echo", "value": array_ext("float32", [2, 1], b"\0" * 8)})
    assert reply["ok"] == array_ext("float32", [2, 1], b"\0" * 8)
    still_serves(server)


# -- shared memory -----------------------------------------------------------------------------------

@pytest.fixture
def segment() -> Iterator[tuple[str, int]]:
    """A shared-memory segment named as one of this process's reply buffers, 1 MiB: (name, fd)."""
    name = f"/spear-{os.getpid()}-r{900_000 + os.getpid() % 1000}"
    fd = os.open("/dev/shm" + name, os.O_CREAT | os.O_EXCL | os.O_RDWR, 0o600)
    os.ftruncate(fd, 1 << 20)
    yield name, fd
    os.close(fd)
    try:
        os.unlink("/dev/shm" + name)
    except FileNotFoundError:
        pass  # the server removes the buffers it was offered when the connection ends


def test_a_reply_buffer_shrunk_after_it_was_offered_is_not_written(server: LaunchedServer,
                                                                    segment: tuple[str, int]) -> None:
    name, fd = segment
    connection = RpcConnection(server.address)
    connection._reply_buffers.close()  # noqa: SLF001  (offers only the buffer below)
    connection.request("echo", value=None, reply_buffers=[[name, 1 << 20]])  # the server maps it
    os.ftruncate(fd, 0)
    # Offered again at its first size: the server trusted that size and wrote 1 MiB into it (SIGBUS).
    value = np.full(1 << 18, 7, np.float32)
    assert np.array_equal(connection.request("echo", value=value, reply_buffers=[[name, 1 << 20]]), value)
    connection.close()
    still_serves(server)


def test_an_argument_segment_smaller_than_it_claims_is_refused(server: LaunchedServer,
                                                              segment: tuple[str, int]) -> None:
    name, fd = segment
    os.ftruncate(fd, 4096)
    client = RawClient(server)
    reply = client.request({"id": 1, "op": "echo", "value": array_ext("uint8", [1 << 20], {"shm": name, "size": 1 << 20})})
    assert reply["error"] == ["InvalidArgumentError", f"echo(): shared-memory array: SharedMemorySegment::open(): "
                                                      f"segment '{name}' holds 4096 bytes, fewer than 1048576"]
    still_serves(server)


def test_an_argument_segment_of_another_process_is_not_opened(server: LaunchedServer) -> None:
    # A segment another process made (here: named with the server's pid, as its reply segments are) must not
    # be readable through the server by naming it: only the connected client's own segments are arguments.
    name = f"/spear-{server.process.pid}-{900_002}"
    fd = os.open("/dev/shm" + name, os.O_CREAT | os.O_EXCL | os.O_RDWR, 0o600)
    try:
        os.ftruncate(fd, 1 << 20)
        client = RawClient(server)
        reply = client.request({"id": 1, "op": "echo",
                                "value": array_ext("uint8", [1 << 20], {"shm": name, "size": 1 << 20})})
        assert reply["error"] == ["InvalidArgumentError", f"echo(): shared-memory array '{name}' is not a segment "
                                                          f"of the connected client (pid {os.getpid()})"]
        still_serves(server)
    finally:
        os.close(fd)
        os.unlink("/dev/shm" + name)


def test_segments_shrunk_while_in_use_never_crash_the_server(server: LaunchedServer) -> None:
    # Another process shrinks and regrows a reply buffer and an argument segment as fast as it can while
    # the server copies 16 MiB from one to the other: between the server's size check and its access is a
    # window no check closes. The server's SIGBUS guard turns a hit into an error for that request alone.
    # (This test never maps either segment itself, so the shrinking cannot fault in pytest.)
    size = 16 << 20
    buffer, argument = f"/spear-{os.getpid()}-r{900_001}", f"/spear-{os.getpid()}-{900_001}"
    for name in (buffer, argument):
        fd = os.open("/dev/shm" + name, os.O_CREAT | os.O_EXCL | os.O_RDWR, 0o600)
        os.ftruncate(fd, size)
        os.close(fd)
    client = RawClient(server)
    client.request({"id": 0, "op": "echo", "reply_buffers": [[buffer, size]]})  # the server maps the buffer
    script = (  # each segment spends about half its time empty, switching at varied moments
        "import os, random, sys\n"
        "fds = [os.open('/dev/shm' + name, os.O_RDWR) for name in sys.argv[2:]]\n"
        "print('ready', flush=True)\n"
        "while True:\n"
        "    for size in (0, int(sys.argv[1])):\n"
        "        for fd in fds:\n"
        "            os.ftruncate(fd, size)\n"
        "        for _ in range(random.randrange(2000)):\n"
        "            pass\n"
    )
    vandal = subprocess.Popen([sys.executable, "-c", script, str(size), buffer, argument], stdout=subprocess.PIPE,
                              text=True)
    assert vandal.stdout is not None and vandal.stdout.readline() == "ready\n"
    outcomes: set[str] = set()
    try:
        for i in range(1, 200):
            reply = client.request({"id": i, "op": "echo", "reply_buffers": [[buffer, size]],
                                    "value": array_ext("uint8", [size], {"shm": argument, "size": size})})
            if "ok" in reply:
                outcomes.add("ok")
                continue
            assert reply["error"][0] == "InvalidArgumentError"
            message = reply["error"][1]
            if "was truncated while the server used it" in message:
                assert message == ("echo(): a shared-memory segment was truncated while the server used it; "
                                   "its contents are lost")
                outcomes.add("truncated")
                break  # the guard was exercised
            assert message.endswith(f"segment '{argument}' holds 0 bytes, fewer than {size}"), message
    finally:
        vandal.kill()
        vandal.wait()
        vandal.stdout.close()
        for name in (buffer, argument):
            try:
                os.unlink("/dev/shm" + name)
            except FileNotFoundError:
                pass  # the server removes the reply buffers it was offered
    assert server.process.poll() is None
    still_serves(server)


def start_client(code: str, *, ready: str) -> subprocess.Popen[str]:
    """A Python process running `code` with this source tree's spear importable, once it has printed `ready`
    (killed if it does not)."""
    path = str(Path(spear.__file__).parent.parent)
    process = subprocess.Popen([sys.executable, "-c", f"import sys; sys.path.insert(0, {path!r})\n" + code],
                               stdout=subprocess.PIPE, text=True)
    assert process.stdout is not None
    line = process.stdout.readline()
    if line != ready + "\n":
        process.kill()
        process.wait()
        process.stdout.close()
        raise AssertionError(f"start_client(): the client printed {line!r}, not {ready!r}")
    return process


def alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().split(") ")[1][0] != "Z"  # a zombie has exited
    except FileNotFoundError:
        return False


def test_a_launched_server_outlives_the_launching_thread_and_goes_with_the_client_process() -> None:
    # A server launched from a worker thread that then ended kept serving (it went when the thread did), and
    # one whose client was killed went away by itself.
    client = start_client(
        "import threading, time\nimport spear\n"
        "instances = []\n"
        "thread = threading.Thread(target=lambda: instances.append(spear.Instance(server='launch')))\n"
        "thread.start(); thread.join(); time.sleep(0.5)\n"
        "print('launched', flush=True)\n"
        "print(instances[0].server_pid, flush=True)\n"
        "instances[0].get_worlds()\n"
        "print('served', flush=True)\n"
        "time.sleep(60)\n", ready="launched")
    try:
        assert client.stdout is not None
        server_pid = int(client.stdout.readline())
        assert client.stdout.readline() == "served\n"
        assert alive(server_pid)
        client.kill()
        client.wait()
        deadline = time.monotonic() + 10.0
        while alive(server_pid) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not alive(server_pid), "the launched server kept running after its client was killed"
    finally:
        client.kill()
        client.wait()
        if client.stdout:
            client.stdout.close()


# -- frames ------------------------------------------------------------------------------------------

def test_a_frame_left_open_by_a_killed_client_is_aborted(server: LaunchedServer) -> None:
    client_a = start_client(
        "import time, spear\n"
        f"instance = spear.Instance(server={server.address!r})\n"
        "instance.begin_frame().__enter__()\n"
        "print('in frame', flush=True)\n"
        "time.sleep(600)\n", ready="in frame")
    client_a.send_signal(signal.SIGKILL)
    client_a.wait()
    if client_a.stdout:
        client_a.stdout.close()
    # Client B used to get "the engine is inside begin_frame, expected idle" from here on.
    with spear.Instance(server=server.address) as client_b:
        assert client_b.frame_state == "idle"
        assert client_b.frame_count == 1  # A's frame ended, with its tick, as a frame whose block raised
        game = client_b.get_game()
        with client_b.begin_frame():
            game.spawn_actor(uclass=spear.AActor)
        with client_b.end_frame():
            assert game.get_actor_count() == 1
        assert client_b.frame_count == 2


def test_a_frame_left_open_by_a_client_that_hung_up_is_aborted(server: LaunchedServer) -> None:
    client_a = RawClient(server)
    assert "ok" in client_a.request({"id": 1, "op": "frame", "action": "begin"})
    client_a.sock.close()  # no end_frame
    client_b = RawClient(server)
    for action in ("begin", "execute", "begin_end", "end"):
        reply = client_b.request({"id": 2, "op": "frame", "action": action})
        assert "ok" in reply, reply
    assert reply["ok"]["state"] == "idle"


# -- clients that do not read --------------------------------------------------------------------------

def frames(count: int, value: str) -> bytes:
    """`count` echo requests, ids 0..count-1, as one stream of frames."""
    bodies = (msgpack.packb({"id": i, "op": "echo", "value": value}) for i in range(count))
    return b"".join(struct.pack("<I", len(body)) + body for body in bodies)


def complete_a_frame(client: RawClient) -> int:
    for action in ("begin", "execute", "begin_end", "end"):
        reply = client.request({"id": 1, "op": "frame", "action": action})
        assert "ok" in reply, reply
    assert reply["ok"]["state"] == "idle"
    return int(reply["ok"]["frame_count"])


def test_a_client_that_never_reads_its_replies_cannot_stop_the_server(server: LaunchedServer) -> None:
    # The server sent each reply with a blocking send(): once a client that never reads had filled its
    # socket's buffers, the server waited in send() for good, and every other client with it (here: the
    # sends below, and client B, time out instead of completing).
    value = "x" * (32 << 10)
    slow = RawClient(server)
    slow.sock.sendall(frames(100, value))  # 3 MiB of replies, more than the socket holds: some wait queued
    other = RawClient(server)
    first = complete_a_frame(other)
    assert complete_a_frame(other) == first + 1
    # Replies that waited are delivered whole and in order once the client reads.
    for i in range(100):
        (length,) = struct.unpack("<I", slow._receive(4))  # noqa: SLF001
        assert msgpack.unpackb(slow._receive(length), raw=False) == {"id": i, "ok": value}  # noqa: SLF001

    # A client that holds a frame open and never reads: past the queue's bound it is dropped, and its frame
    # aborted, so that the others go on.
    hog = RawClient(server)
    assert "ok" in hog.request({"id": 1, "op": "frame", "action": "begin"})
    try:
        hog.sock.sendall(frames(4000, value))  # 128 MiB of replies: past 64 MiB and 256 replies
    except (BrokenPipeError, ConnectionResetError):
        pass  # dropped before it had sent them all
    received = 0
    try:
        while chunk := hog.sock.recv(1 << 20):
            received += len(chunk)
    except ConnectionResetError:
        pass
    assert received < 4000 * len(value)  # it was cut off, not served to the end
    assert complete_a_frame(other) == first + 3  # the hog's frame was aborted (one tick), then B's own
    assert server.process.poll() is None
    still_serves(server)


# -- shared memory after a crash ---------------------------------------------------------------------

def wait_for_zombie(pid: int, timeout: float = 10.0) -> None:
    """Waits until process `pid` has died and is left unreaped (state Z in /proc/<pid>/stat)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        with open(f"/proc/{pid}/stat") as stat:
            if stat.read().rsplit(")", 1)[1].split()[0] == "Z":
                return
        time.sleep(0.01)
    raise AssertionError(f"process {pid} did not die within {timeout} s")


def spear_segments(*pids: int) -> list[str]:
    return [n for n in os.listdir("/dev/shm") if any(n.startswith(f"spear-{pid}-") for pid in pids)]


@pytest.mark.parametrize("next_client", ["inprocess", "rpc"])
def test_segments_of_a_client_and_server_killed_together_go_when_the_next_client_starts(next_client: str) -> None:
    # Both sides SIGKILLed in the middle of 1080p reads leave the segments in flight, and the client's reply
    # buffers, under /dev/shm: only a server start removed them. Now any client start does too: here one that
    # connects to a server started before the crash (which therefore swept nothing), or an in-process one.
    survivor = LaunchedServer(fixed_delta_seconds=1 / 60)
    doomed = LaunchedServer(fixed_delta_seconds=1 / 60)
    client = start_client(
        "import numpy as np\nfrom spear._rpc_client import RpcConnection\n"
        f"connection = RpcConnection({doomed.address!r})\n"
        "frame = np.ones((1080, 1920, 4), np.uint8)\n"
        "for i in range(1 << 30):\n"
        "    connection.request('echo', value=frame)\n"
        "    if i == 3:\n"
        "        print('reading', flush=True)\n", ready="reading")
    try:
        for process in (client, doomed.process):  # frozen first: neither may see the other go and clean up
            process.send_signal(signal.SIGSTOP)
        for process in (client, doomed.process):
            process.kill()
        # Dead but not yet reaped (zombies) their pids still exist, so that no spear process the other test
        # workers start meanwhile sweeps their segments as orphans before they are counted.
        for process in (client, doomed.process):
            wait_for_zombie(process.pid)
        # The client's reply buffers at least: it had made them for the frames it read.
        assert spear_segments(client.pid, doomed.process.pid)
        for process in (client, doomed.process):
            process.wait()
        if next_client == "inprocess":
            spear.Instance().close()
        else:
            spear.Instance(server=survivor.address).close()
        assert not spear_segments(client.pid, doomed.process.pid)
    finally:
        client.kill()
        client.wait()
        if client.stdout:
            client.stdout.close()
        doomed.close()
        survivor.close()


# -- the socket path ---------------------------------------------------------------------------------

def test_socket_path_naming_another_file_is_refused_and_the_file_kept(tmp_path: Path) -> None:
    # The server unlinked whatever --socket named before binding: a typo could delete a user's file.
    precious = tmp_path / "notes.txt"
    precious.write_text("precious")
    done = subprocess.run([str(find_server_binary()), "--socket", str(precious)], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 1
    assert done.stderr.strip() == (f"InvalidArgumentError: spear-server: --socket '{precious}' exists and is not a "
                                   "socket; refusing to replace it")
    assert precious.read_text() == "precious"


def test_a_live_servers_socket_is_not_taken_over(server: LaunchedServer) -> None:
    path = server.address.removeprefix("unix:")
    done = subprocess.run([str(find_server_binary()), "--socket", path], capture_output=True, text=True, timeout=120)
    assert done.returncode == 1
    assert done.stderr.strip() == f"InvalidStateError: spear-server: --socket '{path}': another server is listening there"
    still_serves(server)


# -- what an unauthenticated or untrusted client can make the server do --------------------------------

@contextlib.contextmanager
def started_by_hand(*args: str, **env: str) -> Iterator[tuple[subprocess.Popen[str], str]]:
    """A spear-server started as a user starts one (not through LaunchedServer, which trusts its one client),
    with SPEAR_PLUGIN_PATH and SPEAR_TOKEN only as given; yields the process and its address."""
    environment = {k: v for k, v in os.environ.items() if k not in ("SPEAR_PLUGIN_PATH", "SPEAR_TOKEN")}
    process = subprocess.Popen([str(find_server_binary()), *args, "--exit-with-parent"], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, env={**environment, **env})
    try:
        assert process.stdout is not None and process.stderr is not None
        line = process.stdout.readline()
        assert line.startswith("spear-server: listening on "), process.stderr.read()
        yield process, line.strip().removeprefix("spear-server: listening on ")
    finally:
        process.terminate()
        process.wait(10)


def library_with_a_constructor(directory: Path, name: str) -> tuple[Path, Path]:
    """lib<name>.so, not a plugin, whose static constructor creates a file (returned second): code that runs
    inside dlopen(), before the loader can check anything."""
    marker = directory / f"{name}.ran"
    source = directory / f"{name}.c"
    source.write_text("#include <stdio.h>\n"
                      "__attribute__((constructor)) static void ran(void) {\n"
                      f'    FILE* file = fopen("{marker}", "w");\n'
                      "    if (file) fclose(file);\n"
                      "}\n")
    library = directory / f"lib{name}.so"
    subprocess.run(["cc", "-shared", "-fPIC", "-o", str(library), str(source)], check=True)
    return library, marker


def test_load_plugin_over_the_wire_opens_only_the_servers_own_plugins(tmp_path: Path) -> None:
    # load_plugin dlopen()ed any path a client named: the library's constructors ran with the server's rights
    # before it was found not to be a plugin.
    library, marker = library_with_a_constructor(tmp_path, "intruder")
    with started_by_hand("--socket", str(tmp_path / "server.sock")) as (_, address):
        connection = RpcConnection(address)
        for path in (str(library), f"{tmp_path}/./../{tmp_path.name}/{library.name}"):
            with pytest.raises(spear.InvalidStateError,
                               match=rf"^load_plugin\(\): this server does not load '{re.escape(path)}' for a client: "
                                     r"it loads only the plugins named on its command line \(--plugin\) or found in "
                                     r"its SPEAR_PLUGIN_PATH; .*--allow-remote-plugin-load"):
                connection.request("load_plugin", path=path)
        assert not marker.exists()  # its code never ran
        assert connection.request("echo", value="still serving") == "still serving"
        connection.close()
    # Found in the server's own SPEAR_PLUGIN_PATH (its owner put it there), or any library once the server
    # allows it: loaded, so its constructor runs, and refused as no plugin.
    for args, env, path in ((["--allow-remote-plugin-load"], {}, str(library)),
                            ([], {"SPEAR_PLUGIN_PATH": str(tmp_path)}, "intruder"),
                            ([], {"SPEAR_PLUGIN_PATH": str(tmp_path)}, str(library))):
        marker.unlink(missing_ok=True)
        with started_by_hand("--socket", str(tmp_path / "server.sock"), *args, **env) as (_, address):
            connection = RpcConnection(address)
            with pytest.raises(spear.InvalidArgumentError, match="is not a spear plugin"):
                connection.request("load_plugin", path=path)
            assert marker.exists(), (args, env, path)
            connection.close()


def test_a_client_announcing_a_large_message_before_hello_is_dropped_at_once(server: LaunchedServer) -> None:
    # Two such clients announcing 1 GiB each made the server buffer 2 GB: before hello a message may have
    # 64 KiB at most.
    client = RawClient(server, hello=False)
    client.sock.sendall(struct.pack("<I", 1 << 30))
    assert client.closed_by_server()
    client = RawClient(server, hello=False)
    client.sock.sendall(struct.pack("<I", (64 << 10) + 1))
    assert client.closed_by_server()
    # After hello, messages may be large.
    connection = RpcConnection(server.address)
    assert connection.request("echo", value="x" * (1 << 20)) == "x" * (1 << 20)
    connection.close()
    still_serves(server)


def test_connections_waiting_for_their_hello_are_limited(server: LaunchedServer) -> None:
    waiting = [RawClient(server, hello=False) for _ in range(64)]
    extra = RawClient(server, hello=False)
    assert extra.closed_by_server()  # the 65th, accepted after the 64 before it
    for client in waiting:
        client.sock.close()
    still_serves(server)


def test_a_token_file_keeps_the_token_off_the_command_line(tmp_path: Path) -> None:
    token_file = tmp_path / "token"
    token_file.write_text("s3cret\n")
    token_file.chmod(0o644)
    refused = subprocess.run([str(find_server_binary()), "--port", "0", "--token-file", str(token_file)],
                             capture_output=True, text=True, timeout=30,
                             env={k: v for k, v in os.environ.items() if k != "SPEAR_TOKEN"})
    assert refused.returncode == 1
    assert (f"--token-file '{token_file}' must belong to this user and be readable by it alone (mode 644)"
            in refused.stderr)
    token_file.chmod(0o600)
    with started_by_hand("--port", "0", "--token-file", str(token_file)) as (process, address):
        assert b"s3cret" not in Path(f"/proc/{process.pid}/cmdline").read_bytes()
        connection = RpcConnection(address, token="s3cret")
        assert connection.request("echo", value=1) == 1
        connection.close()
        # Guessing is slowed down: past 3 wrong tokens, each further refusal is held back (1 s, doubling), while
        # the right token is answered at once: on loopback the guesser and every local user are one peer.
        for _ in range(4):  # the fourth refusal comes after a second
            with pytest.raises(spear.InvalidArgumentError, match="^hello\\(\\): wrong or missing token$"):
                RpcConnection(address, token="guess")
        host, port = address.removeprefix("tcp:").rsplit(":", 1)
        guesser = socket.create_connection((host, int(port)), timeout=30)
        body = msgpack.packb({"op": "hello", "id": 1, "api_hash": spear._engine.API_HASH, "token": "guess"},
                             use_bin_type=True)
        guesser.sendall(struct.pack("<I", len(body)) + body)
        readable = select.poll()
        readable.register(guesser, select.POLLIN)
        assert readable.poll(100) == []  # its refusal, the fifth, is held back for 2 s...
        connection = RpcConnection(address, token="s3cret")  # ...while the right token gets in
        assert connection.request("echo", value=2) == 2
        connection.close()
        assert readable.poll(0) == []  # still held
        (length,) = struct.unpack("<I", guesser.recv(4, socket.MSG_WAITALL))  # then sent, and the connection closed
        refusal = msgpack.unpackb(guesser.recv(length, socket.MSG_WAITALL), raw=False)
        assert refusal["error"] == ["InvalidArgumentError", "hello(): wrong or missing token"]
        assert guesser.recv(1) == b""
        guesser.close()
    # SPEAR_TOKEN in the environment works as well (read by the client too).
    with started_by_hand("--port", "0", SPEAR_TOKEN="fr0m-env") as (_, address):
        with pytest.raises(spear.InvalidArgumentError, match="wrong or missing token"):
            RpcConnection(address, token="guess")
        connection = RpcConnection(address, token="fr0m-env")
        assert connection.request("echo", value=3) == 3
        connection.close()


def test_a_server_gone_after_a_frame_ended_is_reported_by_the_next_request() -> None:
    # The end of a frame is sent without waiting for its reply; a server that dies then is found out by the
    # next request, which reads that reply first.
    with spear.Instance(server="launch") as instance:
        with instance.begin_frame():
            pass
        with instance.end_frame():
            instance.get_game()
        os.kill(instance.server_pid, signal.SIGKILL)
        with pytest.raises(spear.ConnectionLostError, match="spear server"):
            with instance.begin_frame():
                pass
