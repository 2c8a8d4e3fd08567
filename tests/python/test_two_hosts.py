"""spear across two hosts, made on this machine: a network namespace of the test's own (with a mount namespace
and an empty /dev/shm of its own inside), joined to this one by a veth pair with link-local addresses, so the
"other host" reaches the server only over TCP and cannot map its memory. On the plain transport (a client there,
the server here) and through spear.distributed (a Dask worker there, its spear-server with it, the environments'
client here). The namespace and its link are removed afterwards; where network namespaces are not permitted
(no iproute2, no CAP_NET_ADMIN) the tests are skipped and say why."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

import spear
from spear._rpc_client import RpcConnection, find_server_binary
from test_remote_client import REMOTE_CLIENT, own_shm_namespace_permitted

TOKEN = "two-hosts-token"
PYTHON_DIR = Path(spear.__file__).resolve().parent.parent


@dataclass(frozen=True)
class OtherHost:
    namespace: str
    here: str   # this namespace's address on the link
    there: str  # the other namespace's

    def run(self, *command: str, stdout: int | None = None, stderr: int | None = None,
            env: dict[str, str] | None = None) -> subprocess.Popen[str]:
        """A process in the other namespace, with its own /dev/shm (an empty tmpfs)."""
        script = 'mount -t tmpfs tmpfs /dev/shm && exec "$@"'
        return subprocess.Popen(["ip", "netns", "exec", self.namespace, "unshare", "--mount", "sh", "-c", script,
                                 "sh", *command], text=True, stdout=stdout, stderr=stderr, env=env)


def _ip(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(["ip", *args], capture_output=True, text=True, timeout=30, check=False)


@pytest.fixture
def other_host() -> Iterator[OtherHost]:
    if shutil.which("ip") is None or shutil.which("unshare") is None:
        pytest.skip("no ip(8) or unshare(1) on this machine (iproute2, util-linux)")
    why = own_shm_namespace_permitted()  # the other host's own /dev/shm
    if why is not None:
        pytest.skip(why)
    name = f"spear-{os.getpid()}"
    made = _ip("netns", "add", name)
    if made.returncode != 0:
        pytest.skip(f"network namespaces are not permitted here: {made.stderr.strip()}")
    # A /30 of the link-local range per test process: nothing else routes there.
    pid = os.getpid()
    third, fourth = pid % 250 + 1, (pid // 250) % 63 * 4
    here, there = f"169.254.{third}.{fourth + 1}", f"169.254.{third}.{fourth + 2}"
    host_link = f"sp{os.getpid() % 100000}h"
    try:
        for args in (["link", "add", host_link, "type", "veth", "peer", "name", "eth0", "netns", name],
                     ["addr", "add", f"{here}/30", "dev", host_link], ["link", "set", host_link, "up"],
                     ["-n", name, "addr", "add", f"{there}/30", "dev", "eth0"], ["-n", name, "link", "set", "eth0", "up"],
                     ["-n", name, "link", "set", "lo", "up"]):
            result = _ip(*args)
            if result.returncode != 0:
                pytest.skip(f"cannot link a network namespace here (ip {' '.join(args)}): {result.stderr.strip()}")
        yield OtherHost(name, here, there)
    finally:
        _ip("netns", "del", name)  # takes its end of the veth pair, and so the pair, with it
        _ip("link", "del", host_link)




def test_a_client_on_another_host_reads_every_modality_and_sends_large_arrays(other_host: OtherHost) -> None:
    server = subprocess.Popen([str(find_server_binary()), "--port", "0", "--bind", other_host.here, "--token", TOKEN,
                               "--exit-with-parent"], stdout=subprocess.PIPE, text=True)
    try:
        assert server.stdout is not None
        address = server.stdout.readline().strip().removeprefix("spear-server: listening on ")
        assert address.startswith(f"tcp:{other_host.here}:"), address
        client = other_host.run(sys.executable, "-c", REMOTE_CLIENT, address, TOKEN, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, env=dict(os.environ, PYTHONPATH=str(PYTHON_DIR)))
        out, err = client.communicate(timeout=300)
        assert client.returncode == 0, out + err
        assert "remote client ok" in out
    finally:
        server.terminate()
        server.wait(10)


def test_a_dask_worker_on_another_host_serves_environments_to_this_one(other_host: OtherHost) -> None:
    distributed = pytest.importorskip("distributed", reason="Debian's python3-distributed (Dask) is not installed")
    import spear.distributed

    scheduler = subprocess.Popen(["dask-scheduler", "--host", other_host.here, "--port", "0",
                                  "--dashboard-address", ":0", "--no-show"],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    worker: subprocess.Popen[str] | None = None
    try:
        assert scheduler.stderr is not None
        address = ""
        deadline = time.monotonic() + 60
        while not address and time.monotonic() < deadline:  # "Scheduler at: tcp://169.254.x.1:port"
            line = scheduler.stderr.readline()
            if "Scheduler at:" in line:
                address = line.split("Scheduler at:")[1].strip()
        assert address, "the Dask scheduler did not say where it listens"
        worker = other_host.run("dask-worker", address, "--host", other_host.there, "--nthreads", "1",
                                "--no-dashboard", stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                env=dict(os.environ, PYTHONPATH=str(PYTHON_DIR)))
        with distributed.Client(address, timeout=60) as client:
            client.wait_for_workers(1, timeout=120)
            with spear.distributed.Servers(client, per_worker=1) as servers:
                (server_address,) = servers.addresses
                assert server_address.startswith(f"tcp:{other_host.there}:"), server_address
                with spear.Instance(server=server_address, token=servers.token) as instance:
                    connection = instance._backend.connection  # type: ignore[attr-defined]
                    assert isinstance(connection, RpcConnection) and connection.shared_memory is False
                    game = instance.get_game()
                    with instance.begin_frame():
                        camera = game.spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor
                        camera.Width, camera.Height = 1920, 1080
                        camera.Modalities = [spear.ECameraModality.FinalColor, spear.ECameraModality.Depth]
                    with instance.end_frame():
                        pixels = camera.read_pixels()
                    assert pixels["final_color"].shape == (1080, 1920, 4)
                    assert pixels["depth"].shape == (1080, 1920)
                    array = np.arange(3_000_000, dtype=np.float32)
                    assert np.array_equal(connection.request("echo", value=array), array)
    finally:
        if worker is not None:
            worker.terminate()
            worker.wait(30)
        scheduler.terminate()
        scheduler.wait(30)
