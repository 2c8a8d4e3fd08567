"""The RPC transport against its floors, measured in the same run on the same machine.

    PYTHONPATH=python /usr/bin/python3 bench/bench_rpc.py [--cpu N]

--cpu N runs this process, the server and the echo process on CPU N only. On a virtual machine a process
waking another on a different vCPU can cost tens of microseconds, and where the scheduler happens to put
the processes then decides a round trip's time more than the protocol does (BENCHMARKS.md, "RPC
transport"); on one CPU both the floor and spear pay only their own work.

- an empty call's round trip vs a raw Unix-socket ping-pong of the same message size (a Python echo
  process with no msgpack and no engine: the least a Python client can pay per round trip); as spear's
  client and server poll their sockets for a while before they sleep (SPEAR_RPC_SPIN_US), so do the
  floor's two sides, and the ping-pong that sleeps at once is printed beside it for what a wake-up costs;
- 10,000 calls in one frame, queued with call_async (one message), vs the same calls made one by one;
- a 1920x1080 RGBA frame from the engine into numpy (read_pixels of a frame already rendered) vs one
  memcpy of the same bytes;
- read_pixels throughput (render + transfer) at latency 0, 1, 2;
- the same 1920x1080 frame over TCP to a client that cannot map the server's shared memory (as on another
  host: the reply carries it inline) vs a raw TCP socket sending the same bytes to a Python client that
  receives them into one buffer.
"""

from __future__ import annotations

import os
import select
import socket
import struct
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402
from spear._rpc_client import RpcConnection, find_server_binary, spin_seconds  # noqa: E402

# The echo polls for up to argv[2] seconds before it sleeps in recv, as spear's server does (spin_poll.h).
ECHO = """
import os, select, socket, struct, sys, time
s = socket.socket(socket.AF_UNIX); s.bind(sys.argv[1]); s.listen(1); print("ready", flush=True)
c, _ = s.accept()
readable = select.poll(); readable.register(c, select.POLLIN); spin = float(sys.argv[2])
while True:
    deadline = time.perf_counter() + spin
    while spin and not readable.poll(0) and time.perf_counter() < deadline:
        os.sched_yield()
    h = c.recv(4, socket.MSG_WAITALL)
    if len(h) < 4: break
    n = struct.unpack("<I", h)[0]
    body = c.recv(n, socket.MSG_WAITALL)
    c.sendall(h + body)
"""


def best(fn, repeat: int = 5) -> float:  # type: ignore[no-untyped-def]
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def raw_ping_pong_us(message_bytes: int, rounds: int, directory: str, spin: float) -> float:
    """A round trip to a Python echo process; both sides poll for up to `spin` seconds before they sleep."""
    path = os.path.join(directory, f"echo-{spin}.sock")
    echo = subprocess.Popen([sys.executable, "-c", ECHO, path, str(spin)], stdout=subprocess.PIPE, text=True)
    assert echo.stdout is not None
    echo.stdout.readline()
    sock = socket.socket(socket.AF_UNIX)
    sock.connect(path)
    frame = struct.pack("<I", message_bytes) + b"x" * message_bytes
    readable = select.poll()
    readable.register(sock, select.POLLIN)

    def run() -> None:
        for _ in range(rounds):
            sock.sendall(frame)
            deadline = time.perf_counter() + spin
            while spin and not readable.poll(0) and time.perf_counter() < deadline:
                os.sched_yield()
            header = sock.recv(4, socket.MSG_WAITALL)
            sock.recv(struct.unpack("<I", header)[0], socket.MSG_WAITALL)

    seconds = best(run)
    sock.close()
    echo.wait(5)
    return seconds / rounds * 1e6

# Sends argv[2] bytes each time a 4-byte request arrives, over TCP: the floor of a frame sent inline.
TCP_SENDER = """
import socket, struct, sys
s = socket.socket(); s.bind(("127.0.0.1", 0)); s.listen(1); print(s.getsockname()[1], flush=True)
c, _ = s.accept(); c.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
payload = struct.pack("<I", int(sys.argv[2])) + bytes(int(sys.argv[2]))
while len(c.recv(4, socket.MSG_WAITALL)) == 4:
    c.sendall(payload)
"""


