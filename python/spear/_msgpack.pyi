# The types of the msgpack functions spear uses (python3-msgpack ships none); see _msgpack.py.
from collections.abc import Callable
from typing import Any

class ExtType:
    code: int
    data: bytes
    def __init__(self, code: int, data: bytes) -> None: ...

def packb(o: Any, *, use_bin_type: bool = ..., default: Callable[[Any], Any] | None = ...) -> bytes: ...
def unpackb(packed: bytes | bytearray | memoryview, *, raw: bool = ..., ext_hook: Callable[[int, bytes], Any] = ...,
            strict_map_key: bool = ...) -> Any: ...

__all__ = ["ExtType", "packb", "unpackb"]
