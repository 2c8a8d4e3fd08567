"""Typing is tested like code: positive cases and examples pass mypy --strict; negative cases are
rejected with exactly the pinned messages (the `# E:` comment on each line)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mypy_runner import ROOT, mismatch, mypy, pinned_errors, reported_errors  # noqa: E402

FAIL = ROOT / "tests/typing/fail"


def test_package_examples_and_positive_cases_pass_strict() -> None:
    result = mypy()  # files, strictness and paths come from pyproject.toml
    assert result.returncode == 0, result.stdout + result.stderr


@pytest.mark.parametrize("case", sorted(p.name for p in FAIL.glob("*.py")))
def test_negative_case_is_rejected_with_pinned_messages(case: str) -> None:
    path = FAIL / case
    expected = pinned_errors(path)
    assert expected, "a negative case must pin at least one error"
    result = mypy(str(path.relative_to(ROOT)))
    actual = reported_errors(result, path)
    assert actual == expected, mismatch(expected, actual)
