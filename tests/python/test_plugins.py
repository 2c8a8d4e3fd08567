"""Plugins and SpFuncs end to end: the example plugin (examples/plugin) built out of tree against the
exported CMake package, loaded, used and unloaded on both transports."""

from __future__ import annotations

import logging
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import spear

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plugin_build import EXAMPLE, ROOT, build, build_importable_plugin, configure  # noqa: E402
from plugin_build import whole_frame as frame  # noqa: E402


@pytest.fixture(scope="session")
def plugin_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The example plugin's package directory (<build>/python), built once for the session."""
    return build_importable_plugin(EXAMPLE, tmp_path_factory)


@pytest.fixture
def plugin(instance: spear.Instance, plugin_dir: Path) -> Iterator[Any]:
    """The example plugin's typed API, loaded into the test's instance."""
    package = instance.load_plugin(plugin_dir / "my_plugin")
    import my_plugin.api

    assert package.MODULE == "my_plugin"
    yield my_plugin.api


# -- Fig. 8 ----------------------------------------------------------------------------------------

def test_fig8_python_side_runs_unchanged(instance: spear.Instance, plugin: Any,
                                        caplog: pytest.LogCaptureFixture) -> None:
    caplog.set_level(logging.INFO, logger="spear")
    game = instance.get_game()
    with frame(instance):
        # The figure's Python code, verbatim:
        my_actor = game.spawn_actor(uclass="AMyActor")
        my_actor.Initialize()

        # returns [4.0, 5.0, 6.0] as a numpy array named "output"
        return_values = my_actor.my_sp_func(arrays={"input": np.array([1.0, 2.0, 3.0], dtype=np.float64)})
        output = return_values["arrays"]["output"]

        my_actor.Terminate()
        game.destroy_actor(actor=my_actor)

    assert output.dtype == np.float64 and output.tolist() == [4.0, 5.0, 6.0]
    assert return_values == {"arrays": {"output": output}, "unreal_objs": {}, "info": ""}
    # SP_LOG's line is a record of the "spear" logger with the plugin header's file and line, on both
    # transports (over RPC, forwarded from the server's stderr by a thread: it may arrive a moment later).
    deadline = time.monotonic() + 10.0
    while not (logged := [r for r in caplog.records if r.getMessage() == "Input is [1 , 2 , 3]"]):
        assert time.monotonic() < deadline, [r.getMessage() for r in caplog.records]
        time.sleep(0.01)
    assert logged[0].filename == "my_actor.h" and logged[0].lineno > 0


def test_sp_funcs_are_listed_registered_and_unregistered(instance: spear.Instance, plugin: Any) -> None:
    game = instance.get_game()
    with frame(instance):
        my_actor = game.spawn_actor(uclass=plugin.AMyActor)
        assert my_actor.get_sp_func_names() == []
        assert not hasattr(my_actor, "my_sp_func")
        my_actor.Initialize()
        assert my_actor.get_sp_func_names() == ["my_sp_func"]
        assert my_actor.SpFuncComponent.GetFuncNames() == ["my_sp_func"]  # the component answers too
        assert my_actor.SpFuncComponent.get_sp_func_names() == ["my_sp_func"]
        with pytest.raises(spear.NotFoundError, match=re.escape(
                "AMyActor.my_sp_fun(): AMyActor 'MyActor_0' has no SpFunc named 'my_sp_fun' (it has 'my_sp_func')")):
            my_actor.call_sp_func("my_sp_fun", arrays={"input": np.zeros(3)})
        with pytest.raises(AttributeError, match="has no attribute or SpFunc 'my_sp_fun'"):
            my_actor.my_sp_fun(arrays={})
        my_actor.Terminate()
        with pytest.raises(spear.NotFoundError, match=re.escape("(it has none)")):
            my_actor.call_sp_func("my_sp_func")


