"""The RPC wire format on the client side: length-prefixed msgpack frames, with extension types for
object references (1), classes (2), arrays (3) and enum values (4). Arrays of 64 KiB or more travel through POSIX shared
memory (/dev/shm/spear-<pid>-<random>): the receiver maps the segment and the array views it, no copy.
Where it can, the connection's reply buffers (spear._reply_buffers) carry them instead of fresh segments.
See core/rpc/value_msgpack.h for the server side.
"""

from __future__ import annotations

import collections.abc
import dataclasses
import enum
import functools
import mmap
import os
import struct
from collections.abc import Callable
from typing import Any

from spear import _msgpack as msgpack
import numpy as np
from numpy.typing import NDArray

from spear._object import SpObject
from spear._reply_buffers import ReplyBuffers
from spear._segments import segment_name

EXT_OBJECT, EXT_CLASS, EXT_ARRAY, EXT_ENUM = 1, 2, 3, 4
SHARED_MEMORY_THRESHOLD = 64 * 1024
# A reply whose length word has TAIL_FLAG set carries its large arrays as raw bytes after the message (for a
# client that cannot map the server's memory): the body is [message length][message][padding][tail], the tail
# starting at 4 + message length rounded up to TAIL_ALIGNMENT (kTailFlag in core/rpc/value_msgpack.h).
TAIL_FLAG = 0x80000000
TAIL_ALIGNMENT = 64
# Lists and dicts nest at most this deep in a value (kMaxValueDepth in core/reflect/value.h): the server
# refuses deeper ones, and refusing them here keeps Python's recursion limit out of it.
MAX_VALUE_DEPTH = 64
# MAP_POPULATE maps every page in one system call instead of one page fault per 4 KiB page as the copy
# touches it: for a 1080p RGBA image that is most of the cost of a transfer.
_MAP_FLAGS = mmap.MAP_SHARED | mmap.MAP_POPULATE


@dataclasses.dataclass(frozen=True)
class ObjectRef:
    """An object reference as it arrives, before it becomes a typed proxy."""

    index: int
    generation: int
    class_name: str


@dataclasses.dataclass(frozen=True)
class ClassRef:
    name: str
    native: str = ""  # for a blueprint (a class defined by data): the native class it is made from


def _segment_path(name: str) -> str:
    if not name.startswith("/spear-") or "/" in name[1:]:
        raise ValueError(f"not a spear shared-memory segment name: {name!r}")
    return "/dev/shm" + name


def map_segment(name: str, size: int, *, unlink: bool) -> mmap.mmap:
    """Maps a segment; with unlink=True its name is removed at once (the mapping stays valid)."""
    path = _segment_path(name)
    fd = os.open(path, os.O_RDWR)
    try:
        mapping = mmap.mmap(fd, max(size, 1), flags=_MAP_FLAGS)
    finally:
        os.close(fd)
        if unlink:
            try:
                os.unlink(path)
            except FileNotFoundError:
                pass
    return mapping


