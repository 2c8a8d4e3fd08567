"""Views of the IR for the TypeScript template (api.gen.ts): the typed client the browser inspector is written
against. Types are spelled here (naming's job for Python), the template only loops; the same IR also becomes
the reflection data (API) that the client encodes arguments with and the inspector builds its editors from."""

from __future__ import annotations

import json
from dataclasses import dataclass

from codegen import naming, pyviews, specifiers
from codegen.model import Class, Function, Module, Param, Property, TypeRef

RUNTIME = "../../../inspector/src/spear/client.js"


@dataclass(frozen=True)
class TsParam:
    name: str
    type: str
    optional: bool


@dataclass(frozen=True)
class TsFunction:
    name: str
    doc: str
    params: tuple[TsParam, ...]
    returns: str
    type_params: str  # "<T extends AActor = AActor>" for DeterminesOutputType, else ""
    is_static: bool


@dataclass(frozen=True)
class TsField:
    name: str
    type: str
    doc: str
    optional: bool = False
    read_only: bool = False


@dataclass(frozen=True)
class TsClass:
    name: str
    parent: str | None
    doc: str
    properties: tuple[TsField, ...]
    functions: tuple[TsFunction, ...]


@dataclass(frozen=True)
class TsStruct:
    name: str
    doc: str
    fields: tuple[TsField, ...]


@dataclass(frozen=True)
class TsEnum:
    name: str
    doc: str
    entries: tuple[tuple[str, int, str], ...]  # name, value, doc


def ts_type(t: TypeRef, *, result: bool, nullable: bool = True) -> str:
    """The TypeScript type of a value; objects are proxies (null where the engine may return none)."""
    if t.kind == "void":
        return "void"
    if t.kind == "bool":
        return "boolean"
    if t.kind in ("int", "float"):
        return "number"
    if t.kind == "str":
        return "string"
    if t.kind in ("enum", "struct"):
        return t.name
    if t.kind == "object":
        return f"{t.name} | null" if nullable else t.name
    if t.kind == "class":
        return "ClassRef | null" if result else f"SpClass<{t.name}> | string"
    if t.kind == "list":
        return f"{_group(ts_type(t.args[0], result=result, nullable=False))}[]"
    if t.kind == "dict":
        return f"Record<string, {ts_type(t.args[0], result=result, nullable=False)}>"
    if t.kind == "array":
        return f'NDArray<"{t.name}">'
    raise ValueError(f"unknown type kind {t.kind}")


def _group(text: str) -> str:
    return f"({text})" if " " in text else text


def doc_comment(doc: str, indent: str) -> str:
    """A /** */ comment of the IR's doc ("" when there is none)."""
    lines = [line.replace("*/", "*\\/") for line in naming.doc_lines(doc)]
    if not lines:
        return ""
    if len(lines) == 1:
        return f"{indent}/** {lines[0]} */\n"
    body = "".join(f"{indent} * {line}".rstrip() + "\n" for line in lines)
    return f"{indent}/**\n{body}{indent} */\n"


def _param_type(p: Param) -> str:
    if p.type.kind == "object":
        return ts_type(p.type, result=False, nullable=p.default_cpp == "nullptr")
    return ts_type(p.type, result=False)


def _function(c: Class, f: Function) -> TsFunction:
    params = [TsParam(p.name, _param_type(p), p.default_cpp is not None) for p in naming.in_params(f)]
    outs = naming.out_params(f)
    type_params = ""
    if outs:
        fields = ([f"ReturnValue: {ts_type(f.returns, result=True)}"] if f.returns.kind != "void" else []) + [
            f"{p.name}: {ts_type(p.type, result=True)}" for p in outs]
        returns = "{ " + "; ".join(fields) + " }"
    elif f.determines_output_type:
        target = next(p for p in f.params if p.name == f.determines_output_type)
        base = target.type.name
        type_params = f"<T extends {base} = {base}>"
        params = [TsParam(p.name, "SpClass<T> | string", p.optional) if p.name == target.name else p
                  for p in params]
        t = f.returns
        returns = "T[]" if t.kind == "list" else "Record<string, T>" if t.kind == "dict" else (
            "T" if f.not_null else "T | null")
    elif f.returns.kind in ("object", "class") and f.not_null:
        returns = f.returns.name if f.returns.kind == "object" else "ClassRef"
    else:
        returns = ts_type(f.returns, result=True)
    return TsFunction(name=f.name, doc=doc_comment(f.doc, "  "), params=tuple(params), returns=returns,
                      type_params=type_params, is_static=f.is_static)


