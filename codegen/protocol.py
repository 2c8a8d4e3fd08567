"""The RPC protocol's messages from their one source, core/rpc/protocol.json:

    python3 -m codegen.protocol generate|check --root .

generate writes the server's constants (generated/rpc/cpp/protocol.gen.h), the Python client's typed requests
(generated/rpc/python/protocol.py, imported as spear._protocol) and the TypeScript client's request types
(generated/rpc/ts/protocol.gen.ts); check reports any of them that differs from what generate would write. A
malformed source is refused with its file and the entry at fault.
"""

from __future__ import annotations

import argparse
import json
import keyword
import re
import sys
from dataclasses import dataclass
from pathlib import Path

from codegen.emit import _env

SOURCE = "core/rpc/protocol.json"
OUTPUTS = {
    "generated/rpc/cpp/protocol.gen.h": "protocol.gen.h.j2",
    "generated/rpc/python/protocol.py": "protocol.py.j2",
    "generated/rpc/ts/protocol.gen.ts": "protocol.gen.ts.j2",
}
_BASE_TYPES = ("str", "int", "bool", "any", "object", "map", "list")
_LITERAL = re.compile(r"'([a-z_]+)'")
_NAME = re.compile(r"[a-z][a-z_]*")


def _camel(name: str) -> str:
    """snake_case -> CamelCase: "call_typed" -> "CallTyped"."""
    return "".join(part.capitalize() for part in name.split("_"))


class _Named:
    """What the templates call a field or an op: "kCallTyped" in C++, "CallTyped" in Python and TypeScript."""

    name: str

    @property
    def constant(self) -> str:
        return "k" + _camel(self.name)

    @property
    def title(self) -> str:
        return _camel(self.name)


class ProtocolError(Exception):
    """A malformed protocol source: the message names the file and the entry."""


@dataclass(frozen=True)
class FieldType:
    base: str  # one of _BASE_TYPES, or "literal"
    literals: tuple[str, ...]
    optional: bool

    @property
    def python(self) -> str:
        if self.base == "literal":
            return "Literal[" + ", ".join(f'"{v}"' for v in self.literals) + "]"
        return {"str": "str", "int": "int", "bool": "bool", "any": "Any", "object": "Any", "map": "Mapping[str, Any]",
                "list": "Sequence[Any]"}[self.base]

    @property
    def typescript(self) -> str:
        if self.base == "literal":
            return " | ".join(f'"{v}"' for v in self.literals)
        return {"str": "string", "int": "number", "bool": "boolean", "any": "Packable", "object": "Packable",
                "map": "{ readonly [name: string]: Packable }", "list": "readonly Packable[]"}[self.base]


@dataclass(frozen=True)
class Field(_Named):
    name: str
    type: FieldType
    doc: str

    @property
    def keyword(self) -> bool:
        """Named like a Python keyword ("class"): no keyword parameter can have its name."""
        return keyword.iskeyword(self.name)


@dataclass(frozen=True)
class Op(_Named):
    name: str
    doc: str
    fields: tuple[Field, ...]
    reply: tuple[Field, ...]


@dataclass(frozen=True)
class Protocol:
    doc: tuple[str, ...]
    common: tuple[Field, ...]
    ops: tuple[Op, ...]
    reply: tuple[Field, ...]
    push: tuple[Field, ...]

    @property
    def field_names(self) -> list[Field]:
        """Every request field once (its first declaration), sorted by name."""
        seen: dict[str, Field] = {}
        for field in (*self.common, *(f for op in self.ops for f in op.fields)):
            seen.setdefault(field.name, field)
        return sorted(seen.values(), key=lambda f: f.name)

    @property
    def reply_names(self) -> list[Field]:
        seen: dict[str, Field] = {}
        for field in (*self.reply, *self.push, *(f for op in self.ops for f in op.reply)):
            seen.setdefault(field.name, field)
        return sorted(seen.values(), key=lambda f: f.name)

    @property
    def literals(self) -> list[str]:
        """Every literal value a field may take, once, sorted."""
        return sorted({v for op in self.ops for f in op.fields for v in f.type.literals})


