"""Shared pytest set-up: the spear package from the source tree, and engine instances per transport."""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))
sys.path.insert(0, str(ROOT))  # for `codegen`

import spear  # noqa: E402

# Every API test runs once per transport, with the same assertions.
TRANSPORTS = ["inprocess", "rpc"]


@pytest.fixture(params=TRANSPORTS)
def instance(request: pytest.FixtureRequest) -> Iterator[spear.Instance]:
    inst = spear.Instance() if request.param == "inprocess" else spear.Instance(server="launch")
    yield inst
    inst.close()


@pytest.fixture(params=TRANSPORTS)
def make_instance(request: pytest.FixtureRequest) -> Iterator[Callable[..., spear.Instance]]:
    """Instance(**options) on the test's transport (a launched spear-server for "rpc"), closed afterwards."""
    made: list[spear.Instance] = []

    def make(**options: Any) -> spear.Instance:
        if request.param == "rpc":
            options["server"] = "launch"
        made.append(spear.Instance(**options))
        return made[-1]

    yield make
    for inst in made:
        inst.close()


@pytest.fixture(autouse=True, scope="session")
def nothing_left_behind() -> Iterator[None]:
    """After the whole suite: no spear-server process of ours and no shared-memory segment remain."""
    import os
    import subprocess

    yield
    children = subprocess.run(["pgrep", "-P", str(os.getpid()), "spear-server"], capture_output=True, text=True)
    assert children.stdout.strip() == "", f"spear-server processes left running: {children.stdout}"
    leftovers = [n for n in os.listdir("/dev/shm") if n.startswith(f"spear-{os.getpid()}-")]
    assert not leftovers, f"shared-memory segments left behind: {leftovers}"