def test_bad_sp_func_arguments_name_the_function_and_array(instance: spear.Instance, plugin: Any) -> None:
    game = instance.get_game()
    with frame(instance):
        my_actor = game.spawn_actor(uclass=plugin.AMyActor)
        my_actor.Initialize()
        cases = [
            ({"input": np.zeros(3, dtype=np.float32)}, spear.InvalidArgumentError,
             "AMyActor.my_sp_func(): array 'input' must have dtype float64, got float32"),
            ({"inptu": np.zeros(3)}, spear.InvalidArgumentError,
             "AMyActor.my_sp_func(): array 'input' was not passed (got 'inptu')"),
            ({"input": [1.0, 2.0, 3.0]}, spear.InvalidArgumentError,
             "AMyActor.my_sp_func(): arrays['input'] must be a numpy array, got list"),
        ]
        for arrays, error, message in cases:
            with pytest.raises(error) as raised:
                my_actor.call_sp_func("my_sp_func", arrays=arrays)
            assert str(raised.value) == message
        with pytest.raises(spear.InvalidArgumentError, match=re.escape("unreal_objs['actor'] cannot be sent")):
            my_actor.call_sp_func("my_sp_func", arrays={"input": np.zeros(3)}, unreal_objs={"actor": object()})
        # The engine kept running, and the SpFunc still works.
        result = my_actor.call_sp_func("my_sp_func", arrays={"input": np.ones(3)})
        assert result["arrays"]["output"].tolist() == [4.0, 5.0, 6.0]


def test_sp_funcs_follow_the_frame_rule(instance: spear.Instance, plugin: Any) -> None:
    game = instance.get_game()
    with frame(instance):
        my_actor = game.spawn_actor(uclass=plugin.AMyActor)
        my_actor.Initialize()
    with pytest.raises(spear.InvalidStateError, match=r"^AMyActor\.my_sp_func\(\): called outside a frame"):
        my_actor.call_sp_func("my_sp_func", arrays={"input": np.zeros(3)})
    with pytest.raises(spear.InvalidStateError, match=r"^AMyActor\.get_sp_func_names\(\): called outside a frame"):
        my_actor.get_sp_func_names()
    # The attribute form fails as attribute lookups must, saying why.
    with pytest.raises(AttributeError, match=r"its SpFuncs cannot be listed now: AMyActor\.my_sp_func\(\): called "
                                             "outside a frame"):
        my_actor.my_sp_func(arrays={"input": np.zeros(3)})
    assert not hasattr(my_actor, "my_sp_func")


def test_large_arrays_objects_and_info_round_trip(instance: spear.Instance, plugin: Any) -> None:
    game = instance.get_game()
    image = np.random.default_rng(3).integers(0, 256, size=(1080, 1920, 4), dtype=np.uint8)
    with frame(instance):
        tools = game.spawn_actor(uclass=plugin.AArrayTools)
        echoed = tools.echo(arrays={"image": image, "small": np.arange(5, dtype=np.int16)},
                            unreal_objs={"pose": spear.FVector(1.0, 2.0, 3.0), "names": ["a", "b"], "n": 7},
                            info="hello")
        inverted = tools.call_sp_func("invert", arrays={"image": image})
        calls = tools.CallCount
    assert np.array_equal(echoed["arrays"]["image"], image)
    assert echoed["arrays"]["small"].dtype == np.int16 and echoed["arrays"]["small"].tolist() == [0, 1, 2, 3, 4]
    assert echoed["unreal_objs"] == {"pose": {"X": 1.0, "Y": 2.0, "Z": 3.0}, "names": ["a", "b"], "n": 7}
    assert echoed["info"] == "hello"
    assert inverted["arrays"]["image"].shape == (1080, 1920, 4)
    assert np.array_equal(inverted["arrays"]["image"], 255 - image)
    assert inverted["info"] == "inverted (1080, 1920, 4)"
    assert calls == 2


def test_objects_cross_as_json_and_come_back_as_structs_in_cpp(instance: spear.Instance, plugin: Any) -> None:
    game = instance.get_game()
    points = np.array([[1.0, 2.0, 3.0], [3.0, 2.0, 1.0]])
    with frame(instance):
        tools = game.spawn_actor(uclass=plugin.AArrayTools)
        result = tools.call_sp_func("center_points", arrays={"points": points},
                                    unreal_objs={"origin": spear.FVector(1.0, 1.0, 1.0)})
        with pytest.raises(spear.InvalidArgumentError) as raised:
            tools.call_sp_func("center_points", arrays={"points": points}, unreal_objs={"origin": {"X": "far"}})
        assert str(raised.value) == "AArrayTools.center_points(): object 'origin': FVector.X must be a float, got str 'far'"
        with pytest.raises(spear.InvalidArgumentError) as raised:
            tools.call_sp_func("center_points", arrays={"points": points})
        assert str(raised.value) == "AArrayTools.center_points(): object 'origin' was not passed (got no objects)"
    assert np.array_equal(result["arrays"]["points"], points - 1.0)
    assert result["unreal_objs"] == {"centroid": {"X": 1.0, "Y": 1.0, "Z": 1.0}}


