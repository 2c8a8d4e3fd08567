"""The RPC transport itself: handshake, hostile input, crashes, permissions, shared memory, cleanup."""

from __future__ import annotations

import mmap
import dataclasses
import os
import socket
import stat
import struct
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import spear
import spear._engine
from spear import _wire
from spear._rpc_client import LaunchedServer, RpcConnection, find_server_binary


@pytest.fixture
def server() -> Iterator[LaunchedServer]:
    launched = LaunchedServer(fixed_delta_seconds=1 / 60)
    yield launched
    launched.close()


def root_buffer(array: np.ndarray) -> object:
    """What an array's memory ultimately belongs to."""
    base: object = array
    while isinstance(base, np.ndarray) and base.base is not None:
        base = base.base
    return base.obj if isinstance(base, memoryview) else base


def raw_socket(server: LaunchedServer) -> socket.socket:
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    sock.connect(server.address.removeprefix("unix:"))
    sock.settimeout(10)
    return sock


def still_serves(server: LaunchedServer) -> None:
    connection = RpcConnection(server.address)
    assert connection.request("echo", value=[1, "two", 3.0]) == [1, "two", 3.0]
    connection.close()


def test_api_hash_mismatch_is_refused_naming_both(server: LaunchedServer, monkeypatch: pytest.MonkeyPatch) -> None:
    real = spear._engine.API_HASH
    monkeypatch.setattr(spear._engine, "API_HASH", "0123456789abcdef")
    with pytest.raises(spear.InvalidStateError, match=rf"client's API \(0123456789abcdef\) does not match the server's \({real}\)"):
        RpcConnection(server.address)
    monkeypatch.undo()
    still_serves(server)


def test_requests_before_hello_are_refused(server: LaunchedServer) -> None:
    sock = raw_socket(server)
    import msgpack

    body = msgpack.packb({"id": 1, "op": "world", "kind": "game"})
    sock.sendall(struct.pack("<I", len(body)) + body)
    length = struct.unpack("<I", sock.recv(4))[0]
    reply = msgpack.unpackb(sock.recv(length))
    assert reply["error"] == ["InvalidStateError", "world(): say hello first"]
    assert sock.recv(1) == b""  # and the connection is closed
    still_serves(server)


def test_garbage_truncated_and_oversized_messages_leave_the_server_serving(server: LaunchedServer) -> None:
    garbage = raw_socket(server)
    garbage.sendall(struct.pack("<I", 5) + b"\xc1\xc1\xc1\xc1\xc1")  # 0xc1 is never valid msgpack
    length = struct.unpack("<I", garbage.recv(4))[0]
    assert b"malformed message" in garbage.recv(length)
    truncated = raw_socket(server)
    truncated.sendall(struct.pack("<I", 1000) + b"\x81\xa2id")  # promises 1000 bytes, sends 4, then hangs up
    truncated.close()
    oversized = raw_socket(server)
    oversized.sendall(struct.pack("<I", 0xFFFFFFFF))
    assert oversized.recv(1) == b""  # dropped
    still_serves(server)


def test_a_client_killed_mid_call_does_not_take_the_server_down(server: LaunchedServer) -> None:
    script = (
        "import socket, struct, time; s = socket.socket(socket.AF_UNIX); s.connect(%r); "
        "s.sendall(struct.pack('<I', 500) + b'\\x82'); time.sleep(30)" % server.address.removeprefix("unix:")
    )
    victim = subprocess.Popen([sys.executable, "-c", script])
    time.sleep(0.3)
    victim.kill()
    victim.wait()
    still_serves(server)


def test_engine_errors_arrive_with_their_type_and_the_server_survives(server: LaunchedServer) -> None:
    with spear.Instance(server=server.address) as instance:
        game = instance.get_game()
        with instance.begin_frame():
            with pytest.raises(spear.InvalidArgumentError, match="argument 'location' must be FVector, got str"):
                instance.call_function(uobject=game, function="spawn_actor",
                                       args={"uclass": spear.AActor, "location": "here"})
            with pytest.raises(spear.NotFoundError):
                instance.call_function(uobject=game, function="no_such_function")
            actor = game.spawn_actor(uclass=spear.AActor)
            game.destroy_actor(actor=actor)
            with pytest.raises(spear.StaleObjectError):
                actor.GetName()
        with instance.end_frame():
            pass
        with pytest.raises(spear.InvalidStateError, match="outside a frame"):
            game.get_actor_count()
    still_serves(server)


