"""The generator: golden outputs, rejected inputs, determinism, and the committed engine bindings."""

from __future__ import annotations

import difflib
import os
import shutil
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from codegen_runner import ROOT, engine_headers, run_codegen, tree  # noqa: E402

from codegen.model import Module  # noqa: E402

CASES = ROOT / "tests/codegen/cases"
NEGATIVE = ROOT / "tests/codegen/negative"
# Extra generator arguments of a golden case: the plugin case is generated as a plugin package would be.
CASE_ARGS = {"plugin_actor": ["--package", "plugin_actor"], "namespaced_plugin": ["--package", "namespaced_plugin"]}


def _diff(expected: bytes, actual: bytes, name: str) -> str:
    return "".join(difflib.unified_diff(
        expected.decode().splitlines(keepends=True), actual.decode().splitlines(keepends=True),
        f"expected/{name}", f"actual/{name}", n=2))


@pytest.mark.parametrize("case", sorted(p.name for p in CASES.iterdir() if p.is_dir()))
def test_golden_case(case: str, tmp_path: Path) -> None:
    header = f"tests/codegen/cases/{case}/input.h"
    result = run_codegen("generate", case, tmp_path, [header], extra=CASE_ARGS.get(case))
    assert result.returncode == 0, result.stderr
    expected_dir = CASES / case / "expected"
    actual = tree(tmp_path / case)
    if os.environ.get("SPEAR_UPDATE_GOLDEN") == "1":
        shutil.rmtree(expected_dir, ignore_errors=True)
        shutil.copytree(tmp_path / case, expected_dir)
    expected = tree(expected_dir)
    assert sorted(actual) == sorted(expected)
    diffs = [_diff(expected[n], actual[n], n) for n in sorted(actual) if actual[n] != expected[n]]
    assert not diffs, "generated output differs from the golden files (SPEAR_UPDATE_GOLDEN=1 to accept):\n" + "\n".join(diffs)


def test_generated_cpp_of_a_namespaced_plugin_compiles(tmp_path: Path) -> None:
    """Classes in a namespace, one deriving from another, with defaults spelled as inside the namespace: the
    generated C++ (outside it) names them in full. Checked by the compiler, not by reading."""
    import subprocess

    compiler = shutil.which("c++")
    if compiler is None:
        pytest.skip("no C++ compiler")
    out = tmp_path / "generated"
    result = run_codegen("generate", "namespaced_plugin", out, ["tests/codegen/cases/namespaced_plugin/input.h"],
                         extra=CASE_ARGS["namespaced_plugin"])
    assert result.returncode == 0, result.stderr
    import pybind11  # type: ignore[import-untyped]
    import sysconfig

    flags = ["-std=c++20", "-fsyntax-only", f"-I{ROOT}", f"-I{tmp_path}", "-isystem", "/usr/include/eigen3",
             "-isystem", pybind11.get_include(), "-isystem", sysconfig.get_paths()["include"]]
    for source in sorted((out / "namespaced_plugin" / "cpp").glob("*.cpp")):
        # The generated files include each other as generated/<module>/cpp/..., from the output's parent.
        compiled = subprocess.run([compiler, *flags, str(source)], capture_output=True, text=True, check=False)
        assert compiled.returncode == 0, f"{source.name}:\n{compiled.stderr[-3000:]}"


@pytest.mark.parametrize("header", sorted(p.name for p in NEGATIVE.glob("*.h")))
def test_rejected_input(header: str, tmp_path: Path) -> None:
    path = NEGATIVE / header
    expected = path.read_text().splitlines()[0].removeprefix("// expect: ")
    result = run_codegen("generate", "negative", tmp_path, [path.relative_to(ROOT).as_posix()])
    assert result.returncode == 1
    assert result.stderr.strip().splitlines()[-1] == expected
    assert not (tmp_path / "negative").exists(), "a rejected input must not leave partial outputs"


def test_output_is_byte_identical_across_runs(tmp_path: Path) -> None:
    first, second = tmp_path / "a", tmp_path / "b"
    assert run_codegen("generate", "engine", first, engine_headers(), hash_seed="0").returncode == 0
    assert run_codegen("generate", "engine", second, engine_headers(), hash_seed="12345").returncode == 0
    assert tree(first) == tree(second)


def test_committed_engine_bindings_are_current(tmp_path: Path) -> None:
    result = run_codegen("check", "engine", ROOT / "generated", engine_headers())
    assert result.returncode == 0, result.stderr + "\nregenerate with the build and commit generated/"


