"""Runs mypy the way the typing tests do, and reads the errors a negative case pins with `# E:`."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def mypy(*targets: str, extra_path: Path | None = None) -> subprocess.CompletedProcess[str]:
    """mypy --strict (pyproject.toml) on `targets`; `extra_path` adds stubs, e.g. a plugin's package."""
    env = dict(os.environ)
    if extra_path is not None:
        env["MYPYPATH"] = str(extra_path)
    return subprocess.run(
        [sys.executable, "-m", "mypy", "--no-error-summary", "--hide-error-context", "--no-pretty",
         "--show-error-codes", *targets],
        cwd=ROOT, capture_output=True, text=True, check=False, env=env,
    )


def pinned_errors(path: Path, marker: str = "E") -> set[tuple[int, str]]:
    """(line, message) for every `# E: message` comment in `path` (mypy's); `marker="P"` reads the
    `# P: rule: message` comments pinned for pyright. A line may carry one E and several P pins."""
    expected = set()
    for number, line in enumerate(path.read_text().splitlines(), start=1):
        for pin in line.split("  # ")[1:]:
            if pin.startswith(f"{marker}: "):
                expected.add((number, pin[len(marker) + 2:].strip()))
    return expected


def reported_errors(result: subprocess.CompletedProcess[str], path: Path) -> set[tuple[int, str]]:
    relative = re.escape(str(path.relative_to(ROOT)))
    actual = set()
    for line in result.stdout.splitlines():
        m = re.match(rf"{relative}:(\d+): error: (.*)$", line)
        if m:
            actual.add((int(m.group(1)), m.group(2).strip()))
    return actual


def mismatch(expected: set[tuple[int, str]], actual: set[tuple[int, str]]) -> str:
    return "\n".join(["missing:", *map(str, sorted(expected - actual)),
                      "unexpected:", *map(str, sorted(actual - expected))])
