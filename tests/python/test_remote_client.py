"""A client that cannot map the server's shared memory (on another host, or with a /dev/shm of its own) gets
large replies inline: shared memory is an optimisation each connection proves it can use (the server's hello
names a segment holding a nonce; shm_proof sends back what the client read), never assumed.

The remote client is simulated on this machine: a Python process in a mount namespace of its own with a fresh
tmpfs on /dev/shm (unshare), talking to a TCP server outside it. Where namespaces are not permitted, that test
is skipped and says why."""

from __future__ import annotations

import mmap
import os
import shutil
import subprocess
import sys
import textwrap
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

import spear
from spear._rpc_client import RpcConnection, _encode_fields, find_server_binary
from spear._wire import pack_frame

TOKEN = "remote-test-token"
PYTHON_DIR = Path(spear.__file__).resolve().parent.parent


@pytest.fixture
def tcp_server() -> Iterator[str]:
    process = subprocess.Popen([str(find_server_binary()), "--port", "0", "--token", TOKEN, "--exit-with-parent"],
                               stdout=subprocess.PIPE, text=True)
    try:
        assert process.stdout is not None
        address = process.stdout.readline().strip().removeprefix("spear-server: listening on ")
        assert address.startswith("tcp:127.0.0.1:"), address
        yield address
    finally:
        process.terminate()
        process.wait(10)


def root_buffer(array: NDArray[Any]) -> object:
    base: object = array
    while isinstance(base, np.ndarray) and base.base is not None:
        base = base.base
    return base.obj if isinstance(base, memoryview) else base


def own_shm_namespace_permitted() -> str | None:
    """None where a process can get a mount namespace with its own /dev/shm here, else why not."""
    if shutil.which("unshare") is None:
        return "no unshare(1) on this machine"
    probe = subprocess.run(["unshare", "--mount", "sh", "-c", "mount -t tmpfs tmpfs /dev/shm"],
                           capture_output=True, text=True, timeout=30)
    if probe.returncode != 0:
        return f"mount namespaces are not permitted here: {probe.stderr.strip()}"
    return None


# What a client on another host does (here and in test_two_hosts.py): large arrays both ways, every modality of a
# 1080p camera, a typed call with array arguments and results; nothing of the server's shared memory.
REMOTE_CLIENT = textwrap.dedent("""
    import os, sys
    import numpy as np
    import spear
    address, token = sys.argv[1], sys.argv[2]
    assert os.listdir("/dev/shm") == [], "the namespace's /dev/shm should start empty"
    with spear.Instance(server=address, token=token) as instance:
        connection = instance._backend.connection
        assert connection.shared_memory is False
        rng = np.random.default_rng(1)
        for size in (100 * 1024, 8 * 1024 * 1024 + 3):  # large arguments and results, raw in the frames' tails
            big = rng.integers(0, 255, size=size, dtype=np.uint8)
            assert np.array_equal(connection.request("echo", value=big), big)
        game = instance.get_game()
        with instance.begin_frame():
            game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun")
            cube = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Cube",
                                    location=spear.FVector(3.0, 0.0, 0.0))
            cube.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
            camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera").CameraSensor
            camera.Width, camera.Height = 1920, 1080
            camera.Modalities = list(spear.ECameraModality)
        with instance.end_frame():
            pixels = camera.read_pixels()
        assert len(pixels) == len(list(spear.ECameraModality)), sorted(pixels)
        color = pixels["final_color"]
        assert color.shape == (1080, 1920, 4) and int(color[540, 960, 3]) == 255
        assert int((pixels["object_ids"] != 0).sum()) > 1000  # the cube is in view
        points = rng.uniform(0, 1000, size=(200000, 2))  # 3.2 MB in, 3.2 MB out
        with instance.begin_frame():
            undistorted = camera.UndistortPixels(Points=points)
        with instance.end_frame():
            pass
        assert undistorted.shape == points.shape and np.allclose(undistorted, points)
    assert os.listdir("/dev/shm") == [], os.listdir("/dev/shm")
    print("remote client ok")
""")


def test_a_client_with_its_own_shared_memory_gets_every_reply_inline(tcp_server: str) -> None:
    why = own_shm_namespace_permitted()
    if why is not None:
        pytest.skip(why)
    script = f"mount -t tmpfs tmpfs /dev/shm && exec {sys.executable} -c \"$0\" \"$@\""
    env = dict(os.environ, PYTHONPATH=str(PYTHON_DIR))
    result = subprocess.run(["unshare", "--mount", "sh", "-c", script, REMOTE_CLIENT, tcp_server, TOKEN],
                            capture_output=True, text=True, timeout=300, env=env)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "remote client ok" in result.stdout


