"""Typing holds under pyright too (the checker behind Pylance, so what IDE users see): the examples and
positive cases pass pyright strict; every negative case is rejected with exactly its pinned `# P:` rules
and messages; and the package's public surface is fully typed by `pyright --verifytypes` (no symbol of
unknown or ambiguous type), which is what makes completion and checking work in users' own code."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mypy_runner import ROOT, mismatch, pinned_errors  # noqa: E402
from pyright_runner import errors, pyright, reported_errors  # noqa: E402

FAIL = ROOT / "tests/typing/fail"


def test_examples_and_positive_cases_pass_pyright_strict() -> None:
    result, report = pyright()  # files and settings from [tool.pyright] in pyproject.toml
    assert report["summary"]["errorCount"] == 0, "\n".join(errors(report)) + result.stderr


@pytest.mark.parametrize("case", sorted(p.name for p in FAIL.glob("*.py")))
def test_negative_case_is_rejected_by_pyright_with_pinned_messages(case: str) -> None:
    path = FAIL / case
    expected = pinned_errors(path, marker="P")
    assert expected, "a negative case must pin at least one pyright error"
    _, report = pyright(str(path.relative_to(ROOT)))
    assert reported_errors(report, path) == expected, mismatch(expected, reported_errors(report, path))


def test_public_api_is_completely_typed() -> None:
    _, report = pyright(args=("--verifytypes", "spear", "--ignoreexternal"))
    completeness = report["typeCompleteness"]
    unknown = [s["name"] for s in completeness["symbols"] if not s.get("isTypeKnown", True)]
    assert completeness["exportedSymbolCounts"]["withKnownType"] > 50, completeness["exportedSymbolCounts"]
    assert completeness["completenessScore"] == 1, f"symbols of unknown type: {unknown}"
