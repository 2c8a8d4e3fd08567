"""A request that keeps a shared server's engine for long (a path-traced frame at the largest sample count) does
not leave the other clients waiting unanswered: after a second their requests are answered "busy" (not run),
and SIGTERM ends the frame and the server within a pixel's work, the frame's owner told why."""

from __future__ import annotations

import re
import signal
import threading
import time

import pytest

import spear
from spear._rpc_client import LaunchedServer, RpcConnection


def test_other_clients_are_answered_busy_and_sigterm_ends_a_long_frame() -> None:
    server = LaunchedServer(fixed_delta_seconds=1 / 60)
    owner = spear.Instance(server=server.address)
    other = RpcConnection(server.address)
    game = owner.get_game()
    failures: list[Exception] = []

    def long_frame() -> None:
        try:
            with owner.begin_frame():
                box = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Box",
                                       location=spear.FVector(3.0, 0.0, 0.0))
                box.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
                camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera").CameraSensor
                camera.Width, camera.Height = 320, 240
                camera.Modalities = [spear.ECameraModality.FinalColor]
                camera.Renderer = spear.ECameraRenderer.PathTraced
                camera.SamplesPerPixel, camera.MaxBounces = 65536, 64  # hours of work on a few cores
            with owner.end_frame():
                pass
        except Exception as error:  # noqa: BLE001 (checked below, on the test's thread)
            failures.append(error)

    owner_thread = threading.Thread(target=long_frame)
    try:
        owner_thread.start()
        # Run until the frame starts; once it has kept the engine for a second, answered but not run, not left
        # to time out.
        busy: spear.InvalidStateError | None = None
        for _ in range(6000):
            try:
                assert other.request("echo", value=1) == 1
            except spear.InvalidStateError as error:
                busy = error
                break
            time.sleep(0.01)
        assert busy is not None and re.match(
            r"^spear-server: busy: another client's request has kept the engine for [0-9.]+ s "
            r"\(path tracing 320x240, 65536 samples per pixel\); this request was not run", str(busy)), busy
        with pytest.raises(spear.InvalidStateError, match="busy"):
            other.request("echo", value=2)  # and again: each request is answered
        server.process.send_signal(signal.SIGTERM)
        server.process.wait(30)  # within the frame's next pixel, not after the frame
        owner_thread.join(30)
        assert not owner_thread.is_alive()
        assert len(failures) == 1 and isinstance(failures[0], (spear.InvalidStateError, spear.ConnectionLostError))
        if isinstance(failures[0], spear.InvalidStateError):
            assert "stopped before the frame was traced: the process is shutting down" in str(failures[0])
    finally:
        other.close()
        owner.close()
        server.close()