def test_batches_carry_many_calls_in_one_message(server: LaunchedServer) -> None:
    connection = RpcConnection(server.address)
    results = connection.batch([{"op": "echo", "value": i} for i in range(1000)] + [{"op": "nonsense"}])
    assert results[:1000] == list(range(1000))
    assert isinstance(results[1000], spear.InvalidArgumentError)
    connection.close()


def test_large_arrays_travel_through_shared_memory_and_are_released(server: LaunchedServer) -> None:
    connection = RpcConnection(server.address)
    frame = np.random.default_rng(0).integers(0, 255, size=(1080, 1920, 4), dtype=np.uint8)
    echoed = connection.request("echo", value=frame)
    assert echoed.dtype == np.uint8 and echoed.shape == frame.shape
    assert np.array_equal(echoed, frame)
    assert isinstance(root_buffer(echoed), mmap.mmap)  # a view of the mapped segment, not a copy of a message
    small = connection.request("echo", value=np.arange(10, dtype=np.float32))
    assert small.dtype == np.float32 and list(small) == list(range(10))
    connection.request("echo", value=None)  # the server releases the last reply's segments on the next request
    assert not [n for n in os.listdir("/dev/shm") if n.startswith(f"spear-{server.process.pid}-")]
    # The request's segment is gone; what stays is the reply buffer the client keeps for the next large
    # reply (spear._reply_buffers), until the connection is closed.
    mine = [n for n in os.listdir("/dev/shm") if n.startswith(f"spear-{os.getpid()}-")]
    assert mine == [f"spear-{os.getpid()}-r{n.split('-r')[-1]}" for n in mine] and len(mine) == 1
    connection.close()
    assert not [n for n in os.listdir("/dev/shm") if n.startswith(f"spear-{os.getpid()}-")]
    assert np.array_equal(echoed, frame)


def test_unix_socket_is_owner_only(server: LaunchedServer) -> None:
    path = Path(server.address.removeprefix("unix:"))
    assert stat.S_IMODE(path.stat().st_mode) & 0o077 == 0
    assert stat.S_IMODE(path.parent.stat().st_mode) & 0o077 == 0


def test_tcp_listens_on_loopback_and_requires_the_token() -> None:
    binary = str(find_server_binary())
    refused = subprocess.run([binary, "--port", "0"], capture_output=True, text=True, timeout=30,
                             env={k: v for k, v in os.environ.items() if k != "SPEAR_TOKEN"})
    assert refused.returncode == 1 and "TCP needs a token" in refused.stderr
    process = subprocess.Popen([binary, "--port", "0", "--token", "s3cret", "--exit-with-parent"],
                               stdout=subprocess.PIPE, text=True)
    try:
        assert process.stdout is not None
        address = process.stdout.readline().strip().removeprefix("spear-server: listening on ")
        assert address.startswith("tcp:127.0.0.1:")
        with pytest.raises(spear.InvalidArgumentError, match="wrong or missing token"):
            RpcConnection(address, token="guess")
        with spear.Instance(server=address, token="s3cret") as instance:
            with instance.begin_frame():
                assert instance.get_game().get_actor_count() == 0
            with instance.end_frame():
                pass
            # Over TCP the server cannot tell which process offers reply buffers, so none are used.
            connection = instance._backend.connection  # type: ignore[attr-defined]
            assert connection._reply_buffers.closed  # noqa: SLF001
            assert np.array_equal(connection.request("echo", value=np.ones(1 << 17)), np.ones(1 << 17))
    finally:
        process.terminate()
        process.wait(10)


def test_closing_an_instance_stops_its_server() -> None:
    instance = spear.Instance(server="launch")
    backend = instance._backend
    process = backend._launched.process  # type: ignore[attr-defined]
    instance.close()
    assert process.poll() is not None


def test_read_pixels_lands_in_the_segment_the_client_maps(server: LaunchedServer) -> None:
    with spear.Instance(server=server.address) as instance:
        game = instance.get_game()
        with instance.begin_frame():
            camera = game.spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor
            camera.Width, camera.Height = 320, 240
            camera.Modalities = [spear.ECameraModality.FinalColor, spear.ECameraModality.Depth]
        with instance.end_frame():
            pixels = camera.read_pixels()
            again = camera.read_pixels()  # cached for this frame: sent again from a fresh segment
        assert set(pixels) == {"final_color", "depth"}
        color = pixels["final_color"]
        assert color.shape == (240, 320, 4) and color.dtype == np.uint8
        assert isinstance(root_buffer(color), mmap.mmap)  # a view of the mapped segment, not a copy
        assert np.array_equal(again["depth"], pixels["depth"])
        instance.get_game()  # any request: the server releases the segments of the last reply
        assert not [n for n in os.listdir("/dev/shm") if n.startswith(f"spear-{server.process.pid}-")]