def test_a_moved_header_leaves_no_orphaned_output(tmp_path: Path) -> None:
    """A header moved to another folder changes its registry file's name: generate removes the old file, and
    check reports one left behind, so that a build never compiles a stale copy beside the new one."""
    header = "tests/codegen/cases/all_types/input.h"
    assert run_codegen("generate", "all_types", tmp_path, [header]).returncode == 0
    cpp = tmp_path / "all_types" / "cpp"
    orphan = cpp / "core_old_place_input.gen.cpp"
    shutil.copy(cpp / "tests_codegen_cases_all_types_input.gen.cpp", orphan)
    checked = run_codegen("check", "all_types", tmp_path, [header])
    assert checked.returncode == 1
    assert "all_types/cpp/core_old_place_input.gen.cpp" in checked.stderr
    generated = run_codegen("generate", "all_types", tmp_path, [header])
    assert generated.returncode == 0, generated.stderr
    assert "1 orphaned files removed" in generated.stdout
    assert not orphan.exists()
    assert run_codegen("check", "all_types", tmp_path, [header]).returncode == 0


def test_listed_outputs_are_the_generated_files(tmp_path: Path) -> None:
    listed = run_codegen("list-outputs", "engine", tmp_path, engine_headers())
    assert listed.returncode == 0
    assert run_codegen("generate", "engine", tmp_path, engine_headers()).returncode == 0
    produced = {str(tmp_path / name) for name in tree(tmp_path)}
    assert set(listed.stdout.split()) == produced


def test_every_generated_file_says_do_not_edit() -> None:
    for path in (ROOT / "generated").rglob("*"):
        if path.is_file() and path.suffix in (".cpp", ".h", ".py", ".pyi"):
            assert "DO NOT EDIT" in path.read_text().splitlines()[0], path


def test_ir_json_round_trips_and_records_the_facts() -> None:
    module = Module.from_json((CASES / "all_types/expected/reflection.json").read_text())
    assert Module.from_json(module.to_json()) == module
    actor = next(c for c in module.classes if c.name == "AAllTypes")
    assert actor.parent == "AActor"
    funcs = {f.name: f for f in actor.functions}
    assert [(p.name, p.is_out) for p in funcs["Split"].params] == [("Text", False), ("Head", True), ("Rest", True)]
    assert funcs["Collect"].determines_output_type == "ActorClass"
    assert funcs["Histogram"].is_static and funcs["Scale"].is_const
    assert [p.default_cpp for p in funcs["Scale"].params] == [None, "2.0", "EChannel::Red"]
    assert funcs["Normalise"].params[0].type.kind == "array" and funcs["Normalise"].params[0].type.name == "float32"
    assert funcs["Self"].not_null
    props = {p.name: p for p in actor.properties}
    assert props["Counter"].read_only and props["Speed"].setter == "SetSpeed"
    assert props["Weights"].type.kind == "dict" and props["Weights"].type.args[0].cpp == "float"
    sample = next(c for c in module.classes if c.name == "FSample")
    assert sample.kind == "struct" and [p.default_cpp for p in sample.properties][:2] == ["{1.0, 2.0, 3.0}", "EChannel::Green"]
    assert "tests/codegen/cases/all_types/input.h" in module.headers
    assert "/" not in module.headers[0][:1], "IR paths are relative to the project root"


@pytest.mark.parametrize("case, expected", [
    ("bad_parent", "tests/codegen/negative_blueprints/bad_parent/BP_Bad.json:4: error: blueprint parent "
                   "'ANoSuchActor' is not a reflected class of module 'engine'"),
    ("bad_json", "tests/codegen/negative_blueprints/bad_json/BP_Broken.json:5: error: blueprint is not valid "
                 "JSON: Expecting ',' delimiter"),
    ("bad_function_type", "tests/codegen/negative_blueprints/bad_function_type/BP_BadType.json:9: error: parameter "
                          "'Height' of blueprint function 'Fly': unknown type 'double' (bool, int, float, str, or a "
                          "reflected struct, enum or class of module 'engine')"),
    ("function_twice", "tests/codegen/negative_blueprints/function_twice/BP_Twice.json:8: error: blueprint function "
                       "'Go' is declared twice"),
    ("self_parameter", "tests/codegen/negative_blueprints/self_parameter/BP_Self.json:10: error: parameter 'self' of "
                       "blueprint function 'Go' is not a public Python identifier"),
    ("inherited_name", "tests/codegen/negative_blueprints/inherited_name/BP_Shadow.json:7: error: blueprint function "
                       "'Tags' has the name of a member of AStaticMeshActor"),
])
def test_rejected_blueprint_asset(case: str, expected: str, tmp_path: Path) -> None:
    import subprocess

    from codegen_runner import EIGEN

    result = subprocess.run(
        [sys.executable, "-m", "codegen", "generate", "--module", "engine", "--root", str(ROOT), "--out", str(tmp_path),
         "--include-dir", EIGEN, "--blueprint-dir", f"tests/codegen/negative_blueprints/{case}", *engine_headers()],
        cwd=ROOT, capture_output=True, text=True, check=False,
    )
    assert result.returncode == 1
    assert result.stderr.strip().splitlines()[-1] == expected


