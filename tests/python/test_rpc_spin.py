"""Client and server poll their sockets briefly before they sleep (SPEAR_RPC_SPIN_US; core/rpc/spin_poll.h):
the setting is checked by both, and the transport behaves the same polling or sleeping."""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numpy as np
from numpy.typing import NDArray
import pytest

import spear
from spear._rpc_client import LaunchedServer, RpcConnection, spin_seconds

REFUSAL = r"SPEAR_RPC_SPIN_US must be a whole number of microseconds from 0 to 10000, got 'abc'"


def test_the_client_refuses_a_bad_setting_by_name(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("SPEAR_RPC_SPIN_US", "abc")
    with pytest.raises(spear.InvalidArgumentError, match=rf"Instance\(\): {REFUSAL}"):
        spin_seconds()
    for bad in ("-1", "10001", "1.5", "", "٣"):
        monkeypatch.setenv("SPEAR_RPC_SPIN_US", bad)
        with pytest.raises(spear.InvalidArgumentError, match="SPEAR_RPC_SPIN_US"):
            spin_seconds()


def test_a_launched_server_refuses_a_bad_setting_by_name(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("SPEAR_RPC_SPIN_US", "abc")
    with pytest.raises(spear.InvalidArgumentError, match=rf"spear-server: {REFUSAL}"):
        spear.Instance(server="launch")


def test_the_budget_and_none_on_one_cpu(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("SPEAR_RPC_SPIN_US", "250")
    saved = os.sched_getaffinity(0)
    if len(saved) > 1:
        assert spin_seconds() == pytest.approx(250e-6)
    os.sched_setaffinity(0, {min(saved)})
    try:
        assert spin_seconds() == 0.0
    finally:
        os.sched_setaffinity(0, saved)


def frame_of_calls(spin: str, monkeypatch: pytest.MonkeyPatch) -> tuple[str, list[bool], NDArray[np.uint8]]:
    """Calls one by one and queued, a frame and a camera read over RPC, with both sides' budget `spin`."""
    monkeypatch.setenv("SPEAR_RPC_SPIN_US", spin)
    with spear.Instance(server="launch") as instance:
        game = instance.get_game()
        with instance.begin_frame():
            actor = game.spawn_actor(uclass=spear.AActor, name="Probe")
            camera = game.spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor
            camera.Width, camera.Height = 64, 48
            camera.Modalities = [spear.ECameraModality.FinalColor]
            name = actor.GetName()
            futures = [actor.call_async.ActorHasTag(Tag="t") for _ in range(50)]
        with instance.end_frame():
            image = camera.read_pixels()["final_color"]
        return name, [future.get() for future in futures], image


def test_polling_and_sleeping_behave_the_same(monkeypatch: pytest.MonkeyPatch) -> None:
    sleeping = frame_of_calls("0", monkeypatch)
    polling = frame_of_calls("10000", monkeypatch)
    assert sleeping[:2] == polling[:2] == ("Probe", [False] * 50)
    np.testing.assert_array_equal(sleeping[2], polling[2])


class CountingPoll:
    """A connection's readiness poll, counting the times it is asked."""

    def __init__(self, wrapped: Any) -> None:
        self.wrapped, self.calls = wrapped, 0

    def poll(self, timeout: int) -> list[tuple[int, int]]:
        self.calls += 1
        result: list[tuple[int, int]] = self.wrapped.poll(timeout)
        return result


def test_only_the_main_thread_polls(monkeypatch: pytest.MonkeyPatch) -> None:
    # Threads polling side by side would fight over the GIL (VectorEnv drives each server from a thread).
    monkeypatch.setenv("SPEAR_RPC_SPIN_US", "10000")
    if spin_seconds() == 0.0:
        pytest.skip("this process may run on one CPU only, where nothing polls")
    server = LaunchedServer(fixed_delta_seconds=1 / 60)
    try:
        connection = RpcConnection(server.address)
        counting = CountingPoll(connection._readable)
        connection._readable = counting  # type: ignore[assignment]
        with ThreadPoolExecutor(1) as pool:
            assert pool.submit(connection.request, "echo", value=1).result() == 1
        assert counting.calls == 0
        assert connection.request("echo", value=2) == 2
        assert counting.calls >= 1
        connection.close()
    finally:
        server.close()


def test_replies_that_came_quickly_lately_are_polled_for_longer() -> None:
    from spear._rpc_client import _ADAPTIVE_SPIN_MAX, poll_budget
    assert poll_budget(100e-6, None) == pytest.approx(100e-6)  # nothing known yet: the budget
    assert poll_budget(100e-6, 40e-6) == pytest.approx(100e-6)  # quicker than the budget
    assert poll_budget(100e-6, 600e-6) == pytest.approx(750e-6)  # a physics step: polled through
    assert poll_budget(100e-6, 2 * _ADAPTIVE_SPIN_MAX) == pytest.approx(100e-6)  # a rendered frame: slept through
    assert poll_budget(0.0, 600e-6) == 0.0  # polling off (or one CPU): never


def test_a_connection_learns_how_long_each_kind_of_request_takes() -> None:
    with spear.Instance(server="launch") as instance:
        game = instance.get_game()
        for _ in range(3):
            with instance.begin_frame():
                game.find_actor_by_name(name="Nobody")
            with instance.end_frame():
                pass
        times = instance._backend.connection._reply_times  # type: ignore[attr-defined]
        assert times and all(0.0 < t < 10.0 for t in times.values()), times
        assert any(kind.startswith("batch:begin") for kind in times), times