def test_empty_arrays_keep_their_dtype_and_shape(instance: spear.Instance, plugin: Any) -> None:
    game = instance.get_game()
    with frame(instance):
        points_filter = game.spawn_actor(uclass=plugin.APointFilter)
        none_inside = points_filter.Filter(Points=np.full((4, 3), 9.0, dtype=np.float32), Center=spear.FVector(),
                                           Radius=1.0)
        tools = game.spawn_actor(uclass=plugin.AArrayTools)
        centered = tools.call_sp_func("center_points", arrays={"points": np.zeros((0, 3))},
                                      unreal_objs={"origin": spear.FVector()})
    assert none_inside["Points"].shape == (0, 3) and none_inside["Points"].dtype == np.float32
    assert none_inside["Indices"].shape == (0,) and none_inside["Indices"].dtype == np.int64
    assert centered["arrays"]["points"].shape == (0, 3)


def test_arrays_cross_in_any_byte_order_layout_or_writability(instance: spear.Instance, plugin: Any) -> None:
    game = instance.get_game()
    points = np.arange(12, dtype=np.float64).reshape(4, 3)
    read_only = points.copy()
    read_only.flags.writeable = False
    variants = {"big-endian": points.astype(">f8"), "transposed": np.ascontiguousarray(points.T).T,
                "read-only": read_only}
    with frame(instance):
        tools = game.spawn_actor(uclass=plugin.AArrayTools)
        results = {name: tools.call_sp_func("center_points", arrays={"points": array},
                                            unreal_objs={"origin": spear.FVector(1.0, 1.0, 1.0)})
                   for name, array in variants.items()}
        with pytest.raises(spear.InvalidArgumentError) as raised:
            tools.call_sp_func("echo", arrays={"z": np.zeros(3, dtype=np.complex128)})
    for name, result in results.items():
        assert np.array_equal(result["arrays"]["points"], points - 1.0), name
    assert str(raised.value) == ("AArrayTools.echo(): arrays['z'] has dtype complex128, which cannot cross "
                                 "(use bool, an integer or a float dtype)")


def test_arrays_an_sp_func_keeps_are_never_overwritten(instance: spear.Instance, plugin: Any) -> None:
    game = instance.get_game()
    kept = np.random.default_rng(5).integers(0, 256, size=(512, 512, 4), dtype=np.uint8)  # 1 MiB
    with frame(instance):
        tools = game.spawn_actor(uclass=plugin.AArrayTools)
        tools.call_sp_func("echo", arrays={"image": np.zeros_like(kept)})  # over RPC: makes reusable buffers
        tools.call_sp_func("store", arrays={"image": kept.copy()})  # ... one of which the engine now keeps
        for i in range(4):  # arrays of the same size travel afterwards, in the same shared memory if free
            other = np.full_like(kept, i)
            assert np.array_equal(tools.call_sp_func("echo", arrays={"image": other})["arrays"]["image"], other)
        recalled = tools.call_sp_func("recall")["arrays"]["image"]
    assert np.array_equal(recalled, kept)


def test_sp_func_calls_can_be_asynchronous(instance: spear.Instance, plugin: Any) -> None:
    game = instance.get_game()
    with frame(instance):
        tools = game.spawn_actor(uclass=plugin.AArrayTools)
        futures = [tools.call_async.echo(arrays={"x": np.full(4, i)}) for i in range(3)]
        results = [f.get()["arrays"]["x"].tolist() for f in futures]
    assert results == [[0] * 4, [1] * 4, [2] * 4]


# -- typed SPFUNCTIONs -----------------------------------------------------------------------------

def test_typed_spfunction_returns_typed_arrays(instance: spear.Instance, plugin: Any) -> None:
    game = instance.get_game()
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 0.2, 0], [3, 3, 3]], dtype=np.float32)
    with frame(instance):
        points_filter = game.spawn_actor(uclass=plugin.APointFilter)
        result = points_filter.Filter(Points=points, Center=spear.FVector(0.0, 0.0, 0.0), Radius=0.5)
        seen = points_filter.PointsSeen
    assert result["Indices"].dtype == np.int64 and result["Indices"].tolist() == [0, 2]
    assert result["Points"].dtype == np.float32 and result["Points"].shape == (2, 3)
    assert np.array_equal(result["Points"], points[[0, 2]])
    assert seen == 4


