"""Files that clients name are confined to the server's file roots (spear-server --file-root); in-process,
and on a server a user launched for themselves, a path means what it means to the user."""

from __future__ import annotations

import json
import os
import subprocess
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

import spear
from spear._rpc_client import find_server_binary

ASSETS = Path(__file__).resolve().parents[2] / "assets"


@pytest.fixture
def confined(tmp_path: Path) -> Iterator[tuple[spear.Instance, Path, int]]:
    """An instance on a spear-server whose clients may use tmp_path/root only (and the built-in assets)."""
    root = tmp_path / "root"
    root.mkdir()
    socket_path = tmp_path / "server.sock"
    server = subprocess.Popen([str(find_server_binary()), "--socket", str(socket_path), "--file-root", str(root)],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL, text=True,
                              cwd=tmp_path)
    assert server.stdout is not None
    assert server.stdout.readline().startswith("spear-server: listening on ")
    instance = spear.Instance(server=f"unix:{socket_path}")
    try:
        yield instance, root, server.pid
    finally:
        instance.close()
        server.terminate()
        server.wait(30)


def outside_message(function: str, what: str, path: str, root: Path, *, write: bool = False) -> str:
    """A path outside the roots: to be read, the file roots and the asset folders are named; to be written, the
    file roots alone (clients never write the assets)."""
    roots = f"'{root.resolve()}'" if write else f"'{root.resolve()}', '{ASSETS.resolve()}'"
    return (f"{function}: {what} '{path}' is outside the server's file roots ({roots}); start spear-server with "
            "--file-root DIR to allow another folder")


def test_scenes_inside_the_root_are_saved_whole_and_loaded(confined: tuple[spear.Instance, Path, int]) -> None:
    instance, root, _ = confined
    game = instance.get_game()
    with instance.begin_frame():
        game.spawn_actor(uclass=spear.AStaticMeshActor, name="Kept")
        game.save_scene(path=str(root / "scene.json"))
        game.save_scene(path="root/relative.json")  # relative to the server's working directory, tmp_path
        with pytest.raises(spear.InvalidArgumentError, match="is outside the server's file roots"):
            game.save_scene(path="relative.json")  # tmp_path itself is not a root
    with instance.end_frame():
        pass
    saved = json.loads((root / "scene.json").read_text())
    assert any(actor["name"] == "Kept" for actor in saved["actors"])
    assert (root / "relative.json").read_text() == (root / "scene.json").read_text()
    assert sorted(p.name for p in root.iterdir()) == ["relative.json", "scene.json"]  # no temporary file left
    with instance.begin_frame():
        game.load_scene(path=str(root / "scene.json"))
        assert game.find_actor_by_name(name="Kept") is not None
    with instance.end_frame():
        pass


def test_paths_outside_the_roots_are_refused_telling_nothing_about_the_file(
        confined: tuple[spear.Instance, Path, int], tmp_path: Path) -> None:
    instance, root, _ = confined
    game = instance.get_game()
    (tmp_path / "outside.json").write_text('{"format": "spear.scene", "version": 1, "actors": []}')
    (root / "link.json").symlink_to(tmp_path / "outside.json")
    with instance.begin_frame():
        for path in [str(tmp_path / "outside.json"), str(tmp_path / "missing.json"), f"{root}/../outside.json",
                     str(root / "link.json"), "/etc/passwd"]:
            with pytest.raises(spear.InvalidArgumentError) as error:
                game.load_scene(path=path)
            # The same message whether the file exists or not: nothing about it is told.
            assert str(error.value) == outside_message("UWorld.load_scene()", "scene file", path, root)
    with instance.end_frame():
        pass


def test_save_scene_cannot_write_outside_the_roots(confined: tuple[spear.Instance, Path, int],
                                                   tmp_path: Path) -> None:
    instance, root, pid = confined
    game = instance.get_game()
    comm = Path(f"/proc/{pid}/comm").read_text()
    with instance.begin_frame():
        for path in ["/proc/self/comm", str(tmp_path / "elsewhere.json")]:
            with pytest.raises(spear.InvalidArgumentError) as error:
                game.save_scene(path=path)
            assert str(error.value) == outside_message("UWorld.save_scene()", "scene file", path, root, write=True)
    with instance.end_frame():
        pass
    assert Path(f"/proc/{pid}/comm").read_text() == comm
    assert not (tmp_path / "elsewhere.json").exists()


def test_meshes_outside_the_roots_are_not_loaded(confined: tuple[spear.Instance, Path, int], tmp_path: Path) -> None:
    instance, root, _ = confined
    game = instance.get_game()
    mesh = tmp_path / "tri.obj"
    mesh.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Mesh")
        # Refused, naming the roots and how to allow another folder; the mesh is kept as it was.
        with pytest.raises(spear.InvalidArgumentError, match=r"SetStaticMesh\(\): mesh file '.*tri.obj' cannot be read: "
                                                             r".* is outside the server's file roots"):
            actor.StaticMeshComponent.SetStaticMesh(NewMesh=str(mesh))
        assert actor.StaticMeshComponent.StaticMesh == ""
        os.replace(mesh, root / "tri.obj")
        assert actor.StaticMeshComponent.SetStaticMesh(NewMesh=str(root / "tri.obj")) is True
    with instance.end_frame():
        pass


