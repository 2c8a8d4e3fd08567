"""The generator's type model alone (codegen/types.py, codegen/naming.py, codegen/typecodes.py), without rendering
any output: which C++ types cross the boundary as which TypeRef, the reasons given for those that do not, the
Python spellings and defaults the templates print, and the type codes the registry and type_codes.py hold."""

from __future__ import annotations

import sys
from pathlib import Path

import clang.cindex as ci
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
from codegen import naming, typecodes  # noqa: E402
from codegen.model import Function, Param, Property, TypeRef  # noqa: E402
from codegen.types import TypeMapper, UnsupportedType  # noqa: E402

# Stand-ins for the engine's reflection types (matched by qualified name) and a few reflected declarations.
PRELUDE = """
#include <cstdint>
#include <map>
#include <string>
#include <vector>
namespace sp::reflect {
template <typename T> class SpArray {};
struct Half {};
struct TypeInfo {};
}
using UClass = sp::reflect::TypeInfo;
template <typename T> class TSubclassOf {};
class UThing {};
struct FPoint { double X; };
enum class EMode : uint8_t { A, B };
enum class EPlain { C };
struct FPlainStruct {};
"""

REFLECTED = {"UThing": "class", "FPoint": "struct", "EMode": "enum"}


def mapped(type_spelling: str) -> TypeRef:
    """The TypeRef of a variable declared with `type_spelling` after the prelude."""
    source = PRELUDE + f"extern {type_spelling} probe;\n"
    tu = ci.Index.create().parse("probe.cpp", args=["-x", "c++", "-std=c++20"],
                                 unsaved_files=[("probe.cpp", source)])
    errors = [d.spelling for d in tu.diagnostics if d.severity >= ci.Diagnostic.Error]
    assert not errors, errors
    probe = next(c for c in tu.cursor.get_children() if c.spelling == "probe")
    mapper = TypeMapper(lambda decl: REFLECTED.get(decl.spelling))
    return mapper.map(probe.type)


@pytest.mark.parametrize("spelling, kind, cpp, name", [
    ("bool", "bool", "bool", ""),
    ("int8_t", "int", "int8_t", ""),
    ("uint16_t", "int", "uint16_t", ""),
    ("int", "int", "int32_t", ""),
    ("long long", "int", "int64_t", ""),
    ("unsigned long", "int", "uint64_t", ""),
    ("float", "float", "float", ""),
    ("double", "float", "double", ""),
    ("std::string", "str", "std::string", ""),
    ("EMode", "enum", "EMode", "EMode"),
    ("FPoint", "struct", "FPoint", "FPoint"),
    ("UThing*", "object", "UThing*", "UThing"),
    ("const UClass*", "class", "const UClass*", "UObject"),
    ("TSubclassOf<UThing>", "class", "TSubclassOf<UThing>", "UThing"),
    ("sp::reflect::SpArray<float>", "array", "sp::reflect::SpArray<float>", "float32"),
    ("sp::reflect::SpArray<uint8_t>", "array", "sp::reflect::SpArray<uint8_t>", "uint8"),
    ("sp::reflect::SpArray<sp::reflect::Half>", "array", "sp::reflect::SpArray<sp::reflect::Half>", "float16"),
])
def test_supported_types_map_to_their_kind(spelling: str, kind: str, cpp: str, name: str) -> None:
    t = mapped(spelling)
    assert (t.kind, t.cpp, t.name) == (kind, cpp, name)


def test_containers_nest_their_element_types() -> None:
    t = mapped("std::vector<std::map<std::string, UThing*>>")
    assert t.kind == "list" and t.cpp == "std::vector<std::map<std::string, UThing*>>"
    inner = t.args[0]
    assert inner.kind == "dict" and inner.args == (TypeRef("object", "UThing*", "UThing"),)
    assert naming.py_type(t) == "list[dict[str, UThing]]"


@pytest.mark.parametrize("spelling, reason", [
    ("char", "'char': char is ambiguous; use int8_t, uint8_t or std::string"),
    ("EPlain", "enum 'EPlain' is not reflected; mark it SPENUM()"),
    ("UClass*", "a class reference must be 'const UClass*'"),
    ("FPoint*", "'FPoint *': pass reflected structs by value or const reference"),
    ("int*", "pointer type 'int *' is not supported; only pointers to reflected classes cross the boundary"),
    ("std::wstring", "only std::string is supported"),
    ("std::map<int, double>", "map keys must be std::string"),
    ("UThing", "'UThing': reflected classes cross the boundary by pointer (UThing*)"),
    ("FPlainStruct", "type 'FPlainStruct' is not supported across the boundary; reflect it with SPSTRUCT()"),
    ("TSubclassOf<FPoint>", "TSubclassOf needs a reflected class"),
    ("sp::reflect::SpArray<FPoint>", "unsupported array element type"),
])
def test_unsupported_types_are_rejected_with_the_reason(spelling: str, reason: str) -> None:
    with pytest.raises(UnsupportedType) as caught:
        mapped(spelling)
    assert reason in str(caught.value)