def test_typed_spfunction_rejects_wrong_dtype_and_shape(instance: spear.Instance, plugin: Any) -> None:
    game = instance.get_game()
    with frame(instance):
        points_filter = game.spawn_actor(uclass=plugin.APointFilter)
        with pytest.raises(spear.InvalidArgumentError) as raised:
            points_filter.Filter(Points=np.zeros((4, 3)), Center=spear.FVector(), Radius=1.0)
        assert str(raised.value) == "APointFilter.Filter(): argument 'Points' must have dtype float32, got float64"
        with pytest.raises(spear.InvalidArgumentError) as raised:
            points_filter.Filter(Points=np.zeros((3, 4), dtype=np.float32), Center=spear.FVector(), Radius=1.0)
        assert str(raised.value) == "APointFilter.Filter(): array 'Points' must have shape (*, 3), got (3, 4)"
        assert points_filter.PointsSeen == 0


# -- plugin classes in the engine ------------------------------------------------------------------

def test_plugin_classes_spawn_query_and_check_like_engine_classes(instance: spear.Instance, plugin: Any) -> None:
    game = instance.get_game()
    with frame(instance):
        mine = game.spawn_actor(uclass=plugin.AMyActor, name="Mine")
        other = game.spawn_actor(uclass=spear.AStaticMeshActor)
        assert isinstance(mine, plugin.AMyActor) and isinstance(mine, spear.AActor)
        assert game.find_actors_by_class(uclass=plugin.AMyActor) == [mine]
        assert set(game.find_actors_by_class(uclass=spear.AActor)) == {mine, other}
        assert game.find_actor_by_name(name="Mine") == mine
        component = mine.SpFuncComponent
        assert isinstance(component, spear.USpFuncComponent) and component.GetOwner() == mine


def test_scene_files_hold_plugin_actors(instance: spear.Instance, plugin: Any, tmp_path: Path) -> None:
    game = instance.get_game()
    path = tmp_path / "scene.json"
    with frame(instance):
        points_filter = game.spawn_actor(uclass=plugin.APointFilter, name="Filter")
        points_filter.Tags = ["plugin"]
        game.save_scene(path=str(path))
        game.destroy_actor(actor=points_filter)
        game.load_scene(path=str(path))
        loaded = game.find_actor_by_name(name="Filter")
        assert isinstance(loaded, plugin.APointFilter)
        assert loaded.Tags == ["plugin"]
    assert "APointFilter" in path.read_text()


def test_unload_is_refused_while_objects_live_then_classes_go_and_come_back(instance: spear.Instance,
                                                                          plugin_dir: Path) -> None:
    instance.load_plugin(plugin_dir / "my_plugin")
    game = instance.get_game()
    with frame(instance):
        actor = game.spawn_actor(uclass="AMyActor", name="Keep")
    with pytest.raises(spear.InvalidStateError, match=re.escape(
            "unload_plugin('my_plugin'): 1 object(s) of its classes are alive (AMyActor 'Keep'); destroy them first")):
        instance.unload_plugin("my_plugin")
    with frame(instance):
        game.destroy_actor(actor=actor)
    instance.unload_plugin("my_plugin")
    with frame(instance):
        with pytest.raises(spear.NotFoundError, match="class 'AMyActor' is not registered"):
            game.spawn_actor(uclass="AMyActor")
    with pytest.raises(spear.NotFoundError, match="no plugin named 'my_plugin' is loaded"):
        instance.unload_plugin("my_plugin")
    instance.load_plugin("my_plugin")  # by name, now that its directory is on sys.path
    with frame(instance):
        assert game.spawn_actor(uclass="AMyActor").GetName() == "MyActor_0"


def test_unload_takes_default_objects_and_blueprints_of_its_classes(instance: spear.Instance, plugin_dir: Path,
                                                                   tmp_path: Path) -> None:
    instance.load_plugin(plugin_dir / "my_plugin")
    game = instance.get_game()
    blueprint = tmp_path / "BP_MyActor.json"
    blueprint.write_text('{"format": "spear.blueprint", "version": 1, "parent": "AMyActor", "properties": '
                         '{"Tags": ["from a blueprint"]}}')
    with frame(instance):
        default = game.get_default_object(uclass="AMyActor")
        uclass = game.load_class(uclass=spear.AActor, name=str(blueprint))
        spawned = game.spawn_actor(uclass=uclass)
        assert spawned.Tags == ["from a blueprint"] and spawned.GetClassName() == "BP_MyActor"
        game.destroy_actor(actor=spawned)
    instance.unload_plugin("my_plugin")  # the world's default object goes with the plugin
    with frame(instance):
        assert not default.is_valid()
        with pytest.raises(spear.InvalidArgumentError, match="'parent': class 'AMyActor' is not registered"):
            game.load_class(uclass=spear.AActor, name=str(blueprint))
    instance.load_plugin(plugin_dir / "my_plugin")
    with frame(instance):
        assert game.spawn_actor(uclass=game.load_class(uclass=spear.AActor, name=str(blueprint))).is_valid()


