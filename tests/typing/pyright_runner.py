"""Runs pyright (pinned in tests/typing/pyright/package-lock.json, installed by test.sh) the way the typing
tests do. Settings come from [tool.pyright] in pyproject.toml (strict); pyright reads the search paths of
Debian's /usr/bin/python3, which sees numpy, and PYTHONPATH adds the spear package and any plugin stubs."""

from __future__ import annotations

import json
import os
import subprocess
import tempfile
import tomllib
from pathlib import Path
from typing import Any

from mypy_runner import ROOT

PYRIGHT = ROOT / "tests/typing/pyright/node_modules/.bin/pyright"
INSTALL_HINT = "pyright is not installed: run `bash test.sh`, or `npm ci --prefix tests/typing/pyright`"


def pyright(*files: str, extra_path: Path | None = None,
            args: tuple[str, ...] = ()) -> tuple[subprocess.CompletedProcess[str], dict[str, Any]]:
    """pyright --outputjson on `files` (relative to the root), or on pyproject's include list when none
    are given; returns the process and its parsed report, having checked that every file was read."""
    assert PYRIGHT.exists(), INSTALL_HINT
    paths = [str(ROOT / "python")] + ([str(extra_path)] if extra_path is not None else [])
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(paths))
    with tempfile.TemporaryDirectory() as tmp:
        project: list[str] = []
        if files:
            # Files named on the command line would still fall under pyproject's excludes (examples/plugin
            # needs its plugin's stubs), so they get a config of their own with pyproject's settings.
            settings = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["pyright"]
            settings = {k: v for k, v in settings.items() if k not in ("include", "exclude")}
            # pyright reads a config's paths relative to the config's folder, and only so.
            settings["extraPaths"] = [os.path.relpath(ROOT / p, tmp) for p in settings.get("extraPaths", [])]
            if "stubPath" in settings:
                settings["stubPath"] = os.path.relpath(ROOT / settings["stubPath"], tmp)
            settings["include"] = [os.path.relpath(ROOT / f, tmp) for f in files]
            config = Path(tmp) / "pyrightconfig.json"
            config.write_text(json.dumps(settings))
            project = ["--project", str(config)]
        result = subprocess.run([str(PYRIGHT), "--outputjson", "--pythonpath", "/usr/bin/python3", *project, *args],
                                cwd=ROOT, capture_output=True, text=True, check=False, env=env)
    report: dict[str, Any] = json.loads(result.stdout)
    assert report["summary"]["filesAnalyzed"] >= max(len(files), 1), f"pyright read no file:\n{result.stdout}"
    return result, report


def errors(report: dict[str, Any]) -> list[str]:
    """Every error as `file:line: rule: message`, for an assertion message."""
    return [f"{Path(d['file']).relative_to(ROOT)}:{d['range']['start']['line'] + 1}: {d.get('rule', '')}: "
            f"{d['message']}" for d in report["generalDiagnostics"] if d["severity"] == "error"]


def one_line(message: str) -> str:
    """pyright's message on one line: its lines (the specifics come after the first) joined by " / "."""
    return " / ".join(line.strip() for line in message.splitlines())


def reported_errors(report: dict[str, Any], path: Path) -> set[tuple[int, str]]:
    """(line, "rule: message") for each error pyright reports in `path`, as the `# P:` pins spell them."""
    return {(d["range"]["start"]["line"] + 1, f"{d.get('rule', '')}: {one_line(d['message'])}")
            for d in report["generalDiagnostics"]
            if d["severity"] == "error" and Path(d["file"]) == path}