@pytest.mark.parametrize("t, spelling, as_result", [
    (TypeRef("void", "void"), "None", "None"),
    (TypeRef("object", "UThing*", "UThing"), "UThing | None", "UThing | None"),
    (TypeRef("class", "TSubclassOf<UThing>", "UThing"), "type[UThing] | str", "type[UThing] | None"),
    (TypeRef("array", "sp::reflect::SpArray<float>", "float32"), "NDArray[np.float32]", "NDArray[np.float32]"),
    (TypeRef("dict", "std::map<std::string, double>", args=(TypeRef("float", "double"),)), "dict[str, float]",
     "dict[str, float]"),
])
def test_python_spellings(t: TypeRef, spelling: str, as_result: str) -> None:
    assert naming.py_type(t) == spelling
    assert naming.py_type(t, result=True) == as_result


@pytest.mark.parametrize("cpp_type, default, python", [
    (TypeRef("bool", "bool"), "true", "True"),
    (TypeRef("float", "double"), "1", "1.0"),  # an integer literal for a float parameter stays a float
    (TypeRef("float", "float"), "0.5f", "0.5"),
    (TypeRef("int", "int32_t"), "-3", "-3"),
    (TypeRef("str", "std::string"), '"name"', '"name"'),
    (TypeRef("str", "std::string"), '"a\\"b"', None),  # an escape: no faithful spelling, so none is printed
    (TypeRef("list", "std::vector<int32_t>", args=(TypeRef("int", "int32_t"),)), "{}", "[]"),
    (TypeRef("object", "UThing*", "UThing"), "nullptr", "None"),
    (TypeRef("enum", "EMode", "EMode"), "EMode::B", "EMode.B"),
    (TypeRef("enum", "EMode", "EMode"), "EOther::B", None),  # not a known enum
    (TypeRef("struct", "FPoint", "FPoint"), "FPoint(1.0, 2)", "FPoint(1.0, 2)"),
    (TypeRef("struct", "FPoint", "FPoint"), "FPoint(Origin())", None),
])
def test_cpp_defaults_get_a_python_spelling_only_when_faithful(cpp_type: TypeRef, default: str,
                                                               python: str | None) -> None:
    param = Param("P", cpp_type, cpp_type.cpp, default_cpp=default)
    assert naming.py_default(param, {"EMode"}) == python


def test_cpp_spellings() -> None:
    assert naming.cpp_string('say "hi"\n\\') == '"say \\"hi\\"\\n\\\\"'
    assert naming.header_stem("core/world/actor.h") == "core_world_actor"
    pointer = Param("Actor", TypeRef("object", "UThing*", "UThing"), "UThing *", default_cpp="nullptr")
    assert naming.cpp_default_value(pointer) == "static_cast<UThing*>(nullptr)"
    braced = Param("Tags", TypeRef("list", "std::vector<std::string>", args=(TypeRef("str", "std::string"),)),
                   "const std::vector<std::string> &", default_cpp="{}")
    assert naming.cpp_default_value(braced) == "std::vector<std::string>{}"


THING = TypeRef("object", "UThing*", "UThing")
THINGS = TypeRef("list", "std::vector<UThing*>", args=(THING,))


def test_type_codes_say_where_none_is_a_value() -> None:
    # Objects are nullable unless declared NotNull; list elements never are; a class result may be None.
    assert typecodes.of_property(Property("Owner", "", THING)) == typecodes.TypeCode("object", "UThing", True)
    assert typecodes.of_property(Property("Owner", "", THING, not_null=True)).optional is False
    assert typecodes.of_property(Property("All", "", THINGS)) == typecodes.TypeCode(
        "list", element=typecodes.TypeCode("object", "UThing"))
    # A parameter takes None only with a nullptr default.
    assert typecodes.of_param(Param("A", THING, "UThing *")).optional is False
    assert typecodes.of_param(Param("A", THING, "UThing *", default_cpp="nullptr")).optional is True
    cls = TypeRef("class", "TSubclassOf<UThing>", "UThing")
    assert typecodes.of_result(Function("F", "", cls, ())).optional is True
    assert typecodes.of_result(Function("F", "", cls, (), not_null=True)).optional is False
    # Out-parameters come back as results do; class references in a result may be None, in a list too.
    assert typecodes.of_param(Param("Hit", THING, "UThing *&", is_out=True)).optional is True
    classes = TypeRef("list", "std::vector<TSubclassOf<UThing>>", args=(cls,))
    assert typecodes.of_result(Function("F", "", classes, ())).element == typecodes.TypeCode("class", "UThing", True)
    assert typecodes.of_param(Param("C", classes, "")).element == typecodes.TypeCode("class", "UThing")