def test_built_in_blueprints_stay_usable_on_a_confined_server(confined: tuple[spear.Instance, Path, int]) -> None:
    instance, _, _ = confined
    game = instance.get_game()
    with instance.begin_frame():
        crate = game.spawn_actor(uclass=spear.BP_Crate, name="Crate")
        assert crate.GetName() == "Crate"
    with instance.end_frame():
        pass


def test_files_that_are_not_json_are_not_echoed_in_errors(instance: spear.Instance, tmp_path: Path) -> None:
    secret = tmp_path / "secret.json"
    secret.write_text('"TOPSECRET-VALUE and more of the file\n')
    game = instance.get_game()
    with instance.begin_frame():
        with pytest.raises(spear.InvalidArgumentError) as error:
            game.load_scene(path=str(secret))
    with instance.end_frame():
        pass
    assert "TOPSECRET" not in str(error.value)
    assert str(error.value).startswith(f"UWorld.load_scene(): scene file '{secret}' is not valid JSON: "
                                       "parse error at line 2, column 0")


def test_relative_paths_mean_the_users_directory_in_process_and_on_a_launched_server(
        make_instance: Callable[..., spear.Instance], tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)  # a launched server starts in the client's directory
    instance = make_instance()
    game = instance.get_game()
    with instance.begin_frame():
        game.save_scene(path="relative.json")
        game.load_scene(path="relative.json")
    with instance.end_frame():
        pass
    assert json.loads((tmp_path / "relative.json").read_text())["format"] == "spear.scene"


def test_render_jobs_write_inside_the_roots_only(confined: tuple[spear.Instance, Path, int], tmp_path: Path) -> None:
    instance, root, _ = confined
    game = instance.get_game()
    outside = tmp_path / "elsewhere"
    with instance.begin_frame():
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera").CameraSensor
        camera.Width, camera.Height = 16, 12
        queue = spear.UMoviePipelineQueueEngineSubsystem.GetMoviePipelineQueueEngineSubsystem(WorldContextObject=game)
        jobs = []
        for name, folder in [("outside", outside), ("inside", root / "frames")]:
            job = queue.AllocateJob(Camera=camera, JobName=name)
            job.SetConfiguration(Configuration=spear.FMoviePipelineConfiguration(
                OutputDirectory=str(folder), Modalities=[spear.ECameraModality.Depth], FrameEnd=2))
            queue.RenderJob(Job=job)
            jobs.append(job)
    with instance.end_frame():
        pass
    with instance.begin_frame():
        pass
    with instance.end_frame():
        refused, kept = jobs
        assert refused.GetStatus() == spear.EMoviePipelineJobStatus.Failed
        assert refused.GetErrorMessage() == outside_message(
            "UMoviePipelineQueueEngineSubsystem.RenderJob()", "output folder", str(outside), root, write=True)
        assert kept.GetStatus() == spear.EMoviePipelineJobStatus.Finished
    assert not outside.exists()
    assert sorted(p.name for p in (root / "frames" / "depth").iterdir()) == ["0000.exr", "0001.exr"]


def test_clients_read_the_built_in_assets_but_never_write_them(confined: tuple[spear.Instance, Path, int]) -> None:
    instance, root, _ = confined
    game = instance.get_game()
    crate, apartment = ASSETS / "blueprints" / "BP_Crate.json", ASSETS / "scenes" / "apartment.json"
    before = {path: path.read_bytes() for path in (crate, apartment)}
    read_only = (f"is under a read-only asset folder of the server ('{ASSETS.resolve()}'): clients read the assets, "
                 f"never write them; write under a --file-root folder ('{root.resolve()}')")
    with instance.begin_frame():
        game.load_scene(path=str(apartment))  # reading is fine
        for path in (crate, apartment, ASSETS / "scenes" / "new.json"):
            with pytest.raises(spear.InvalidArgumentError) as error:
                game.save_scene(path=str(path))
            assert str(error.value) == f"UWorld.save_scene(): scene file '{path}' {read_only}"
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera").CameraSensor
        camera.Width, camera.Height = 16, 12
        queue = spear.UMoviePipelineQueueEngineSubsystem.GetMoviePipelineQueueEngineSubsystem(WorldContextObject=game)
        job = queue.AllocateJob(Camera=camera, JobName="into assets")
        job.SetConfiguration(Configuration=spear.FMoviePipelineConfiguration(
            OutputDirectory=str(ASSETS / "frames"), Modalities=[spear.ECameraModality.Depth], FrameEnd=1))
        queue.RenderJob(Job=job)
    with instance.end_frame():
        pass
    with instance.begin_frame():
        pass
    with instance.end_frame():
        assert job.GetStatus() == spear.EMoviePipelineJobStatus.Failed
        assert job.GetErrorMessage() == (f"UMoviePipelineQueueEngineSubsystem.RenderJob(): output folder "
                                         f"'{ASSETS / 'frames'}' {read_only}")
    assert {path: path.read_bytes() for path in before} == before
    assert not (ASSETS / "frames").exists() and not (ASSETS / "scenes" / "new.json").exists()
