"""Views of the IR for the Python templates (api.py, api.pyi, rpc.py): frozen dataclasses built here, each
type spelled twice, as the API module and as the RPC module (whose own object classes are api.X)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

from codegen import naming, specifiers, typecodes
from codegen.model import Blueprint, Class, Function, Module, Param, Property


@dataclass(frozen=True)
class ParamView:
    name: str
    type: str
    rpc_type: str
    stub_default: str  # " = value", " = ..." or ""
    proxy_default: str  # " = _DEFAULT" or ""


@dataclass(frozen=True)
class OverloadView:
    params: tuple[ParamView, ...]
    returns: str
    rpc_returns: str


@dataclass(frozen=True)
class FieldView:
    name: str
    type: str
    default: str = ""  # a dataclass field's default ("" for a TypedDict's)


@dataclass(frozen=True)
class FunctionView:
    name: str
    doc: str
    params: tuple[ParamView, ...]
    returns: str
    rpc_returns: str
    result_name: str
    result_fields: tuple[FieldView, ...]
    overloads: tuple[OverloadView, ...]
    is_static: bool
    result_code: str  # the api.py constant of the result's TypeCode
    param_spec: str  # ((param, required), ...) as a Python literal: how a static function checks its call


@dataclass(frozen=True)
class PropertyView:
    name: str
    type: str
    rpc_type: str
    code: str  # the api.py constant of its TypeCode
    read_only: bool
    doc: str


@dataclass(frozen=True)
class ObjectView:
    name: str
    parent: str
    rpc_parent: str
    doc: str
    properties: tuple[PropertyView, ...]
    functions: tuple[FunctionView, ...]


@dataclass(frozen=True)
class StructView:
    name: str
    typed_dict: bool
    partial: bool
    doc: str
    fields: tuple[FieldView, ...]


@dataclass(frozen=True)
class EnumEntryView:
    name: str
    value: int
    doc: str


@dataclass(frozen=True)
class EnumView:
    name: str
    doc: str
    entries: tuple[EnumEntryView, ...]


@dataclass(frozen=True)
class BlueprintView:
    name: str
    parent: str
    asset: str
    doc_literal: str
    doc: str  # after a `Name: type[Parent]` line (a blueprint without functions)
    class_doc: str  # inside its stub class (a blueprint with functions)
    functions: tuple[FunctionView, ...]
    function_types: str  # {name: (result TypeCode, ((param, required), ...))} for spear._blueprint.declare; "" for none


@dataclass(frozen=True)
class TypeVarView:
    name: str
    bound: str
    rpc_bound: str


@dataclass(frozen=True)
class TypeCodeView:
    name: str
    value: str


@dataclass(frozen=True)
class FieldTypesView:
    owner: str  # a struct, or a result tuple ("AActor.GetThingsResult")
    fields: tuple[tuple[str, str], ...]  # (field, the api.py constant of its TypeCode)


@dataclass(frozen=True)
class ForeignProxyView:
    name: str
    alias: str


def _typevar(base: str) -> str:
    return f"_{base}T"


def _field_default(p: Property, enums: dict[str, str], default_cpp: str | None) -> str:
    """A dataclass default for a struct field: the C++ initializer if it has a Python spelling, else zero."""
    from codegen.model import Param

    t = p.type
    if default_cpp is not None:
        text = default_cpp
        if t.kind == "struct" and text.startswith("{"):
            text = t.name + text
        value = naming.py_default(Param(p.name, t, "", text), set(enums))
        if value is not None:
            return f"field(default_factory=lambda: {value})" if t.kind == "struct" else value
    zero = {"bool": "False", "int": "0", "float": "0.0", "str": '""'}
    if t.kind in zero:
        return zero[t.kind]
    if t.kind == "enum":
        return f"{t.name}.{enums[t.name]}"
    if t.kind == "struct":
        return f"field(default_factory={t.name})"
    if t.kind == "list":
        return "field(default_factory=list)"
    if t.kind == "dict":
        return "field(default_factory=dict)"
    raise ValueError(f"struct field {p.name} of kind {t.kind} has no Python default")


def rpc_qualifier(object_names: set[str]) -> naming.Qualifier:
    """How the RPC module spells a class: its own module's object classes as api.X (its own names are
    proxies); other modules' classes keep their names (rpc.py imports them from their API module)."""
    return lambda name: f"api.{name}" if name in object_names else name


