"""Views of the IR for the C++ templates (registry, bindings, pybind module): frozen dataclasses built in one
place, holding what the templates lay out. Flags are real booleans (templates write C++ literals through
the cpp_bool filter); the decisions live here, not in the templates.
"""

from __future__ import annotations

from dataclasses import dataclass

from codegen import naming, specifiers, typecodes
from codegen.model import Class, Enum, Function, Param, Property


@dataclass(frozen=True)
class ParamView:
    name: str
    name_literal: str
    type_code: str  # a C++ expression (codegen/typecodes.py)
    index: int  # among the input parameters; -1 for an out-parameter
    has_default: bool
    is_out: bool
    cpp_type: str
    context_literal: str
    default_value: str  # the C++ default, "" without one
    not_none: bool  # an object or class argument without a nullptr default


@dataclass(frozen=True)
class FunctionView:
    name: str
    name_literal: str
    doc: str
    doc_literal: str
    signature_doc_literal: str
    returns_code: str
    result_name: str
    params: tuple[ParamView, ...]
    outs: tuple[ParamView, ...]
    ins: tuple[ParamView, ...]
    is_static: bool
    is_const: bool
    context_literal: str
    call: str  # the call body's call of the C++ function (calls.gen.h.j2)
    returns_void: bool
    returns_cpp: str
    not_null: bool
    returns_struct: bool  # a struct result may be a complete TypedDict, whose array fields are checked


@dataclass(frozen=True)
class PropertyView:
    name: str
    name_literal: str
    type_code: str
    doc: str
    doc_literal: str
    read_only: bool
    not_null: bool
    is_array: bool
    setter: str | None
    cpp_type: str
    context_literal: str


@dataclass(frozen=True)
class ClassView:
    name: str
    cpp_name: str
    name_literal: str
    doc: str
    doc_literal: str
    kind_enum: str
    parent: str | None
    parent_cpp: str | None
    parent_expr: str
    abstract: bool
    create: bool
    is_struct: bool
    typed_dict: bool
    partial: bool
    properties: tuple[PropertyView, ...]
    functions: tuple[FunctionView, ...]
    self_attribute: str


@dataclass(frozen=True)
class EnumEntryView:
    name: str
    name_literal: str
    value: int
    doc: str


@dataclass(frozen=True)
class EnumView:
    name: str
    cpp_name: str
    name_literal: str
    doc: str
    doc_literal: str
    entries: tuple[EnumEntryView, ...]


def param_view(owner: str, f: Function, p: Param) -> ParamView:
    ins = naming.in_params(f)
    return ParamView(
        name=p.name,
        name_literal=naming.cpp_string(p.name),
        type_code=typecodes.cpp(typecodes.of_param(p)),
        index=ins.index(p) if not p.is_out else -1,
        has_default=p.default_cpp is not None,
        is_out=p.is_out,
        cpp_type=p.type.cpp,
        context_literal=naming.cpp_string(f"{owner}.{f.name}(): argument '{p.name}'"),
        default_value=naming.cpp_default_value(p) if p.default_cpp is not None else "",
        not_none=p.type.kind in ("object", "class") and p.default_cpp != "nullptr",
    )


def _signature_doc(f: Function) -> str:
    """A function's doc for help(): its Python signature (as the stubs spell it, defaults elided), then the
    C++ doc comment."""
    params = [f"{p.name}: {naming.param_py_type(p)}" + (" = ..." if p.default_cpp is not None else "")
              for p in naming.in_params(f)]
    head = ([] if f.is_static else ["self"]) + (["*", *params] if params else [])
    signature = f"{f.name}({', '.join(head)}) -> {naming.return_py_type(f)}"
    return f"{signature}\n\n{f.doc}" if f.doc else signature


def function_view(c: Class, f: Function) -> FunctionView:
    args = ", ".join(f"{p.name}Out" if p.is_out else f"{p.name}Arg" for p in f.params)
    params = tuple(param_view(c.name, f, p) for p in f.params)
    return FunctionView(
        name=f.name,
        name_literal=naming.cpp_string(f.name),
        doc=f.doc,
        doc_literal=naming.cpp_string(f.doc),
        signature_doc_literal=naming.cpp_string(_signature_doc(f)),
        returns_code=typecodes.cpp(typecodes.of_result(f)),
        result_name=naming.result_tuple_name(f),
        params=params,
        outs=tuple(v for v in params if v.is_out),
        ins=tuple(v for v in params if not v.is_out),
        is_static=f.is_static,
        is_const=f.is_const,
        context_literal=naming.cpp_string(f"{c.name}.{f.name}()"),
        call=f"Self::{f.name}({args})" if f.is_static else f"self->{f.name}({args})",
        returns_void=f.returns.kind == "void",
        returns_cpp=f.returns.cpp,
        not_null=f.not_null,
        returns_struct=f.returns.kind == "struct",
    )


def property_view(c: Class, p: Property) -> PropertyView:
    return PropertyView(
        name=p.name,
        name_literal=naming.cpp_string(p.name),
        type_code=typecodes.cpp(typecodes.of_property(p)),
        doc=p.doc,
        doc_literal=naming.cpp_string(p.doc),
        read_only=p.read_only,
        not_null=p.not_null,
        is_array=p.type.kind == "array",
        setter=p.setter,
        cpp_type=p.type.cpp,
        context_literal=naming.cpp_string(f"{c.name}.{p.name}"),
    )


def class_view(c: Class) -> ClassView:
    return ClassView(
        name=c.name,
        cpp_name=c.cpp_name,
        name_literal=naming.cpp_string(c.name),
        doc=c.doc,
        doc_literal=naming.cpp_string(c.doc),
        kind_enum="Class" if c.kind == "class" else "Struct",
        parent=c.parent,
        parent_cpp=c.parent_cpp,
        parent_expr=f"&{c.parent_cpp}::StaticClass()" if c.parent_cpp else "nullptr",
        abstract=c.abstract,
        create=c.kind == "class" and not c.abstract,
        is_struct=c.kind == "struct",
        typed_dict=specifiers.has(c.specifiers, "TypedDict"),
        partial=specifiers.has(c.specifiers, "Partial"),
        properties=tuple(property_view(c, p) for p in c.properties),
        functions=tuple(function_view(c, f) for f in c.functions),
        # The registry's `Self` alias is read by the factory and the property accessors only; a class with
        # neither marks it unused (a warning otherwise).
        self_attribute="" if (c.kind == "class" and not c.abstract) or c.properties else " [[maybe_unused]]",
    )


def enum_view(e: Enum) -> EnumView:
    return EnumView(
        name=e.name,
        cpp_name=e.cpp_name,
        name_literal=naming.cpp_string(e.name),
        doc=e.doc,
        doc_literal=naming.cpp_string(e.doc),
        entries=tuple(EnumEntryView(name=x.name, name_literal=naming.cpp_string(x.name), value=x.value, doc=x.doc)
                      for x in e.entries),
    )
