"""The generated TypeScript client is typed as the Python stubs are: the inspector page and the positive cases
type-check under tsc --strict (the compiler pinned by inspector/package-lock.json), and each negative case is
rejected with exactly its pinned `// T: TSnnnn: message` errors (a misspelt property, a wrong argument type, a
wrong modality key, a read-only property)."""

from __future__ import annotations

import json
import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CASES = ROOT / "tests/typing/typescript"
TSC = ROOT / "inspector/node_modules/typescript/bin/tsc"

pytestmark = pytest.mark.skipif(not TSC.is_file(), reason="no tsc: npm ci --prefix inspector (test.sh runs it)")


def tsc(project: Path) -> tuple[int, set[tuple[str, int, str]]]:
    """tsc's exit status and its errors as (file, line, "TSnnnn: message"), the message's first line."""
    result = subprocess.run(["node", str(TSC), "-p", str(project), "--noEmit", "--pretty", "false"],
                            capture_output=True, text=True, cwd=ROOT, timeout=300)
    errors = set()
    for line in result.stdout.splitlines():
        m = re.match(r"(.+?)\((\d+),\d+\): error (TS\d+: .*)$", line)
        if m:
            errors.add((str((ROOT / m.group(1)).resolve()), int(m.group(2)), m.group(3).strip()))  # paths from cwd
    return result.returncode, errors


def test_the_inspector_page_type_checks_against_the_generated_client() -> None:
    status, errors = tsc(ROOT / "inspector/tsconfig.json")
    assert (status, errors) == (0, set())


def test_positive_cases_type_check() -> None:
    status, errors = tsc(CASES / "tsconfig.json")
    assert (status, errors) == (0, set())


@pytest.mark.parametrize("case", sorted(p.name for p in (CASES / "fail").glob("*.ts")))
def test_negative_case_is_rejected_with_pinned_errors(case: str, tmp_path: Path) -> None:
    path = (CASES / "fail" / case).resolve()
    expected = set()
    for number, line in enumerate(path.read_text().splitlines(), start=1):
        for pin in line.split("  // ")[1:]:
            if pin.startswith("T: "):
                expected.add((str(path), number, pin[3:].strip()))
    assert expected, "a negative case must pin at least one error"
    project = tmp_path / "tsconfig.json"
    project.write_text(json.dumps({"extends": str(CASES / "tsconfig.json"), "include": [str(path)],
                                   "compilerOptions": {"rootDir": str(ROOT), "noEmit": True}}))
    _, errors = tsc(project)
    assert errors == expected, f"missing: {sorted(expected - errors)}\nunexpected: {sorted(errors - expected)}"
