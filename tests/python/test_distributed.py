"""spear.distributed: a spear-server on each worker of a two-worker Dask LocalCluster, environments spread over
them through spear.vector, and the servers gone when the context ends."""

from __future__ import annotations

import itertools
from collections.abc import Iterator

import numpy as np
import pytest

import spear
import spear.distributed
from spear.vector import VectorEnv

distributed = pytest.importorskip("distributed", reason="Debian's python3-distributed (Dask) is not installed")

from test_vector_env import Slide  # noqa: E402  (after the skip: the environment the vector tests use)


@pytest.fixture(scope="module")
def client() -> Iterator[distributed.Client]:
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=40) as cluster, distributed.Client(cluster) as dask_client:
        yield dask_client


def test_each_worker_runs_servers_that_hold_environments(client: distributed.Client) -> None:
    with spear.distributed.Servers(client, per_worker=2) as servers:
        assert len(servers.workers) == 2 and len(servers.addresses) == 4
        assert all(address.startswith("tcp:127.0.0.1:") for address in servers.addresses)
        counter = itertools.count()
        with VectorEnv.on_servers(lambda: Slide(next(counter)), num_servers=4, worlds_per_server=2,
                                  servers=servers.addresses, token=servers.token) as envs:
            observations, _ = envs.reset(seed=0)
            assert observations["position"][:, 0].tolist() == [float(i) for i in range(8)]
            observations, rewards, _, _, _ = envs.step([np.array([0.25], np.float32)] * 8)
            assert rewards.tolist() == [i + 0.25 for i in range(8)]
            assert len({group.instance.server_pid for group in envs._groups}) == 4  # four server processes
        # A wrong token is refused by the workers' servers.
        with pytest.raises(spear.InvalidArgumentError, match="wrong or missing token"):
            spear.Instance(server=servers.addresses[0], token="not-the-token")
    # Stopped with the context: nothing listens at the addresses any more.
    with pytest.raises((spear.ConnectionLostError, OSError)):
        spear.Instance(server=servers.addresses[0], token=servers.token)


def test_two_sets_of_servers_on_one_cluster_keep_to_themselves(client: distributed.Client) -> None:
    with spear.distributed.Servers(client) as first, spear.distributed.Servers(client) as second:
        assert len(first.addresses) == len(second.addresses) == 2
        assert not set(first.addresses) & set(second.addresses)
        for servers in (first, second):  # starting the second did not stop the first's
            for address in servers.addresses:
                spear.Instance(server=address, token=servers.token).close()
