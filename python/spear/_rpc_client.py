"""The RPC transport: a connection to spear-server, and the server launcher.

One request at a time over a Unix socket (or TCP on loopback with a token), each a length-prefixed
msgpack frame; replies carry a value or an error that is raised as the same spear.errors class the
in-process engine raises.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
import os
import select
import shutil
import socket
import struct
import subprocess
import tempfile
import threading
import time
import weakref
from pathlib import Path
from typing import Any, NoReturn

import numpy as np

from spear import _logging, _progress, errors
from spear._object import SpObject
from spear._protocol import BatchMessage, FrameAction, Requests, message
from spear._reply_buffers import ReplyBuffers
from spear._rpc_types import convert, convert_result_tuple
from spear._type_code import TypeCode
from spear._segments import remove_orphaned_segments
from spear._wire import (SHARED_MEMORY_THRESHOLD, TAIL_ALIGNMENT, TAIL_FLAG, OutgoingSegments, ValueRefused,
                         _object_ext, encode, map_segment, pack_frame, unpack_body)
from spear.futures import Future, warn_send_failed

_ERRORS: dict[str, type[errors.SpearError]] = {
    "InvalidArgumentError": errors.InvalidArgumentError,
    "NotFoundError": errors.NotFoundError,
    "StaleObjectError": errors.StaleObjectError,
    "InvalidStateError": errors.InvalidStateError,
    "SpearError": errors.SpearError,
}


ConnectionLost = errors.ConnectionLostError  # the name this module has always raised

_SPIN_DEFAULT_US, _SPIN_MAX_US = 100, 10_000  # as the server's (core/rpc/spin_poll.h)
# A kind of request whose reply lately came within this many seconds is waited for by polling up to 1.25 times
# that long, not only the SPEAR_RPC_SPIN_US budget (see RpcConnection._poll_briefly).
_ADAPTIVE_SPIN_MAX = 2e-3


def spin_seconds() -> float:
    """How long a client polls its socket for a reply before it sleeps: SPEAR_RPC_SPIN_US microseconds.

    A process asleep waiting for a socket is woken by the kernel when the message arrives, which costs
    5-50 us when the server runs on another CPU, more than a short call's own work; a reply to a short
    call comes within microseconds, so the client polls first (yielding its CPU to anything else runnable)
    and sleeps only when nothing came. None where this process may run on one CPU only: there the polling
    would keep the CPU from the very server it waits for. (A client polls on the main thread only: see
    _poll_briefly.)
    """
    text = os.environ.get("SPEAR_RPC_SPIN_US")
    microseconds = _SPIN_DEFAULT_US
    if text is not None:
        if not (text.isascii() and text.isdigit() and int(text) <= _SPIN_MAX_US):
            raise errors.InvalidArgumentError(f"Instance(): SPEAR_RPC_SPIN_US must be a whole number of "
                                              f"microseconds from 0 to {_SPIN_MAX_US}, got {text!r}")
        microseconds = int(text)
    if len(os.sched_getaffinity(0)) < 2:
        return 0.0
    return microseconds * 1e-6


def poll_budget(spin: float, expected: float | None) -> float:
    """Seconds to poll for a reply before sleeping: the SPEAR_RPC_SPIN_US budget `spin` (none: no polling at
    all), or 1.25 times the time replies of its kind took lately (`expected`) where that is within
    _ADAPTIVE_SPIN_MAX."""
    if not spin or expected is None or expected > _ADAPTIVE_SPIN_MAX:
        return spin
    return max(spin, 1.25 * expected)


def _kind_of(calls: list[dict[str, Any]]) -> str:
    """A request's kind for the adaptive polling: its calls' operations, frame actions and functions (the first
    eight; a batch of more is told by its count too)."""
    names = [str(call.get("action") or call.get("function") or call.get("op")) for call in calls[:8]]
    return "batch:" + ",".join(names) + (f"+{len(calls)}" if len(calls) > 8 else "")


class RpcConnection(Requests):
    """A connection to a spear server; implements the RpcClient protocol the generated proxies use. Its
    request(op, **fields) is typed per op by spear._protocol (generated from core/rpc/protocol.json)."""

    def __init__(self, address: str, *, token: str | None = None, timeout: float | None = None) -> None:
        from spear._engine import API_HASH

        self._spin = spin_seconds()
        # How long replies to each kind of request took lately (seconds), and the kind now awaited.
        self._reply_times: dict[str, float] = {}
        self._awaited = ("", 0.0)  # (kind, when its request was sent)
        remove_orphaned_segments()  # what a client and server killed together left behind
        self.address = address
        if address.startswith("unix:"):
            path = address[len("unix:"):]
            self._socket = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            try:
                self._socket.connect(path)
            except FileNotFoundError:
                self._socket.close()
                raise errors.NotFoundError(
                    f"Instance(): no socket at {path!r}: start a server there (spear-server --socket {path}) "
                    f"or let the instance start its own (server='launch')") from None
            except ConnectionRefusedError:
                self._socket.close()
                raise ConnectionRefusedError(f"Instance(): nothing listens on the socket {path!r} (a server that "
                                             f"exited leaves its socket file behind)") from None
        elif address.startswith("tcp:"):
            host, _, port = address[len("tcp:"):].rpartition(":")
            if not host or not port.isdigit() or int(port) > 65535:
                raise errors.InvalidArgumentError(f"Instance(): a TCP server address is 'tcp:HOST:PORT' with a port "
                                                  f"in [0, 65535], got {address!r}")
            try:
                self._socket = socket.create_connection((host, int(port)))
            except ConnectionRefusedError:
                raise ConnectionRefusedError(f"Instance(): nothing listens at {host}:{port} "
                                             f"(spear-server --port {port} there?)") from None
            self._socket.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        else:
            raise errors.InvalidArgumentError(f"Instance(): server must be 'launch' (a server of its own), "
                                              f"'unix:PATH' or 'tcp:HOST:PORT', got {address!r}")
        self._socket.settimeout(timeout)
        self._readable = select.poll()
        self._readable.register(self._socket, select.POLLIN)
        self._ids = itertools.count(1)
        self.messages_sent = 0  # messages so far (batches count once)
        # A posted message (a frame's end) has a reply still unread: it is read before the next request.
        self._posted = False
        # The engine's frame state after the last frame operation this connection saw succeed (its reply says).
        self._frame_state: str | None = None
        self._deferring: bool | None = None  # None: calls run now; else queued (True: result discarded)
        # Calls waiting for the next message: (call, its future or None, result conversion, critical). A
        # critical call (a frame operation) stops the rest of its batch when it fails, and its error is raised.
        self._queue: list[tuple[dict[str, Any], Future[Any] | None, Callable[[Any], Any], bool]] = []
        self._queue_segments: OutgoingSegments | None = None  # those the queued calls' arguments went into
        self._reply_buffers = ReplyBuffers()
        # Their names go when the connection is closed, or when it is collected without being closed.
        self._buffers_cleanup = weakref.finalize(self, self._reply_buffers.close)
        if token is None:  # as the server, the token may come from the environment (off the command line)
            token = os.environ.get("SPEAR_TOKEN")
        hello = self.request("hello", api_hash=API_HASH, token=token or "")
        self.server_pid = int(hello["pid"])
        # The engine this connection reaches: several connections to one server reach the same engine.
        self.engine: tuple[str, int] = (address, self.server_pid)
        if not hello.get("reply_buffers"):  # TCP: the server cannot tell which process offers buffers
            self._reply_buffers.close()
        # Whether the server sends large reply arrays through shared memory: once this client has shown that it
        # maps the server's segments; else (another host, a /dev/shm of its own) they come inline.
        self.shared_memory = False
        probe = hello.get("shm_probe")
        if isinstance(probe, str):
            self.shared_memory = self._prove_shared_memory(probe)

    def _prove_shared_memory(self, name: str) -> bool:
        """Reads the nonce of the segment hello named and sends it back (an empty one where the segment cannot be
        mapped, so that the server removes it at once); the reply says whether shared memory is on."""
        nonce = ""
        try:
            with map_segment(name, 32, unlink=True) as mapping:
                nonce = bytes(mapping[:32]).decode("ascii", "replace")
        except (OSError, ValueError):
            pass
        return bool(self.request("shm_proof", nonce=nonce))

    # -- requests ------------------------------------------------------------------------------

    def deferred(self, discard: bool) -> _Deferring:
        """Queues the calls made inside the block (call_async / send_async) instead of sending them."""
        return _Deferring(self, discard)

    def flush(self) -> None:
        """Sends every queued call in one message and resolves their futures."""
        if self._queue:
            self._send_queue(None)
        else:
            self._read_posted()

    def post(self) -> None:
        """Sends the queue without waiting for its reply when it holds frame operations only (a frame's end, the
        last message of a frame): its reply is read before the next request, so that the caller goes on while
        the server answers. Anything else in the queue is sent as flush() sends it."""
        actions = [call.get("action") if critical else None for call, _, _, critical in self._queue]
        # Only an end that cannot fail is posted: the engine is inside this connection's end_frame (its opening
        # went with a read and succeeded), or between its frame's execution and end_frame. Misuse (end_frame
        # without a frame) is raised by end_frame itself, as in-process.
        safe = ((actions == ["end"] and self._frame_state == "inside end_frame") or
                (actions == ["begin_end", "end"] and self._frame_state == "between begin_frame and end_frame"))
        if not safe:
            self.flush()
            return
        self._read_posted()
        queue, segments = self._take_queue()
        if segments is not None:  # none was made for frame operations; released all the same
            segments.release()
        calls = [call for call, _, _, _ in queue]
        # No reply buffers offered (the reply is read later, and carries no arrays) and no dropped ones named:
        # those go with the next request, whose reply settles them.
        self._send(pack_frame(message({"id": next(self._ids), "op": "batch", "calls": calls,
                                       "critical": list(range(len(calls)))})))
        self._awaited = (_kind_of(calls), time.perf_counter())
        self._posted = True
        self._frame_state = None  # known again once the reply is read

    def _read_posted(self) -> None:
        """Reads the reply to the posted message, if any; raises the error of a frame operation in it (the
        queue, whose calls would act on a frame that did not end, is dropped then: their futures fail)."""
        if not self._posted:
            return
        self._posted = False
        for item in self._result(self._read_reply(None)):
            if "error" in item:
                failure = self._error(item)
                self._drop_queue(failure)
                raise failure
            self._frame_state = item["ok"]["state"]

    def _take_queue(self) -> tuple[list[tuple[dict[str, Any], Future[Any] | None, Callable[[Any], Any], bool]],
                                   OutgoingSegments | None]:
        """The queued calls and the segments their arguments went into, leaving the queue empty."""
        queue, self._queue = self._queue, []
        segments, self._queue_segments = self._queue_segments, None
        return queue, segments

    def _drop_queue(self, error: errors.SpearError) -> None:
        queue, segments = self._take_queue()
        if segments is not None:
            segments.release()
        for _, future, _, _ in queue:
            if future is not None:
                future._set(error=error)

    def queue_frame(self, action: FrameAction) -> None:
        """Queues a frame operation ahead of the calls that follow it: it travels with the next message, so
        a frame's begin and the calls of its block (and its execution) cost one round trip. When it fails,
        the calls after it do not run (they would act outside the frame, or in another client's) and its
        error is raised by the call that sent it."""
        self._queue.append((message({"op": "frame", "action": action}), None, _unchanged, True))

    def _send_queue(self, last: dict[str, Any] | None) -> Any:
        """Sends the queued calls, then `last` if given, in one message; returns the result of `last`."""
        self._read_posted()
        queue, segments = self._take_queue()
        if segments is None:
            segments = self._segments()
        calls = [call for call, _, _, _ in queue]  # encoded when they were queued
        refused: dict[int, Exception] = {}
        if last is not None:
            _encode_call(last, segments, calls, refused)
        critical = [i for i, entry in enumerate(queue) if entry[3]]
        results = self._batch_encoded(calls, critical, segments, refused)
        failure = next((results[i] for i in critical if isinstance(results[i], errors.SpearError)), None)
        if failure is None and critical:
            self._frame_state = results[critical[-1]]["state"]
        for (_, future, convert_result, is_critical), result in zip(queue, results):
            if is_critical:
                continue
            if future is None:
                if isinstance(result, errors.SpearError) and failure is None:
                    warn_send_failed(result, stacklevel=3)
                continue
            if isinstance(result, errors.SpearError):
                future._set(error=result)
            else:
                try:
                    future._set(convert_result(result))
                except Exception as error:  # noqa: BLE001
                    future._set(error=error)
        if failure is not None:
            raise failure
        if last is None:
            return None
        if len(results) - 1 in refused or isinstance(results[-1], errors.SpearError):
            raise results[-1]
        return results[-1]

    def _queue_call(self, call: dict[str, Any], arguments: str,
                    convert_result: Callable[[Any], Any] | None) -> Any:
        """Queues a call, its arguments (the field named `arguments`) encoded now: a value the caller changes
        after queueing it (a struct it reuses, an array it fills again) travels as it was at the call, as
        in-process, where the call runs at once. A value the wire cannot carry fails this call alone: a
        warning for send_async, an error in the future for call_async, as in-process."""
        if self._queue_segments is None:
            self._queue_segments = self._segments()
        try:
            call[arguments] = _encode_field(call["op"], call, arguments, call[arguments], self._queue_segments)
        except Exception as error:  # noqa: BLE001 - a value's own error (a struct's emptied field) is the call's
            if self._deferring:
                # At the caller's line (through the queueing caller, the proxy's method and _sp_call, call).
                warn_send_failed(error, stacklevel=6)
                return None
            return Future.failed(error)
        future: Future[Any] | None = None if self._deferring else Future(self.flush)
        self._queue.append((call, future, convert_result or _unchanged, False))
        return future

    def _segments(self) -> OutgoingSegments:
        return OutgoingSegments(self._reply_buffers, inline=self.address.startswith("tcp:"), owner=self)

    def _request(self, op: str, fields: dict[str, Any]) -> Any:
        if self._queue:  # queued calls run first, in the order they were made, in the same message
            return self._send_queue({"op": op, **fields})
        self._read_posted()
        segments = self._segments()
        reply: Any = None
        try:
            outgoing = {"id": next(self._ids), "op": op, **_encode_fields(op, fields, segments)}
            reply = self._round_trip(pack_frame(self._offer_buffers(outgoing), segments),
                                     f"{op}:{fields.get('function', '')}")
        finally:
            segments.release()
            self._settle_buffers(reply, batch=False)
        return self._result(reply)

    def batch(self, calls: list[dict[str, Any]], *, critical: Sequence[int] = ()) -> list[Any]:
        """Sends many requests in one message; returns each result, or the exception it raised. When a call at
        one of the `critical` positions fails, the server runs none of the calls after it."""
        self.flush()
        segments = self._segments()
        refused: dict[int, Exception] = {}  # calls refused before sending, by position
        encoded: list[dict[str, Any]] = []
        for call in calls:
            _encode_call(call, segments, encoded, refused)
        return self._batch_encoded(encoded, critical, segments, refused)

    def _batch_encoded(self, encoded: list[dict[str, Any]], critical: Sequence[int], segments: OutgoingSegments,
                       refused: dict[int, Exception]) -> list[Any]:
        """Sends encoded calls in one message; their segments are released once the reply has arrived."""
        reply: Any = None
        try:
            batch: BatchMessage = {"id": next(self._ids), "op": "batch", "calls": encoded}
            if critical:
                batch["critical"] = list(critical)
            reply = self._round_trip(pack_frame(self._offer_buffers(message(batch)), segments), _kind_of(encoded))
        finally:
            segments.release()
            self._settle_buffers(reply, batch=True)
        results = [self._error(item) if "error" in item else item["ok"] for item in self._result(reply)]
        for i, error in refused.items():
            results[i] = error
        return results

    def _settle_buffers(self, reply: Any, batch: bool) -> None:
        """Buffers that carried arguments come back, unless the engine kept their arrays; buffers the engine
        kept arrays in leave the pool too."""
        items = [reply] if isinstance(reply, dict) else []
        if batch and items and isinstance(reply.get("ok"), list):  # each call's reply says what it kept
            items += [item for item in reply["ok"] if isinstance(item, dict)]
        kept: set[str] = set()
        for item in items:
            names = item.get("kept", [])
            kept.update(name for name in (names if isinstance(names, list) else []) if isinstance(name, str))
        failed = not items or any("error" in item for item in items)
        self._reply_buffers.settle(kept, failed)

    def _offer_buffers(self, message: dict[str, Any]) -> dict[str, Any]:
        """Offers the reply buffers no array views, and names those removed (spear._reply_buffers)."""
        if message["op"] != "hello":
            offers, dropped = self._reply_buffers.offers(), self._reply_buffers.take_dropped()
            if offers:
                message["reply_buffers"] = offers
            if dropped:
                message["dropped_buffers"] = dropped
        return message

    def _round_trip(self, frame: list[bytes | memoryview], kind: str) -> Any:
        self._send(frame)
        self._awaited = (kind, time.perf_counter())
        return self._read_reply(self._reply_buffers)

    def _send(self, frame: list[bytes | memoryview]) -> None:
        self.messages_sent += 1
        try:
            for part in frame:  # the message, then any arrays of its tail as they are (no copy)
                self._socket.sendall(part)
        except OSError as error:
            self._lost(error)

    def _read_reply(self, buffers: ReplyBuffers | None) -> Any:
        """The next reply; `buffers`: the reply buffers its request offered (None: it offered none)."""
        try:
            self._poll_briefly()
            (length,) = struct.unpack("<I", self._receive(4))
            self._learn_reply_time()
            if length & TAIL_FLAG:  # large arrays after the message (a client that cannot map the server's memory)
                body = self._receive(length & ~TAIL_FLAG)
                (message_length,) = struct.unpack_from("<I", body)
                return unpack_body(body[4:4 + message_length], buffers,
                                   tail=(body, -(-(4 + message_length) // TAIL_ALIGNMENT) * TAIL_ALIGNMENT))
            return unpack_body(self._receive(length), buffers)
        except OSError as error:
            self._lost(error)

    def _lost(self, error: OSError) -> NoReturn:
        # A late reply could still arrive into buffers reused since: the connection is done.
        self.close()
        raise ConnectionLost(f"the connection to the spear server at {self.address} was lost: {error}") from None

    def _poll_briefly(self) -> None:
        """Returns when the socket has a reply to read or the spin budget is spent (spin_seconds).

        On the main thread only: each turn of the loop takes the GIL back, so threads polling side by side
        (VectorEnv's, one per server) would keep those with work to do from it (on a 16-core host, 16 servers
        stepped from 16 threads lost a third of their steps per second).

        A kind of request whose reply lately came within _ADAPTIVE_SPIN_MAX (a frame whose physics step takes
        half a millisecond) is polled for up to 1.25 times as long as it took: sleeping, the process is woken by
        the kernel when the reply comes, which on a virtual machine costs a tenth of a millisecond or more a
        message. Longer work (a rendered frame) is slept through, the CPU left to the server's threads.
        """
        if self._spin and threading.current_thread() is threading.main_thread():
            kind, sent = self._awaited
            poll, deadline = self._readable.poll, sent + poll_budget(self._spin, self._reply_times.get(kind))
            while not poll(0) and time.perf_counter() < deadline:
                os.sched_yield()

    def _learn_reply_time(self) -> None:
        """Records how long the reply now being read took to come (a moving average per kind of request)."""
        kind, sent = self._awaited
        took = time.perf_counter() - sent
        if len(self._reply_times) >= 256 and kind not in self._reply_times:
            self._reply_times.clear()  # many kinds (calls of many functions, one at a time): start again
        last = self._reply_times.get(kind)
        self._reply_times[kind] = took if last is None else 0.5 * (last + took)

    def _receive(self, size: int) -> memoryview:
        # Into one buffer as it arrives: a reply carrying a frame inline (over TCP from another host) is copied
        # once here, not once per chunk and again to join them. A large one uninitialised (np.empty): a
        # bytearray is zero-filled first, a pass over every byte (0.3 ms of a 1080p frame) the receive overwrites.
        view = memoryview(np.empty(size, np.uint8) if size >= SHARED_MEMORY_THRESHOLD  # type: ignore[arg-type]
                          else bytearray(size))
        received = 0
        while received < size:
            count = self._socket.recv_into(view[received:], size - received)
            if not count:
                raise ConnectionLost(f"the spear server at {self.address} closed the connection")
            received += count
        return view

    @staticmethod
    def _result(reply: dict[str, Any]) -> Any:
        if "error" in reply:
            raise RpcConnection._error(reply)
        return reply["ok"]

    @staticmethod
    def _error(reply: dict[str, Any]) -> errors.SpearError:
        """A failed reply's error, as the spear.errors class the server named."""
        kind, message = reply["error"]
        return _ERRORS.get(kind, errors.SpearError)(message)

    # -- RpcClient protocol --------------------------------------------------------------------

    def call(self, handle: tuple[int, int], function: str, args: dict[str, Any], result_type: TypeCode,
             context: str = "", result_tuple: Any = None) -> Any:
        if self._deferring is not None:  # the object reference made at once: it is this connection's own handle
            call = message({"op": "call", "object": _object_ext(handle[0], handle[1]), "function": function,
                            "args": args, "context": context})
            return self._queue_call(call, "args", None if self._deferring else _ResultConversion(
                self, result_type, result_tuple))
        return self._call({"object": _HandleRef(handle)}, function, args, result_type, context, result_tuple)

    def call_static(self, class_name: str, function: str, args: dict[str, Any], result_type: TypeCode,
                    context: str = "", result_tuple: Any = None) -> Any:
        """Calls a static function of an engine class: the request names the class instead of an object."""
        return self._call({"class": class_name}, function, args, result_type, context, result_tuple)

    def _call(self, target: dict[str, Any], function: str, args: dict[str, Any], result_type: TypeCode,
              context: str, result_tuple: Any) -> Any:
        convert_result = _ResultConversion(self, result_type, result_tuple)
        call: dict[str, Any] = {**target, "function": function, "args": args, "context": context}
        if self._deferring is not None:
            return self._queue_call({"op": "call", **call}, "args", convert_result)
        return convert_result(self.request("call", **call))

    def get_property(self, handle: tuple[int, int], name: str, result_type: TypeCode, context: str = "") -> Any:
        value = self.request("get", object=_HandleRef(handle), property=name, context=context)
        return convert(value, result_type, self)

    def set_property(self, handle: tuple[int, int], name: str, value: Any, context: str = "") -> None:
        self.request("set", object=_HandleRef(handle), property=name, value=value, context=context)

    def is_valid(self, handle: tuple[int, int]) -> bool:
        return bool(self.request("is_valid", object=_HandleRef(handle)))

    def call_sp_func(self, handle: tuple[int, int], name: str, arrays: dict[str, Any], unreal_objs: dict[str, str],
                     info: str, finish: Callable[[Any], Any], context: str = "") -> Any:
        call: dict[str, Any] = {"name": name, "arrays": arrays, "unreal_objs": unreal_objs, "info": info,
                                "context": context}
        if self._deferring is not None:  # its other fields are names (unreal_objs: names as text)
            return self._queue_call({"op": "sp_func", "object": _object_ext(handle[0], handle[1]), **call}, "arrays",
                                    finish)
        return finish(self.request("sp_func", object=_HandleRef(handle), **call))

    def sp_func_names(self, handle: tuple[int, int], context: str = "") -> list[str]:
        return list(self.request("sp_func_names", object=_HandleRef(handle), context=context))

    def same_engine(self, other: object) -> bool:
        """Whether `other` (a connection) reaches the engine this one does: their handles mean the same objects."""
        return other is self or getattr(other, "engine", None) == self.engine

    def close(self) -> None:
        if self._queue_segments is not None:  # calls queued and never sent
            self._queue_segments.release()
        self._buffers_cleanup()
        try:
            self._socket.close()
        except OSError:
            pass


class _Deferring:
    """RpcConnection.deferred()'s block, as a class: it is entered once per queued call, and a generator-based
    context manager costs several times as much."""

    __slots__ = ("_connection", "_discard", "_previous")

    def __init__(self, connection: RpcConnection, discard: bool) -> None:
        self._connection = connection
        self._discard = discard
        self._previous: bool | None = None

    def __enter__(self) -> None:
        self._previous, self._connection._deferring = self._connection._deferring, self._discard

    def __exit__(self, *exc: object) -> None:
        self._connection._deferring = self._previous


def _unchanged(value: Any) -> Any:
    return value


class _ResultConversion:
    """A queued call's result conversion (to the declared type), as a small object instead of a closure."""

    __slots__ = ("_connection", "_type", "_tuple")

    def __init__(self, connection: RpcConnection, result_type: TypeCode, result_tuple: Any) -> None:
        self._connection, self._type, self._tuple = connection, result_type, result_tuple

    def __call__(self, value: Any) -> Any:
        if self._tuple is not None:
            return convert_result_tuple(value, self._tuple, self._connection)
        return convert(value, self._type, self._connection)


def _encode_call(call: dict[str, Any], segments: OutgoingSegments, encoded: list[dict[str, Any]],
                 refused: dict[int, Exception]) -> None:
    """Appends a request of a batch, encoded; one refused before sending leaves its error at its position and an
    echo in its place, which keeps the positions of the replies (and the calls queued before it, such as the
    frame it runs in, go as they would have). Its error is what the value raised: the wire's refusal, or the
    value's own (a struct's emptied field raises AttributeError here as in-process)."""
    try:
        encoded.append(_encode_fields(str(call.get("op", "")), call, segments))
    except Exception as error:  # noqa: BLE001 - raised for this call alone, after the batch
        refused[len(encoded)] = error
        encoded.append(message({"op": "echo"}))


def _encode_fields(op: str, fields: dict[str, Any], segments: OutgoingSegments) -> dict[str, Any]:
    """A request's fields, encoded. A value the wire cannot carry is refused naming the function, and for a
    typed call the argument, as the in-process engine names it."""
    return {key: _encode_field(op, fields, key, value, segments) for key, value in fields.items()}


def _encode_field(op: str, fields: dict[str, Any], key: str, value: Any, segments: OutgoingSegments) -> Any:
    if type(value) is str:
        return value  # the names, unchanged
    context = fields.get("context")
    if key == "args" and context and isinstance(value, dict):  # a typed call's arguments, each named
        arguments: dict[str, Any] = {}
        for name, item in value.items():
            try:
                arguments[name] = encode(item, segments)
            except ValueRefused as error:
                raise errors.InvalidArgumentError(f"{context}: argument '{name}': {error}") from None
        return arguments
    try:
        return encode(value, segments)
    except ValueRefused as error:
        raise errors.InvalidArgumentError(f"{_context(op, fields)}: {error}") from None


def _context(op: str, fields: dict[str, Any]) -> str:
    """What the server calls a request in its messages (Dispatcher::execute in core/rpc/dispatcher.cpp)."""
    if fields.get("context"):
        return str(fields["context"])
    if op in ("call", "call_typed"):
        return f"call_function('{fields.get('function')}')"
    if op in ("get", "get_typed", "set"):
        return f"{'set' if op == 'set' else 'get'}_property('{fields.get('property')}')"
    if op == "sp_func":
        return f"call_sp_func('{fields.get('name')}')"
    return f"{op}()"


class _HandleRef(SpObject):
    """A bare handle, sent as an object reference: the connection's own (taken from one of its proxies)."""

    __slots__ = ("_sp_handle",)
    _sp_own_handle = True

    def __init__(self, handle: tuple[int, int]) -> None:
        self._sp_handle = handle


# -- launching a server ------------------------------------------------------------------------

def find_server_binary() -> Path:
    """SPEAR_SERVER if set, else the binary the build places beside the package."""
    configured = os.environ.get("SPEAR_SERVER")
    candidate = Path(configured) if configured else Path(__file__).resolve().parent / "bin" / "spear-server"
    if not candidate.is_file():
        raise errors.NotFoundError(f"Instance(): spear-server not found at {candidate}; build the project (bash "
                                   "run.sh) or set SPEAR_SERVER")
    return candidate


class LaunchedServer:
    """A spear-server process started for one Instance, on a private Unix socket; stopped by close().

    tcp_bind: listen on TCP instead, on that address and a free port, for clients on other machines that give
    `token` (spear.distributed starts one per Dask worker so). Such a server is not private: it loads only the
    plugins it is started with and confines files to its working directory and `file_roots`."""

    def __init__(self, *, fixed_delta_seconds: float, mode: str = "game", scene: str = "",
                 startup_timeout: float = 30.0, tcp_bind: str | None = None, token: str | None = None,
                 file_roots: Sequence[str] = ()) -> None:
        self._directory = tempfile.mkdtemp(prefix="spear-")  # 0700: only this user reaches the socket
        self._stderr_forwarder: threading.Thread | None = None
        socket_path = os.path.join(self._directory, "server.sock")
        extra = ["--scene", scene] if scene else []  # relative to the client's directory, which the server shares
        if tcp_bind is None:
            # This server is private to this user (its socket is in a 0700 directory) and serves the one
            # client that started it: loading any library there grants nothing the user lacks, and
            # instance.load_plugin(path) works as in-process. For the same reason its files are not confined:
            # a scene or mesh path means what it means in-process.
            listen = ["--socket", socket_path, "--allow-remote-plugin-load", "--file-root", "/"]
        else:
            if not token:
                raise errors.InvalidArgumentError("LaunchedServer(): a TCP server needs a token")
            listen = ["--port", "0", "--bind", tcp_bind, *(arg for root in file_roots for arg in ("--file-root", root))]
        self.process = subprocess.Popen(
            [str(find_server_binary()), *listen, "--fixed-delta-seconds", repr(fixed_delta_seconds), "--mode", mode,
             *extra, "--exit-with-parent"],
            # The token in the environment, not on the command line; our pid for --exit-with-parent, in case we
            # are gone before the server looks for its parent.
            env={**os.environ, "SPEAR_PARENT_PID": str(os.getpid()),
                 **({} if tcp_bind is None else {"SPEAR_TOKEN": token or ""})},
            # errors="replace": a log line with bytes that are not UTF-8 (a name from a mesh file) must not stop
            # the reading of the server's stderr.
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL, text=True, errors="replace",
        )
        # Its stderr is read from the start (a start-up that says much would otherwise block on a full pipe):
        # log lines and progress become logging records of the "spear" logger; other lines are kept until the
        # server is listening (a start-up error), then logged as they are.
        self._startup_lines: list[str] | None = []
        assert self.process.stdout is not None and self.process.stderr is not None
        self._stderr_forwarder = _logging.forward_stream(self.process.stderr, self._other_stderr_line)
        ready, _, _ = select.select([self.process.stdout], [], [], startup_timeout)
        line = self.process.stdout.readline() if ready else ""
        if not line.startswith("spear-server: listening on "):
            if not ready:
                self.process.kill()
            self.process.wait(10)
            self._stderr_forwarder.join(timeout=10.0)  # to the end of what it said
            message = "\n".join(self._startup_lines or []).strip()
            self.close()
            # The engine's own message (a missing scene file, say) is the useful part.
            kind, _, text = message.rpartition("\n")[2].partition(": ")
            if kind in _ERRORS:
                raise _ERRORS[kind](text)
            said = "nothing within {:g} s".format(startup_timeout) if not ready else repr(line.strip())
            raise errors.SpearError(message or f"Instance(): spear-server did not start (said {said})")
        self._startup_lines = None
        self.address = line.strip().removeprefix("spear-server: listening on ")

    def _other_stderr_line(self, line: str) -> None:
        if self._startup_lines is not None:
            self._startup_lines.append(line)
        else:
            _logging.emit("spear-server", 0, line)

    def close(self, timeout: float = 10.0) -> None:
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        if self._stderr_forwarder is not None:  # the server has exited: its last lines, then end of file
            self._stderr_forwarder.join(timeout=2.0)
            _progress.abandon_unfinished()
        for stream in (self.process.stdout, self.process.stderr):
            if stream:
                stream.close()
        shutil.rmtree(self._directory, ignore_errors=True)
