"""Blueprint assets -> IR: the generator types each data-defined class as its native parent, and the
functions a blueprint declares as methods of a stub class of its own.

Only the header of an asset (its name, parent and doc) and its functions' signatures matter here; the engine
reads the rest when the class is loaded, and checks the functions' bodies then. A malformed asset, a parent
that is not a reflected class, or a function signature that is not well-formed is an error with the asset's
file and line, like a malformed header.
"""

from __future__ import annotations

import dataclasses
import json
import keyword
import os
from pathlib import Path
from typing import Any, TypeGuard

from codegen.errors import GeneratorError
from codegen.model import Blueprint, Function, Module, Param, TypeRef

_SCALARS = {"bool", "int", "float", "str"}


def add_blueprints(module: Module, directory: Path, root: Path) -> Module:
    blueprints = []
    classes = {c.name for c in module.classes if c.kind == "class"}
    for path in sorted(directory.glob("*.json")):
        rel = Path(os.path.relpath(path, root)).as_posix()
        text = path.read_text()
        try:
            data = json.loads(text)
        except json.JSONDecodeError as e:
            raise GeneratorError(rel, e.lineno, f"blueprint is not valid JSON: {e.msg}") from None
        line = _line_of(text, '"parent"')
        parent = data.get("parent") if isinstance(data, dict) else None
        if not isinstance(parent, str) or parent not in classes:
            raise GeneratorError(rel, line, f"blueprint parent {parent!r} is not a reflected class of module "
                                            f"'{module.name}'")
        functions = _functions(data.get("functions", []), module, parent, rel, text)
        blueprints.append(Blueprint(name=path.stem, parent=parent, doc=str(data.get("doc", "")), asset=rel,
                                    functions=functions))
    names = {c.name for c in module.classes} | {e.name for e in module.enums}
    for b in blueprints:
        if b.name in names:
            raise GeneratorError(b.asset, 1, f"blueprint '{b.name}' has the name of a reflected type")
    return dataclasses.replace(module, blueprints=tuple(blueprints))


def _line_of(text: str, needle: str, after: int = 1) -> int:
    """The first line at or after `after` that holds `needle` (1 when none does)."""
    lines = text.splitlines()
    return next((n for n in range(after, len(lines) + 1) if needle in lines[n - 1]), 1)


def _name_line(text: str, name: Any, after: int) -> int:
    """The line of the entry `"name": <name>` at or after `after`; `after` itself when the name is no string."""
    return _line_of(text, f'"name": {json.dumps(name)}', after) if isinstance(name, str) else after


def _is_name(name: Any) -> TypeGuard[str]:
    """A public Python identifier: what a method or keyword argument of the stubs can be called."""
    return isinstance(name, str) and name.isidentifier() and not keyword.iskeyword(name) and \
        not name.startswith("_") and name != "self"


def _inherited(module: Module, parent: str) -> set[str]:
    """The members a blueprint's objects have already: its parent chain's functions and properties (in this
    module), and what every engine object has in Python (spear._object.SpObject, call_async, send_async)."""
    names = {"is_valid", "call_sp_func", "get_sp_func_names", "call_async", "send_async"}
    classes = {c.name: c for c in module.classes}
    current = classes.get(parent)
    while current is not None:
        names |= {f.name for f in current.functions} | {p.name for p in current.properties}
        current = classes.get(current.parent) if current.parent else None
    return names


def _functions(entries: Any, module: Module, parent: str, rel: str, text: str) -> tuple[Function, ...]:
    if not isinstance(entries, list):
        raise GeneratorError(rel, _line_of(text, '"functions"'), "blueprint 'functions' must be a list")
    functions: list[Function] = []
    inherited = _inherited(module, parent)
    cursor = _line_of(text, '"functions"')  # each function's lines come after the one before
    for entry in entries:
        name = entry.get("name") if isinstance(entry, dict) else None
        line = _name_line(text, name, cursor)
        cursor = line + 1
        if not _is_name(name):
            raise GeneratorError(rel, line, f"blueprint function name {name!r} is not a public Python identifier")
        if any(f.name == name for f in functions):
            raise GeneratorError(rel, line, f"blueprint function '{name}' is declared twice")
        if name in inherited:
            raise GeneratorError(rel, line, f"blueprint function '{name}' has the name of a member of {parent}")
        declared = entry.get("params", [])
        if not isinstance(declared, list):
            raise GeneratorError(rel, _line_of(text, '"params"', line),
                                 f"'params' of blueprint function '{name}' must be a list")
        params: list[Param] = []
        pcursor = line
        for p in declared:
            pname = p.get("name") if isinstance(p, dict) else None
            pline = _name_line(text, pname, pcursor)
            pcursor = pline + 1
            if not _is_name(pname):
                raise GeneratorError(rel, pline, f"parameter {pname!r} of blueprint function '{name}' is not a "
                                                 "public Python identifier")
            if any(q.name == pname for q in params):
                raise GeneratorError(rel, pline, f"parameter '{pname}' of blueprint function '{name}' is declared twice")
            ptype = _type(p.get("type"), module, rel, pline, f"parameter '{pname}' of blueprint function '{name}'")
            default = _default(p["default"], ptype, module) if "default" in p else None
            params.append(Param(name=pname, type=ptype, cpp_decl="", default_cpp=default))
        returns = TypeRef(kind="void", cpp="void")
        if "returns" in entry:
            returns = _type(entry["returns"], module, rel, _line_of(text, '"returns"', line),
                            f"the result of blueprint function '{name}'")
        functions.append(Function(name=name, doc=str(entry.get("doc", "")), returns=returns, params=tuple(params)))
    return tuple(functions)


def _type(name: Any, module: Module, rel: str, line: int, what: str) -> TypeRef:
    """A blueprint's type name as the IR's type: a scalar, or a struct, enum or class of the module."""
    if name in _SCALARS:
        return TypeRef(kind=name, cpp=name)
    for c in module.classes:
        if c.name == name:
            return TypeRef(kind="struct" if c.kind == "struct" else "object", cpp=c.cpp_name, name=c.name)
    for e in module.enums:
        if e.name == name:
            return TypeRef(kind="enum", cpp=e.cpp_name, name=e.name)
    raise GeneratorError(rel, line, f"{what}: unknown type {name!r} (bool, int, float, str, or a reflected "
                                    f"struct, enum or class of module '{module.name}')")


def _default(value: Any, t: TypeRef, module: Module) -> str:
    """A JSON default in the C++ spelling the stubs turn into a Python default (naming.py_default); what has
    none there is shown as `= ...`."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "nullptr"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, str) and t.kind == "enum":
        return f"{t.name}::{value}"
    if isinstance(value, str):
        return json.dumps(value)
    return "{...}"  # a struct or list: shown as `= ...`
