"""libclang scanner: one parse of an umbrella translation unit -> the IR (codegen.model).

The headers are parsed with SPEAR_GENERATOR defined, so reflection macros become `annotate`
attributes (see core/reflect/macros.h). Types are resolved by clang itself, with the real include
paths; nothing here guesses at C++ syntax.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from pathlib import Path

import clang.cindex as ci

from codegen import specifiers
from codegen.errors import GeneratorError
from codegen.model import Class, Enum, EnumEntry, Function, Module, Param, Property, TypeRef
from codegen.types import TypeMapper, UnsupportedType, qualified_name

MARKER_PREFIX = "SpReflectMarker_"
BODY_MARKER = "SpReflectGeneratedBody_"
_RECORD_KINDS = (ci.CursorKind.CLASS_DECL, ci.CursorKind.STRUCT_DECL)
_SYSTEM_PREFIXES = ("/usr/", "/opt/")


@dataclass(frozen=True)
class ScanOptions:
    root: Path
    include_dirs: tuple[Path, ...] = ()
    defines: tuple[str, ...] = ()


def _kind(cursor: ci.Cursor) -> ci.CursorKind | None:
    """The cursor's kind, or None for kinds newer than these Python bindings know (seen in system headers)."""
    try:
        return cursor.kind
    except ValueError:
        return None


def _annotation(cursor: ci.Cursor) -> tuple[str, str] | None:
    """('property', 'EditAnywhere') for a cursor carrying an sp: annotation."""
    for child in cursor.get_children():
        if _kind(child) == ci.CursorKind.ANNOTATE_ATTR and child.spelling.startswith("sp:"):
            _, kind, args = child.spelling.split(":", 2)
            return kind, args
    return None


def clean_doc(raw: str | None) -> str:
    if not raw:
        return ""
    lines = []
    for line in raw.splitlines():
        line = line.strip()
        for prefix in ("///<", "///", "//!", "/**", "/*!", "*/", "*", "//"):
            if line.startswith(prefix):
                line = line[len(prefix):]
                break
        if line.endswith("*/"):
            line = line[:-2]
        lines.append(line.strip())
    return "\n".join(line for line in lines if line).strip()


def _join_tokens(tokens: list[str]) -> str:
    out = ""
    for tok in tokens:
        if out and (out[-1].isalnum() or out[-1] in "_\"'") and (tok[0].isalnum() or tok[0] in "_\"'"):
            out += " "
        elif out.endswith(","):
            out += " "
        out += tok
    return out


