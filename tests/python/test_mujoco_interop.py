"""The mujoco_interop plugin (examples/mujoco_interop) on both transports: MuJoCo steps, spear's actors take
MuJoCo's poses in the same call, the spawned actors match the MJCF, errors are clear and the engine keeps
running; its example runs and type-checks against the stubs generated from the plugin's headers."""

from __future__ import annotations

import ctypes.util
import math
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import spear

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plugin_build import ROOT, build_importable_plugin, spear_build_dir  # noqa: E402
from plugin_build import whole_frame as frame  # noqa: E402

EXAMPLE = ROOT / "examples/mujoco_interop"
MJCF = EXAMPLE / "falling_shapes.xml"

if ctypes.util.find_library("mujoco") is None or not Path("/usr/include/mujoco/mujoco.h").is_file():
    pytest.skip("MuJoCo is not installed (apt-get install libmujoco-dev)", allow_module_level=True)

MESHES = {"box": "Cube", "sphere": "Sphere", "ellipsoid": "Sphere", "cylinder": "Cylinder", "plane": "Plane"}


@pytest.fixture(scope="session")
def plugin_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The directory holding the mujoco_interop package: spear's build made it when it found MuJoCo;
    otherwise it is built here out of tree, as a plugin author would."""
    built = spear_build_dir() / "python"
    if (built / "mujoco_interop" / "libmujoco_interop.so").is_file():
        if str(built) not in sys.path:
            sys.path.insert(0, str(built))
        return built
    return build_importable_plugin(EXAMPLE, tmp_path_factory)


@pytest.fixture
def api(instance: spear.Instance, plugin_dir: Path) -> Iterator[Any]:
    """The plugin's typed API, loaded into the test's instance."""
    instance.load_plugin(plugin_dir / "mujoco_interop")
    import mujoco_interop.api

    yield mujoco_interop.api


def assert_actors_show_mujoco_poses(scene: Any) -> None:
    """Every body's actor has MuJoCo's xpos and xquat (w, x, y, z; q and -q are one rotation) to 1e-9."""
    poses = scene.GetBodyPoses()
    actors = scene.GetBodyActors()
    assert len(actors) == len(poses["Positions"]) == len(poses["Quaternions"]) == scene.NumBodies
    for body, actor in enumerate(actors):
        assert actor.BodyId == body
        transform = actor.GetActorTransform()
        location = transform.Translation
        rotation = transform.Rotation
        np.testing.assert_allclose([location.X, location.Y, location.Z], poses["Positions"][body], rtol=0, atol=1e-9,
                                   err_msg=actor.BodyName)
        quat = np.array([rotation.W, rotation.X, rotation.Y, rotation.Z])
        expected = poses["Quaternions"][body]
        if np.dot(quat, expected) < 0:
            quat = -quat
        np.testing.assert_allclose(quat, expected, rtol=0, atol=1e-9, err_msg=actor.BodyName)


# -- poses --------------------------------------------------------------------------------------------------

def test_actors_take_mujocos_poses_in_the_same_call(instance: spear.Instance, api: Any) -> None:
    game = instance.get_game()
    with frame(instance):
        scene = game.spawn_actor(uclass=api.AMujocoScene, name="Mujoco")
        scene.LoadMjcf(Path=str(MJCF))
        assert_actors_show_mujoco_poses(scene)  # the initial poses
        start = scene.GetBodyPoses()["Positions"].copy()
    for _ in range(3):
        with frame(instance):
            scene.Step(NumSteps=8)
            assert_actors_show_mujoco_poses(scene)  # in the same frame block, right after the call
    with frame(instance):
        scene.Step(NumSteps=400)
        assert_actors_show_mujoco_poses(scene)
        time = scene.GetSimTime()
        end = scene.GetBodyPoses()["Positions"]
        moving = {actor.BodyName: not actor.bStaticBody for actor in scene.GetBodyActors()}
        names = scene.GetBodyNames()
    assert math.isclose(time, 424 * 0.002, rel_tol=1e-12)
    for body, name in enumerate(names):
        if moving[name]:
            assert end[body, 2] < start[body, 2] - 0.05, name  # everything that moves fell
        else:
            assert np.array_equal(end[body], start[body]), name  # the world and the ramp did not


def test_forces_push_bodies_through_xfrc_applied(instance: spear.Instance, api: Any) -> None:
    game = instance.get_game()
    with frame(instance):
        pushed = game.spawn_actor(uclass=api.AMujocoScene, name="Pushed")
        still = game.spawn_actor(uclass=api.AMujocoScene, name="Still")
        for scene in (pushed, still):
            scene.LoadMjcf(Path=str(MJCF))
        ball = pushed.GetBodyNames().index("ball")
        forces = np.zeros((pushed.NumBodies, 3))
        forces[ball] = [20.0, 0.0, 0.0]
        pushed.SetForces(Forces=forces)
        with_torques = np.zeros((still.NumBodies, 6))
        still.SetForces(Forces=with_torques)
        for scene in (pushed, still):
            scene.Step(NumSteps=100)
        assert_actors_show_mujoco_poses(pushed)
        pushed_x = pushed.GetBodyActor(BodyName="ball").GetActorLocation().X
        still_x = still.GetBodyActor(BodyName="ball").GetActorLocation().X
    # 20 N on a body of about 7 kg for 0.2 s moves it some 5 cm along +X.
    assert pushed_x - still_x > 0.03


# -- what is spawned --------------------------------------------------------------------------------------

def test_spawned_actors_and_components_match_the_mjcf(instance: spear.Instance, api: Any) -> None:
    game = instance.get_game()
    root = ET.parse(MJCF).getroot()
    worldbody = root.find("worldbody")
    assert worldbody is not None
    bodies = ["world"] + [body.attrib["name"] for body in worldbody.iter("body")]
    geoms = {"world": worldbody.findall("geom")} | {body.attrib["name"]: body.findall("geom")
                                                    for body in worldbody.iter("body")}
    materials = {m.attrib["name"]: m.attrib["rgba"] for m in root.iter("material")}
    with frame(instance):
        scene = game.spawn_actor(uclass=api.AMujocoScene, name="Mujoco")
        scene.LoadMjcf(Path=str(MJCF))
        assert scene.GetBodyNames() == bodies
        assert scene.NumBodies == len(bodies) and scene.NumGeoms == sum(len(g) for g in geoms.values())
        assert scene.ModelPath == str(MJCF)
        assert len(game.find_actors_by_class(uclass=api.AMujocoBody)) == len(bodies)
        assert len(game.find_actors_by_tag(tag="Mujoco")) == len(bodies)
        library = game.find_actor_by_class(uclass=spear.AMaterialLibrary)
        assert library is not None
        shown = 0
        for name in bodies:
            actor = scene.GetBodyActor(BodyName=name)
            assert game.find_actor_by_name(name=f"Mujoco/{name}") == actor
            assert actor.BodyName == name and actor.NumGeoms == len(geoms[name])
            assert actor.bStaticBody == (name in ("world", "ramp"))
            meshes = {c.GetName(): c for c in game.get_components_by_class(actor=actor, uclass=spear.UStaticMeshComponent)}
            for component in game.get_components_by_class(actor=actor, uclass=spear.USceneComponent):
                assert component.Mobility == (spear.EComponentMobility.Static if actor.bStaticBody
                                              else spear.EComponentMobility.Movable)
            for component in meshes.values():
                assert not component.IsSimulatingPhysics()  # MuJoCo owns the dynamics
            for geom in geoms[name]:
                kind = geom.attrib["type"]
                size = [float(s) for s in geom.attrib["size"].split()] if "size" in geom.attrib else []
                if kind == "capsule":  # a cylinder and two spheres under one scene component
                    parts = [meshes[f"{geom.attrib['name']}_{p}"] for p in ("cylinder", "cap_top", "cap_bottom")]
                    assert [p.StaticMesh for p in parts] == ["/Engine/BasicShapes/Cylinder",
                                                             "/Engine/BasicShapes/Sphere", "/Engine/BasicShapes/Sphere"]
                    assert all(p.GetAttachParent().GetName() == geom.attrib["name"] for p in parts)
                    radius, half = size
                    assert parts[0].RelativeScale3D == spear.FVector(2 * radius, 2 * radius, 2 * half)
                    assert parts[1].RelativeLocation == spear.FVector(0.0, 0.0, half)
                    assert parts[2].RelativeScale3D == spear.FVector(2 * radius, 2 * radius, 2 * radius)
                    component = parts[0]
                    shown += 3
                elif kind == "mesh":
                    component = meshes[geom.attrib["name"]]
                    assert component.StaticMesh.endswith(".obj") and Path(component.StaticMesh).is_file()
                    shown += 1
                else:
                    component = meshes[geom.attrib["name"]]
                    assert component.StaticMesh == f"/Engine/BasicShapes/{MESHES[kind]}"
                    scale = component.RelativeScale3D
                    expected = {"box": lambda: [2 * s for s in size], "ellipsoid": lambda: [2 * s for s in size],
                                "sphere": lambda: [2 * size[0]] * 3,
                                "cylinder": lambda: [2 * size[0], 2 * size[0], 2 * size[1]],
                                "plane": lambda: [2 * size[0], 2 * size[1], 1.0]}[kind]()
                    assert [scale.X, scale.Y, scale.Z] == pytest.approx(expected, abs=1e-12), geom.attrib["name"]
                    shown += 1
                rgba = geom.attrib.get("rgba") or materials[geom.attrib["material"]]
                colour = library.GetMaterial(Name=component.Materials[0]).BaseColor
                assert [colour.R, colour.G, colour.B] == pytest.approx([float(c) for c in rgba.split()[:3]])
        assert sum(len(game.get_components_by_class(actor=a, uclass=spear.UStaticMeshComponent))
                   for a in scene.GetBodyActors()) == shown
        # A geom's offset in its body is its component's relative location.
        dumbbell = scene.GetBodyActor(BodyName="dumbbell")
        left = game.get_component_by_name(actor=dumbbell, component_name="weight_left")
        assert isinstance(left, spear.USceneComponent)
        assert left.RelativeLocation == spear.FVector(-0.2, 0.0, 0.0)


def test_loading_again_replaces_the_bodies_and_clear_removes_them(instance: spear.Instance, api: Any) -> None:
    game = instance.get_game()
    with frame(instance):
        scene = game.spawn_actor(uclass=api.AMujocoScene, name="Mujoco")
        scene.LoadMjcf(Path=str(MJCF))
        first = scene.GetBodyActor(BodyName="ball")
        scene.LoadMjcfString(Xml='<mujoco><worldbody><body name="ball" pos="0 0 1"><freejoint/>'
                                 '<geom type="sphere" size="0.1"/></body></worldbody></mujoco>')
        assert not first.is_valid()
        assert scene.GetBodyNames() == ["world", "ball"] and scene.ModelPath == "<string>"
        assert len(game.find_actors_by_class(uclass=api.AMujocoBody)) == 2
        assert scene.GetBodyActor(BodyName="ball").GetActorLocation() == spear.FVector(0.0, 0.0, 1.0)
        scene.Clear()
        assert scene.NumBodies == 0 and game.find_actors_by_class(uclass=api.AMujocoBody) == []


# -- errors -------------------------------------------------------------------------------------------------

def test_bad_input_gives_clear_errors_and_the_engine_keeps_running(instance: spear.Instance, api: Any,
                                                                   tmp_path: Path) -> None:
    game = instance.get_game()
    missing = tmp_path / "missing.xml"
    broken = tmp_path / "broken.xml"
    broken.write_text("<mujoco><worldbody><geom type='sphere' size='0.1'></worldbody></mujoco>")
    with frame(instance):
        scene = game.spawn_actor(uclass=api.AMujocoScene, name="Mujoco")
        with pytest.raises(spear.InvalidStateError) as raised:
            scene.Step(NumSteps=1)
        assert str(raised.value) == "AMujocoScene.Step(): no model is loaded (call LoadMjcf first)"
        with pytest.raises(spear.NotFoundError) as raised:
            scene.LoadMjcf(Path=str(missing))
        assert str(raised.value) == f"AMujocoScene.LoadMjcf(): no MJCF file '{missing}'"
        with pytest.raises(spear.InvalidArgumentError) as raised:
            scene.LoadMjcf(Path=str(broken))
        assert str(raised.value).startswith(f"AMujocoScene.LoadMjcf(): MuJoCo cannot load '{broken}': XML parse error")
        scene.LoadMjcf(Path=str(MJCF))
        with pytest.raises(spear.InvalidArgumentError) as raised:  # MuJoCo's own message comes through
            scene.LoadMjcfString(Xml="<mujoco><worldbody><geom type='sphere' size='-1'/></worldbody></mujoco>")
        assert re.match(r"AMujocoScene\.LoadMjcfString\(\): MuJoCo cannot load '<string>': .*size", str(raised.value))
        assert scene.ModelPath == str(MJCF)  # a model that does not load leaves the loaded one
        bodies = scene.NumBodies
        for shape in [(bodies, 4), (bodies - 1, 3), (bodies * 3,)]:
            with pytest.raises(spear.InvalidArgumentError) as raised:
                scene.SetForces(Forces=np.zeros(shape))
            assert str(raised.value) == (f"AMujocoScene.SetForces(): array 'Forces' must have shape ({bodies}, 3) or "
                                         f"({bodies}, 6) (one row per body, the world first), got "
                                         f"({', '.join(map(str, shape))}{',' if len(shape) == 1 else ''})")
        with pytest.raises(spear.InvalidArgumentError) as raised:
            scene.SetForces(Forces=np.zeros((bodies, 3), dtype=np.float32))
        assert str(raised.value) == "AMujocoScene.SetForces(): argument 'Forces' must have dtype float64, got float32"
        with pytest.raises(spear.InvalidArgumentError) as raised:
            scene.Step(NumSteps=-1)
        assert str(raised.value) == "AMujocoScene.Step(): NumSteps must be >= 0, got -1"
        with pytest.raises(spear.NotFoundError) as raised:
            scene.GetBodyActor(BodyName="nope")
        assert str(raised.value) == "AMujocoScene.GetBodyActor(): the model has no body named 'nope'"
        game.destroy_actor(actor=scene.GetBodyActor(BodyName="ball"))
        with pytest.raises(spear.StaleObjectError) as raised:
            scene.Step(NumSteps=1)
        assert str(raised.value) == ("AMujocoScene.Step(): the actor of body 'ball' was destroyed (LoadMjcf again "
                                     "to respawn the bodies)")
        assert scene.GetSimTime() == 0.0  # the failed call did not step
        taken = game.spawn_actor(uclass=spear.AActor, name="Mujoco/ball")  # the name the ball's actor gets
        with pytest.raises(spear.InvalidArgumentError) as raised:
            scene.LoadMjcf(Path=str(MJCF))
        assert str(raised.value) == "UWorld.spawn_actor(): name 'Mujoco/ball' is already used in this world"
        assert scene.NumBodies == 0 and game.find_actors_by_class(uclass=api.AMujocoBody) == []  # nothing half-made
        game.destroy_actor(actor=taken)
        scene.LoadMjcf(Path=str(MJCF))
        scene.Step(NumSteps=10)
        assert_actors_show_mujoco_poses(scene)
    with frame(instance):
        assert game.get_frame_count() >= 1 and scene.GetSimTime() == pytest.approx(0.02)


# -- the server, the example and its types -------------------------------------------------------------------

def test_spear_server_loads_the_plugin_by_name(plugin_dir: Path, tmp_path: Path) -> None:
    from spear._rpc_client import find_server_binary

    socket_path = tmp_path / "spear.sock"
    env = {**os.environ, "SPEAR_PLUGIN_PATH": str(plugin_dir)}
    server = subprocess.Popen([str(find_server_binary()), "--socket", str(socket_path), "--plugin", "mujoco_interop"],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        assert server.stdout is not None and "listening on" in server.stdout.readline()
        instance = spear.Instance(server=f"unix:{socket_path}")
        instance.load_plugin("mujoco_interop")
        from mujoco_interop.api import AMujocoScene

        with frame(instance):
            scene = instance.get_game().spawn_actor(uclass=AMujocoScene)
            scene.LoadMjcf(Path=str(MJCF))
            scene.Step(NumSteps=5)
            assert_actors_show_mujoco_poses(scene)
        instance.close()
    finally:
        server.terminate()
        server.wait(timeout=10)


@pytest.mark.parametrize("flags", [[], ["--server", "launch"]])
def test_example_runs_as_documented(plugin_dir: Path, flags: list[str], tmp_path: Path) -> None:
    from PIL import Image

    out = tmp_path / "mujoco_interop.png"
    result = subprocess.run([sys.executable, str(EXAMPLE / "mujoco_interop.py"), "--seconds", "0.5", "--out", str(out),
                             "--width", "320", "--height", "240", *flags], capture_output=True, text=True, timeout=300,
                            env={**os.environ, "PYTHONPATH": str(ROOT / "python"), "SPEAR_PLUGIN_DIR": str(plugin_dir)})
    assert result.returncode == 0, result.stdout + result.stderr
    assert "loaded falling_shapes.xml: 9 bodies (7 moving), 11 geoms; 8 MuJoCo steps per frame" in result.stdout
    assert "t = 0.480 s: heights" in result.stdout
    assert f"wrote {out} (320x240)" in result.stdout
    image = np.asarray(Image.open(out))
    assert image.shape == (240, 320, 3) and image.std() > 10  # a picture, not a blank


def test_example_type_checks_against_stubs_from_the_headers(tmp_path: Path) -> None:
    sys.path.insert(0, str(ROOT / "tests/typing"))
    import pyright_runner
    from mypy_runner import mypy

    headers = ["mujoco_body.h", "mujoco_scene.h"]
    generated = subprocess.run(
        [sys.executable, "-m", "codegen", "generate", "--module", "mujoco_interop", "--package", "mujoco_interop",
         "--root", str(EXAMPLE), "--out", str(tmp_path / "generated"), "--python-out",
         str(tmp_path / "python/mujoco_interop"), "--include-dir", str(ROOT), "--include-dir", "/usr/include/eigen3",
         *headers], cwd=ROOT, capture_output=True, text=True, check=False)
    assert generated.returncode == 0, generated.stderr
    example = "examples/mujoco_interop/mujoco_interop.py"
    # A cache of its own: mypy 1.0 would carry the plugin's stubs over into spear's own check of examples/.
    result = mypy("--cache-dir", str(tmp_path / "mypy_cache"), example, extra_path=tmp_path / "python")
    assert result.returncode == 0, result.stdout + result.stderr
    _, report = pyright_runner.pyright(example, extra_path=tmp_path / "python")
    assert report["summary"]["errorCount"] == 0, "\n".join(pyright_runner.errors(report))