def test_type_codes_spelled_for_cpp_and_python() -> None:
    code = typecodes.of_property(Property("All", "", TypeRef("dict", "std::map<std::string, std::vector<UThing*>>",
                                                             args=(THINGS,))))
    t, k = "sp::reflect::TypeCode", "sp::reflect::TypeCode::Kind"
    assert typecodes.cpp(code) == f'{t}({k}::Dict, {t}({k}::List, {t}({k}::Object, "UThing")))'
    assert typecodes.cpp(typecodes.TypeCode("object", "UThing", True)) == f'{t}({k}::Object, "UThing", true)'
    assert typecodes.py_name(code) == "T_dict_of_list_of_UThing"
    assert typecodes.py_value(code) == "TypeCode(\"dict\", element=T_list_of_UThing)"
    assert typecodes.py_name(typecodes.TypeCode("class", "UThing", True)) == "T_class_UThing_or_None"
    assert typecodes.py_name(typecodes.TypeCode("array", "float32")) == "T_array_float32"
    # Each element is defined before the codes that hold it.
    names = [typecodes.py_name(c) for c in typecodes.constants({code})]
    assert names == ["T_UThing", "T_list_of_UThing", "T_dict_of_list_of_UThing"]


def test_header_deps_follow_the_types_each_header_uses() -> None:
    """A header's generated code includes the headers of the types its classes use, transitively; the
    definitions-only deps (parents, struct fields) are what the bindings headers include each other along."""
    from codegen.model import Class, Enum, EnumEntry, Module

    vec = TypeRef(kind="struct", cpp="FVec", name="FVec")
    mood = TypeRef(kind="enum", cpp="EMood", name="EMood")
    actor = TypeRef(kind="object", cpp="AThing *", name="AThing")
    module = Module(
        name="m", headers=("a.h", "b.h", "c.h", "d.h"),
        classes=(
            Class(name="FVec", cpp_name="FVec", kind="struct", header="a.h", doc="",
                  properties=(Property(name="X", doc="", type=mood),)),
            Class(name="AThing", cpp_name="AThing", kind="class", header="b.h", doc=""),
            Class(name="APawnish", cpp_name="APawnish", kind="class", header="c.h", doc="", parent="AThing",
                  parent_cpp="AThing",
                  functions=(Function(name="Move", doc="", returns=TypeRef(kind="void", cpp="void"),
                                      params=(Param(name="To", type=vec, cpp_decl="const FVec &"),)),)),
            Class(name="ALonely", cpp_name="ALonely", kind="class", header="d.h", doc="",
                  properties=(Property(name="Target", doc="", type=actor),)),
        ),
        enums=(Enum(name="EMood", cpp_name="EMood", header="d.h", doc="",
                    entries=(EnumEntry(name="Calm", value=0, doc=""),)),),
    )
    assert naming.header_deps(module) == {"a.h": ["b.h", "d.h"], "b.h": [], "c.h": ["a.h", "b.h", "d.h"],
                                          "d.h": ["b.h"]}
    assert naming.header_deps(module, definitions_only=True) == {"a.h": ["d.h"], "b.h": [], "c.h": ["b.h"],
                                                                 "d.h": []}


def test_value_kinds_are_one_list() -> None:
    """codegen/model.py's TypeKind is the list of value kinds: the C++ enum (read with libclang, as the
    generator reads headers) holds them capitalised in the same order, and the runtime package's Kind
    spells them the same."""
    import typing

    from codegen.model import KINDS

    root = Path(__file__).resolve().parents[2]
    sys.path.insert(0, str(root / "python"))
    from spear._type_code import Kind

    assert typing.get_args(Kind) == KINDS
    index = ci.Index.create()
    unit = index.parse(str(root / "core/reflect/type_code.h"), args=["-x", "c++", "-std=c++20", f"-I{root}"])

    def children(cursors: list[ci.Cursor], name: str) -> list[ci.Cursor]:
        return [c for cursor in cursors for c in cursor.get_children() if c.spelling == name]

    structs = children(children(children([unit.cursor], "sp"), "reflect"), "TypeCode")
    (kind,) = children([c for c in structs if c.is_definition()], "Kind")
    enumerators = [c.spelling for c in kind.get_children()]
    assert enumerators == [kind.capitalize() for kind in KINDS]
    assert {typecodes.cpp(typecodes.TypeCode(kind)).split("::")[-1].rstrip(")") for kind in KINDS} == set(enumerators)
