"""Long engine work reports progress: a terminal bar while it runs, an INFO record of the "spear" logger at
its end, on both transports (core/base/progress.h, spear/_progress.py). Work done within half a second says
nothing."""

from __future__ import annotations

import logging
import os
import pty
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

import spear


def _big_mesh(path: Path, n: int = 500) -> Path:
    """An OBJ grid of n x n quads (2 n^2 triangles): importing it takes the importer about a second."""
    with path.open("w") as out:
        out.writelines(f"v {x} {y} {(x * y) % 7 * 0.01}\n" for y in range(n + 1) for x in range(n + 1))
        for y in range(n):
            for x in range(n):
                a = y * (n + 1) + x + 1
                out.write(f"f {a} {a + 1} {a + n + 2}\nf {a} {a + n + 2} {a + n + 1}\n")
    return path


@pytest.fixture(scope="module")
def big_mesh(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return _big_mesh(tmp_path_factory.mktemp("progress") / "grid.obj")


def _import(instance: spear.Instance, mesh: Path) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor)
        actor.StaticMeshComponent.SetStaticMesh(NewMesh=str(mesh))
    with instance.end_frame():
        pass


def test_long_work_ends_with_a_record(make_instance: Callable[..., spear.Instance], big_mesh: Path,
                                      caplog: pytest.LogCaptureFixture) -> None:
    caplog.set_level(logging.INFO, logger="spear")
    instance = make_instance()
    _import(instance, big_mesh)
    instance.close()  # over RPC, the server's last lines are forwarded before close() returns
    done = [r.getMessage() for r in caplog.records if r.getMessage().startswith("importMesh(): grid.obj: done in")]
    assert len(done) == 1, [r.getMessage() for r in caplog.records]


def test_short_work_says_nothing(make_instance: Callable[..., spear.Instance], tmp_path: Path,
                                 caplog: pytest.LogCaptureFixture) -> None:
    caplog.set_level(logging.INFO, logger="spear")
    instance = make_instance()
    _import(instance, _big_mesh(tmp_path / "small.obj", n=4))
    instance.close()
    assert not [r for r in caplog.records if "small.obj" in r.getMessage()]


def test_a_terminal_shows_a_bar(big_mesh: Path) -> None:
    # stderr is a terminal (a pseudo-terminal here): the import draws a tqdm bar, then logs its end.
    script = ("import sys, spear\nsys.path.insert(0, {tests!r})\nfrom test_progress import _import\n"
              "instance = spear.Instance()\n_import(instance, __import__('pathlib').Path({mesh!r}))\n"
              "instance.close()\n").format(tests=str(Path(__file__).parent), mesh=str(big_mesh))
    controller, terminal = pty.openpty()
    process = subprocess.Popen([sys.executable, "-c", script], stderr=terminal, stdout=subprocess.DEVNULL)
    os.close(terminal)
    output = b""
    while True:
        try:
            chunk = os.read(controller, 65536)
        except OSError:  # the terminal closed: the process has ended
            break
        if not chunk:
            break
        output += chunk
    os.close(controller)
    assert process.wait(120) == 0, output.decode(errors="replace")
    text = output.decode(errors="replace")
    assert "importMesh(): grid.obj:" in text and "%|" in text, text  # the bar
    assert "[spear] importMesh(): grid.obj: done in" in text


def test_a_long_path_traced_frame_ends_with_a_record(make_instance: Callable[..., spear.Instance],
                                                     caplog: pytest.LogCaptureFixture) -> None:
    # A path-traced camera's frame is long work too (here a second or two of samples on two cores).
    caplog.set_level(logging.INFO, logger="spear")
    instance = make_instance()
    game = instance.get_game()
    with instance.begin_frame():
        sky = game.spawn_actor(uclass=spear.ASkyLight)
        sky.SkyLightComponent.Intensity = 1.0
        ball = game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(X=3.0))
        ball.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Sphere")
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor
        camera.Width, camera.Height, camera.FOV = 160, 120, 20.0
        camera.Renderer = spear.ECameraRenderer.PathTraced
        camera.SamplesPerPixel = 256
    with instance.end_frame():
        pass
    instance.close()
    done = [r.getMessage() for r in caplog.records
            if r.getMessage().startswith("path tracing 160x120, 256 samples per pixel: done in")]
    assert len(done) == 1, [r.getMessage() for r in caplog.records]


def test_a_large_procedural_generation_ends_with_a_record(make_instance: Callable[..., spear.Instance],
                                                          caplog: pytest.LogCaptureFixture) -> None:
    # Spawning thousands of scattered actors (each grounded by a physics raycast) is long work too.
    caplog.set_level(logging.INFO, logger="spear")
    instance = make_instance()
    game = instance.get_game()
    with instance.begin_frame():
        floor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Floor")
        floor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        floor.SetActorScale3D(NewScale3D=spear.FVector(X=200.0, Y=200.0, Z=1.0))
        volume = game.spawn_actor(uclass=spear.APCGVolume, name="Forest", location=spear.FVector(Z=2.0))
        volume.BoxComponent.SetBoxExtent(InBoxExtent=spear.FVector(X=90.0, Y=90.0, Z=5.0))
        pcg = volume.PCGComponent
        pcg.Spacing, pcg.MaxCount = 1.0, 15000
        pcg.Generate()
        count = len(pcg.GetGeneratedActors())
    with instance.end_frame():
        pass
    instance.close()
    done = [r.getMessage() for r in caplog.records if f"spawning {count} actors: done in" in r.getMessage()]
    assert len(done) == 1, [r.getMessage() for r in caplog.records]