def tcp_frame_floor_s(size: int) -> float:
    """A raw TCP round trip that brings `size` bytes into one buffer, best of a few."""
    sender = subprocess.Popen([sys.executable, "-c", TCP_SENDER, "", str(size)], stdout=subprocess.PIPE, text=True)
    try:
        assert sender.stdout is not None
        port = int(sender.stdout.readline())
        sock = socket.create_connection(("127.0.0.1", port))
        sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        buffer = bytearray(size)

        def round_trip() -> None:
            sock.sendall(b"\0\0\0\0")
            (length,) = struct.unpack("<I", sock.recv(4, socket.MSG_WAITALL))
            view, received = memoryview(buffer), 0
            while received < length:
                received += sock.recv_into(view[received:], length - received)
            np.frombuffer(buffer, np.uint8)

        result = best(round_trip, repeat=20)
        sock.close()
        return result
    finally:
        sender.wait(10)


def inprocess_read_pixels_s() -> float:
    """The same read of a rendered 1920x1080 frame in-process: the engine's own part of the rows above."""
    with spear.Instance() as instance:
        with instance.begin_frame():
            camera = instance.get_game().spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor
            camera.Width, camera.Height = 1920, 1080
            camera.Modalities = [spear.ECameraModality.FinalColor]
            camera.bShadows = False
            camera.AntiAliasingMethod = spear.EAntiAliasingMethod.AAM_None
        with instance.end_frame():
            camera.read_pixels()
            return best(lambda: camera.read_pixels()["final_color"], repeat=20)


def tcp_inline_read_pixels_s() -> float:
    """read_pixels of a rendered 1920x1080 frame over TCP by a client that did not prove it maps the server's
    memory (as a client on another host): the reply carries the frame inline."""
    token = "bench"
    server = subprocess.Popen([str(find_server_binary()), "--port", "0", "--token", token, "--exit-with-parent"],
                              stdout=subprocess.PIPE, text=True)
    original = RpcConnection._prove_shared_memory
    try:
        assert server.stdout is not None
        address = server.stdout.readline().strip().removeprefix("spear-server: listening on ")
        RpcConnection._prove_shared_memory = lambda self, name: False  # type: ignore[assignment]
        with spear.Instance(server=address, token=token) as instance:
            assert not instance._backend.connection.shared_memory  # type: ignore[attr-defined]
            with instance.begin_frame():
                camera = instance.get_game().spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor
                camera.Width, camera.Height = 1920, 1080
                camera.Modalities = [spear.ECameraModality.FinalColor]
                camera.bShadows = False
                camera.AntiAliasingMethod = spear.EAntiAliasingMethod.AAM_None  # as above: the transfer alone
            with instance.end_frame():
                camera.read_pixels()
                return best(lambda: camera.read_pixels()["final_color"], repeat=20)
    finally:
        RpcConnection._prove_shared_memory = original  # type: ignore[assignment]
        server.terminate()
        server.wait(10)


