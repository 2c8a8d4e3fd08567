"""Naming and sweeping the POSIX shared-memory segments that carry large arrays (spear._wire,
spear._reply_buffers; core/rpc/shared_memory.h on the server's side)."""

from __future__ import annotations

import os
import secrets


def segment_name(kind: str = "") -> str:
    """A new segment's name: this process's id, so that a sweep can tell when its creator is gone
    (remove_orphaned_segments), and 64 random bits, so that no other user can create the name first and
    make this process's segments fail (or hand it a segment of theirs)."""
    return f"/spear-{os.getpid()}-{kind}{secrets.token_hex(8)}"


def remove_orphaned_segments() -> int:
    """Removes /dev/shm/spear-<pid>-* segments whose creating process no longer exists, as every server
    start does (removeOrphanedSegments in core/rpc/shared_memory.cpp): a client and server killed together
    leave the segments in flight behind, and the next client to start removes them even when no server
    starts again. Segments of live processes, and other users' (which the sticky /dev/shm protects), are
    left alone. Returns how many were removed."""
    removed = 0
    try:
        names = os.listdir("/dev/shm")
    except OSError:
        return 0
    for name in names:
        pid_text = name[len("spear-"):].partition("-")[0] if name.startswith("spear-") else ""
        if not pid_text.isdigit() or int(pid_text) <= 0:
            continue
        try:
            os.kill(int(pid_text), 0)
            continue  # alive (or another user's process: PermissionError below)
        except ProcessLookupError:
            pass
        except PermissionError:
            continue
        try:
            os.unlink("/dev/shm/" + name)
            removed += 1
        except OSError:
            pass  # gone already, or not ours to remove
    return removed