def _function_view(c: Class, f: Function, enums: set[str], rpc: naming.Qualifier) -> FunctionView:
    ins = naming.in_params(f)
    params = []
    for p in ins:
        default = naming.py_default(p, enums)
        params.append(ParamView(
            name=p.name,
            type=naming.param_py_type(p),
            rpc_type=naming.param_py_type(p, rpc),
            stub_default=(" = " + default) if default is not None else (" = ..." if p.default_cpp else ""),
            proxy_default=" = _DEFAULT" if p.default_cpp is not None else "",
        ))
    outs = naming.out_params(f)
    result_fields = []
    if outs:
        if f.returns.kind != "void":
            result_fields.append(FieldView(name="ReturnValue", type=naming.py_type(f.returns, result=True)))
        result_fields += [FieldView(name=p.name, type=naming.py_type(p.type, result=True)) for p in outs]
    overloads = []
    if f.determines_output_type:
        target = next(p for p in f.params if p.name == f.determines_output_type)
        base = target.type.name
        tv = _typevar(base)
        inner = f.returns.args[0] if f.returns.kind in ("list", "dict") else f.returns
        for uclass_type, ret, rpc_ret in (
                (f"type[{tv}]", naming.return_py_type(f, tv), naming.return_py_type(f, tv)),
                ("str", naming.return_py_type(f, inner.name), naming.return_py_type(f, rpc(inner.name)))):
            overloads.append(OverloadView(
                params=tuple(dataclasses.replace(p, type=uclass_type, rpc_type=uclass_type)
                             if p.name == target.name else p for p in params),
                returns=ret,
                rpc_returns=rpc_ret,
            ))
    result = naming.result_tuple_name(f)
    returns = f"{c.name}.{result}" if outs else naming.return_py_type(f)
    return FunctionView(
        name=f.name,
        doc=naming.py_docstring(f.doc, " " * 8),
        params=tuple(params),
        returns=returns,
        rpc_returns=f"{rpc(c.name)}.{result}" if outs else naming.return_py_type(f, qualify=rpc),
        result_name=result,
        result_fields=tuple(result_fields),
        overloads=tuple(overloads),
        is_static=f.is_static,
        result_code=typecodes.py_name(typecodes.of_result(f)),
        param_spec=_param_spec(ins),
    )


def _param_spec(params: list[Param]) -> str:
    """((name, required), ...) as Python spells it: what spear._blueprint.check_call checks a call against."""
    return "(" + "".join(f'("{p.name}", {p.default_cpp is None}), ' for p in params).rstrip(" ") + ")"


def _function_types(b: Blueprint) -> str:
    """The result type and the parameters (name, required) of each function a blueprint declares, as api.py
    spells them for _declare_blueprint: a call that does not fit is refused in Python with a TypeError, as the
    generated bindings refuse one to a C++ function."""
    if not b.functions:
        return ""
    items = []
    for f in b.functions:
        items.append(f'"{f.name}": (_{typecodes.py_value(typecodes.of_result(f))}, {_param_spec(list(f.params))})')
    return "{" + ", ".join(items) + "}"


def _blueprint_class(b: Blueprint) -> Class:
    """The class a blueprint's functions belong to, as _function_view asks for one."""
    return Class(name=b.name, cpp_name=b.name, kind="class", header=b.asset, doc=b.doc, parent=b.parent,
                 functions=b.functions)


def _property_view(p: Property, rpc: naming.Qualifier) -> PropertyView:
    return PropertyView(
        name=p.name,
        type=naming.property_py_type(p),
        rpc_type=naming.property_py_type(p, rpc),
        code=typecodes.py_name(typecodes.of_property(p)),
        read_only=p.read_only,
        doc=naming.py_docstring(p.doc, " " * 8),
    )


def typevars(module: Module, rpc: naming.Qualifier) -> list[TypeVarView]:
    bases = sorted({
        next(p for p in f.params if p.name == f.determines_output_type).type.name
        for c in module.classes for f in c.functions if f.determines_output_type
    })
    return [TypeVarView(name=_typevar(b), bound=b, rpc_bound=rpc(b)) for b in bases]


def _proxy_parent(c: Class, foreign: set[str]) -> str:
    """The base of a class's RPC proxy: its parent's proxy, which for another module's class (a plugin
    actor's AActor) is imported from that module's rpc.py under a private alias."""
    if c.parent is None:
        return "_ObjectProxy"
    return _proxy_alias(c.parent) if c.parent in foreign else c.parent


def _proxy_alias(name: str) -> str:
    return f"_{name}Proxy"


