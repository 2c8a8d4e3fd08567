"""Reply buffers: shared-memory segments this client owns and keeps, so that large arrays cross in memory
that is already mapped and faulted in (see core/rpc/reply_buffers.h for the server's side and the reasons).

- Replies: free buffers are offered with each request; the array returned for a reply in one is a view of
  the client's own, long-lived mapping. A buffer is offered only while no numpy array of the client's
  views it.
- Requests: a large argument is copied into a free buffer instead of a fresh segment. If the engine kept
  the array (the reply says "kept"), that buffer leaves the pool: the server's mapping is the engine's now.

After an array of a new size went through a fresh segment, a buffer of that size is made for the next
one, within the limits below.
"""

from __future__ import annotations

import mmap
import os
import weakref
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from spear._segments import segment_name

# As many buffers as the server maps for one client (kMaxBuffers in core/rpc/reply_buffers.h): a camera's 14
# modalities held by the caller while the next frame's 14 are read take 28. With 8, six arrays of such a frame
# went through fresh segments, each page faulted in on both sides (1080p over RPC: 246-254 -> 198-211 ms a frame).
MAX_BUFFERS = 32
MAX_BYTES = 512 << 20


@dataclass
class _Buffer:
    name: str
    size: int
    mapping: mmap.mmap
    held: bool = False  # a numpy array of the client's views it
    lent: bool = False  # it carries an argument of the request in flight


