"""A WebSocket client for the inspector's tests, written against RFC 6455 from a plain socket: it speaks spear's
protocol as a browser does (core/rpc/web.h), so the tests see the server exactly as the page does, and can also
send what a browser never would (unmasked frames, another site's Origin)."""

from __future__ import annotations

import base64
import concurrent.futures
import os
import socket
import struct
from collections.abc import Callable
from typing import Any, TypeVar
from urllib.parse import parse_qs, urlparse

import msgpack

import spear
from spear._engine import API_HASH

T = TypeVar("T")


def served(instance: spear.Instance, work: Callable[[], T]) -> T:
    """Runs `work` (a browser's side) in a thread while this one lets the engine answer it: in-process the engine
    is this thread's, and answers its inspector between frames or in serve_inspector()."""
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        future = pool.submit(work)
        while not future.done():
            instance.serve_inspector(seconds=0.02)
        return future.result()


def split_url(url: str) -> tuple[str, int, str]:
    """(host, port, token) of an inspector address "http://host:port/?token=..."."""
    parsed = urlparse(url)
    return parsed.hostname or "", parsed.port or 80, parse_qs(parsed.query).get("token", [""])[0]


def http_get(url: str, *, headers: dict[str, str] | None = None, method: str = "GET") -> tuple[int, bytes]:
    """(status, body) of one request, read to the end (the server closes after each response)."""
    parsed = urlparse(url)
    target = parsed.path + (f"?{parsed.query}" if parsed.query else "")
    lines = [f"{method} {target} HTTP/1.1", f"Host: {parsed.hostname}:{parsed.port}"]
    lines += [f"{k}: {v}" for k, v in (headers or {}).items()]
    with socket.create_connection((parsed.hostname, parsed.port), timeout=10) as s:
        s.sendall(("\r\n".join(lines) + "\r\n\r\n").encode())
        data = b""
        while chunk := s.recv(65536):
            data += chunk
    head, _, body = data.partition(b"\r\n\r\n")
    return int(head.split(b" ")[1]), body


def frame(payload: bytes, opcode: int = 2, *, masked: bool = True, fin: bool = True) -> bytes:
    """One client frame (masked, as a browser's must be)."""
    header = bytes([(0x80 if fin else 0) | opcode])
    size = len(payload)
    mask_bit = 0x80 if masked else 0
    if size < 126:
        header += bytes([mask_bit | size])
    elif size < 65536:
        header += bytes([mask_bit | 126]) + struct.pack(">H", size)
    else:
        header += bytes([mask_bit | 127]) + struct.pack(">Q", size)
    if not masked:
        return header + payload
    mask = os.urandom(4)
    return header + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(payload))


class WebSocketClient:
    def __init__(self, url: str, *, origin: str | None = None) -> None:
        host, port, self.token = split_url(url)
        self.sock = socket.create_connection((host, port), timeout=20)
        key = base64.b64encode(os.urandom(16)).decode()
        headers = [f"GET / HTTP/1.1", f"Host: {host}:{port}", "Upgrade: websocket", "Connection: Upgrade",
                   f"Sec-WebSocket-Key: {key}", "Sec-WebSocket-Version: 13"]
        if origin is not None:
            headers.append(f"Origin: {origin}")
        self.sock.sendall(("\r\n".join(headers) + "\r\n\r\n").encode())
        self.buffer = b""
        while b"\r\n\r\n" not in self.buffer:
            chunk = self.sock.recv(65536)
            if not chunk:
                break
            self.buffer += chunk
        head, _, self.buffer = self.buffer.partition(b"\r\n\r\n")
        self.status = int(head.split(b" ")[1]) if head else 0
        self.next_id = 1
        self.pushes: list[dict[str, Any]] = []  # what the server sent unasked (log lines, progress)

    def _read(self, n: int) -> bytes:
        while len(self.buffer) < n:
            chunk = self.sock.recv(65536)
            if not chunk:
                raise ConnectionError("closed")
            self.buffer += chunk
        data, self.buffer = self.buffer[:n], self.buffer[n:]
        return data

    def receive_frame(self) -> tuple[int, bytes]:
        first, second = self._read(2)
        size = second & 0x7F
        if size == 126:
            size = struct.unpack(">H", self._read(2))[0]
        elif size == 127:
            size = struct.unpack(">Q", self._read(8))[0]
        return first & 0x0F, self._read(size)

    def send_raw(self, data: bytes) -> None:
        self.sock.sendall(data)

    def request(self, op: str, **fields: Any) -> dict[str, Any]:
        """One request; its reply ({"id", "ok"} or {"id", "error": [type, message]})."""
        message = msgpack.packb({"id": self.next_id, "op": op, **fields}, use_bin_type=True)
        self.next_id += 1
        self.send_raw(frame(struct.pack("<I", len(message)) + message))
        while True:
            opcode, payload = self.receive_frame()
            assert opcode == 2, f"expected a binary message, got opcode {opcode}"
            word = struct.unpack_from("<I", payload)[0]
            if word & 0x80000000:  # a reply with a tail: [word][message length][message]...
                size = struct.unpack_from("<I", payload, 4)[0]
                body = payload[8:8 + size]
            else:
                body = payload[4:4 + word]
            reply = dict(msgpack.unpackb(body, raw=False, strict_map_key=False))
            if "id" in reply:
                return reply
            self.pushes.append(reply)

    def hello(self, token: str | None = None) -> dict[str, Any]:
        return self.request("hello", api_hash=API_HASH, token=self.token if token is None else token)

    def closed_by_server(self) -> bool:
        """Whether the server closes the connection (reads to the end)."""
        try:
            while self.sock.recv(65536):
                pass
        except (ConnectionError, OSError):
            pass
        return True

    def close(self) -> None:
        self.sock.close()