def _property(p: Property) -> TsField:
    return TsField(name=p.name, type=ts_type(p.type, result=True, nullable=not p.not_null),
                   doc=doc_comment(p.doc, "  "), read_only=p.read_only)


def _struct(c: Class) -> TsStruct:
    partial = any(name == "Partial" for name, _ in c.specifiers)
    return TsStruct(name=c.name, doc=doc_comment(c.doc, ""),
                    fields=tuple(TsField(p.name, ts_type(p.type, result=True), doc_comment(p.doc, "  "),
                                         optional=partial) for p in c.properties))


def _type_json(t: TypeRef) -> dict[str, object]:
    out: dict[str, object] = {"kind": t.kind}
    if t.name:
        out["name"] = t.name
    if t.args:
        out["args"] = [_type_json(a) for a in t.args]
    return out


def _property_json(p: Property) -> dict[str, object]:
    """A property as the inspector's panel needs it; "min"/"max" from ClampMin/ClampMax (the range its editor
    offers; the engine's setter still checks every value)."""
    out: dict[str, object] = {"name": p.name, "type": _type_json(p.type), "readOnly": p.read_only,
                              "notNull": p.not_null, "doc": p.doc}
    for key, field in (("ClampMin", "min"), ("ClampMax", "max")):
        value = specifiers.lookup(p.specifiers, key)
        if value is not None:
            number = float(value)
            out[field] = int(number) if number.is_integer() else number
    return out


def reflection_json(module: Module) -> str:
    """The reflection data the client encodes arguments with and the inspector builds its panels from: classes
    (parent, properties, functions' parameters), structs' fields, enums' entries. Compact, sorted JSON."""
    classes: dict[str, object] = {}
    structs: dict[str, object] = {}
    for c in module.classes:
        if c.kind == "struct":
            structs[c.name] = {"doc": c.doc, "fields": [{"name": p.name, "type": _type_json(p.type)}
                                                        for p in c.properties]}
            continue
        classes[c.name] = {
            "parent": c.parent, "doc": c.doc, "abstract": c.abstract,
            "properties": [_property_json(p) for p in c.properties],
            "functions": {f.name: {"static": f.is_static, "params": [
                {"name": p.name, "type": _type_json(p.type), "optional": p.default_cpp is not None}
                for p in naming.in_params(f)]} for f in c.functions},
        }
    enums = {e.name: {"doc": e.doc, "entries": [{"name": x.name, "value": x.value} for x in e.entries]}
             for e in module.enums}
    data = {"apiHash": pyviews.api_hash(module), "classes": classes, "structs": structs, "enums": enums}
    return json.dumps(data, sort_keys=True, separators=(",", ":"))


def module_view(module: Module) -> dict[str, object]:
    classes = [c for c in naming.topo_classes(module) if c.kind == "class"]
    return {
        "runtime": RUNTIME,
        "ts_enums": [TsEnum(e.name, doc_comment(e.doc, ""), tuple((x.name, x.value, doc_comment(x.doc, "  "))
                                                                  for x in e.entries)) for e in module.enums],
        "ts_structs": [_struct(c) for c in sorted(module.classes, key=lambda c: c.name) if c.kind == "struct"],
        "ts_classes": [TsClass(c.name, c.parent, doc_comment(c.doc, ""), tuple(_property(p) for p in c.properties),
                               tuple(_function(c, f) for f in c.functions)) for c in classes],
        "reflection": reflection_json(module),
    }
