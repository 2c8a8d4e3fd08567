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
you do not trust. A worker's servers read and write files only under `file_roots` (the worker's working
directory when none are given) and the built-in assets.
"""

from __future__ import annotations

import concurrent.futures
import secrets
from collections.abc import Sequence
from typing import Any

from distributed.diagnostics.plugin import WorkerPlugin

from spear._rpc_client import LaunchedServer
from spear.errors import InvalidArgumentError


class _ServerPlugin(WorkerPlugin):
    """The Dask worker plugin that runs spear-servers on a worker, registered under `name` (one per Servers)."""

    def __init__(self, *, name: str, token: str, per_worker: int, fixed_delta_seconds: float,
                 file_roots: Sequence[str] = ()) -> None:
        self.name: str = name
        self.token: str = token
        self.per_worker: int = per_worker
        self.fixed_delta_seconds: float = fixed_delta_seconds
        self.file_roots: list[str] = list(file_roots)
        self.servers: list[LaunchedServer] = []

    def setup(self, worker: Any) -> None:
        # Started together (each waits up to its start-up timeout for its process to listen); if one fails, the
        # others are stopped and the error is the worker's (register_worker_plugin raises it).
        def start() -> LaunchedServer:
            return LaunchedServer(fixed_delta_seconds=self.fixed_delta_seconds, tcp_bind=str(worker.ip),
                                  token=self.token, file_roots=self.file_roots)

        with concurrent.futures.ThreadPoolExecutor(self.per_worker) as pool:
            futures = [pool.submit(start) for _ in range(self.per_worker)]
        self.servers = [f.result() for f in futures if f.exception() is None]
        failure = next((f.exception() for f in futures if f.exception() is not None), None)
        if failure is not None:
            self.teardown(worker)
            raise failure

    def teardown(self, worker: Any) -> None:
        for server in self.servers:
            server.close()
        self.servers = []

    @property
    def addresses(self) -> list[str]:
        return [server.address for server in self.servers]


def _addresses_on_worker(dask_worker: Any, name: str) -> list[str]:
    plugin: _ServerPlugin = dask_worker.plugins[name]
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
        # A name of its own: Dask replaces a plugin registered under a name already taken, which would stop the
        # servers of another Servers on the same cluster.
        self._name = f"spear-servers-{secrets.token_hex(4)}"
        plugin = _ServerPlugin(name=self._name, token=self.token, per_worker=per_worker,
                               fixed_delta_seconds=fixed_delta_seconds, file_roots=file_roots)
        try:
            client.register_worker_plugin(plugin, name=self._name)
            by_worker: dict[str, list[str]] = client.run(_addresses_on_worker, name=self._name)
        except BaseException:
            client.unregister_worker_plugin(self._name)  # the workers whose servers did start stop them
            raise
        self.workers: list[str] = sorted(by_worker)
        """The workers' addresses, in the order their servers appear in `addresses`."""
        self.addresses: list[str] = [address for worker in self.workers for address in by_worker[worker]]
        """The servers' "tcp:HOST:PORT" addresses, per_worker consecutive ones for each worker."""
        self._running = True

    def stop(self) -> None:
        """Stops every worker's servers (clients still connected see their connection lost)."""
        if self._running:
            self._running = False
            self.client.unregister_worker_plugin(self._name)

    def __enter__(self) -> Servers:
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()
