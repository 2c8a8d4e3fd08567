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
