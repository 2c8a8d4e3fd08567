"""The stubs match the built module (what mypy.stubtest does for pure-Python modules; pybind11 functions
expose no inspect.signature, so this reads their signature lines instead).

Every class, function, parameter (name, order, keyword-only, default or not) and property in api.pyi
must exist in the pybind11 module with the same shape, and the reverse, so the stubs never promise
what the module lacks.
"""

from __future__ import annotations

import ast
import inspect
import re
from pathlib import Path

import pytest

import spear
from spear import _inprocess
from spear._engine import api
from spear._object import SpObject

STUB = Path(api.__file__).with_suffix(".pyi")
ROOT_MEMBERS = {k for k in vars(SpObject) if not k.startswith("_")}


def stub_classes() -> dict[str, ast.ClassDef]:
    tree = ast.parse(STUB.read_text())
    return {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}


def blueprint_classes() -> list[str]:
    """Stub classes of blueprints (assets with functions): made at run time, no class in the module."""
    return [n for n in stub_classes() if hasattr(getattr(api, n, None), "__sp_asset__")]


def is_struct(cls: ast.ClassDef) -> bool:
    """A struct's stub class: decorated @dataclass or @dataclass(...)."""
    return any(isinstance(d, ast.Name) and d.id == "dataclass" or
               isinstance(d, ast.Call) and isinstance(d.func, ast.Name) and d.func.id == "dataclass"
               for d in cls.decorator_list)


def object_classes() -> list[str]:
    return [n for n, c in stub_classes().items() if not n.endswith(("Async", "Send")) and not is_struct(c) and not any(
        isinstance(b, ast.Attribute) and b.attr == "IntEnum" or isinstance(b, ast.Name) and b.id == "TypedDict"
        for b in c.bases) and n not in blueprint_classes()]


def stub_signature(fn: ast.FunctionDef) -> list[tuple[str, bool]]:
    """(name, has_default) of the keyword-only parameters."""
    args = fn.args
    return [(a.arg, d is not None) for a, d in zip(args.kwonlyargs, args.kw_defaults)]


def native_doc(native: type, class_name: str, name: str, decorators: set[str]) -> tuple[str, bool]:
    """The module's doc of a stubbed function, and whether it is static (a static method in both)."""
    member = native.__dict__[name]
    static = "staticmethod" in decorators
    assert isinstance(member, staticmethod) == static, f"{class_name}.{name} is static in one of stub and module only"
    return (member.__func__ if static else member).__doc__, static


def native_signature(doc: str, static: bool, name: str) -> tuple[list[tuple[str, bool]], bool]:
    """(keyword-only params, whether positional parameters other than self exist) from pybind11's doc line;
    a static function has no self."""
    line = doc.splitlines()[0]
    m = re.match(rf"{name}\((.*)\) -> ", line)
    assert m, line
    params, depth, current = [], 0, ""
    for ch in m.group(1):  # split on top-level commas: defaults such as FVector(X=0.0, ...) contain commas
        depth += ch in "([{" and 1 or 0
        depth -= ch in ")]}" and 1 or 0
        if ch == "," and depth == 0:
            params.append(current.strip())
            current = ""
        else:
            current += ch
    params.append(current.strip())
    if static:
        rest = [p for p in params if p]
    else:
        assert params[0].startswith("self")
        rest = params[1:]
    if not rest:
        return [], False
    assert rest[0] == "*", f"{name}: parameters are not keyword-only: {line}"
    return [(p.split(":")[0], "=" in p) for p in rest[1:]], False


