"""Every name, spelling and type mapping the templates need, computed from the IR.

Templates hold loops and holes only; anything that needs a decision is a function here.
"""

from __future__ import annotations

import re
from collections.abc import Callable

from codegen.model import Class, Function, Module, Param, Property, TypeRef

# The module every other one builds on: plugins derive from its classes and use its structs and enums.
ENGINE_MODULE = "engine"
ENGINE_PACKAGE = "spear._engine"


# -- Python spellings ------------------------------------------------------------------------------

# How a module spells the name of a reflected class: as it is (the API module), or through another module
# (the RPC module writes its own module's object classes api.X, its names being proxies).
Qualifier = Callable[[str], str]


def _as_is(name: str) -> str:
    return name


def py_type(t: TypeRef, *, nullable_objects: bool = True, result: bool = False, qualify: Qualifier = _as_is) -> str:
    """The Python annotation for a type, as used in stubs and proxies (declared types at run time are type
    codes, codegen/typecodes.py); `qualify` spells the object classes' names.

    Class references are accepted as a class or its name, and returned as the class (or None)."""
    if t.kind == "void":
        return "None"
    if t.kind in ("bool", "int", "float", "str"):
        return t.kind
    if t.kind in ("enum", "struct"):
        return t.name
    if t.kind == "object":
        return f"{qualify(t.name)} | None" if nullable_objects else qualify(t.name)
    if t.kind == "class":
        return f"type[{qualify(t.name)}] | None" if result else f"type[{qualify(t.name)}] | str"
    if t.kind == "list":
        return f"list[{py_type(t.args[0], nullable_objects=False, result=result, qualify=qualify)}]"
    if t.kind == "dict":
        return f"dict[str, {py_type(t.args[0], nullable_objects=False, result=result, qualify=qualify)}]"
    if t.kind == "array":
        return f"NDArray[np.{t.name}]"
    raise ValueError(f"unknown type kind {t.kind}")


def property_py_type(p: Property, qualify: Qualifier = _as_is) -> str:
    return py_type(p.type, nullable_objects=not p.not_null, result=True, qualify=qualify)


def param_py_type(p: Param, qualify: Qualifier = _as_is) -> str:
    """Object parameters are required unless their default is nullptr. A list of objects is taken as a
    Sequence, which is covariant: a list[AStaticMeshActor] is accepted where actors are asked for (a list is
    invariant). Both transports take any collections.abc.Sequence but text and bytes as a list
    (core/pybind/value_convert.cpp, spear/_wire.py)."""
    nullable = p.default_cpp == "nullptr"
    if p.type.kind == "list" and p.type.args[0].kind == "object":
        return f"Sequence[{qualify(p.type.args[0].name)}]"
    if p.type.kind in ("object", "class"):
        base = py_type(p.type, nullable_objects=False, qualify=qualify)
        return f"{base} | None" if nullable else base
    return py_type(p.type, qualify=qualify)


def return_py_type(f: Function, typevar: str | None = None, qualify: Qualifier = _as_is) -> str:
    """The result annotation; with DeterminesOutputType the class part becomes the type variable."""
    t = f.returns
    outs = out_params(f)
    if outs:
        return result_tuple_name(f)
    if typevar is not None:
        if t.kind == "list":
            return f"list[{typevar}]"
        if t.kind == "dict":
            return f"dict[str, {typevar}]"
        if t.kind == "class":  # a class result: the class passed, or a class derived from it
            return f"type[{typevar}]" if f.not_null else f"type[{typevar}] | None"
        return typevar if f.not_null else f"{typevar} | None"
    if t.kind == "object" and f.not_null:
        return qualify(t.name)
    if t.kind == "class" and f.not_null:
        return f"type[{qualify(t.name)}]"
    return py_type(t, result=True, qualify=qualify)


def result_tuple_name(f: Function) -> str:
    return f"{f.name}Result"


def out_params(f: Function) -> list[Param]:
    return [p for p in f.params if p.is_out]


def in_params(f: Function) -> list[Param]:
    return [p for p in f.params if not p.is_out]


_NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?[fFlLuU]*$")


def py_default(p: Param, enums: set[str]) -> str | None:
    """A Python expression for a C++ default, or None when it has no faithful Python spelling."""
    text = p.default_cpp
    if text is None:
        return None
    if text in ("true", "false"):
        return "True" if text == "true" else "False"
    if text == "nullptr":
        return "None"
    if _NUMBER.match(text):
        number = text.rstrip("fFlLuU")
        if p.type.kind == "float" and not any(c in number for c in ".eE"):
            number += ".0"
        return number
    if text.startswith('"') and text.endswith('"') and "\\" not in text:
        return text
    if text in ("{}", "{ }"):
        return {"list": "[]", "dict": "{}", "str": '""'}.get(p.type.kind)
    scope, sep, member = text.rpartition("::")
    if sep and scope in enums and member.isidentifier():
        return f"{scope}.{member}"
    m = re.match(r"^(\w+)\s*[({]\s*(.*?)\s*[)}]$", text)
    if m and p.type.kind == "struct" and m.group(1) == p.type.name:
        args = [a.strip() for a in m.group(2).split(",")] if m.group(2) else []
        if all(_NUMBER.match(a) for a in args):
            return f"{p.type.name}({', '.join(a.rstrip('fFlLuU') for a in args)})"
    return None


# -- C++ spellings ---------------------------------------------------------------------------------

def cpp_string(text: str) -> str:
    """A C++ string literal."""
    escaped = text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
    return f'"{escaped}"'