def module_view(module: Module) -> dict[str, Any]:
    enums = {e.name: e.entries[0].name for e in module.enums}
    structs: list[StructView] = []
    objects: list[ObjectView] = []
    rpc = rpc_qualifier({c.name for c in module.classes if c.kind == "class"})
    names = sorted([e.name for e in module.enums] + [c.name for c in module.classes] +
                   [b.name for b in module.blueprints])
    # Types of other modules (a plugin's API mentions AActor, FVector, ...) come from the engine's API.
    referenced = naming.referenced_names(module) - set(names) if module.name != naming.ENGINE_MODULE else set()
    for c in naming.topo_classes(module):
        if c.kind == "struct":
            typed_dict = specifiers.has(c.specifiers, "TypedDict")
            structs.append(StructView(
                name=c.name,
                typed_dict=typed_dict,
                partial=specifiers.has(c.specifiers, "Partial"),
                doc=naming.py_docstring(c.doc, "    "),
                fields=tuple(
                    FieldView(name=p.name, type=naming.py_type(p.type),
                              default="" if typed_dict else _field_default(p, enums, p.default_cpp))
                    for p in c.properties
                ),
            ))
        else:
            objects.append(ObjectView(
                name=c.name,
                parent=c.parent or "_SpObject",
                rpc_parent=_proxy_parent(c, referenced),
                doc=naming.py_docstring(c.doc, "    "),
                properties=tuple(_property_view(p, rpc) for p in c.properties),
                functions=tuple(_function_view(c, f, set(enums), rpc) for f in c.functions),
            ))
    enum_views = [
        EnumView(
            name=e.name,
            doc=naming.py_docstring(e.doc, "    "),
            entries=tuple(EnumEntryView(name=x.name, value=x.value, doc=naming.py_docstring(x.doc, "    "))
                          for x in e.entries),
        )
        for e in module.enums
    ]
    # A local class whose parent is foreign derives its Async and Send views from the parent's.
    foreign_parents = sorted({c.parent for c in module.classes if c.parent is not None and c.parent in referenced})
    foreign = sorted(referenced | {f"{p}{suffix}" for p in foreign_parents for suffix in ("Async", "Send")})
    enum_names = {e.name for e in module.enums}
    blueprint_views = [
        BlueprintView(
            name=b.name, parent=b.parent, asset=b.asset, doc_literal=repr(b.doc), doc=naming.py_docstring(b.doc, ""),
            class_doc=naming.py_docstring(b.doc, " " * 4),
            # Called by name on objects of the native class (spear._blueprint), so no class but the stub's.
            functions=tuple(_function_view(_blueprint_class(b), f, enum_names, rpc) for f in b.functions),
            function_types=_function_types(b))
        for b in module.blueprints]
    return {
        "type_codes": [TypeCodeView(typecodes.py_name(t), typecodes.py_value(t))
                       for t in typecodes.constants(typecodes.module_codes(module))],
        "field_types": _field_types(module),
        "blueprints": blueprint_views,
        "foreign_names": foreign,
        "value_names": sorted([e.name for e in module.enums] + [c.name for c in module.classes if c.kind == "struct"]),
        "foreign_rpc_names": sorted(referenced),
        "foreign_proxies": [ForeignProxyView(name=p, alias=_proxy_alias(p)) for p in foreign_parents],
        "structs": structs,
        "objects": objects,
        "enums": enum_views,
        "typevars": typevars(module, rpc),
        "all_names": names,
        "has_static_functions": any(f.is_static for c in module.classes for f in c.functions),
    }


def _field_types(module: Module) -> list[FieldTypesView]:
    """The field types RPC results decode structs and result tuples by, in the module's class order."""
    views = []
    for c in module.classes:
        if c.kind == "struct":
            codes = typecodes.field_codes(c)
            views.append(FieldTypesView(c.name, tuple((k, typecodes.py_name(v)) for k, v in codes.items())))
        for f in c.functions:
            if naming.out_params(f):
                codes = typecodes.result_codes(f)
                views.append(FieldTypesView(f"{c.name}.{naming.result_tuple_name(f)}",
                                            tuple((k, typecodes.py_name(v)) for k, v in codes.items())))
    return views


# The RPC wire format's version, part of every API hash, so that a client and a server (or a plugin and an
# engine) from either side of a change refuse each other on connect instead of failing on the first reply.
# 2: declared types travel as type codes (call_typed, get_typed).
WIRE_FORMAT = 2


def api_hash(module: Module) -> str:
    """Identifies the generated API and the wire format: client and server compare it on connect."""
    import hashlib

    return hashlib.sha256(f"wire {WIRE_FORMAT}\n{module.to_json()}".encode()).hexdigest()[:16]

