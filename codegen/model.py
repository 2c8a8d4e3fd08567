"""The IR: frozen dataclasses between libclang and the emitters.

libclang cursors never leave the scanner; templates only ever see these. The IR dumps to stable JSON
(sorted keys, header paths relative to the project root, no line numbers), which is committed as
generated/<module>/reflection.json so that API changes show up in review.
"""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass, field
from typing import Any, Literal, get_args

# The kinds of value that cross the boundary: the one list. The C++ enum sp::reflect::TypeCode::Kind has
# these, capitalised, in this order, and spear._type_code.Kind spells them as here (the runtime package
# cannot import the generator); tests/codegen/test_type_model.py holds both to it.
TypeKind = Literal[
    "void", "bool", "int", "float", "str", "enum", "struct", "object", "class", "array", "list", "dict"
]
KINDS: tuple[TypeKind, ...] = get_args(TypeKind)


@dataclass(frozen=True)
class TypeRef:
    """A type that crosses the boundary.

    cpp is the C++ value type as generated code must spell it (no const or reference). name is the
    reflected type's name for enum/struct/object/class (for class: the required base class), or the
    numpy dtype for array. args holds the element type of list and dict (dict keys are always str).
    """

    kind: TypeKind
    cpp: str
    name: str = ""
    args: tuple[TypeRef, ...] = ()


@dataclass(frozen=True)
class Param:
    name: str
    type: TypeRef
    cpp_decl: str  # the parameter's declared type, e.g. "const FVector &"
    default_cpp: str | None = None
    is_out: bool = False


@dataclass(frozen=True)
class Function:
    name: str
    doc: str
    returns: TypeRef
    params: tuple[Param, ...]
    is_static: bool = False
    is_const: bool = False
    specifiers: tuple[tuple[str, str], ...] = ()
    determines_output_type: str | None = None  # name of the TSubclassOf parameter that fixes the result class
    not_null: bool = False  # object results are never None


@dataclass(frozen=True)
class Property:
    name: str
    doc: str
    type: TypeRef
    read_only: bool = False
    setter: str | None = None  # reflected function that writes it (UE's Setter= specifier)
    specifiers: tuple[tuple[str, str], ...] = ()
    default_cpp: str | None = None  # the member initializer, e.g. "1.0" or "{1.0, 1.0, 1.0}"
    not_null: bool = False  # an object reference that is never None (set in the constructor)


@dataclass(frozen=True)
class Class:
    name: str
    cpp_name: str  # fully qualified
    kind: Literal["class", "struct"]
    header: str
    doc: str
    parent: str | None = None
    parent_cpp: str | None = None  # the parent, fully qualified (C++ code names it from outside its namespace)
    abstract: bool = False
    properties: tuple[Property, ...] = ()
    functions: tuple[Function, ...] = ()
    specifiers: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True)
class EnumEntry:
    name: str
    value: int
    doc: str


@dataclass(frozen=True)
class Enum:
    name: str
    cpp_name: str
    header: str
    doc: str
    entries: tuple[EnumEntry, ...]


@dataclass(frozen=True)
class Blueprint:
    """A data-defined class: an asset naming a native parent (core/scene/blueprint.h)."""

    name: str
    parent: str
    doc: str
    asset: str  # relative to the project root
    functions: tuple[Function, ...] = ()  # the functions it declares (core/scene/blueprint_functions.h)


@dataclass(frozen=True)
class Module:
    """Everything reflected in one set of headers (the engine, or one plugin)."""

    name: str
    headers: tuple[str, ...]
    classes: tuple[Class, ...] = ()
    enums: tuple[Enum, ...] = ()
    imports: tuple[str, ...] = field(default=())  # modules whose types this one uses (plugins import "engine")
    blueprints: tuple[Blueprint, ...] = ()

    def to_json(self) -> str:
        return json.dumps(dataclasses.asdict(self), indent=1, sort_keys=True) + "\n"

    @staticmethod
    def from_json(text: str) -> Module:
        return _module_from_dict(json.loads(text))


def _type_from_dict(d: dict[str, Any]) -> TypeRef:
    return TypeRef(kind=d["kind"], cpp=d["cpp"], name=d["name"], args=tuple(_type_from_dict(a) for a in d["args"]))


def _pairs(items: list[list[str]]) -> tuple[tuple[str, str], ...]:
    return tuple((k, v) for k, v in items)


def _module_from_dict(d: dict[str, Any]) -> Module:
    classes = []
    for c in d["classes"]:
        props = tuple(
            Property(
                name=p["name"], doc=p["doc"], type=_type_from_dict(p["type"]), read_only=p["read_only"],
                setter=p["setter"], specifiers=_pairs(p["specifiers"]), default_cpp=p["default_cpp"],
                not_null=p["not_null"],
            )
            for p in c["properties"]
        )
        funcs = tuple(
            Function(
                name=f["name"], doc=f["doc"], returns=_type_from_dict(f["returns"]),
                params=tuple(
                    Param(
                        name=p["name"], type=_type_from_dict(p["type"]), cpp_decl=p["cpp_decl"],
                        default_cpp=p["default_cpp"], is_out=p["is_out"],
                    )
                    for p in f["params"]
                ),
                is_static=f["is_static"], is_const=f["is_const"], specifiers=_pairs(f["specifiers"]),
                determines_output_type=f["determines_output_type"], not_null=f["not_null"],
            )
            for f in c["functions"]
        )
        classes.append(
            Class(
                name=c["name"], cpp_name=c["cpp_name"], kind=c["kind"], header=c["header"], doc=c["doc"],
                parent=c["parent"], parent_cpp=c["parent_cpp"], abstract=c["abstract"], properties=props,
                functions=funcs,
                specifiers=_pairs(c["specifiers"]),
            )
        )
    enums = tuple(
        Enum(
            name=e["name"], cpp_name=e["cpp_name"], header=e["header"], doc=e["doc"],
            entries=tuple(EnumEntry(**x) for x in e["entries"]),
        )
        for e in d["enums"]
    )
    return Module(
        name=d["name"], headers=tuple(d["headers"]), classes=tuple(classes), enums=enums, imports=tuple(d["imports"]),
        blueprints=tuple(Blueprint(**b) for b in d.get("blueprints", [])),
    )