@pytest.mark.parametrize("name", object_classes())
def test_class_matches_stub(name: str) -> None:
    native = getattr(_inprocess.module(), name)
    cls = stub_classes()[name]
    assert issubclass(native, getattr(api, name)), "registered as the typed API class"
    assert native.__sp_class__ == name
    base = cls.bases[0]
    if isinstance(base, ast.Name) and base.id != "_SpObject":
        assert issubclass(native, getattr(_inprocess.module(), base.id))
    stub_members = set()
    for node in cls.body:
        if isinstance(node, ast.FunctionDef):
            decorators = {d.id if isinstance(d, ast.Name) else getattr(d, "attr", "") for d in node.decorator_list}
            stub_members.add(node.name)
            if "property" in decorators:
                if node.name in ("call_async", "send_async"):  # inherited from the root class
                    assert isinstance(inspect.getattr_static(native, node.name), property)
                    continue
                assert isinstance(native.__dict__[node.name], property), node.name
                has_setter = any(isinstance(n, ast.FunctionDef) and n.name == node.name and any(
                    isinstance(d, ast.Attribute) and d.attr == "setter" for d in n.decorator_list) for n in cls.body)
                assert (native.__dict__[node.name].fset is not None) == has_setter, node.name
            elif "setter" in decorators:
                continue
            elif "overload" in decorators:
                params, _ = native_signature(*native_doc(native, name, node.name, decorators), node.name)
                assert [p for p, _ in params] == [p for p, _ in stub_signature(node)], node.name
            else:
                assert node.name in native.__dict__, f"{name}.{node.name} is in the stub but not in the module"
                params, _ = native_signature(*native_doc(native, name, node.name, decorators), node.name)
                assert params == stub_signature(node), node.name
    # The root's own surface (is_valid, call_sp_func, ...) is declared once, in spear._object.SpObject.
    native_members = {k for k in native.__dict__ if not k.startswith("_")} - ROOT_MEMBERS - {"call_async", "send_async"}
    assert native_members == stub_members - {"call_async", "send_async"}, \
        "the module has members the stub lacks, or the reverse"


def test_root_class_implements_what_spobject_declares() -> None:
    root = _inprocess.module().UObject
    for member in ROOT_MEMBERS:
        assert member in root.__dict__, f"UObject lacks SpObject.{member}"
        declared = getattr(SpObject, member)
        if inspect.isfunction(root.__dict__[member]):
            assert list(inspect.signature(root.__dict__[member]).parameters) == \
                list(inspect.signature(declared).parameters), member


def test_structs_and_enums_are_shared_python_types() -> None:
    structs = 0
    for name, cls in stub_classes().items():
        if name.endswith(("Async", "Send")):
            continue
        runtime = getattr(spear, name)
        if is_struct(cls):
            structs += 1
            # Slotted, so that a misspelt field is refused (the stub says so too, for type checkers).
            assert "__slots__" in runtime.__dict__ and not hasattr(runtime(), "__dict__"), name
            stub_fields = [n.target.id for n in cls.body if isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name)
                           and n.target.id != "__sp_class__"]
            assert list(runtime.__dataclass_fields__)[1:] == stub_fields or [
                f for f in runtime.__dataclass_fields__ if f != "__sp_class__"] == stub_fields
    assert structs >= 10, "the stub's structs were not recognised"


@pytest.mark.parametrize("name", blueprint_classes())
def test_blueprint_stub_class_matches_its_asset(name: str) -> None:
    # The stub's methods are the asset's functions, with its parameters (name, order, default or not); the
    # engine checks the bodies when it loads the asset, and test_blueprints.py calls them on both transports.
    import json

    document = json.loads((Path(api.__file__).resolve().parents[3] / getattr(api, name).__sp_asset__).read_text())
    declared = {f["name"]: [(p["name"], "default" in p) for p in f.get("params", [])] for f in document["functions"]}
    def methods(cls: str) -> dict[str, list[tuple[str, bool]]]:
        return {node.name: stub_signature(node) for node in stub_classes()[cls].body
                if isinstance(node, ast.FunctionDef) and node.name not in ("call_async", "send_async")}

    # The class, and its asynchronous and fire-and-forget views (call_async, send_async), each over its
    # parent's.
    for cls, base in ((name, ""), (f"{name}Async", "Async"), (f"{name}Send", "Send")):
        assert methods(cls) == declared, cls
        parent = stub_classes()[cls].bases[0]
        assert isinstance(parent, ast.Name) and parent.id == document["parent"] + base