class OutgoingSegments:
    """Segments this client created for a request's arrays; removed once the reply has arrived. With the
    connection's reply buffers, an array goes into a free buffer that fits instead, when there is one."""

    def __init__(self, buffers: ReplyBuffers | None = None, *, inline: bool = False, owner: object = None) -> None:
        self.paths: list[str] = []
        # The connection the request goes to: engine objects passed in it must be that engine's.
        self.owner = owner
        self._buffers = buffers
        # Over TCP the server cannot tell which process (or machine) a segment comes from, so it opens none:
        # every argument array travels in the message's frame, the large ones raw in its tail (TAIL_FLAG),
        # each at an aligned offset.
        self.inline = inline
        self.tail: list[tuple[int, NDArray[Any]]] = []
        self.tail_size = 0

    def add_to_tail(self, data: NDArray[Any]) -> int:
        """Places a contiguous array in the frame's tail; returns its offset there."""
        offset = -(-self.tail_size // TAIL_ALIGNMENT) * TAIL_ALIGNMENT
        self.tail.append((offset, data))
        self.tail_size = offset + data.nbytes
        return offset

    def create(self, data: NDArray[Any]) -> str:
        if self._buffers is not None:
            lent = self._buffers.lend(data)
            if lent is not None:
                return lent
            self._buffers.learn(data.nbytes)  # for the next array of this size
        name = segment_name()
        path = _segment_path(name)
        fd = os.open(path, os.O_CREAT | os.O_EXCL | os.O_RDWR, 0o600)
        self.paths.append(path)
        try:
            os.ftruncate(fd, max(data.nbytes, 1))
            with mmap.mmap(fd, max(data.nbytes, 1), flags=_MAP_FLAGS) as mapping:
                np.frombuffer(mapping, dtype=data.dtype, count=data.size).reshape(data.shape)[...] = data
        finally:
            os.close(fd)
        return name

    def release(self) -> None:
        for path in self.paths:
            try:
                os.unlink(path)
            except FileNotFoundError:
                pass
        self.paths.clear()


def _encode_array(array: NDArray[Any], segments: OutgoingSegments) -> msgpack.ExtType:
    array = np.ascontiguousarray(array)
    if not array.dtype.isnative:  # the server reads native (little-endian) elements, as in-process C++ does
        array = array.astype(array.dtype.newbyteorder("="))
    dtype = "bool" if array.dtype == np.bool_ else array.dtype.name
    payload: Any
    if array.nbytes >= SHARED_MEMORY_THRESHOLD and not segments.inline:
        payload = {"shm": segments.create(array), "size": array.nbytes}
    elif array.nbytes >= SHARED_MEMORY_THRESHOLD:  # raw after the message, not copied through msgpack
        payload = {"tail": segments.add_to_tail(array), "size": array.nbytes}
    else:
        payload = array.tobytes()
    return msgpack.ExtType(EXT_ARRAY, msgpack.packb([dtype, list(array.shape), payload], use_bin_type=True))


class ValueRefused(ValueError):
    """A value the wire cannot carry, refused in the words the in-process engine uses (toValue() in
    core/pybind/value_convert.cpp); the caller puts the function and argument in front."""


class ValueTooDeep(ValueRefused):
    """A value nests lists or dicts deeper than MAX_VALUE_DEPTH."""


def of_engine(value: SpObject, connection: Any) -> bool:
    """Whether an engine object belongs to the engine `connection` reaches (its own bare handles do), or with
    connection None, to the in-process engine (whose objects have no RPC client)."""
    if getattr(type(value), "_sp_own_handle", False):  # on the class: an instance lookup would try SpFuncs
        return True
    client = getattr(value, "_sp_client", None)
    if connection is None:
        return client is None
    return client is not None and bool(connection.same_engine(client))


# The engine struct types (with their field names) and engine object types encode() has met, so that their
# later values skip the checks below (SpObject's isinstance is an ABC check) and dataclasses.fields(): an
# RPC frame of many calls spends most of its client time encoding them (64 AddForce calls a frame in Table 3).
_STRUCT_FIELDS: dict[type, tuple[str, ...]] = {}
_OBJECT_TYPES: set[type] = set()


def encode(value: Any, segments: OutgoingSegments, depth: int = 0) -> Any:
    """Python value -> msgpack-ready value."""
    kind = type(value)
    if kind is float or kind is str or kind is bool or value is None:
        return value
    names = _STRUCT_FIELDS.get(kind)
    if names is not None:
        return _encode_struct(value, names, segments, depth)
    if kind in _OBJECT_TYPES:
        return _encode_object(value, segments)
    if isinstance(value, (bool, str, float)):
        return value
    if isinstance(value, enum.IntEnum):  # with its enum's name: the server refuses a bare int for an enum
        return _enum_ext(value)
    if isinstance(value, int):
        if not -(2**63) <= value < 2**63:  # as the in-process engine refuses it: 64 bits at most
            raise ValueRefused(f"integer {value} is too large")
        return value
    if isinstance(value, SpObject):
        _OBJECT_TYPES.add(kind)
        return _encode_object(value, segments)
    if isinstance(value, type) and hasattr(value, "__sp_class__"):
        asset = getattr(value, "__sp_asset__", "")  # a generated blueprint class: the server loads it if needed
        body = f"{value.__sp_class__}\0\0{asset}" if asset else value.__sp_class__
        return msgpack.ExtType(EXT_CLASS, body.encode())
    if isinstance(value, (np.integer, np.bool_, np.floating)):
        return value.item()  # a numpy scalar is sent as the Python number it holds, as pybind11 takes it in-process
    if isinstance(value, np.ndarray):
        return _encode_array(value, segments)
    is_struct = dataclasses.is_dataclass(value) and hasattr(value, "__sp_class__")
    # Any sequence but text and bytes goes as a list, as in-process (the API types lists of objects as Sequence).
    is_sequence = isinstance(value, (list, tuple)) or (
        isinstance(value, collections.abc.Sequence) and not isinstance(value, (str, bytes, bytearray)))
    if (is_struct or is_sequence or isinstance(value, dict)) and depth >= MAX_VALUE_DEPTH:
        raise ValueTooDeep(f"a value has lists or dicts nested deeper than {MAX_VALUE_DEPTH} levels")
    if is_struct:
        names = _STRUCT_FIELDS.setdefault(kind, tuple(f.name for f in dataclasses.fields(value)))
        return _encode_struct(value, names, segments, depth)
    if is_sequence:  # the connection's own proxies without a call each (a list of components, every frame)
        owner = segments.owner
        return [_object_ext(*item._sp_handle) if owner is not None and getattr(item, "_sp_client", None) is owner
                else encode(item, segments, depth + 1) for item in value]
    if isinstance(value, dict):
        if not all(isinstance(key, str) for key in value):
            raise ValueRefused("dict keys must be str")
        return {key: encode(item, segments, depth + 1) for key, item in value.items()}
    raise ValueRefused(f"cannot pass a value of type '{type(value).__name__}'")


def _encode_struct(value: Any, names: tuple[str, ...], segments: OutgoingSegments, depth: int) -> dict[str, Any]:
    """An engine struct as a dict of its fields; its plain fields (an FVector's floats) without a call each."""
    if depth >= MAX_VALUE_DEPTH:
        raise ValueTooDeep(f"a value has lists or dicts nested deeper than {MAX_VALUE_DEPTH} levels")
    fields = {}
    for name in names:
        item = getattr(value, name)
        plain = type(item)
        is_plain = (plain is float or plain is str or plain is bool or item is None
                    or (plain is int and -(2**63) <= item < 2**63))
        fields[name] = item if is_plain else encode(item, segments, depth + 1)
    return fields


def _encode_object(value: SpObject, segments: OutgoingSegments) -> msgpack.ExtType:
    owner = segments.owner
    if owner is not None and getattr(value, "_sp_client", None) is owner:  # the connection's own proxy (the usual)
        handle = value._sp_handle  # type: ignore[attr-defined]
        return _object_ext(handle[0], handle[1])
    handle = getattr(value, "_sp_handle", None)
    if handle is None:
        raise TypeError(f"{type(value).__name__} is not an engine object of this connection")
    if segments.owner is not None and not of_engine(value, segments.owner):
        # A handle means something only to the engine that made it: sent elsewhere, it would name
        # whatever object that engine has under the same number.
        raise ValueRefused(f"{type(value).__name__} belongs to another engine (a different spear.Instance)")
    return _object_ext(handle[0], handle[1])


@functools.lru_cache(maxsize=1024, typed=True)  # typed: equal values of two enums are two entries
def _enum_ext(value: enum.IntEnum) -> msgpack.ExtType:
    """An enum value, made once for each (an argument many calls pass, such as a space or a mode)."""
    return msgpack.ExtType(EXT_ENUM, struct.pack("<q", int(value)) + type(value).__name__.encode())


@functools.lru_cache(maxsize=4096)
def _object_ext(index: int, generation: int) -> msgpack.ExtType:
    """An object reference, made once for the objects a client names often: an ExtType costs more to make
    than the rest of a call's encoding. A handle's index and generation name one object for good, so a
    cached reference never names another."""
    return msgpack.ExtType(EXT_OBJECT, struct.pack("<II", index, generation))


def _ext_hook(code: int, data: bytes, buffers: ReplyBuffers | None = None,
              tail: tuple[memoryview, int] | None = None) -> Any:
    if code == EXT_OBJECT:
        index, generation = struct.unpack_from("<II", data)
        return ObjectRef(index, generation, data[8:].decode())
    if code == EXT_CLASS:
        name, _, native = data.decode().partition("\0")
        return ClassRef(name, native)
    if code == EXT_ARRAY:
        dtype, shape, payload = msgpack.unpackb(data, raw=False)
        if isinstance(payload, dict) and "tail" in payload:
            if tail is None:
                raise ValueError("a reply named its tail, but has none")
            body, start = tail
            count = int(np.prod(shape)) if shape else 1
            offset = start + int(payload["tail"])
            if offset + int(payload["size"]) > len(body):
                raise ValueError("a reply's array runs past its tail")
            # A view of the reply's own buffer, which no later reply reuses: no copy.
            return np.frombuffer(body, dtype=np.dtype(dtype), count=count, offset=offset).reshape(shape)
        if isinstance(payload, dict) and "buffer" in payload:
            if buffers is None:
                raise ValueError("a reply named a reply buffer, but none was offered")
            return buffers.receive(payload["buffer"], np.dtype(dtype), shape, payload["size"])
        if isinstance(payload, dict):
            if buffers is not None:
                buffers.learn(payload["size"])
            mapping = map_segment(payload["shm"], payload["size"], unlink=True)
            count = int(np.prod(shape)) if shape else 1
            return np.frombuffer(mapping, dtype=np.dtype(dtype), count=count).reshape(shape)
        return np.frombuffer(payload, dtype=np.dtype(dtype)).reshape(shape).copy()
    return msgpack.ExtType(code, data)


def pack_frame(message: dict[str, Any], segments: OutgoingSegments | None = None) -> list[bytes | memoryview]:
    """A message's frame, as the buffers to send in order: [length][message], or, when its arguments placed
    arrays in the tail of `segments`, [length | TAIL_FLAG][message length][message][padding][tail]."""
    body: bytes = msgpack.packb(message, use_bin_type=True)
    if segments is None or not segments.tail:
        return [struct.pack("<I", len(body)) + body]
    tail_start = -(-(4 + len(body)) // TAIL_ALIGNMENT) * TAIL_ALIGNMENT  # from the byte after the length word
    length = tail_start + segments.tail_size
    if length >= TAIL_FLAG:
        raise ValueRefused(f"a message of {length} bytes is past the 2 GiB a frame can carry")
    parts: list[bytes | memoryview] = [struct.pack("<II", length | TAIL_FLAG, len(body)) + body
                                       + bytes(tail_start - 4 - len(body))]
    written = 0
    for offset, array in segments.tail:
        if offset > written:
            parts.append(bytes(offset - written))
        parts.append(memoryview(array.reshape(-1).view(np.uint8)))  # type: ignore[arg-type]
        written = offset + array.nbytes
    return parts


def unpack_body(body: bytes | bytearray | memoryview, buffers: ReplyBuffers | None = None,
                tail: tuple[memoryview, int] | None = None) -> Any:
    """A reply; `buffers` are the reply buffers its request offered (spear._reply_buffers); `tail` the frame's
    buffer and where its tail starts there, when the reply has one (TAIL_FLAG)."""
    if buffers is not None:
        buffers.begin_reply()
    hook: Callable[[int, bytes], Any] = _ext_hook
    if buffers is not None or tail is not None:
        hook = functools.partial(_ext_hook, buffers=buffers, tail=tail)
    try:
        return msgpack.unpackb(body, raw=False, ext_hook=hook, strict_map_key=False)
    finally:
        if buffers is not None:
            buffers.end_reply()  # only the arrays the caller keeps hold buffers from here on
