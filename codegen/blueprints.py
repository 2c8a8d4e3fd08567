"""Blueprint assets -> IR: the generator types each data-defined class as its native parent.

Only the header of an asset matters here (its name, parent and doc); the engine reads the rest when the
class is loaded. A malformed asset, or one whose parent is not a reflected class, is an error with the
asset's file and line, like a malformed header.
"""

from __future__ import annotations

import dataclasses
import json
import os
from pathlib import Path

from codegen.errors import GeneratorError
from codegen.model import Blueprint, Module


def add_blueprints(module: Module, directory: Path, root: Path) -> Module:
    blueprints = []
    classes = {c.name for c in module.classes if c.kind == "class"}
    for path in sorted(directory.glob("*.json")):
        rel = Path(os.path.relpath(path, root)).as_posix()
        text = path.read_text()
        try:
            data = json.loads(text)
        except json.JSONDecodeError as e:
            raise GeneratorError(rel, e.lineno, f"blueprint is not valid JSON: {e.msg}") from None
        line = next((n for n, s in enumerate(text.splitlines(), 1) if '"parent"' in s), 1)
        parent = data.get("parent") if isinstance(data, dict) else None
        if not isinstance(parent, str) or parent not in classes:
            raise GeneratorError(rel, line, f"blueprint parent {parent!r} is not a reflected class of module "
                                            f"'{module.name}'")
        blueprints.append(Blueprint(name=path.stem, parent=parent, doc=str(data.get("doc", "")), asset=rel))
    names = {c.name for c in module.classes} | {e.name for e in module.enums}
    for b in blueprints:
        if b.name in names:
            raise GeneratorError(b.asset, 1, f"blueprint '{b.name}' has the name of a reflected type")
    return dataclasses.replace(module, blueprints=tuple(blueprints))