def _type(text: object, where: str) -> FieldType:
    if not isinstance(text, str) or not text:
        raise ProtocolError(f"{where}: a field's type must be a string, got {text!r}")
    optional = text.endswith("?")
    body = text[:-1] if optional else text
    if body in _BASE_TYPES:
        return FieldType(body, (), optional)
    parts = body.split("|")
    literals = tuple(m.group(1) for m in (_LITERAL.fullmatch(p) for p in parts) if m)
    if len(literals) != len(parts):
        raise ProtocolError(f"{where}: unknown type '{text}' (one of {', '.join(_BASE_TYPES)}, or 'a'|'b', "
                            "with ? for an optional field)")
    return FieldType("literal", literals, optional)


def _fields(entries: object, where: str) -> tuple[Field, ...]:
    if not isinstance(entries, dict):
        raise ProtocolError(f"{where}: expected an object of fields")
    fields = []
    for name, spec in entries.items():
        if not _NAME.fullmatch(name):
            raise ProtocolError(f"{where}: field name '{name}' is not snake_case")
        doc = ""
        if isinstance(spec, dict):
            doc = str(spec.get("doc", ""))
            spec = spec.get("type")
        fields.append(Field(name, _type(spec, f"{where}.{name}"), doc))
    return tuple(fields)


def load(path: Path) -> Protocol:
    try:
        data = json.loads(path.read_text())
    except (OSError, json.JSONDecodeError) as error:
        raise ProtocolError(f"{path}: {error}") from None
    where = str(path)
    ops = []
    for name, spec in data.get("ops", {}).items():
        if not _NAME.fullmatch(name) or not isinstance(spec, dict):
            raise ProtocolError(f"{where}: ops.{name}: an op is a snake_case name with an object of fields")
        ops.append(Op(name, str(spec.get("doc", "")), _fields(spec.get("fields", {}), f"{where}: ops.{name}.fields"),
                      _fields(spec.get("reply", {}), f"{where}: ops.{name}.reply")))
    if not ops:
        raise ProtocolError(f"{where}: no ops")
    common = _fields(data.get("common", {}), f"{where}: common")
    for op in ops:
        for field in op.fields:
            if any(field.name == c.name for c in common):
                raise ProtocolError(f"{where}: ops.{op.name}.fields.{field.name}: already a common field")
    doc = data.get("doc", [])
    return Protocol(tuple(doc if isinstance(doc, list) else [doc]), common, tuple(ops),
                    _fields(data.get("reply", {}), f"{where}: reply"), _fields(data.get("push", {}), f"{where}: push"))


def render(protocol: Protocol) -> dict[str, str]:
    env = _env()
    return {out: env.get_template(template).render(p=protocol, source=SOURCE) for out, template in OUTPUTS.items()}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python3 -m codegen.protocol", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("command", choices=["generate", "check"])
    parser.add_argument("--root", type=Path, required=True, help="project root")
    parser.add_argument("--stamp", type=Path, help="file to touch after a successful generate (for build systems)")
    args = parser.parse_args(argv)
    root = args.root.resolve()
    try:
        outputs = render(load(root / SOURCE))
    except ProtocolError as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    stale = [name for name, text in outputs.items()
             if not (root / name).is_file() or (root / name).read_text() != text]
    if args.command == "check":
        for name in stale:
            print(f"{name}: differs from what {SOURCE} generates (python3 -m codegen.protocol generate)",
                  file=sys.stderr)
        return 1 if stale else 0
    for name in stale:  # unchanged files keep their time stamps: nothing rebuilds for nothing
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(outputs[name])
    if args.stamp:
        args.stamp.parent.mkdir(parents=True, exist_ok=True)
        args.stamp.touch()
    print(f"codegen.protocol: {SOURCE}: {len(outputs)} outputs, {len(stale)} written")
    return 0


if __name__ == "__main__":
    sys.exit(main())