class Scanner:
    def __init__(self, options: ScanOptions) -> None:
        self.options = options
        # USR -> "class" | "struct" | "enum" for every reflected declaration in the translation unit.
        self._reflected: dict[str, str] = {}
        self._types = TypeMapper(self._reflected_kind)
        self._files: dict[str, bytes] = {}

    # -- helpers ---------------------------------------------------------------------------------

    def _rel(self, path: str) -> str:
        try:
            return Path(os.path.relpath(path, self.options.root)).as_posix()
        except ValueError:
            return path

    def _error(self, cursor: ci.Cursor, message: str) -> GeneratorError:
        loc = cursor.location
        return GeneratorError(self._rel(loc.file.name) if loc.file else "<unknown>", loc.line, message)

    def _reflected_kind(self, decl: ci.Cursor) -> str | None:
        definition = decl.get_definition() or decl
        return self._reflected.get(definition.get_usr())

    # -- parsing ---------------------------------------------------------------------------------

    def parse(self, headers: list[Path]) -> ci.TranslationUnit:
        umbrella = "".join(f'#include "{h.resolve()}"\n' for h in headers)
        args = ["-x", "c++", "-std=c++20", "-DSPEAR_GENERATOR", "-Wno-inconsistent-missing-override"]
        args += [f"-I{d}" for d in (self.options.root, *self.options.include_dirs)]
        args += [f"-D{d}" for d in self.options.defines]
        index = ci.Index.create()
        name = str(self.options.root / "spear_codegen_umbrella.cpp")
        tu = index.parse(
            name, args=args, unsaved_files=[(name, umbrella)],
            options=ci.TranslationUnit.PARSE_SKIP_FUNCTION_BODIES,
        )
        for diag in tu.diagnostics:
            if diag.severity >= ci.Diagnostic.Error:
                loc = diag.location
                file = self._rel(loc.file.name) if loc.file else "<command line>"
                raise GeneratorError(file, loc.line, f"C++ parse error: {diag.spelling}")
        return tu

    def _scopes(self, cursor: ci.Cursor) -> list[ci.Cursor]:
        """The cursor and every namespace inside it, outermost first, skipping system headers."""
        scopes = [cursor]
        for child in cursor.get_children():
            file = child.location.file
            if file is None or file.name.startswith(_SYSTEM_PREFIXES):
                continue
            if _kind(child) in (ci.CursorKind.NAMESPACE, ci.CursorKind.LINKAGE_SPEC):
                scopes.extend(self._scopes(child))
        return scopes

    def _pair_markers(self, tu: ci.TranslationUnit) -> list[tuple[str, str, ci.Cursor]]:
        """(kind, macro args, declaration) for every marked declaration, in source order."""
        found: list[tuple[str, str, ci.Cursor]] = []
        for scope in self._scopes(tu.cursor):
            pending: tuple[str, str, ci.Cursor] | None = None
            for child in scope.get_children():
                file = child.location.file
                if file is None or file.name.startswith(_SYSTEM_PREFIXES):
                    continue
                kind_of_child = _kind(child)
                if kind_of_child is None:
                    continue
                if _kind(child) == ci.CursorKind.STRUCT_DECL and child.spelling.startswith(MARKER_PREFIX):
                    ann = _annotation(child)
                    if pending is not None:
                        raise self._error(pending[2], f"SP{pending[0].upper()}() is not followed by a declaration")
                    assert ann is not None
                    pending = (ann[0], ann[1], child)
                    continue
                if pending is None:
                    if _kind(child) in _RECORD_KINDS and child.is_definition():
                        self._check_unmarked(child)
                    continue
                kind, args, marker = pending
                pending = None
                expected = ci.CursorKind.ENUM_DECL if kind == "enum" else _RECORD_KINDS
                if _kind(child) not in (expected if isinstance(expected, tuple) else (expected,)) or not (
                    child.is_definition()
                ):
                    raise self._error(marker, f"SP{kind.upper()}() must be followed by a {kind} definition")
                if child.location.file.name != marker.location.file.name:
                    raise self._error(marker, f"SP{kind.upper()}() is not followed by a declaration in the same file")
                found.append((kind, args, child))
            if pending is not None:
                raise self._error(pending[2], f"SP{pending[0].upper()}() is not followed by a declaration")
        return found

    def _check_unmarked(self, record: ci.Cursor) -> None:
        """A class without SPCLASS() must not use the other reflection macros."""
        for member in record.get_children():
            if _kind(member) == ci.CursorKind.CXX_METHOD and member.spelling == BODY_MARKER:
                raise self._error(member, f"'{record.spelling}' has SP_GENERATED_BODY() but no SPCLASS() or SPSTRUCT()")
            ann = _annotation(member)
            if ann and ann[0] in ("property", "function"):
                raise self._error(
                    member, f"SP{ann[0].upper()}() on '{member.spelling}' in '{record.spelling}', "
                    "which is not reflected (mark the class SPCLASS())",
                )

    # -- IR construction -------------------------------------------------------------------------

    def scan(self, module_name: str, headers: list[Path]) -> Module:
        tu = self.parse(headers)
        marked = self._pair_markers(tu)
        for kind, _, decl in marked:
            self._reflected[decl.get_usr()] = kind
        wanted = {str(h.resolve()) for h in headers}
        self._check_unique_names(marked, wanted)
        classes: list[Class] = []
        enums: list[Enum] = []
        for kind, args, decl in marked:
            if not self._is_local(decl, wanted):
                continue  # reflected in another module (e.g. the engine, seen from a plugin)
            try:
                spec = specifiers.parse(kind, args)
            except specifiers.SpecifierError as e:
                raise self._error(decl, f"malformed SP{kind.upper()}({args}): {e}") from None
            if kind == "enum":
                enums.append(self._enum(decl))
            else:
                classes.append(self._record(kind, spec, decl))
        rel_headers = tuple(sorted(self._rel(str(h.resolve())) for h in headers))
        return Module(
            name=module_name,
            headers=rel_headers,
            classes=tuple(sorted(classes, key=lambda c: c.name)),
            enums=tuple(sorted(enums, key=lambda e: e.name)),
        )

    @staticmethod
    def _is_local(decl: ci.Cursor, wanted: set[str]) -> bool:
        """Whether the declaration belongs to this module (is in one of its headers)."""
        return str(Path(decl.location.file.name).resolve()) in wanted

    def _check_unique_names(self, marked: list[tuple[str, str, ci.Cursor]], wanted: set[str]) -> None:
        """Reflected types are found by their unqualified name (the registry, the Python API), so a module's
        type may not reuse the name of another reflected type, its own or another module's (a plugin's
        AActor in its own namespace would shadow the engine's)."""
        seen: dict[str, ci.Cursor] = {}
        # Other modules' declarations first, so that a clash is reported at this module's declaration.
        for _, _, decl in sorted(marked, key=lambda m: self._is_local(m[2], wanted)):
            other = seen.setdefault(decl.spelling, decl)
            if other is not decl and self._is_local(decl, wanted):
                where = self._rel(other.location.file.name)
                raise self._error(decl, f"'{decl.spelling}' is already the name of a reflected type in {where}; "
                                  "reflected names are global (rename one)")

    def _enum(self, decl: ci.Cursor) -> Enum:
        entries = tuple(
            EnumEntry(name=c.spelling, value=c.enum_value, doc=clean_doc(c.raw_comment))
            for c in decl.get_children()
            if _kind(c) == ci.CursorKind.ENUM_CONSTANT_DECL
        )
        if not entries:
            raise self._error(decl, f"enum '{decl.spelling}' has no entries")
        return Enum(
            name=decl.spelling, cpp_name=qualified_name(decl), header=self._rel(decl.location.file.name),
            doc=clean_doc(decl.raw_comment), entries=entries,
        )

    def _record(self, kind: str, spec: tuple[tuple[str, str], ...], decl: ci.Cursor) -> Class:
        name = decl.spelling
        if _kind(decl.semantic_parent) in _RECORD_KINDS:
            raise self._error(decl, f"nested reflected type '{name}' is not supported; declare it at namespace scope")
        has_body = any(_kind(c) == ci.CursorKind.CXX_METHOD and c.spelling == BODY_MARKER for c in decl.get_children())
        if not has_body:
            raise self._error(decl, f"'{name}' is marked SP{kind.upper()}() but has no SP_GENERATED_BODY()")
        parent, parent_cpp = self._parent(kind, decl)
        self._record_kind = kind
        properties: list[Property] = []
        functions: list[Function] = []
        for member in decl.get_children():
            ann = _annotation(member)
            if _kind(member) in _RECORD_KINDS and member.spelling.startswith(MARKER_PREFIX):
                raise self._error(member, f"nested reflected types are not supported (inside '{name}')")
            if ann is None or member.spelling == BODY_MARKER:
                continue
            mkind, margs = ann
            if mkind not in ("property", "function"):
                raise self._error(member, f"SP{mkind.upper()}() cannot be used inside '{name}'")
            try:
                mspec = specifiers.parse(mkind, margs)
            except specifiers.SpecifierError as e:
                raise self._error(member, f"malformed SP{mkind.upper()}({margs}) on '{member.spelling}': {e}") from None
            if member.access_specifier != ci.AccessSpecifier.PUBLIC:
                raise self._error(member, f"reflected member '{name}::{member.spelling}' must be public")
            if mkind == "property":
                properties.append(self._property(name, member, mspec))
            else:
                functions.append(self._function(name, member, mspec))
        self._check_functions(decl, functions)
        self._check_setters(decl, properties, functions)
        if specifiers.has(spec, "Partial") and not specifiers.has(spec, "TypedDict"):
            raise self._error(decl, f"SPSTRUCT(Partial) on '{name}' needs TypedDict: SPSTRUCT(TypedDict, Partial)")
        abstract = specifiers.has(spec, "Abstract") or decl.is_abstract_record()
        if not abstract and kind == "class" and not self._default_constructible(decl):
            raise self._error(decl, f"'{name}' needs a public default constructor, or SPCLASS(Abstract)")
        return Class(
            name=name, cpp_name=qualified_name(decl), kind=kind, header=self._rel(decl.location.file.name),  # type: ignore[arg-type]
            doc=clean_doc(decl.raw_comment), parent=parent, parent_cpp=parent_cpp, abstract=abstract, properties=tuple(properties),
            functions=tuple(functions), specifiers=spec,
        )

    def _parent(self, kind: str, decl: ci.Cursor) -> tuple[str | None, str | None]:
        """The reflected base: its name, and its fully qualified name."""
        reflected_bases: list[ci.Cursor] = []
        derives_object_base = False
        for base in decl.get_children():
            if _kind(base) != ci.CursorKind.CXX_BASE_SPECIFIER:
                continue
            base_decl = base.type.get_canonical().get_declaration()
            if qualified_name(base_decl) == "sp::reflect::ObjectBase":
                derives_object_base = True
            elif self._reflected_kind(base_decl) == kind:
                reflected_bases.append(base_decl)
        if len(reflected_bases) > 1:
            names = ", ".join(b.spelling for b in reflected_bases)
            raise self._error(decl, f"'{decl.spelling}' has more than one reflected base: {names}")
        if kind == "class" and not reflected_bases and not derives_object_base:
            raise self._error(decl, f"SPCLASS '{decl.spelling}' must derive from UObject (or another reflected class)")
        if not reflected_bases:
            return None, None
        return reflected_bases[0].spelling, qualified_name(reflected_bases[0])

    @staticmethod
    def _default_constructible(decl: ci.Cursor) -> bool:
        constructors = [c for c in decl.get_children() if _kind(c) == ci.CursorKind.CONSTRUCTOR]
        if not constructors:
            return True
        return any(
            len(list(c.get_arguments())) == 0 and c.access_specifier == ci.AccessSpecifier.PUBLIC
            and not c.is_deleted_method()
            for c in constructors
        )

    def _map(self, cursor: ci.Cursor, t: ci.Type, what: str) -> TypeRef:
        try:
            return self._types.map(t)
        except UnsupportedType as e:
            raise self._error(cursor, f"{what}: {e}") from None

    def _property(self, owner: str, field: ci.Cursor, spec: tuple[tuple[str, str], ...]) -> Property:
        if _kind(field) != ci.CursorKind.FIELD_DECL:
            raise self._error(field, f"SPPROPERTY() on '{owner}::{field.spelling}', which is not a non-static data member")
        t = field.type
        if specifiers.has(spec, "NotNull") and t.get_canonical().kind != ci.TypeKind.POINTER:
            raise self._error(field, f"NotNull on '{owner}::{field.spelling}', which is not an object reference")
        if self._record_kind == "struct" and t.get_canonical().kind == ci.TypeKind.POINTER:
            raise self._error(field, f"struct field '{owner}::{field.spelling}' cannot hold an object reference; "
                              "structs are plain values")
        read_only = t.is_const_qualified() or any(
            specifiers.has(spec, k) for k in ("ReadOnly", "BlueprintReadOnly", "VisibleAnywhere",
                                              "VisibleDefaultsOnly", "VisibleInstanceOnly")
        )
        mapped = self._map(field, t, f"property '{owner}::{field.spelling}'")
        self._check_range(field, owner, mapped.kind, spec)
        return Property(
            name=field.spelling, doc=clean_doc(field.raw_comment),
            type=mapped, read_only=read_only,
            setter=specifiers.lookup(spec, "Setter"), specifiers=spec, default_cpp=self._initializer(field),
            not_null=specifiers.has(spec, "NotNull"),
        )

    def _check_range(self, field: ci.Cursor, owner: str, kind: str, spec: tuple[tuple[str, str], ...]) -> None:
        """ClampMin / ClampMax (the range editors offer; the setter still checks): numbers, on a number, in order."""
        bounds = {}
        for key in ("ClampMin", "ClampMax"):
            value = specifiers.lookup(spec, key)
            if value is None:
                continue
            if kind not in ("int", "float"):
                raise self._error(field, f"{key} on '{owner}::{field.spelling}', which is not a number")
            try:
                bounds[key] = float(value)
            except ValueError:
                raise self._error(field, f"{key}={value} on '{owner}::{field.spelling}' is not a number") from None
        if len(bounds) == 2 and bounds["ClampMin"] > bounds["ClampMax"]:
            raise self._error(field, f"ClampMin {bounds['ClampMin']:g} > ClampMax {bounds['ClampMax']:g} on "
                              f"'{owner}::{field.spelling}'")

    def _initializer(self, field: ci.Cursor) -> str | None:
        """The member initializer as written ("1.0", "{1.0, 1.0, 1.0}"), read from the source text.

        (libclang yields no tokens for a declaration whose extent starts inside a macro expansion.)
        """
        text = self._source_text(field)
        m = re.search(rf"\b{re.escape(field.spelling)}\b\s*(=\s*(?P<eq>.+)|(?P<brace>\{{.*\}}))\s*$", text, re.S)
        if not m:
            return None
        value = m.group("eq") if m.group("eq") is not None else m.group("brace")
        return " ".join(value.split())

    def _source_text(self, cursor: ci.Cursor) -> str:
        start, end = cursor.extent.start, cursor.extent.end
        if start.file is None:
            return ""
        data = self._files.get(start.file.name)
        if data is None:
            data = self._files[start.file.name] = Path(start.file.name).read_bytes()
        return data[start.offset:end.offset].decode("utf-8", errors="replace")

    def _function(self, owner: str, method: ci.Cursor, spec: tuple[tuple[str, str], ...]) -> Function:
        fname = f"{owner}::{method.spelling}"
        if _kind(method) != ci.CursorKind.CXX_METHOD:
            raise self._error(method, f"SPFUNCTION() on '{fname}', which is not a member function (templates, "
                              "constructors and operators cannot be reflected)")
        if method.spelling.startswith("operator"):
            raise self._error(method, f"SPFUNCTION() on operator '{fname}' is not supported")
        result = method.result_type
        if result.kind == ci.TypeKind.LVALUEREFERENCE:
            if not result.get_pointee().is_const_qualified():
                raise self._error(method, f"'{fname}' returns a non-const reference, which cannot cross the boundary")
            result = result.get_pointee()
        returns = self._map(method, result, f"return type of '{fname}'")
        params: list[Param] = []
        for index, arg in enumerate(method.get_arguments()):
            if not arg.spelling:
                raise self._error(arg, f"parameter {index + 1} of '{fname}' has no name")
            params.append(self._param(fname, arg))
        determines = specifiers.lookup(spec, "DeterminesOutputType")
        if determines is not None:
            target = next((p for p in params if p.name == determines), None)
            if target is None or target.type.kind != "class":
                raise self._error(method, f"DeterminesOutputType={determines} on '{fname}' must name a class parameter")
            inner = returns.args[0] if returns.kind in ("list", "dict") else returns
            if inner.kind not in ("object", "class"):
                raise self._error(method, f"DeterminesOutputType on '{fname}' needs an object or class (or list/dict "
                                  "of object) result")
        return Function(
            name=method.spelling, doc=clean_doc(method.raw_comment), returns=returns, params=tuple(params),
            is_static=method.is_static_method(), is_const=method.is_const_method(), specifiers=spec,
            determines_output_type=determines, not_null=specifiers.has(spec, "NotNull"),
        )

    def _param(self, fname: str, arg: ci.Cursor) -> Param:
        t = arg.type
        is_out = False
        if t.kind == ci.TypeKind.RVALUEREFERENCE:
            raise self._error(arg, f"parameter '{arg.spelling}' of '{fname}' is an rvalue reference; pass by value")
        if t.kind == ci.TypeKind.LVALUEREFERENCE:
            pointee = t.get_pointee()
            is_out = not pointee.is_const_qualified()
            t = pointee
        ptype = self._map(arg, t, f"parameter '{arg.spelling}' of '{fname}'")
        default = self._default(arg)
        if is_out and default is not None:
            raise self._error(arg, f"out-parameter '{arg.spelling}' of '{fname}' cannot have a default")
        return Param(name=arg.spelling, type=ptype, cpp_decl=arg.type.spelling, default_cpp=default, is_out=is_out)

    @staticmethod
    def _default(arg: ci.Cursor) -> str | None:
        """The default argument's expression, with the names it refers to spelled in full: the generated code
        that uses it is outside the namespace the function is declared in ("EGait::Run" in namespace acme
        becomes "acme::EGait::Run")."""
        tokens = list(arg.get_tokens())
        spellings = [t.spelling for t in tokens]
        if "=" not in spellings:
            return None
        start = spellings.index("=") + 1
        spans: dict[int, tuple[int, str]] = {}  # first token -> (last token, qualified name)
        for node in arg.walk_preorder():
            if _kind(node) not in (ci.CursorKind.DECL_REF_EXPR, ci.CursorKind.TYPE_REF) or node.referenced is None:
                continue
            covered = [i for i in range(start, len(tokens))
                       if tokens[i].extent.start.offset >= node.extent.start.offset
                       and tokens[i].extent.end.offset <= node.extent.end.offset]
            if not covered:
                continue
            first, last = covered[0], covered[-1]
            if _kind(node) == ci.CursorKind.DECL_REF_EXPR:  # its name is the last token, after any qualifiers
                first = next((i for i in reversed(covered) if spellings[i] == node.referenced.spelling), last)
                last = first
            while first - 2 >= start and spellings[first - 1] == "::" and spellings[first - 2].isidentifier():
                first -= 2  # a qualifier spelled before the name
            if first - 1 >= start and spellings[first - 1] == "::":
                continue  # qualified by something other than names (a template's arguments): kept as written
            if any(f <= first and last <= l for f, (l, _) in spans.items()):
                continue  # inside a name already taken
            spans[first] = (last, qualified_name(node.referenced))
        out: list[str] = []
        i = start
        while i < len(tokens):
            if i in spans:
                last, qualified = spans[i]
                spelled = "".join(spellings[i:last + 1])
                # Only qualifiers are added: a name spelled another way (an alias) is kept as written.
                out.append(qualified if qualified.endswith("::" + spelled) else spelled)
                i = last + 1
            else:
                out.append(spellings[i])
                i += 1
        return _join_tokens(out)

    def _check_functions(self, decl: ci.Cursor, functions: list[Function]) -> None:
        seen: set[str] = set()
        for f in functions:
            if f.name in seen:
                method = next(c for c in reversed(list(decl.get_children())) if c.spelling == f.name)
                raise self._error(method, f"'{decl.spelling}::{f.name}' is overloaded; reflected functions "
                                  "cannot be overloaded (give each a distinct name)")
            seen.add(f.name)

    def _check_setters(self, decl: ci.Cursor, properties: list[Property], functions: list[Function]) -> None:
        names = {f.name: f for f in functions}
        for p in properties:
            if p.setter is None:
                continue
            setter = names.get(p.setter)
            inputs = [x for x in setter.params if not x.is_out] if setter else []
            if setter is None or len(inputs) != 1 or inputs[0].type != p.type:
                field = next(c for c in decl.get_children() if c.spelling == p.name)
                raise self._error(field, f"Setter={p.setter} of '{decl.spelling}::{p.name}' must be a reflected "
                                  f"function of '{decl.spelling}' taking one {p.type.cpp}")


def scan(module_name: str, headers: list[Path], options: ScanOptions) -> Module:
    return Scanner(options).scan(module_name, headers)
