"""A plugin's stubs come from its headers alone (the generator, no build), and code using them is checked
like code using the engine: examples/plugin/use_plugin.py and a positive case pass mypy --strict and
pyright strict, and the negative case is rejected by both with exactly its pinned messages."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
import pyright_runner  # noqa: E402
from mypy_runner import ROOT, mismatch, mypy, pinned_errors, reported_errors  # noqa: E402

EXAMPLE = ROOT / "examples/plugin"
CASES = ROOT / "tests/typing/plugin"


@pytest.fixture(scope="module")
def plugin_stubs(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The example plugin's Python package, generated into a temporary directory; returns its parent."""
    out = tmp_path_factory.mktemp("plugin_stubs")
    headers = [line.split()[0] for line in (EXAMPLE / "CMakeLists.txt").read_text().split("HEADERS", 1)[1]
               .split("SOURCES", 1)[0].split()]
    result = subprocess.run(
        [sys.executable, "-m", "codegen", "generate", "--module", "my_plugin", "--package", "my_plugin",
         "--root", str(EXAMPLE), "--out", str(out / "generated"), "--python-out", str(out / "python/my_plugin"),
         "--include-dir", str(ROOT), "--include-dir", "/usr/include/eigen3", *headers],
        cwd=ROOT, capture_output=True, text=True, check=False)
    assert result.returncode == 0, result.stderr
    return out / "python"


def test_plugin_example_and_usage_pass_strict(plugin_stubs: Path) -> None:
    result = mypy("examples/plugin/use_plugin.py", "tests/typing/plugin/plugin_usage.py", extra_path=plugin_stubs)
    assert result.returncode == 0, result.stdout + result.stderr


def test_plugin_misuse_is_rejected_with_pinned_messages(plugin_stubs: Path) -> None:
    path = CASES / "plugin_misuse.py"
    expected = pinned_errors(path)
    result = mypy(str(path.relative_to(ROOT)), extra_path=plugin_stubs)
    actual = reported_errors(result, path)
    assert actual == expected, mismatch(expected, actual)


def test_plugin_example_and_usage_pass_pyright_strict(plugin_stubs: Path) -> None:
    _, report = pyright_runner.pyright("examples/plugin/use_plugin.py", "tests/typing/plugin/plugin_usage.py",
                                       extra_path=plugin_stubs)
    assert report["summary"]["errorCount"] == 0, "\n".join(pyright_runner.errors(report))


def test_plugin_misuse_is_rejected_by_pyright_with_pinned_messages(plugin_stubs: Path) -> None:
    path = CASES / "plugin_misuse.py"
    expected = pinned_errors(path, marker="P")
    _, report = pyright_runner.pyright(str(path.relative_to(ROOT)), extra_path=plugin_stubs)
    actual = pyright_runner.reported_errors(report, path)
    assert actual == expected, mismatch(expected, actual)
