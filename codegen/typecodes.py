"""Declared types as data: the type code of every property, parameter and result, built from the IR's type
model, and its two spellings (a C++ expression for the registry, a Python constant of type_codes.py).

Everything that converts a value by its declared type at run time (the RPC client's result decoding, the
in-process dynamic access, scene files) reads these codes; none of it parses an annotation string.
"""

from __future__ import annotations

from dataclasses import dataclass

from codegen.model import KINDS, Class, Function, Module, Param, Property, TypeKind, TypeRef


@dataclass(frozen=True)
class TypeCode:
    """kind is the IR's (void, bool, int, float, str, enum, struct, object, class, array, list, dict); name the
    reflected type's name (a class reference's base) or an array's dtype; optional says None is a value
    (a nullable object, a class result); element is a list's or dict's element (dict keys are str)."""

    kind: TypeKind
    name: str = ""
    optional: bool = False
    element: TypeCode | None = None


def of(t: TypeRef, optional: bool = False, result: bool = True) -> TypeCode:
    """The code of a type, as the Python annotations say (naming.py_type): a list's or dict's elements are
    never None, except class references in a result (a class that is gone comes back as None)."""
    element = None
    if t.args:
        inner = t.args[0]
        element = of(inner, optional=result and inner.kind == "class", result=result)
    return TypeCode(t.kind, t.name, optional, element)


def of_property(p: Property) -> TypeCode:
    return of(p.type, optional=p.type.kind == "class" or (p.type.kind == "object" and not p.not_null))


def of_param(p: Param) -> TypeCode:
    """An input takes None only for an object or class parameter whose default is nullptr; an out-parameter
    comes back as a result does."""
    if p.is_out:
        return of(p.type, optional=p.type.kind in ("object", "class"))
    return of(p.type, optional=p.type.kind in ("object", "class") and p.default_cpp == "nullptr",
              result=False)


def of_result(f: Function) -> TypeCode:
    return of(f.returns, optional=f.returns.kind in ("object", "class") and not f.not_null)


# -- C++ -------------------------------------------------------------------------------------------

# sp::reflect::TypeCode::Kind's enumerators are the model's kinds capitalised (model.KINDS).
_CPP_KINDS = {kind: kind.capitalize() for kind in KINDS}


def cpp(code: TypeCode) -> str:
    """A C++ expression building the code. Fully qualified: it stands inside a reflected class's
    StaticClass(), where a member of the class named like an alias would win the lookup."""
    kind = f"sp::reflect::TypeCode::Kind::{_CPP_KINDS[code.kind]}"
    if code.element is not None:
        return f"sp::reflect::TypeCode({kind}, {cpp(code.element)})"
    args = [kind]
    if code.name or code.optional:
        args.append(f'"{code.name}"')
    if code.optional:
        args.append("true")
    return f"sp::reflect::TypeCode({', '.join(args)})"


# -- Python ----------------------------------------------------------------------------------------

def py_name(code: TypeCode) -> str:
    """The type_codes.py constant holding the code: T_AActor_or_None, T_list_of_FVector, T_array_float64."""
    return "T_" + _mangled(code)


def _mangled(code: TypeCode) -> str:
    if code.element is not None:
        base = f"{code.kind}_of_{_mangled(code.element)}"
    elif code.kind in ("class", "array"):
        base = f"{code.kind}_{code.name}"
    else:
        base = code.name or code.kind
    return base + "_or_None" if code.optional else base


def py_value(code: TypeCode) -> str:
    """The constant's value; an element is the constant defined for it (constants() lists it first)."""
    args = [f'"{code.kind}"']
    if code.element is not None:
        args.append(f"element={py_name(code.element)}")
    else:
        if code.name:
            args.append(f'"{code.name}"')
        if code.optional:
            args.append("optional=True")
    return f"TypeCode({', '.join(args)})"


def constants(codes: set[TypeCode]) -> list[TypeCode]:
    """Every code and its elements, each element before the codes holding it, otherwise by name."""
    closed: set[TypeCode] = set()
    for code in codes:
        current: TypeCode | None = code
        while current is not None:
            closed.add(current)
            current = current.element

    def depth(code: TypeCode) -> int:
        return 0 if code.element is None else 1 + depth(code.element)

    return sorted(closed, key=lambda c: (depth(c), py_name(c)))


def field_codes(c: Class) -> dict[str, TypeCode]:
    """A struct's fields, as RPC results decode them."""
    return {p.name: of_property(p) for p in c.properties}


def result_codes(f: Function) -> dict[str, TypeCode]:
    """The fields of the result tuple a function with out-parameters returns."""
    fields = {"ReturnValue": of_result(f)} if f.returns.kind != "void" else {}
    return fields | {p.name: of_param(p) for p in f.params if p.is_out}


def module_codes(module: Module) -> set[TypeCode]:
    """Every code the module's Python needs: object properties, results, out-parameters, struct fields."""
    codes: set[TypeCode] = set()
    for c in module.classes:
        codes.update(of_property(p) for p in c.properties)
        for f in c.functions:
            codes.add(of_result(f))
            codes.update(result_codes(f).values())
    return codes
