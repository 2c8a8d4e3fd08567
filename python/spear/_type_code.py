"""Declared types as data: how an RPC result becomes the typed value the in-process API returns.

The generator writes one TypeCode per type a module's properties, results and struct fields have (the `T_...`
constants of its type_codes.py, and FIELD_TYPES there for each struct and result tuple); the server sends the
same codes with dynamic calls' results (`call_typed`, `get_typed`), in the wire form core/reflect/type_code.h
writes. spear._rpc_types decodes by
them; nothing parses an annotation string.
"""

from __future__ import annotations

from typing import Any, Literal, NamedTuple

# The generator's type model, spelled as codegen/model.py's TypeKind (held to it by a test).
Kind = Literal["void", "bool", "int", "float", "str", "enum", "struct", "object", "class", "array", "list", "dict"]


class TypeCode(NamedTuple):
    """kind: see Kind. name: an enum's, struct's or object class's name, a class reference's base, an array's
    dtype. optional: None is a value of it. element: a list's or dict's element (dict keys are str)."""

    kind: Kind
    name: str = ""
    optional: bool = False
    element: TypeCode | None = None

    @staticmethod
    def from_wire(wire: Any) -> TypeCode:
        """The code the server sent: [kind, name, optional, element or None]."""
        kind, name, optional, element = wire
        return TypeCode(kind, name, bool(optional), TypeCode.from_wire(element) if element is not None else None)