PLUGIN_ARGS = ["--package", "plugin_actor"]
PLUGIN_HEADER = "tests/codegen/cases/plugin_actor/input.h"


def _generate_plugin_package(tmp_path: Path) -> Path:
    """Generates the plugin case as a plugin would: its package in a directory of its own (--python-out)."""
    packages = tmp_path / "packages"
    args = [*PLUGIN_ARGS, "--python-out", str(packages / "plugin_actor")]
    result = run_codegen("generate", "plugin_actor", tmp_path / "generated", [PLUGIN_HEADER], extra=args)
    assert result.returncode == 0, result.stderr
    return packages


def test_listed_outputs_follow_python_out(tmp_path: Path) -> None:
    packages = _generate_plugin_package(tmp_path)
    args = [*PLUGIN_ARGS, "--python-out", str(packages / "plugin_actor")]
    listed = run_codegen("list-outputs", "plugin_actor", tmp_path / "generated", [PLUGIN_HEADER], extra=args)
    assert listed.returncode == 0, listed.stderr
    produced = {str(p) for p in tmp_path.rglob("*") if p.is_file()}
    assert set(listed.stdout.split()) == produced
    assert {Path(p).name for p in produced if Path(p).parent == packages / "plugin_actor"} == {
        "__init__.py", "api.py", "api.pyi", "rpc.py", "type_codes.py"}


def test_plugin_package_derives_from_the_engine_api_and_proxies(tmp_path: Path) -> None:
    import subprocess

    packages = _generate_plugin_package(tmp_path)
    # In a fresh interpreter: importing registers proxy classes, which must not leak into this process.
    script = """
import plugin_actor, plugin_actor.api as api, plugin_actor.rpc as rpc
import spear._engine.api as engine_api, spear._engine.rpc as engine_rpc
assert plugin_actor.MODULE == "plugin_actor"
assert issubclass(api.APluginActor, engine_api.AActor)
assert issubclass(api.APluginActorAsync, engine_api.AActorAsync)
assert issubclass(api.APluginActorSend, engine_api.AActorSend)
assert issubclass(rpc.APluginActor, engine_rpc.AActor) and issubclass(rpc.APluginActor, api.APluginActor)
assert issubclass(rpc.APluginChild, rpc.APluginActor) and issubclass(rpc.APluginChild, api.APluginChild)
"""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(packages), str(ROOT / "python")]))
    result = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, env=env, capture_output=True, text=True,
                            check=False)
    assert result.returncode == 0, result.stderr


def test_plugin_package_passes_mypy_strict(tmp_path: Path) -> None:
    import subprocess

    pytest.importorskip("mypy")
    packages = _generate_plugin_package(tmp_path)
    config = tmp_path / "mypy.ini"
    # Errors inside the spear package are its own tests' business (tests/typing); here only the plugin's count.
    config.write_text(f"[mypy]\nstrict = True\nmypy_path = {ROOT / 'python'}\ncache_dir = {tmp_path / 'cache'}\n\n"
                      "[mypy-spear.*]\nfollow_imports = silent\n\n"
                      "[mypy-msgpack,spear._spear_engine]\nignore_missing_imports = True\n")
    result = subprocess.run([sys.executable, "-m", "mypy", "--config-file", str(config), "plugin_actor"],
                            cwd=packages, capture_output=True, text=True, check=False)
    assert result.returncode == 0, result.stdout + result.stderr