def test_a_client_on_the_servers_host_proves_it_and_gets_shared_memory(tcp_server: str) -> None:
    connection = RpcConnection(tcp_server, token=TOKEN)
    try:
        assert connection.shared_memory is True
        frame = np.ones((512, 512), np.float32)
        echoed = connection.request("echo", value=frame)
        assert np.array_equal(echoed, frame) and isinstance(root_buffer(echoed), mmap.mmap)
    finally:
        connection.close()


def test_a_wrong_proof_keeps_replies_inline_and_leaves_no_segment(tcp_server: str,
                                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    sent: list[bool] = []

    def wrong_proof(self: RpcConnection, name: str) -> bool:
        sent.append(bool(self.request("shm_proof", nonce="0" * 32)))
        return sent[-1]

    monkeypatch.setattr(RpcConnection, "_prove_shared_memory", wrong_proof)
    before = set(os.listdir("/dev/shm"))
    connection = RpcConnection(tcp_server, token=TOKEN)
    try:
        assert sent == [False] and connection.shared_memory is False
        frame = np.arange(1 << 16, dtype=np.float64)
        echoed = connection.request("echo", value=frame)
        assert np.array_equal(echoed, frame) and not isinstance(root_buffer(echoed), mmap.mmap)
        # The probe was removed with the proof: nothing of the server's is left.
        assert not [n for n in set(os.listdir("/dev/shm")) - before if n.startswith("spear-")]
        assert connection.request("shm_proof", nonce="") is False  # a second try without a probe: still off
    finally:
        connection.close()


def test_inline_replies_carry_several_arrays_exactly_reply_after_reply(tcp_server: str,
                                                                        monkeypatch: pytest.MonkeyPatch) -> None:
    """Arrays of odd sizes in one inline reply (each at its aligned place in the tail, padding between) and
    replies that grow and shrink: the server builds each frame in the memory of the last one."""
    monkeypatch.setattr(RpcConnection, "_prove_shared_memory", lambda self, name: False)
    connection = RpcConnection(tcp_server, token=TOKEN)
    try:
        assert connection.shared_memory is False
        rng = np.random.default_rng(7)
        for sizes in [(70_001, 3, 1 << 20), (1 << 22, 65_537), (100_000,), (5_000_003, 9, 131_071)]:
            arrays = [rng.integers(0, 255, size=n, dtype=np.uint8) for n in sizes]
            arrays.append(rng.standard_normal(len(arrays) * 40_000))  # float64 beside the bytes
            echoed = connection.request("echo", value=arrays)
            assert len(echoed) == len(arrays)
            for sent, got in zip(arrays, echoed):
                assert got.dtype == sent.dtype and np.array_equal(got, sent)
    finally:
        connection.close()


def test_inline_replies_the_socket_does_not_take_at_once_arrive_whole_and_in_order(
        tcp_server: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """Two large echoes sent before either reply is read: the socket takes only part of the first reply (the
    server sends the arrays from their own memory), the rest waits in the server's outbox, copied, and the
    second queues behind it; both arrive whole and in order once the client reads."""
    monkeypatch.setattr(RpcConnection, "_prove_shared_memory", lambda self, name: False)
    connection = RpcConnection(tcp_server, token=TOKEN)
    try:
        assert connection.shared_memory is False
        rng = np.random.default_rng(11)
        arrays = [rng.integers(0, 255, size=12_000_001, dtype=np.uint8), rng.standard_normal(1_500_000)]
        ids = []
        for array in arrays:
            segments = connection._segments()
            outgoing = {"id": next(connection._ids), "op": "echo",
                        **_encode_fields("echo", {"value": array}, segments)}
            connection._send(pack_frame(outgoing, segments))
            ids.append(outgoing["id"])
        time.sleep(0.5)  # the server has answered both meanwhile: more than the socket holds
        for array, request_id in zip(arrays, ids):
            reply = connection._read_reply(None)
            assert reply["id"] == request_id
            echoed = reply["ok"]
            assert echoed.dtype == array.dtype and np.array_equal(echoed, array)
        assert np.array_equal(connection.request("echo", value=arrays[1]), arrays[1])  # and it serves on
    finally:
        connection.close()
