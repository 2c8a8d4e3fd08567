"""spear across machines on Dask: a spear-server on every Dask worker, for vectorised environments.

    from dask.distributed import Client
    import spear.distributed
    from spear.vector import VectorEnv

    client = Client("tcp://scheduler:8786")            # any Dask cluster; LocalCluster() on one machine
    with spear.distributed.Servers(client, per_worker=1) as servers:
        envs = VectorEnv.on_servers(PushPuck, num_servers=len(servers.addresses), worlds_per_server=8,
                                    servers=servers.addresses, token=servers.token)
        ...

Servers registers a Dask worker plugin: each worker starts `per_worker` spear-server processes listening on TCP
at the worker's own address (127.0.0.1 on a LocalCluster), with a token made for this session, and stops them
when the plugin is removed or the worker goes (a server exits with its worker process). A worker that joins
later starts its servers too, but `addresses` lists the servers that were running when Servers started.

The environments' Python code runs where the Servers context does; each environment's calls and observations
travel straight between that process and the server holding its world, not through the scheduler. The token
reaches the workers inside the plugin, over Dask's own connections: use a cluster with TLS across networks
you do not trust. A worker's servers read and write files only under its working directory and `file_roots`.
"""

from __future__ import annotations

import secrets
from collections.abc import Sequence
from typing import Any

from spear._rpc_client import LaunchedServer
from spear.errors import InvalidArgumentError

PLUGIN_NAME = "spear-servers"


class ServerPlugin:
    """The Dask worker plugin (distributed.WorkerPlugin's protocol) that runs spear-servers on a worker."""

    name = PLUGIN_NAME

    def __init__(self, *, token: str, per_worker: int, fixed_delta_seconds: float,
                 file_roots: Sequence[str] = ()) -> None:
        self.token: str = token
        self.per_worker: int = per_worker
        self.fixed_delta_seconds: float = fixed_delta_seconds
        self.file_roots: list[str] = list(file_roots)
        self.servers: list[LaunchedServer] = []

    def setup(self, worker: Any) -> None:
        host = str(worker.ip)
        self.servers = [LaunchedServer(fixed_delta_seconds=self.fixed_delta_seconds, tcp_bind=host, token=self.token,
                                       file_roots=self.file_roots) for _ in range(self.per_worker)]

    def teardown(self, worker: Any) -> None:
        for server in self.servers:
            server.close()
        self.servers = []

    @property
    def addresses(self) -> list[str]:
        return [server.address for server in self.servers]


def _addresses_on_worker(dask_worker: Any) -> list[str]:
    plugin: ServerPlugin = dask_worker.plugins[PLUGIN_NAME]
    return plugin.addresses


class Servers:
    """spear-servers on every worker of a Dask cluster, while the context is open (or until stop())."""

    def __init__(self, client: Any, *, per_worker: int = 1, fixed_delta_seconds: float = 1.0 / 60.0,
                 file_roots: Sequence[str] = ()) -> None:
        """client: a distributed.Client. per_worker: servers started on each worker (one per core it may use)."""
        if per_worker < 1:
            raise InvalidArgumentError(f"spear.distributed.Servers(): per_worker must be >= 1, got {per_worker}")
        self.client: Any = client
        self.token: str = secrets.token_hex(16)
        plugin = ServerPlugin(token=self.token, per_worker=per_worker, fixed_delta_seconds=fixed_delta_seconds,
                              file_roots=file_roots)
        client.register_worker_plugin(plugin, name=PLUGIN_NAME)
        by_worker: dict[str, list[str]] = client.run(_addresses_on_worker)
        self.workers: list[str] = sorted(by_worker)
        """The workers' addresses, in the order their servers appear in `addresses`."""
        self.addresses: list[str] = [address for worker in self.workers for address in by_worker[worker]]
        """The servers' "tcp:HOST:PORT" addresses, per_worker consecutive ones for each worker."""
        self._running = True

    def stop(self) -> None:
        """Stops every worker's servers (clients still connected see their connection lost)."""
        if self._running:
            self._running = False
            self.client.unregister_worker_plugin(PLUGIN_NAME)

    def __enter__(self) -> Servers:
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()