def test_loading_something_that_is_not_a_plugin_fails_clearly(instance: spear.Instance, tmp_path: Path) -> None:
    with pytest.raises(spear.NotFoundError, match="cannot import plugin package 'no_such_plugin'"):
        instance.load_plugin("no_such_plugin")
    with pytest.raises(spear.NotFoundError, match="is not a plugin package"):
        instance.load_plugin(tmp_path)
    (tmp_path / "fake").mkdir()
    (tmp_path / "fake" / "__init__.py").write_text("")
    with pytest.raises(spear.InvalidArgumentError, match="'fake' is not a spear plugin package"):
        instance.load_plugin(tmp_path / "fake")


# -- the server, stale stubs, and the example ------------------------------------------------------

def test_spear_server_loads_plugins_named_on_its_command_line(plugin_dir: Path, tmp_path: Path) -> None:
    from spear._rpc_client import find_server_binary

    socket_path = tmp_path / "spear.sock"
    library = plugin_dir / "my_plugin" / "libmy_plugin.so"
    server = subprocess.Popen([str(find_server_binary()), "--socket", str(socket_path), "--plugin", str(library)],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert server.stdout is not None and "listening on" in server.stdout.readline()
        instance = spear.Instance(server=f"unix:{socket_path}")
        with frame(instance):
            # The class exists before the client loads anything; loading then only brings the proxies.
            assert instance.call_function(uobject=instance.get_game(), function="get_actor_count") == 0
            actor = instance.get_game().spawn_actor(uclass="AMyActor")
            assert actor.is_valid()
        instance.load_plugin("my_plugin")
        instance.close()
    finally:
        server.terminate()
        server.wait(timeout=10)
    bad = subprocess.run([str(find_server_binary()), "--socket", str(tmp_path / "b.sock"), "--plugin",
                          str(ROOT / "python/spear/lib/libspear_core.so")], capture_output=True, text=True, timeout=30)
    assert bad.returncode == 1
    assert "InvalidArgumentError: load_plugin():" in bad.stderr and "is not a spear plugin" in bad.stderr


def test_spear_server_finds_plugins_by_name_on_its_search_path(plugin_dir: Path, tmp_path: Path) -> None:
    from spear._rpc_client import find_server_binary

    socket_path = tmp_path / "spear.sock"
    env = {**os.environ, "SPEAR_PLUGIN_PATH": f"{tmp_path}:{plugin_dir}"}
    server = subprocess.Popen([str(find_server_binary()), "--socket", str(socket_path), "--plugin", "my_plugin"],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        assert server.stdout is not None and "listening on" in server.stdout.readline()
        instance = spear.Instance(server=f"unix:{socket_path}")
        with frame(instance):
            assert instance.get_game().spawn_actor(uclass="APointFilter").is_valid()
        instance.close()
    finally:
        server.terminate()
        server.wait(timeout=10)
    missing = subprocess.run([str(find_server_binary()), "--socket", str(tmp_path / "m.sock"), "--plugin", "nope"],
                             capture_output=True, text=True, timeout=30, env=env)
    assert missing.returncode == 1
    assert f"NotFoundError: load_plugin(): no plugin named 'nope' in SPEAR_PLUGIN_PATH ('{tmp_path}:{plugin_dir}')" \
        in missing.stderr


@pytest.mark.parametrize("transport", ["inprocess", "rpc"])
def test_stubs_from_other_headers_are_refused(plugin_dir: Path, tmp_path: Path, transport: str) -> None:
    stale = tmp_path / "my_plugin"
    shutil.copytree(plugin_dir / "my_plugin", stale)
    init = stale / "__init__.py"
    init.write_text(re.sub(r'API_HASH = "\w+"', 'API_HASH = "0123456789abcdef"', init.read_text()))
    server = "None" if transport == "inprocess" else "'launch'"
    code = ("import spear\n"
            f"instance = spear.Instance(server={server})\n"
            "try:\n"
            f"    instance.load_plugin({str(stale)!r})\n"
            "except spear.InvalidStateError as error:\n"
            "    print(error)\n"
            "instance.close()\n")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                            env={**os.environ, "PYTHONPATH": str(ROOT / "python")})
    assert result.returncode == 0, result.stderr
    assert "was built from other headers" in result.stdout and "rebuild the plugin" in result.stdout


@pytest.mark.parametrize("transport", ["inprocess", "rpc"])
def test_a_plugin_built_against_another_engine_api_is_refused(plugin_dir: Path, tmp_path: Path,
                                                              transport: str) -> None:
    from spear._engine import API_HASH as engine_hash

    # As if compiled against another engine: the engine API hash the library recorded is not this engine's.
    old = tmp_path / "my_plugin"
    shutil.copytree(plugin_dir / "my_plugin", old)
    library = old / "libmy_plugin.so"
    data = library.read_bytes()
    assert engine_hash.encode() in data
    library.write_bytes(data.replace(engine_hash.encode(), b"0123456789abcdef"))
    server = "None" if transport == "inprocess" else "'launch'"
    code = ("import spear\n"
            f"instance = spear.Instance(server={server})\n"
            "try:\n"
            f"    instance.load_plugin({str(old)!r})\n"
            "except spear.InvalidStateError as error:\n"
            "    print(error)\n"
            "instance.close()\n")
    # The bindings module finds its library through a run path into the original build; the copy goes first.
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                            env={**os.environ, "PYTHONPATH": str(ROOT / "python"), "LD_LIBRARY_PATH": str(old)})
    assert result.returncode == 0, result.stderr
    assert (f"was built against another engine API (0123456789abcdef) than this engine's ({engine_hash}); "
            "rebuild the plugin against this spear") in result.stdout


