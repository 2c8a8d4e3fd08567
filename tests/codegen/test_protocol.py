"""The RPC protocol's one source (core/rpc/protocol.json) and what codegen.protocol makes of it: the committed
outputs are current, and a malformed source is refused naming the file and the entry at fault."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def run(command: str, root: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "codegen.protocol", command, "--root", str(root)], cwd=ROOT,
                          capture_output=True, text=True, check=False)


def test_committed_protocol_outputs_are_current() -> None:
    result = run("check", ROOT)
    assert result.returncode == 0, result.stderr + "\nregenerate with the build and commit generated/rpc"


def copy_of_source(tmp_path: Path, edit: dict[str, object] | None = None) -> Path:
    source = json.loads((ROOT / "core/rpc/protocol.json").read_text())
    if edit:
        source["ops"].update(edit)
    (tmp_path / "core/rpc").mkdir(parents=True)
    (tmp_path / "core/rpc/protocol.json").write_text(json.dumps(source))
    return tmp_path


def test_generate_writes_every_output_and_check_then_passes(tmp_path: Path) -> None:
    root = copy_of_source(tmp_path)
    assert run("check", root).returncode == 1  # nothing generated yet: every output is missing
    assert run("generate", root).returncode == 0
    for name in ("generated/rpc/cpp/protocol.gen.h", "generated/rpc/python/protocol.py",
                 "generated/rpc/ts/protocol.gen.ts"):
        assert (root / name).read_text() == (ROOT / name).read_text(), name
    assert run("check", root).returncode == 0


def test_an_op_added_to_the_source_reaches_every_client(tmp_path: Path) -> None:
    root = copy_of_source(tmp_path, {"ping": {"doc": "Answers.", "fields": {"mode": "'fast'|'slow'"}}})
    assert run("generate", root).returncode == 0
    assert 'inline constexpr std::string_view kPing{"ping"};' in (root / "generated/rpc/cpp/protocol.gen.h").read_text()
    python = (root / "generated/rpc/python/protocol.py").read_text()
    assert 'PingMode = Literal["fast", "slow"]' in python and 'op: Literal["ping"], *, mode: PingMode' in python
    assert 'readonly op: "ping";' in (root / "generated/rpc/ts/protocol.gen.ts").read_text()


@pytest.mark.parametrize("op, message", [
    ({"Ping": {"fields": {}}}, "ops.Ping: an op is a snake_case name"),
    ({"ping": {"fields": {"mode": "float"}}}, "ops.ping.fields.mode: unknown type 'float'"),
    ({"ping": {"fields": {"mode": "'fast'|slow"}}}, "ops.ping.fields.mode: unknown type"),
    ({"ping": {"fields": {"context": "str"}}}, "ops.ping.fields.context: already a common field"),
    ({"ping": {"fields": {"Mode": "str"}}}, "ops.ping.fields: field name 'Mode' is not snake_case"),
])
def test_a_malformed_source_is_refused_naming_the_entry(tmp_path: Path, op: dict[str, object], message: str) -> None:
    root = copy_of_source(tmp_path, op)
    result = run("generate", root)
    assert result.returncode == 1
    assert f"{root / 'core/rpc/protocol.json'}: {message}" in result.stderr, result.stderr
    assert not (root / "generated").exists(), "nothing is written from a malformed source"


def test_malformed_json_names_the_file(tmp_path: Path) -> None:
    (tmp_path / "core/rpc").mkdir(parents=True)
    (tmp_path / "core/rpc/protocol.json").write_text('{"ops": {')
    result = run("generate", tmp_path)
    assert result.returncode == 1 and "protocol.json" in result.stderr and "line 1" in result.stderr, result.stderr
