"""`spear-server` on PATH (an installed package's console script): runs the server binary the package
carries, with the same arguments."""

from __future__ import annotations

import os
import sys

from spear._rpc_client import find_server_binary


def main() -> None:
    binary = str(find_server_binary())
    os.execv(binary, [binary, *sys.argv[1:]])
