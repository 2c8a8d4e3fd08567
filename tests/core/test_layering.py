"""The C++ libraries include only what they link: a file in core/<lib>/ may include headers of <lib> and of
the libraries <lib> declares in its CMakeLists.txt, directly or through their PUBLIC dependencies. The link
check (build/link_checks) proves the same for symbols; this one also catches a header-only use, and names
the file and line."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CORE = ROOT / "core"
INCLUDE = re.compile(r'^\s*#\s*include\s+"core/([a-z_]+)/', re.M)
LINK = re.compile(r"target_link_libraries\(\s*spear_([a-z_]+)\b(.*?)\)", re.S)


def _declared() -> dict[str, tuple[set[str], set[str]]]:
    """Library -> (PUBLIC dependencies, every dependency), from each core/<lib>/CMakeLists.txt."""
    found: dict[str, tuple[set[str], set[str]]] = {}
    for cmake in sorted(CORE.glob("*/CMakeLists.txt")):
        lib = cmake.parent.name
        for target, body in LINK.findall(cmake.read_text()):
            if target != lib:
                continue
            public: set[str] = set()
            every: set[str] = set()
            scope = "PUBLIC"
            for word in re.sub(r"#[^\n]*", "", body).split():
                if word in ("PUBLIC", "PRIVATE", "INTERFACE"):
                    scope = word
                elif word.startswith("spear_") and word != "spear_warnings":
                    every.add(word.removeprefix("spear_"))
                    if scope != "PRIVATE":
                        public.add(word.removeprefix("spear_"))
            found[lib] = (public, every)
    return found


def _reachable(lib: str, declared: dict[str, tuple[set[str], set[str]]]) -> set[str]:
    """What lib's files may include: itself, its dependencies, and their PUBLIC dependencies, transitively."""
    if lib not in declared:
        return {lib}
    seen = {lib}
    todo = list(declared[lib][1])
    while todo:
        dep = todo.pop()
        if dep in seen:
            continue
        seen.add(dep)
        if dep == "core":  # spear_core: the whole engine in one library
            todo.extend(declared)
        else:
            todo.extend(declared.get(dep, (set(), set()))[0])
    return seen


def test_every_core_include_is_of_a_declared_dependency() -> None:
    declared = _declared()
    assert {"world", "scene", "gameplay", "procedural", "sensors", "engine"} <= set(declared)
    wrong = []
    for lib in sorted(declared):
        allowed = _reachable(lib, declared)
        for path in sorted((CORE / lib).rglob("*")):
            if path.suffix not in (".h", ".cpp"):
                continue
            text = path.read_text()
            for match in INCLUDE.finditer(text):
                if match.group(1) not in allowed:
                    line = text.count("\n", 0, match.start()) + 1
                    wrong.append(f"{path.relative_to(ROOT)}:{line}: includes core/{match.group(1)}/, "
                                 f"which spear_{lib} does not link")
    assert not wrong, "\n".join(wrong)


def test_the_object_model_sits_below_what_builds_on_it() -> None:
    """core/world reaches the gameplay framework, procedural generation and scene files only through its
    seams (WorldHost, AActor::GetInputForwardTarget), so the libraries above can grow without a cycle."""
    reachable = _reachable("world", _declared())
    assert not reachable & {"scene", "gameplay", "procedural", "sensors", "spfunc", "engine"}
