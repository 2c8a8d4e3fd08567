"""Mapping of libclang types to IR TypeRefs. Anything not listed here is rejected with a reason."""

from __future__ import annotations

from collections.abc import Callable

import clang.cindex as ci

from codegen.model import TypeRef

_INT_KINDS = {
    ci.TypeKind.SCHAR: "int8_t",
    ci.TypeKind.UCHAR: "uint8_t",
    ci.TypeKind.SHORT: "int16_t",
    ci.TypeKind.USHORT: "uint16_t",
    ci.TypeKind.INT: "int32_t",
    ci.TypeKind.UINT: "uint32_t",
    ci.TypeKind.LONG: "int64_t",
    ci.TypeKind.ULONG: "uint64_t",
    ci.TypeKind.LONGLONG: "int64_t",
    ci.TypeKind.ULONGLONG: "uint64_t",
}

_DTYPES = {
    ci.TypeKind.BOOL: "bool",
    ci.TypeKind.UCHAR: "uint8",
    ci.TypeKind.SCHAR: "int8",
    ci.TypeKind.USHORT: "uint16",
    ci.TypeKind.SHORT: "int16",
    ci.TypeKind.UINT: "uint32",
    ci.TypeKind.INT: "int32",
    ci.TypeKind.ULONG: "uint64",
    ci.TypeKind.LONG: "int64",
    ci.TypeKind.ULONGLONG: "uint64",
    ci.TypeKind.LONGLONG: "int64",
    ci.TypeKind.FLOAT: "float32",
    ci.TypeKind.DOUBLE: "float64",
}


class UnsupportedType(ValueError):
    """Raised with a message saying what is not supported and what to use instead."""


def qualified_name(cursor: ci.Cursor) -> str:
    parts = []
    c = cursor
    while c is not None and c.kind != ci.CursorKind.TRANSLATION_UNIT:
        # Skip the standard library's inline namespaces (std::__cxx11::basic_string is std::basic_string).
        if c.spelling and not c.spelling.startswith("__"):
            parts.append(c.spelling)
        c = c.semantic_parent
    return "::".join(reversed(parts))


class TypeMapper:
    """Maps clang types, knowing which classes, structs and enums are reflected (by USR)."""

    def __init__(self, reflected_kind: Callable[[ci.Cursor], str | None]) -> None:
        # reflected_kind(decl) -> "class" | "struct" | "enum" | None
        self._reflected_kind = reflected_kind

    def map(self, t: ci.Type) -> TypeRef:
        spelled = t.spelling
        c = t.get_canonical()
        kind = c.kind
        if kind == ci.TypeKind.VOID:
            return TypeRef("void", "void")
        if kind == ci.TypeKind.BOOL:
            return TypeRef("bool", "bool")
        if kind in (ci.TypeKind.CHAR_S, ci.TypeKind.CHAR_U):
            raise UnsupportedType(f"'{spelled}': char is ambiguous; use int8_t, uint8_t or std::string")
        if kind in _INT_KINDS:
            return TypeRef("int", _INT_KINDS[kind])
        if kind in (ci.TypeKind.FLOAT, ci.TypeKind.DOUBLE):
            return TypeRef("float", "float" if kind == ci.TypeKind.FLOAT else "double")
        if kind == ci.TypeKind.ENUM:
            decl = c.get_declaration()
            if self._reflected_kind(decl) != "enum":
                raise UnsupportedType(f"enum '{qualified_name(decl)}' is not reflected; mark it SPENUM()")
            return TypeRef("enum", qualified_name(decl), decl.spelling)
        if kind == ci.TypeKind.POINTER:
            return self._map_pointer(t, c)
        if kind == ci.TypeKind.RECORD:
            return self._map_record(t, c)
        if kind in (ci.TypeKind.LVALUEREFERENCE, ci.TypeKind.RVALUEREFERENCE):
            raise UnsupportedType(f"'{spelled}': references to references are not supported")
        raise UnsupportedType(f"type '{spelled}' is not supported across the boundary")

    def _map_pointer(self, t: ci.Type, c: ci.Type) -> TypeRef:
        pointee = c.get_pointee()
        decl = pointee.get_declaration()
        if pointee.kind == ci.TypeKind.RECORD:
            qname = qualified_name(decl)
            if qname == "sp::reflect::TypeInfo":
                if not pointee.is_const_qualified():
                    raise UnsupportedType("a class reference must be 'const UClass*'")
                return TypeRef("class", "const UClass*", "UObject")
            if self._reflected_kind(decl) == "class":
                return TypeRef("object", qname + "*", decl.spelling)
            if self._reflected_kind(decl) == "struct":
                raise UnsupportedType(f"'{t.spelling}': pass reflected structs by value or const reference")
        raise UnsupportedType(
            f"pointer type '{t.spelling}' is not supported; only pointers to reflected classes cross the boundary"
        )

    def _template_args(self, c: ci.Type) -> list[ci.Type]:
        return [c.get_template_argument_type(i) for i in range(c.get_num_template_arguments())]

    def _map_record(self, t: ci.Type, c: ci.Type) -> TypeRef:
        decl = c.get_declaration()
        qname = qualified_name(decl)
        if qname == "std::basic_string":
            args = self._template_args(c)
            if args and args[0].get_canonical().kind not in (ci.TypeKind.CHAR_S, ci.TypeKind.CHAR_U):
                raise UnsupportedType(f"'{t.spelling}': only std::string is supported")
            return TypeRef("str", "std::string")
        if qname == "std::vector":
            element = self.map(self._template_args(c)[0])
            return TypeRef("list", f"std::vector<{element.cpp}>", args=(element,))
        if qname == "std::map":
            key, value = self._template_args(c)[:2]
            if self.map(key).kind != "str":
                raise UnsupportedType(f"'{t.spelling}': map keys must be std::string")
            element = self.map(value)
            return TypeRef("dict", f"std::map<std::string, {element.cpp}>", args=(element,))
        if qname == "sp::reflect::SpArray":
            element_type = self._template_args(c)[0].get_canonical()
            dtype = _DTYPES.get(element_type.kind)
            if element_type.kind == ci.TypeKind.RECORD and qualified_name(element_type.get_declaration()) == (
                "sp::reflect::Half"
            ):
                dtype = "float16"
            if dtype is None:
                raise UnsupportedType(f"'{t.spelling}': unsupported array element type '{element_type.spelling}'")
            cpp_element = "sp::reflect::Half" if dtype == "float16" else self._scalar_cpp(element_type)
            return TypeRef("array", f"sp::reflect::SpArray<{cpp_element}>", dtype)
        if qname == "TSubclassOf":
            base = self._template_args(c)[0].get_canonical().get_declaration()
            if self._reflected_kind(base) != "class":
                raise UnsupportedType(f"'{t.spelling}': TSubclassOf needs a reflected class")
            return TypeRef("class", f"TSubclassOf<{qualified_name(base)}>", base.spelling)
        kind = self._reflected_kind(decl)
        if kind == "struct":
            return TypeRef("struct", qname, decl.spelling)
        if kind == "class":
            raise UnsupportedType(f"'{t.spelling}': reflected classes cross the boundary by pointer ({decl.spelling}*)")
        raise UnsupportedType(f"type '{t.spelling}' is not supported across the boundary; reflect it with SPSTRUCT()")

    @staticmethod
    def _scalar_cpp(t: ci.Type) -> str:
        if t.kind == ci.TypeKind.FLOAT:
            return "float"
        if t.kind == ci.TypeKind.DOUBLE:
            return "double"
        if t.kind == ci.TypeKind.BOOL:
            return "bool"
        return _INT_KINDS[t.kind]
