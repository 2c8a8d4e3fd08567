"""Shared pytest set-up: the spear package from the source tree, and engine instances per transport."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))
sys.path.insert(0, str(ROOT))  # for `codegen`

import spear  # noqa: E402

# Every API test runs once per transport. The RPC transport joins this list when spear-server exists.
TRANSPORTS = ["inprocess"]


@pytest.fixture(params=TRANSPORTS)
def instance(request: pytest.FixtureRequest) -> Iterator[spear.Instance]:
    inst = spear.Instance()
    yield inst
    inst.close()
