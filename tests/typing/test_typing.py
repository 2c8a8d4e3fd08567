"""Typing is tested like code: positive cases and examples pass mypy --strict; negative cases are
rejected with exactly the pinned messages (the `# E:` comment on each line)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FAIL = ROOT / "tests/typing/fail"


def mypy(*targets: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "mypy", "--no-error-summary", "--hide-error-context", "--no-pretty",
         "--show-error-codes", *targets],
        cwd=ROOT, capture_output=True, text=True, check=False,
    )


def test_package_examples_and_positive_cases_pass_strict() -> None:
    result = mypy()  # files, strictness and paths come from pyproject.toml
    assert result.returncode == 0, result.stdout + result.stderr


@pytest.mark.parametrize("case", sorted(p.name for p in FAIL.glob("*.py")))
def test_negative_case_is_rejected_with_pinned_messages(case: str) -> None:
    path = FAIL / case
    expected = set()
    for number, line in enumerate(path.read_text().splitlines(), start=1):
        if "# E: " in line:
            expected.add((number, line.split("# E: ", 1)[1].strip()))
    assert expected, "a negative case must pin at least one error"
    result = mypy(str(path.relative_to(ROOT)))
    actual = set()
    for line in result.stdout.splitlines():
        m = re.match(rf"{re.escape(str(path.relative_to(ROOT)))}:(\d+): error: (.*)$", line)
        if m:
            actual.add((int(m.group(1)), m.group(2).strip()))
    assert actual == expected, "\n".join(["missing:", *map(str, sorted(expected - actual)),
                                          "unexpected:", *map(str, sorted(actual - expected))])