def test_cmake_module_generates_a_plugin_from_another_project(tmp_path: Path) -> None:
    """cmake/SpearCodegen.cmake included by a project outside the spear tree, as a plugin would use it."""
    import subprocess

    cmake = shutil.which("cmake")
    if cmake is None:
        pytest.skip("cmake is not installed")
    from codegen_runner import EIGEN

    plugin = tmp_path / "plugin"
    (plugin / "include").mkdir(parents=True)
    shutil.copy(ROOT / PLUGIN_HEADER, plugin / "include/plugin_actor.h")
    (plugin / "CMakeLists.txt").write_text(f"""
cmake_minimum_required(VERSION 3.20)
project(plugin LANGUAGES NONE)
set(Python3_EXECUTABLE {sys.executable})
include({ROOT}/cmake/SpearCodegen.cmake)
spear_generate(MODULE plugin_actor ROOT ${{PROJECT_SOURCE_DIR}} OUT_DIR generated HEADERS include/plugin_actor.h
               INCLUDE_DIRS {ROOT} {EIGEN} PYTHON_OUT python/plugin_actor PACKAGE plugin_actor
               OUT_VAR outputs)
file(WRITE ${{PROJECT_BINARY_DIR}}/outputs.txt "${{outputs}}")
add_custom_target(everything ALL DEPENDS spear_codegen_plugin_actor)
""")
    build = tmp_path / "build"
    for command in ([cmake, "-S", str(plugin), "-B", str(build)], [cmake, "--build", str(build)]):
        result = subprocess.run(command, cwd=tmp_path, capture_output=True, text=True, check=False)
        assert result.returncode == 0, result.stdout + result.stderr
    listed = set((build / "outputs.txt").read_text().split(";"))
    produced = {str(p) for p in plugin.rglob("*") if p.is_file() and p.suffix != ".txt" and p.parent.name != "include"}
    assert listed == produced
    assert str(plugin / "python/plugin_actor/api.pyi") in listed
    assert str(plugin / "generated/plugin_actor/cpp/plugin_actor_bindings.gen.h") in listed
    bindings = (plugin / "generated/plugin_actor/cpp/include_plugin_actor.bindings.gen.h").read_text()
    # The engine's generated files for the engine types the plugin uses, not the engine's whole API.
    assert '#include "generated/engine/cpp/core_world_actor.bindings.gen.h"' in bindings
    assert "engine_bindings.gen.h" not in bindings
    assert '"plugin_actor.api"' in bindings
    calls = (plugin / "generated/plugin_actor/cpp/include_plugin_actor.gen.h").read_text()
    assert '#include "generated/engine/cpp/core_world_actor.gen.h"' in calls
    assert "core_sensors_camera_sensor_component" not in calls
    reflection = Module.from_json((plugin / "generated/plugin_actor/reflection.json").read_text())
    assert reflection.headers == ("include/plugin_actor.h",), "header paths are relative to ROOT"


def test_watch_regenerates_the_stubs_when_a_header_is_saved(tmp_path: Path) -> None:
    """`codegen watch` (scripts/codegen.sh watch): the stubs follow a saved header at once; a header that
    does not parse is reported with file:line and watching goes on."""
    import subprocess
    import time

    header = tmp_path / "thing.h"
    body = ('#pragma once\n#include "core/reflect/macros.h"\n#include "core/world/actor.h"\n\n'
            "/// A thing.\nSPCLASS()\nclass AThing : public AActor {\n    SP_GENERATED_BODY()\n  public:\n%s};\n")
    header.write_text(body % "")
    command = [sys.executable, "-m", "codegen", "watch", "--module", "watched", "--root", str(tmp_path),
               "--out", str(tmp_path / "out"), "--include-dir", str(ROOT), "--include-dir", "/usr/include/eigen3",
               "thing.h"]
    watcher = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    stubs = tmp_path / "out/watched/python/api.pyi"
    assert watcher.stdout is not None

    def wait_for(text: str) -> str:
        lines = []
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            line = watcher.stdout.readline()  # type: ignore[union-attr]
            lines.append(line)
            if text in line:
                return line
        raise AssertionError(f"no '{text}' from codegen watch:\n{''.join(lines)}")

    try:
        wait_for("watching 1 files")
        assert "def Twice" not in stubs.read_text()
        time.sleep(0.05)  # a new mtime even on coarse clocks
        header.write_text(body % "    /// Twice.\n    SPFUNCTION()\n    int Twice(int Value) const { return 2 * Value; }\n")
        wait_for("changed: thing.h")
        wait_for("codegen: module 'watched'")
        assert "def Twice(self, *, Value: int) -> int" in stubs.read_text()
        header.write_text(body % "    SPFUNCTION()\n    int Broken(\n")
        assert "thing.h:" in wait_for("thing.h:")
        assert watcher.poll() is None, "a header that does not parse must not stop the watcher"
    finally:
        watcher.terminate()
        watcher.wait(timeout=10)