def cpp_default_value(p: Param) -> str:
    """The default as an expression of the parameter's value type."""
    assert p.default_cpp is not None
    if p.type.cpp.endswith("*"):  # T*(x) is not C++: an object pointer's default (nullptr) is cast instead
        return f"static_cast<{p.type.cpp}>({p.default_cpp})"
    if p.default_cpp.startswith("{"):
        return f"{p.type.cpp}{p.default_cpp}"
    return f"{p.type.cpp}({p.default_cpp})"


def header_stem(header: str) -> str:
    """core/world/actor.h -> core_world_actor"""
    return re.sub(r"[^A-Za-z0-9]", "_", header.rsplit(".", 1)[0])


def classes_by_header(module: Module) -> dict[str, list[Class]]:
    result: dict[str, list[Class]] = {h: [] for h in module.headers}
    for c in module.classes:
        result[c.header].append(c)
    return result


def types_used(module: Module, *, definitions_only: bool = False) -> dict[str, set[str]]:
    """For each header, the reflected type names its classes use: parents, properties, parameters, results
    (definitions_only: parents and struct fields only), whichever module declares them."""
    used: dict[str, set[str]] = {h: set() for h in module.headers}

    def add(header: str, t: TypeRef) -> None:
        if t.kind in ("enum", "struct", "object", "class") and t.name:
            used[header].add(t.name)
        for a in t.args:
            add(header, a)

    for c in module.classes:
        if c.parent:
            used[c.header].add(c.parent)
        for p in c.properties:
            if not definitions_only or c.kind == "struct":
                add(c.header, p.type)
        if definitions_only:
            continue
        for f in c.functions:
            add(c.header, f.returns)
            for q in f.params:
                add(c.header, q.type)
    return used


def header_deps(module: Module, *, definitions_only: bool = False) -> dict[str, list[str]]:
    """For each header, the module's other headers whose types its classes use (parents, properties,
    parameters, results, struct fields), transitively, in module order. A header's generated code includes
    only these: an edit to one header recompiles the generated code of the headers that use its types, not
    the module's.

    definitions_only: only the headers whose generated definitions this header's must follow (its classes'
    parents, its structs' struct and enum fields). Between types those cannot form a cycle, so the bindings
    headers include each other along them (headers whose types need each other's so would be a compile
    error, not a silent misorder)."""
    declared = {c.name: c.header for c in module.classes} | {e.name: e.header for e in module.enums}
    direct = {h: {declared[name] for name in names if name in declared}
              for h, names in types_used(module, definitions_only=definitions_only).items()}
    return {header: [h for h in closure(module, direct, direct[header]) if h != header]
            for header in module.headers}


def closure(module: Module, direct: dict[str, set[str]], start: set[str]) -> list[str]:
    """The headers reachable from `start` through `direct`, in module order."""
    seen: set[str] = set()
    todo = list(start)
    while todo:
        h = todo.pop()
        if h not in seen:
            seen.add(h)
            todo.extend(direct.get(h, ()))
    return [h for h in module.headers if h in seen]


def imported_headers(module: Module, imported: Module, *, definitions_only: bool = False) -> dict[str, list[str]]:
    """For each header of `module` (a plugin), the headers of `imported` (the engine) whose types it uses,
    with theirs (header_deps of `imported`), so that a plugin's generated code includes the engine's
    generated code for those headers only."""
    declared = {c.name: c.header for c in imported.classes} | {e.name: e.header for e in imported.enums}
    deps = header_deps(imported, definitions_only=definitions_only)
    direct = {h: set(deps[h]) for h in imported.headers}
    result = {}
    for header, names in types_used(module, definitions_only=definitions_only).items():
        result[header] = closure(imported, direct, {declared[name] for name in names if name in declared})
    return result


def topo_classes(module: Module) -> list[Class]:
    """Classes with every parent before its children (pybind11 needs bases registered first), and every
    struct after the structs its fields hold (Python dataclass defaults refer to them)."""
    by_name = {c.name: c for c in module.classes}
    ordered: list[Class] = []
    seen: set[str] = set()

    def visit(c: Class) -> None:
        if c.name in seen:
            return
        seen.add(c.name)
        if c.parent in by_name:
            visit(by_name[c.parent])
        for p in c.properties:
            if c.kind == "struct" and p.type.kind == "struct" and p.type.name in by_name:
                visit(by_name[p.type.name])
        ordered.append(c)

    for c in module.classes:
        visit(c)
    return ordered


def doc_lines(doc: str) -> list[str]:
    return doc.splitlines() if doc else []


def py_docstring(doc: str, indent: str) -> str:
    """A triple-quoted docstring, or an empty string when there is no doc."""
    if not doc:
        return ""
    body = doc.replace("\\", "\\\\").replace('"""', '\\"\\"\\"')
    lines = body.splitlines()
    if len(lines) == 1:
        return f'{indent}"""{lines[0]}"""'
    inner = "\n".join(f"{indent}{line}" if line else "" for line in lines[1:])
    return f'{indent}"""{lines[0]}\n{inner}\n{indent}"""'


def referenced_names(module: Module) -> set[str]:
    """Every reflected type name the module's API mentions (parents, parameters, results, fields)."""
    names: set[str] = set()

    def add(t: TypeRef) -> None:
        if t.kind in ("enum", "struct", "object", "class"):
            names.add(t.name)
        for a in t.args:
            add(a)

    for c in module.classes:
        if c.parent:
            names.add(c.parent)
        for p in c.properties:
            add(p.type)
        for f in c.functions:
            add(f.returns)
            for q in f.params:
                add(q.type)
    return names
