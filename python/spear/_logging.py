"""The engine's log lines as Python logging records, on the logger named "spear".

Each line keeps its C++ source file and line (record.pathname, record.lineno) and is logged at INFO.
Until the program configures logging (a handler anywhere above the "spear" logger, or a level set on it),
lines are printed to stderr as the engine prints them ("[spear] gl_context.cpp:228: ..."), so nothing is
lost by default; `logging.getLogger("spear").setLevel(logging.WARNING)` silences them. Lines come from
the in-process engine (core/base/log.h's sink) and from a launched spear-server's stderr, which also
carries the engine's progress reports (spear/_progress.py).
"""

from __future__ import annotations

import logging
import re
import sys
import threading
from collections.abc import Callable
from typing import IO

LOGGER = logging.getLogger("spear")
_LINE = re.compile(r"^\[spear\] (?P<file>[^:\s]+):(?P<line>\d+): (?P<message>.*)$")
_PROGRESS = re.compile(r"^\[spear-progress\] (?P<done>\S+) (?P<total>\S+) (?P<finished>[01]) (?P<task>.*)$")


def _configured() -> bool:
    return LOGGER.level != logging.NOTSET or LOGGER.hasHandlers()


def enabled() -> bool:
    """Whether INFO lines are shown: always until logging is configured, else as configured."""
    return not _configured() or LOGGER.isEnabledFor(logging.INFO)


def emit(file: str, line: int, message: str) -> None:
    """One engine log line."""
    if not _configured():
        sys.stderr.write(f"[spear] {file}:{line}: {message}\n")
    elif LOGGER.isEnabledFor(logging.INFO):
        LOGGER.handle(LOGGER.makeRecord(LOGGER.name, logging.INFO, file, line, message, (), None))


def info(message: str) -> None:
    """A line of the package's own (a task's end), printed or logged as engine lines are."""
    if not _configured():
        sys.stderr.write(f"[spear] {message}\n")
    else:
        LOGGER.info("%s", message)


def handle_line(text: str) -> bool:
    """Shows one line of a server's stderr if it is an engine log line or a progress report; False for
    anything else."""
    match = _LINE.match(text)
    if match:
        emit(match["file"], int(match["line"]), match["message"])
        return True
    progress = _PROGRESS.match(text)
    if progress:
        from spear import _progress

        _progress.report(progress["task"], float(progress["done"]), float(progress["total"]),
                         progress["finished"] == "1")
        return True
    return False


def forward_stream(stream: IO[str], other: Callable[[str], None]) -> threading.Thread:
    """Reads a server's stderr to its end on a daemon thread: a server whose stderr nobody read would block
    once the pipe filled. Log lines and progress reports are shown; every other non-empty line (a start-up
    error, a sanitizer report, a driver's warning) goes to `other`."""

    def pump() -> None:
        while True:
            try:
                text = stream.readline()
            except (OSError, ValueError):  # the stream was closed under us: the server is gone
                return
            if not text:
                return
            text = text.rstrip("\n")
            try:
                if not handle_line(text) and text:
                    other(text)
            except Exception as error:  # noqa: BLE001 - one bad line must not stop the reading
                sys.stderr.write(f"[spear] a line of a server's stderr could not be shown ({error!r})\n")

    thread = threading.Thread(target=pump, name="spear-server stderr", daemon=True)
    thread.start()
    return thread