@dataclass
class ReplyBuffers:
    _buffers: dict[str, _Buffer] = field(default_factory=dict)
    _dropped: list[str] = field(default_factory=list)
    # Sizes to make buffers of before the next request, each with how many buffers of that size the client
    # needs: those it had when arrays of that size had to go through fresh segments, plus one per such array.
    _wanted: dict[int, int] = field(default_factory=dict)
    _this_reply: dict[str, NDArray[Any]] = field(default_factory=dict)  # buffers received in the reply being read
    _offered: set[str] = field(default_factory=set)  # offered with the request in flight
    closed: bool = False

    def offers(self) -> list[list[Any]]:
        """[[name, size], ...] of the buffers no array views: what the request about to be sent offers.

        Buffers learned since the last request are made here, just before the server hears of them, so
        that a client killed between two requests leaves no name the server does not know to remove."""
        wanted = set(self._wanted)
        for size, needed in sorted(self._wanted.items()):
            for _ in range(needed - len(self._fitting(size))):
                self._make(size, wanted)
        self._wanted.clear()
        offered = [b for b in self._buffers.values() if not b.held and not b.lent]
        self._offered = {b.name for b in offered}
        return [[b.name, b.size] for b in offered]

    def take_dropped(self) -> list[str]:
        """Buffers removed since the last request, for the server to let go of."""
        dropped, self._dropped = self._dropped, []
        return dropped

    def begin_reply(self) -> None:
        self._this_reply.clear()

    def end_reply(self) -> None:
        """The reply is read: the buffers its arrays are in stay held only while the caller's arrays live
        (keeping them here until the next reply made the client need one buffer more than it used)."""
        self._this_reply.clear()

    def receive(self, name: str, dtype: np.dtype[Any], shape: list[int], size: int) -> NDArray[Any]:
        """The reply array the server wrote into buffer `name`, as a view of the client's mapping."""
        count = int(np.prod(shape)) if shape else 1
        if name in self._this_reply:  # the same array twice in one reply
            return self._this_reply[name].reshape(shape)
        buffer = self._buffers.get(name)
        if buffer is None or buffer.held or buffer.lent or count * dtype.itemsize > min(size, buffer.size):
            raise ValueError(f"the server named reply buffer {name!r}, which this client did not offer")
        root = np.frombuffer(buffer.mapping, dtype=dtype, count=count)
        buffer.held = True
        # Views keep `root` alive: once it goes, no array of the client's reads the buffer any more.
        weakref.finalize(root, self._give_back, name)
        self._this_reply[name] = root
        return root.reshape(shape)

    def lend(self, data: NDArray[Any]) -> str | None:
        """Copies a request argument into a free buffer that fits; its name, or None (no buffer fits)."""
        fitting = [b for b in self._buffers.values()
                   if not b.held and not b.lent and data.nbytes <= b.size <= 2 * data.nbytes]
        if not fitting:
            return None
        buffer = min(fitting, key=lambda b: b.size)
        np.frombuffer(buffer.mapping, dtype=data.dtype, count=data.size).reshape(data.shape)[...] = data
        buffer.lent = True
        return buffer.name

    def settle(self, kept: set[str], failed: bool) -> None:
        """After a reply: buffers the engine kept an array in leave the pool (they are the engine's now),
        lent ones come back. If a call failed, its reply could not say what was kept: every buffer the
        request lent or offered leaves."""
        for buffer in list(self._buffers.values()):
            involved = buffer.lent or buffer.name in self._offered
            buffer.lent = False
            if buffer.name in kept or (failed and involved):
                self._remove(buffer)
        self._offered.clear()

    def learn(self, size: int) -> None:
        """An array of `size` bytes went through a fresh segment: the buffers that fit it were all in use (an
        array of the last frame's still views one, say), so have one more of that size next time."""
        if not self.closed:
            self._wanted[size] = self._wanted.get(size, len(self._fitting(size))) + 1

    def _fitting(self, size: int) -> list[_Buffer]:
        return [b for b in self._buffers.values() if size <= b.size <= 2 * size]

    def _make(self, size: int, wanted: set[int]) -> None:
        try:
            self._create(size, wanted)
        except OSError:
            pass  # no buffer this time (/dev/shm full, say): the server's own segments carry the arrays

    def _create(self, size: int, wanted: set[int]) -> None:
        if self.closed:
            return
        while self._buffers and (len(self._buffers) >= MAX_BUFFERS or
                                 sum(b.size for b in self._buffers.values()) + size > MAX_BYTES):
            # Room is made from free buffers of sizes nobody wants now (a resolution no longer used); never
            # from one a wanted size fits, which would only be made again at the next request.
            free = [b for b in self._buffers.values() if not b.held and not b.lent
                    and not any(w <= b.size <= 2 * w for w in wanted)]
            if not free:
                return  # the pool is full of buffers in use or wanted: the server's segments carry the rest
            self._remove(min(free, key=lambda b: b.size))
        name = segment_name("r")
        fd = os.open("/dev/shm" + name, os.O_CREAT | os.O_EXCL | os.O_RDWR, 0o600)
        try:
            # Allocated now, not on first touch: a /dev/shm that fills up later then fails here, in the
            # client, instead of as SIGBUS in the server writing a reply.
            os.posix_fallocate(fd, 0, size)
            mapping = mmap.mmap(fd, size, flags=mmap.MAP_SHARED | mmap.MAP_POPULATE)
        except OSError:
            os.unlink("/dev/shm" + name)
            raise
        finally:
            os.close(fd)
        self._buffers[name] = _Buffer(name, size, mapping)

    def close(self) -> None:
        """Removes every buffer's name, and makes no more (also when the server does not take buffers);
        arrays that view one keep their mapping."""
        self.closed = True
        for buffer in list(self._buffers.values()):
            self._remove(buffer)
        self._dropped.clear()
        self._wanted.clear()

    def _give_back(self, name: str) -> None:
        buffer = self._buffers.get(name)
        if buffer is not None:
            buffer.held = False

    def _remove(self, buffer: _Buffer) -> None:
        del self._buffers[buffer.name]
        self._dropped.append(buffer.name)
        try:
            os.unlink("/dev/shm" + buffer.name)
        except FileNotFoundError:
            pass
        if not buffer.held:
            try:
                buffer.mapping.close()
            except BufferError:  # a view made while it was lent still exists: it closes with that view
                pass
