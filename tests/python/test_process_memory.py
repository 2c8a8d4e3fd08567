"""An in-process engine keeps the memory a frame frees, as spear-server does (core/base/process_memory.h), and
the environment's MALLOC_* thresholds win. Each case runs in a Python of its own: the setting is the process's."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

# After an in-process engine starts: three 30 MiB blocks, each under the 32 MiB mmap threshold, freed together
# leave 90 MiB at the top of the heap, which glibc's own settings would hand back (at 64 MiB at most).
PROBE = """
import ctypes, sys
sys.path.insert(0, sys.argv[1])
import spear

class MallInfo2(ctypes.Structure):
    _fields_ = [(name, ctypes.c_size_t) for name in
                ("arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks", "fsmblks", "uordblks", "fordblks",
                 "keepcost")]

libc = ctypes.CDLL("libc.so.6")
libc.mallinfo2.restype = MallInfo2
libc.malloc.restype = ctypes.c_void_p
libc.malloc.argtypes = [ctypes.c_size_t]
libc.free.argtypes = [ctypes.c_void_p]
instance = spear.Instance()
try:
    block = 30 << 20
    before = libc.mallinfo2()
    blocks = [libc.malloc(block) for _ in range(3)]
    for address in blocks:
        ctypes.memset(address, 1, block)
    held = libc.mallinfo2()
    for address in blocks:
        libc.free(address)
    after = libc.mallinfo2()
    print("mapped" if held.hblks > before.hblks else "heap", "kept" if after.arena == held.arena else "trimmed")
finally:
    instance.close()
"""


def probe(**environment: str) -> str:
    env = {k: v for k, v in os.environ.items() if not k.startswith("MALLOC_")} | environment
    done = subprocess.run([sys.executable, "-c", PROBE, str(ROOT / "python")], env=env, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout.strip().splitlines()[-1]


def test_an_in_process_engine_keeps_freed_memory() -> None:
    assert probe() == "heap kept"


@pytest.mark.parametrize("variable", ["MALLOC_TRIM_THRESHOLD_", "MALLOC_MMAP_THRESHOLD_"])
def test_the_environments_thresholds_win(variable: str) -> None:
    # glibc's default of 128 KiB for either: blocks of 30 MiB are mapped on their own, or the heap trimmed.
    assert probe(**{variable: "131072"}) != "heap kept"