def test_shared_memory_is_released_when_either_side_dies() -> None:
    # The server dies (SIGKILL) right after sending an array through shared memory: the client removed
    # the segment's name as soon as it mapped it, so nothing stays under /dev/shm.
    launched = LaunchedServer(fixed_delta_seconds=1 / 60)
    connection = RpcConnection(launched.address)
    array = connection.request("echo", value=np.ones((512, 512), np.float32))
    launched.process.kill()
    launched.process.wait()
    assert float(array.sum()) == 512 * 512  # the mapping outlives the name and the process
    assert not [n for n in os.listdir("/dev/shm") if n.startswith(f"spear-{launched.process.pid}-")]
    connection.close()
    launched.close()
    # A client dies holding a request's array in a segment of its own: the next server start sweeps it. The
    # client is killed only once its segment was seen: every client and server start sweeps the segments of
    # dead processes, and another test's, running beside this one, may do it as soon as the client is gone.
    script = (
        "import os, sys, numpy as np; sys.path.insert(0, %r); from spear._wire import OutgoingSegments; "
        "print(OutgoingSegments().create(np.ones(100000)), flush=True); sys.stdin.read()"
        % str(Path(spear.__file__).parent.parent)
    )
    client = subprocess.Popen([sys.executable, "-c", script], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    assert client.stdout is not None
    name = client.stdout.readline().strip().lstrip("/")
    assert name in os.listdir("/dev/shm"), "the client's segment should exist while it lives"
    client.kill()
    client.wait()
    LaunchedServer(fixed_delta_seconds=1 / 60).close()  # a server start removes segments of dead processes
    assert name not in os.listdir("/dev/shm")


def test_replies_land_in_reply_buffers_that_never_change_under_the_user() -> None:
    with spear.Instance(server="launch") as instance:
        connection = instance._backend.connection  # type: ignore[attr-defined]
        base = np.arange(1 << 20, dtype=np.uint32)  # 4 MiB: through shared memory both ways
        first = connection.request("echo", value=base)  # no buffer yet: a segment of the server's
        held = [connection.request("echo", value=base + i) for i in range(1, 4)]
        buffers = connection._reply_buffers._buffers  # noqa: SLF001
        for _ in range(3):  # warm-up: buffers for the argument and the reply, made as they are learned
            connection.request("echo", value=base)
        made = len(buffers)
        for _ in range(10):  # results dropped at once: the same buffers serve every request and reply
            assert connection.request("echo", value=base)[-1] == base[-1]
        assert len(buffers) == made <= len(held) + 3
        assert np.array_equal(first, base)
        for i, array in enumerate(held, start=1):  # what the user holds was never written again
            assert np.array_equal(array, base + i)
        assert sum(b.held for b in buffers.values()) <= len(held) + 1  # and `first`
        reply = connection.request("echo", value=base)  # in one of the client's own, already mapped buffers
        assert any(root_buffer(reply) is b.mapping for b in buffers.values())
        del reply
        names = [f"spear-{os.getpid()}-r" in n for n in os.listdir("/dev/shm")]
        assert any(names)
    # Closing removes the client's buffers; arrays still viewing one keep their mapping.
    assert not [n for n in os.listdir("/dev/shm") if n.startswith(f"spear-{os.getpid()}-")]
    assert np.array_equal(held[0], base + 1)


def test_frames_held_while_the_next_is_read_settle_on_two_reply_buffers() -> None:
    """A loop that keeps the last frame's image while it reads the next (images = [read_pixels()]) needs
    two buffers of the image's size; once made they serve every frame: no fresh segment, no buffer made
    or dropped per frame, and the camera keeps none of them (it once held the last frame's arrays, which
    made the client give a buffer up every other frame)."""
    with spear.Instance(server="launch") as instance:
        connection = instance._backend.connection  # type: ignore[attr-defined]
        game = instance.get_game()
        with instance.begin_frame():
            camera = game.spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor
            camera.Width, camera.Height = 640, 480  # 1.2 MB of final colour: through shared memory
        with instance.end_frame():
            pass
        buffers = connection._reply_buffers._buffers  # noqa: SLF001
        made: set[str] = set()
        image = None
        for frame in range(12):
            with instance.begin_frame():
                pass
            with instance.end_frame():
                pixels = camera.read_pixels()
                assert "final_color" in pixels
                image = pixels["final_color"]  # the previous frame's image is still held until here
            if frame == 4:
                made = set(buffers)
        assert image is not None and image.shape == (480, 640, 4)
        assert set(buffers) == made and len(made) == 2


def test_a_dead_clients_reply_buffers_are_removed_by_the_server(server: LaunchedServer) -> None:
    script = (
        "import os, sys, numpy as np; sys.path.insert(0, %r); from spear._rpc_client import RpcConnection; "
        "c = RpcConnection(%r); c.request('echo', value=np.ones(1 << 18)); c.request('echo', value=None); "
        "print(os.getpid(), flush=True); os._exit(0)" % (str(Path(spear.__file__).parent.parent), server.address)
    )
    done = subprocess.run([sys.executable, "-c", script], check=True, capture_output=True, text=True)
    pid = done.stdout.strip()
    deadline = time.monotonic() + 10
    while [n for n in os.listdir("/dev/shm") if n.startswith(f"spear-{pid}-")]:
        assert time.monotonic() < deadline, "the server kept a dead client's reply buffers"
        time.sleep(0.01)


def test_the_server_takes_only_the_clients_own_reply_buffers(server: LaunchedServer) -> None:
    # A segment named as if another process's buffer: offered, it must be neither written nor removed.
    foreign = f"/spear-{os.getppid()}-r999"
    fd = os.open("/dev/shm" + foreign, os.O_CREAT | os.O_EXCL | os.O_RDWR, 0o600)
    try:
        os.ftruncate(fd, 1 << 20)
        connection = RpcConnection(server.address)
        reply = connection.request("echo", value=np.full(1 << 18, 7, np.float32), reply_buffers=[[foreign, 1 << 20]])
        assert np.array_equal(reply, np.full(1 << 18, 7, np.float32))
        connection.close()
        with mmap.mmap(fd, 1 << 20) as mapping:
            assert not any(mapping[:])  # untouched
    finally:
        os.close(fd)
        os.unlink("/dev/shm" + foreign)  # still there: the server did not remove it either


def test_a_frame_the_engine_keeps_is_never_overwritten_by_later_arguments() -> None:
    with spear.Instance(server="launch") as instance:
        connection = instance._backend.connection  # type: ignore[attr-defined]
        game = instance.get_game()
        with instance.begin_frame():
            camera = game.spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor
            camera.Width, camera.Height = 512, 512  # 1 MiB of RGBA
            camera.Modalities = [spear.ECameraModality.FinalColor]
        with instance.end_frame():
            camera.read_pixels()
        for _ in range(3):  # frames whose readbacks land in reply buffers once the client has them
            with instance.begin_frame():
                pass
            with instance.end_frame():
                camera.read_pixels()
        with instance.begin_frame():
            pass
        with instance.end_frame():
            first = camera.read_pixels()["final_color"]
            expected = first.copy()
            del first
            for value in range(5):  # same-sized arguments, which could reuse a free buffer
                connection.request("echo", value=np.full((512, 512, 4), value, np.uint8))
            again = camera.read_pixels()["final_color"]  # the frame the engine kept
        assert np.array_equal(again, expected)


def test_a_full_reply_buffer_pool_does_not_churn() -> None:
    """More arrays of one size in flight than the pool may hold: the pool fills up once and then keeps its
    buffers (it never drops a buffer of a size it wants to make room for another of that size)."""
    from spear._reply_buffers import MAX_BUFFERS, ReplyBuffers

    pool = ReplyBuffers()
    try:
        size = 1 << 16
        names = []
        for _ in range(4):
            for _ in range(MAX_BUFFERS + 4):  # this many arrays missed a buffer in one reply
                pool.learn(size)
            pool.offers()
            names.append(set(pool._buffers))  # noqa: SLF001
        assert len(names[0]) == MAX_BUFFERS and names[1] == names[0] and names[3] == names[0]
        # A size nobody wants any more gives way to a wanted one.
        for _ in range(MAX_BUFFERS):
            pool.learn(size * 8)
        pool.offers()
        assert all(b.size >= size * 8 for b in pool._buffers.values())  # noqa: SLF001
    finally:
        pool.close()


class _InlineSegments:
    """What encode() reads of a message's segments when no array is sent: no owner to check objects against."""

    owner = None
    inline = True


def test_a_struct_type_met_before_is_encoded_and_refused_as_the_first_time() -> None:
    # encode() remembers the struct types it met, and their field names, so that later values skip its
    # checks: a later value must encode to the same message and be refused for the same faults.
    segments: Any = _InlineSegments()
    progress = spear.FMoviePipelineProgress(FramesTotal=10, FramesRendered=3, ElapsedSeconds=0.5)
    first = _wire.encode(progress, segments)
    assert first == {field.name: getattr(progress, field.name) for field in dataclasses.fields(progress)}
    assert _wire.encode(progress, segments) == first
    assert spear.FMoviePipelineProgress in _wire._STRUCT_FIELDS  # the later values took the remembered path
    with pytest.raises(_wire.ValueRefused, match=r"^integer 1180591620717411303424 is too large$"):
        _wire.encode(spear.FMoviePipelineProgress(FramesTotal=2**70), segments)
    with pytest.raises(_wire.ValueTooDeep):
        _wire.encode(progress, segments, _wire.MAX_VALUE_DEPTH)
    configuration = spear.FMoviePipelineConfiguration(Modalities=[spear.ECameraModality.Depth])
    for _ in range(2):  # a field that is not plain (a list of enums) is encoded as before, by name
        modalities = _wire.encode(configuration, segments)["Modalities"]
        assert [item.code for item in modalities] == [_wire.EXT_ENUM]
        assert modalities[0].data.endswith(b"ECameraModality")


def test_an_engine_refuses_the_objects_of_another() -> None:
    # A handle names an object only in the engine that made it: sent to another engine it would name
    # whatever that one has under the same number (two servers that made the same objects in the same order
    # give the same handles). Over RPC and in-process alike, it is refused, naming the argument.
    first, second, local = spear.Instance(server="launch"), spear.Instance(server="launch"), spear.Instance()
    try:
        worlds = [engine.create_world(name="Env") for engine in (first, second, local)]
        assert worlds[0] != worlds[1]  # equal handles, different engines
        with first.begin_frame():
            actor = first.get_game().spawn_actor(uclass=spear.AActor)
        with first.end_frame():
            pass
        for engine, foreign in ((second, worlds[0]), (local, worlds[0]), (second, worlds[2])):
            with pytest.raises(spear.InvalidArgumentError,
                               match=r"^destroy_world\(\): UWorld belongs to another engine \(a different "
                                     r"spear.Instance\)$"):
                engine.destroy_world(world=foreign)
        for engine in (second, local):
            with engine.begin_frame():
                with pytest.raises(spear.InvalidArgumentError,
                                   match=r"^UWorld.destroy_actor\(\): argument 'actor': AActor belongs to another "
                                         r"engine \(a different spear.Instance\)$"):
                    engine.get_game().destroy_actor(actor=actor)
            with engine.end_frame():
                pass
        assert len(second.get_worlds()) == len(local.get_worlds()) == 2  # nothing was destroyed
    finally:
        for engine in (first, second, local):
            engine.close()


@pytest.fixture
def two_clients(server: LaunchedServer) -> Iterator[tuple[spear.Instance, spear.Instance]]:
    """Two instances connected to one server: the same engine."""
    first, second = spear.Instance(server=server.address), spear.Instance(server=server.address)
    yield first, second
    first.close()
    second.close()


def test_two_connections_to_one_server_share_its_objects(two_clients: tuple[spear.Instance, spear.Instance]) -> None:
    first, second = two_clients
    with first.begin_frame():
        actor = first.get_game().spawn_actor(uclass=spear.AStaticMeshActor, name="Shared")
    with first.end_frame():
        pass
    with second.begin_frame():
        game = second.get_game()
        assert game.find_actor_by_name(name="Shared") == actor  # the same engine: the same object
        game.set_actor_locations(actors=[actor], locations=np.array([[1.0, 2.0, 3.0]]))
    with second.end_frame():
        pass


def test_clients_taking_turns_see_each_others_frames_ended(two_clients: tuple[spear.Instance, spear.Instance]) -> None:
    # A frame's end is sent without waiting for its reply (read before the client's next request); the server
    # serves the client whose frame is open first, so another client's frame that follows at once is not
    # refused as overlapping it.
    first, second = two_clients
    with first.begin_frame():
        actor = first.get_game().spawn_actor(uclass=spear.AActor, name="Turns")
    with first.end_frame():
        pass
    connection = first._backend.connection  # type: ignore[attr-defined]
    for turn in range(200):
        instance = first if turn % 2 == 0 else second
        with instance.begin_frame():
            pass
        with instance.end_frame():
            if turn % 4 < 2:  # with a read in the block, and without
                assert instance.get_game().find_actor_by_name(name="Turns") == actor
        if instance is first:
            assert connection._posted  # noqa: SLF001 - the end went without a wait
    assert first.frame_count == second.frame_count == 201


def test_an_end_that_failed_after_it_was_sent_is_raised_by_the_next_request(server: LaunchedServer) -> None:
    first, second = spear.Instance(server=server.address), RpcConnection(server.address)
    try:
        with first.begin_frame():
            pass
        with first.end_frame():
            first.get_game()  # the end_frame's opening goes with this request
            second.request("frame", action="end")  # another client ends the frame under it
        with pytest.raises(spear.InvalidStateError, match=r"^end_frame\(\): the engine is idle, expected inside "
                                                          r"end_frame$"):
            with first.begin_frame():
                first.get_game().send_async.spawn_actor(uclass=spear.AActor, name="Dropped")
        with first.begin_frame():  # the engine and the connection go on
            pass
        with first.end_frame():
            assert first.get_game().find_actor_by_name(name="Dropped") is None
    finally:
        first.close()
        second.close()


def test_a_server_address_that_leads_nowhere_says_where_and_what_to_do(tmp_path: Path) -> None:
    missing = tmp_path / "no-server.sock"
    with pytest.raises(spear.NotFoundError, match=rf"Instance\(\): no socket at '{missing}': start a server there "
                                                   rf"\(spear-server --socket {missing}\) or .*server='launch'"):
        spear.Instance(server=f"unix:{missing}")
    stale = tmp_path / "stale.sock"  # a socket file nothing listens on, as an exited server leaves it
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    listener.bind(str(stale))
    listener.close()
    with pytest.raises(ConnectionRefusedError, match=rf"nothing listens on the socket '{stale}'"):
        spear.Instance(server=f"unix:{stale}")
    for bad in ("tcp:localhost", "tcp:localhost:port", "tcp::5000", "tcp:localhost:70000"):
        with pytest.raises(spear.InvalidArgumentError, match=r"'tcp:HOST:PORT' with a port in \[0, 65535\], got"):
            spear.Instance(server=bad)
    with pytest.raises(spear.InvalidArgumentError,
                       match=r"server must be 'launch' \(a server of its own\), 'unix:PATH' or 'tcp:HOST:PORT', "
                             r"got 'lanuch'"):
        spear.Instance(server="lanuch")


def test_spear_server_help_and_bad_command_lines_name_what_is_wrong() -> None:
    binary = str(find_server_binary())
    shown = subprocess.run([binary, "--help"], capture_output=True, text=True, timeout=60)
    assert shown.returncode == 0 and shown.stdout.startswith("usage: spear-server") and shown.stderr == ""
    for args, words in ((["--sockt", "/tmp/x"], "unknown option '--sockt'"),
                        (["--socket"], "--socket needs a value"),
                        ([], "say where to listen: --socket PATH or --port N")):
        result = subprocess.run([binary, *args], capture_output=True, text=True, timeout=60)
        assert result.returncode == 2, args
        assert result.stderr.startswith(f"spear-server: {words}\n") and "usage: spear-server" in result.stderr, args


def test_an_enum_value_is_encoded_with_its_own_enums_name_after_an_equal_value_of_another() -> None:
    # Enum values are encoded once each and remembered: two enums' values that are equal as ints stay two.
    segments: Any = _InlineSegments()
    world, movable = spear.ESplineCoordinateSpace.World, spear.EComponentMobility.Movable
    others = [value for value in spear.EComponentMobility if int(value) == int(world)]
    assert others, "the test needs two enums sharing a value"
    for _ in range(2):
        assert _wire.encode(world, segments).data.endswith(b"ESplineCoordinateSpace")
        assert _wire.encode(others[0], segments).data.endswith(b"EComponentMobility")
        assert _wire.encode(movable, segments).data[:8] == int(movable).to_bytes(8, "little")
