"""Engine log lines reach Python's logging as records of the "spear" logger, with the C++ file and line,
on both transports (in-process through the engine's log sink, over RPC from the launched server's stderr,
which is read to its end so a talkative server never blocks on a full pipe)."""

from __future__ import annotations

import logging
import subprocess
import sys
from collections.abc import Callable

import pytest

import spear


def _too_many_shadowed_lights(instance: spear.Instance) -> None:
    """A camera's first frame of a cube under five shadow-casting spot lights: the renderer says the fifth
    has no shadows (it has four shadow maps)."""
    game = instance.get_game()
    with instance.begin_frame():
        cube = game.spawn_actor(uclass=spear.AStaticMeshActor)
        cube.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        for i in range(5):
            light = game.spawn_actor(uclass=spear.ASpotLight, location=spear.FVector(X=float(i), Z=3.0),
                                     rotation=spear.FRotator(Pitch=-90.0))
            light.LightComponent.bCastShadows = True
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, location=spear.FVector(X=-3.0, Z=1.0))
        camera.CameraSensor.Width = 32
        camera.CameraSensor.Height = 32
    with instance.end_frame():
        camera.CameraSensor.read_pixels()


def test_engine_log_lines_are_logging_records(make_instance: Callable[..., spear.Instance],
                                              caplog: pytest.LogCaptureFixture) -> None:
    caplog.set_level(logging.INFO, logger="spear")
    instance = make_instance()
    _too_many_shadowed_lights(instance)
    instance.close()  # over RPC: the server's last lines are forwarded before close() returns
    records = [r for r in caplog.records if "shadow-casting light(s) beyond the first 4" in r.getMessage()]
    assert len(records) == 1, [r.getMessage() for r in caplog.records]
    record = records[0]
    assert record.name == "spear" and record.levelno == logging.INFO
    assert record.filename == "shadow_maps.cpp" and record.lineno > 0


SCRIPT = """
import logging, sys
import spear
sys.path.insert(0, {tests!r})
from test_logging import _too_many_shadowed_lights
if sys.argv[1] == "quiet":
    logging.getLogger("spear").setLevel(logging.WARNING)
for server in (None, "launch"):
    instance = spear.Instance(server=server)
    _too_many_shadowed_lights(instance)
    instance.close()
"""


@pytest.mark.parametrize("mode", ["unconfigured", "quiet"])
def test_without_logging_configured_lines_go_to_stderr(tmp_path: pytest.TempPathFactory, mode: str) -> None:
    # Unconfigured: printed as the engine prints them; with a level set above INFO: nothing.
    script = SCRIPT.format(tests=str(__import__("pathlib").Path(__file__).parent))
    result = subprocess.run([sys.executable, "-c", script, mode], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    lines = [line for line in result.stderr.splitlines() if "beyond the first 4" in line]
    if mode == "quiet":
        assert lines == []
    else:
        assert len(lines) == 2 and all(line.startswith("[spear] shadow_maps.cpp:") for line in lines)
