"""The part of msgpack the wire format uses. Debian's python3-msgpack ships no type information, so its
types are declared beside this file (_msgpack.pyi): a user's type checker reads those and never needs
msgpack's own stubs."""

from msgpack import ExtType, packb, unpackb

__all__ = ["ExtType", "packb", "unpackb"]
