"""Command line: python3 -m codegen generate|check|list-outputs|dump-ir|watch ..."""

from __future__ import annotations

import argparse
import os
import re
import sys
import time
from pathlib import Path

from codegen import emit
from codegen.errors import GeneratorError
from codegen.scanner import ScanOptions, scan


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python3 -m codegen", description=__doc__)
    p.add_argument("command", choices=["generate", "check", "list-outputs", "dump-ir", "watch"],
                   help="watch: generate, then again whenever a header or blueprint changes (Ctrl-C stops)")
    p.add_argument("--module", required=True, help="module name, e.g. engine")
    p.add_argument("--root", type=Path, required=True, help="project root; header paths are relative to it")
    p.add_argument("--out", type=Path, required=True, help="output root (generated/)")
    p.add_argument("--include-dir", type=Path, action="append", default=[], help="extra include directory")
    p.add_argument("--define", action="append", default=[], help="extra preprocessor definition")
    p.add_argument("--stamp", type=Path, help="file to touch after a successful generate (for build systems)")
    p.add_argument("--blueprint-dir", type=Path, help="blueprint assets (*.json) to emit typed classes for")
    p.add_argument("--python-out", type=Path,
                   help="directory of the module's Python package files (default: <out>/<module>/python)")
    p.add_argument("--package", type=_package_name,
                   help="the importable Python package of the module's API (default: spear._<module>)")
    p.add_argument("headers", nargs="+", type=Path)
    return p


def _package_name(text: str) -> str:
    if not re.fullmatch(r"[A-Za-z_]\w*(\.[A-Za-z_]\w*)*", text):
        raise argparse.ArgumentTypeError(f"'{text}' is not a dotted Python package name")
    return text


def _layout(args: argparse.Namespace) -> emit.OutputLayout:
    # abspath, not resolve(): a package directory reached through a symlink keeps the path it was given.
    python_out = Path(os.path.abspath(args.python_out)).as_posix() if args.python_out else None
    return emit.OutputLayout(args.module, package_name=args.package, python_out=python_out)


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    root = args.root.resolve()
    headers = [h if h.is_absolute() else root / h for h in args.headers]
    layout = _layout(args)
    if args.command == "list-outputs":
        # Output names depend only on the header list, so a build system can know them before parsing.
        from codegen.model import Module

        module = Module(name=args.module, headers=tuple(sorted(h.resolve().relative_to(root).as_posix() for h in headers)))
        print("\n".join(str(args.out / f) for f in layout.files(module)))
        return 0
    for h in headers:
        if not h.is_file():
            print(f"{h}: error: header not found", file=sys.stderr)
            return 1
    if args.command == "watch":
        return _watch(args, root, headers, layout)
    return _run(args, root, headers, layout)


def _run(args: argparse.Namespace, root: Path, headers: list[Path], layout: emit.OutputLayout) -> int:
    started = time.perf_counter()
    try:
        module = scan(args.module, headers, ScanOptions(root=root, include_dirs=tuple(args.include_dir),
                                                        defines=tuple(args.define)))
        if args.blueprint_dir:
            from codegen.blueprints import add_blueprints

            directory = args.blueprint_dir if args.blueprint_dir.is_absolute() else root / args.blueprint_dir
            module = add_blueprints(module, directory, root)
    except GeneratorError as e:
        print(e, file=sys.stderr)
        return 1
    if args.command == "dump-ir":
        sys.stdout.write(module.to_json())
        return 0
    outputs = emit.render(module, layout)
    if args.command == "check":
        stale = emit.check(outputs, args.out)
        if stale:
            print("generated files are stale or orphaned (run the build or `python3 -m codegen generate`):",
                  file=sys.stderr)
            for rel in stale:
                print(f"  {args.out / rel}", file=sys.stderr)
            return 1
        print(f"codegen: {len(outputs)} generated files of module '{args.module}' are up to date")
        return 0
    removed = emit.orphans(outputs, args.out)
    changed = [rel for rel in emit.write(outputs, args.out) if rel not in removed]
    elapsed = time.perf_counter() - started
    gone = f", {len(removed)} orphaned files removed" if removed else ""
    print(f"codegen: module '{args.module}': {len(module.classes)} classes, {len(module.enums)} enums, "
          f"{len(changed)} of {len(outputs)} files changed{gone} ({elapsed:.2f} s)")
    if args.stamp:
        args.stamp.parent.mkdir(parents=True, exist_ok=True)
        args.stamp.write_text("")
    return 0


def _watched(args: argparse.Namespace, root: Path, headers: list[Path]) -> dict[Path, int]:
    """What a regeneration reads that a user edits: the headers and the blueprint assets, by mtime."""
    paths = list(headers)
    if args.blueprint_dir:
        directory = args.blueprint_dir if args.blueprint_dir.is_absolute() else root / args.blueprint_dir
        paths += sorted(directory.glob("*.json"))
    return {p: p.stat().st_mtime_ns for p in paths if p.exists()}


def _watch(args: argparse.Namespace, root: Path, headers: list[Path], layout: emit.OutputLayout) -> int:
    """Regenerates on save: the stubs follow the headers while the C++ is left to the build. A header that
    does not parse is reported (file:line) and watching goes on."""
    args.command = "generate"
    seen = _watched(args, root, headers)
    _run(args, root, headers, layout)
    print(f"codegen: watching {len(seen)} files of module '{args.module}' (Ctrl-C to stop)", flush=True)
    try:
        while True:
            time.sleep(0.25)
            now = _watched(args, root, headers)
            if now != seen:
                changed = sorted({p.name for p in now.keys() ^ seen.keys()} |
                                 {p.name for p in now if p in seen and now[p] != seen[p]})
                seen = now
                print(f"codegen: changed: {', '.join(changed)}", flush=True)
                _run(args, root, headers, layout)
                sys.stdout.flush()
    except KeyboardInterrupt:
        return 0