@pytest.mark.parametrize("flags", [[], ["--rpc"]])
def test_example_runs_as_documented(plugin_dir: Path, flags: list[str]) -> None:
    result = subprocess.run([sys.executable, str(EXAMPLE / "use_plugin.py"), *flags], capture_output=True, text=True,
                            timeout=300, env={**os.environ, "PYTHONPATH": str(ROOT / "python"),
                                              "SPEAR_PLUGIN_DIR": str(plugin_dir)})
    assert result.returncode == 0, result.stdout + result.stderr
    assert "my_sp_func: [4. 5. 6.]" in result.stdout
    assert "invert: inverted (1080, 1920, 4)" in result.stdout
    assert "unloaded plugin 'my_plugin'" in result.stdout


def test_a_changed_header_regenerates_the_stubs_on_rebuild(tmp_path: Path) -> None:
    source = tmp_path / "src"
    shutil.copytree(EXAMPLE, source, ignore=shutil.ignore_patterns("__pycache__"))
    build_dir = tmp_path / "build"
    configure(source, build_dir)
    build(build_dir)
    stub = build_dir / "python/my_plugin/api.pyi"
    assert "Gain" not in stub.read_text()
    assert "codegen" not in build(build_dir), "a build with no header change must not run the generator"

    time.sleep(1.1)  # a new mtime, whatever the file system's resolution
    header = source / "point_filter.h"
    header.write_text(header.read_text().replace(
        "    int64_t PointsSeen = 0;\n",
        "    int64_t PointsSeen = 0;\n\n    /// Scales the points it returns.\n    UPROPERTY(EditAnywhere)\n    float Gain = 1.0f;\n"))
    output = build(build_dir)
    assert "spear codegen: module my_plugin" in output
    assert "def Gain(self) -> float:" in stub.read_text()
    # The rebuilt library has the property too (in a fresh process: this one has the session's plugin).
    code = ("import sys, spear\n"
            f"sys.path.insert(0, {str(build_dir / 'python')!r})\n"
            "instance = spear.Instance()\n"
            "instance.load_plugin('my_plugin')\n"
            "with instance.begin_frame():\n"
            "    f = instance.get_game().spawn_actor(uclass='APointFilter')\n"
            "    f.Gain = 2.5\n"
            "    print('Gain', f.Gain)\n"
            "with instance.end_frame():\n"
            "    pass\n")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                            env={**os.environ, "PYTHONPATH": str(ROOT / "python")}, cwd=tempfile.gettempdir())
    assert result.returncode == 0, result.stderr
    assert "Gain 2.5" in result.stdout
