"""Progress of the engine's long work (importing a mesh, loading a scene, building navigation), reported by
core/base/progress.h: in-process through the engine's sink, over RPC as "[spear-progress]" lines on the
launched server's stderr (spear/_logging.py reads them).

In a terminal each task is a tqdm bar on stderr while it runs. Whatever the output, a task's end is an INFO
record of the "spear" logger ("...: done in 4.2 s"). Setting the "spear" logger above INFO silences both.
Work that ends within half a second reports nothing.
"""

from __future__ import annotations

import importlib
import shutil
import sys
import threading
import time
from typing import Any

from spear import _logging

_LOCK = threading.Lock()
_BARS: dict[str, Any] = {}  # task -> its tqdm bar (or None where no bar is shown)
_STARTED: dict[str, float] = {}


def _bar(task: str, total: float) -> Any:
    if not sys.stderr.isatty() or not _logging.enabled():
        return None
    try:  # Debian's python3-tqdm (untyped); without it, only the end is logged
        tqdm: Any = importlib.import_module("tqdm").tqdm
    except ImportError:
        return None
    # In percent, whatever the task counts (a fraction, actors, tiles); as wide as the terminal says it is.
    return tqdm(total=100, desc=task, leave=False, ncols=shutil.get_terminal_size((100, 24)).columns,
                bar_format="{desc} {percentage:3.0f}%|{bar}| {elapsed}<{remaining}")


def report(task: str, done: float, total: float, finished: bool) -> None:
    """One report of `task`: `done` of `total`, `finished` once, last."""
    with _LOCK:
        if task not in _STARTED:
            # Reports start half a second into the work (core/base/progress.h).
            _STARTED[task] = time.monotonic() - 0.5
            _BARS[task] = _bar(task, total)
        bar = _BARS[task]
        if bar is not None:
            bar.n = round(100 * min(done, total) / total) if total > 0 else 0
            bar.refresh()
        if not finished:
            return
        if bar is not None:
            bar.close()
        elapsed = time.monotonic() - _STARTED.pop(task)
        del _BARS[task]
    _logging.info(f"{task}: done in {elapsed:.1f} s" if done >= total else f"{task}: stopped at "
                  f"{done:g} of {total:g} after {elapsed:.1f} s")


def abandon_unfinished() -> None:
    """Closes the bars of tasks that will never finish (their server is gone)."""
    with _LOCK:
        for bar in _BARS.values():
            if bar is not None:
                bar.close()
        _BARS.clear()
        _STARTED.clear()