def main() -> None:
    import argparse
    import tempfile

    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--cpu", type=int, help="run everything on this CPU (inherited by the processes started)")
    options = parser.parse_args()
    if options.cpu is not None:
        os.sched_setaffinity(0, {options.cpu})
        print(f"pinned to CPU {options.cpu}")

    rounds = 2000
    with spear.Instance(server="launch") as instance, tempfile.TemporaryDirectory() as tmp:
        connection: RpcConnection = instance._backend.connection  # type: ignore[attr-defined]
        game = instance.get_game()
        with instance.begin_frame():
            actor = game.spawn_actor(uclass=spear.AActor, name="A")
        with instance.end_frame():
            pass

        # Message sizes, to give the raw ping-pong the same payload.
        from spear._wire import OutgoingSegments, encode, pack_frame
        from spear._rpc_client import _HandleRef

        (call_frame,) = pack_frame({"id": 1, "op": "call", "object": encode(_HandleRef((1, 0)), OutgoingSegments()),
                                    "function": "GetName", "args": {}, "context": "UObject.GetName()"})
        # The floor does what spear does: with spear polling before it sleeps (SPEAR_RPC_SPIN_US), so does
        # the floor; the sleeping ping-pong shows what a wake-up costs on this machine.
        spin = spin_seconds()
        sleeping_us = raw_ping_pong_us(len(call_frame) - 4, rounds, tmp, 0.0)
        floor_us = raw_ping_pong_us(len(call_frame) - 4, rounds, tmp, spin) if spin else sleeping_us
        echo_us = best(lambda: [connection.request("echo", value=None) for _ in range(rounds)]) / rounds * 1e6
        with instance.begin_frame():
            call_us = best(lambda: [actor.GetName() for _ in range(rounds)]) / rounds * 1e6
        with instance.end_frame():
            pass
        print(f"round trip, {len(call_frame)}-byte request")
        if spin:
            print(f"  raw ping-pong, sleeping in recv     {sleeping_us:8.1f} us")
            print(f"  raw ping-pong, polling {spin * 1e6:4.0f} us first {floor_us:8.1f} us   (floor, as spear)")
        else:
            print(f"  raw Unix-socket ping-pong (floor)   {floor_us:8.1f} us")
        print(f"  echo op (transport + dispatch)      {echo_us:8.1f} us   {echo_us / floor_us:5.2f}x floor")
        print(f"  typed call actor.GetName()          {call_us:8.1f} us   {call_us / floor_us:5.2f}x floor")

        # A frame with no work: the frame protocol alone (its begin rides with the block's first message, the
        # execution with the calls queued in the block, end_frame's opening with its first read).
        frames = 1000
        sent = connection.messages_sent
        frame_us = best(lambda: instance.step(num_frames=frames), repeat=3) / frames * 1e6
        messages = (connection.messages_sent - sent) / (3 * frames)
        print(f"empty frame (begin_frame + end_frame), {messages:.0f} messages")
        print(f"  over RPC                            {frame_us:8.1f} us   {frame_us / floor_us:5.2f}x floor")

        n = 10_000
        with instance.begin_frame():
            start = time.perf_counter()
            for i in range(n):
                actor.ActorHasTag(Tag="t")
            sync_s = time.perf_counter() - start
            start = time.perf_counter()
            futures = [actor.call_async.ActorHasTag(Tag="t") for _ in range(n)]
            connection.flush()
            batched_s = time.perf_counter() - start
        with instance.end_frame():
            assert not any(f.get() for f in futures)
        print(f"{n} calls in one frame")
        print(f"  one by one                          {n / sync_s:8.0f} calls/s")
        print(f"  call_async, one message             {n / batched_s:8.0f} calls/s   {sync_s / batched_s:5.1f}x faster")

        with instance.begin_frame():
            camera = game.spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor
            camera.Width, camera.Height = 1920, 1080
            camera.Modalities = [spear.ECameraModality.FinalColor]
            camera.bShadows = False
            # FXAA (the default) runs on every read of a frame, as the image leaves the renderer: off, so that
            # a later read of the frame is the transfer alone, which this row measures.
            camera.AntiAliasingMethod = spear.EAntiAliasingMethod.AAM_None
        with instance.end_frame():
            camera.read_pixels()  # the first read performs the GPU readback; later reads of the frame only transfer
            transfer_s = best(lambda: camera.read_pixels()["final_color"], repeat=20)
        # Real bytes (an untouched np.empty source reads the kernel's one zero page, which flatters the floor)
        # into memory written before.
        frame = np.full((1080, 1920, 4), 7, np.uint8)
        target = np.zeros_like(frame)
        memcpy_s = best(lambda: np.copyto(target, frame), repeat=20)
        print("1920x1080 RGBA frame into numpy (8.3 MB)")
        print(f"  one memcpy (floor)                  {memcpy_s * 1e3:8.2f} ms")
        print(f"  read_pixels over RPC                {transfer_s * 1e3:8.2f} ms   {transfer_s / memcpy_s:5.2f}x floor")
        inprocess_s = inprocess_read_pixels_s()
        print(f"  read_pixels in-process              {inprocess_s * 1e3:8.2f} ms   {inprocess_s / memcpy_s:5.2f}x floor"
              f"   (RPC {transfer_s / inprocess_s:4.2f}x in-process)")
        inline_s, tcp_floor_s = tcp_inline_read_pixels_s(), tcp_frame_floor_s(1920 * 1080 * 4)
        print("the same frame over TCP, inline (a client that cannot map the server's memory)")
        print(f"  raw TCP socket, same bytes (floor)  {tcp_floor_s * 1e3:8.2f} ms")
        print(f"  read_pixels over TCP, inline        {inline_s * 1e3:8.2f} ms   {inline_s / tcp_floor_s:5.2f}x floor")

        print("read_pixels throughput at 256x256, final colour, render + transfer (llvmpipe)")
        with instance.begin_frame():
            camera.Width, camera.Height = 256, 256
        with instance.end_frame():
            pass
        for latency in (0, 1, 2):
            with instance.begin_frame():
                camera.Latency = latency
            with instance.end_frame():
                pass
            frames = 20
            start = time.perf_counter()
            for _ in range(frames):
                with instance.begin_frame():
                    pass
                with instance.end_frame():
                    camera.read_pixels()
            per_frame = (time.perf_counter() - start) / frames
            print(f"  latency {latency}                           {per_frame * 1e3:8.1f} ms/frame  {1 / per_frame:6.1f} fps")


if __name__ == "__main__":
    main()
