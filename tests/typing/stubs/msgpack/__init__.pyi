# The part of python3-msgpack (Debian ships it untyped) that spear uses, for mypy and pyright.
from collections.abc import Callable
from typing import Any

class ExtType:
    code: int
    data: bytes
    def __init__(self, code: int, data: bytes) -> None: ...

def packb(o: Any, *, use_bin_type: bool = ..., default: Callable[[Any], Any] | None = ...) -> bytes: ...
def unpackb(packed: bytes, *, raw: bool = ..., ext_hook: Callable[[int, bytes], Any] = ...,
            strict_map_key: bool = ...) -> Any: ...
