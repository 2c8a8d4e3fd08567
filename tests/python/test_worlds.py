"""Many worlds in one engine: created worlds tick with the game world, each with its own actors, physics and
render scene; names are unique; destroyed worlds leave stale handles. Every test runs on both transports."""

from __future__ import annotations

import collections
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import NDArray
import pytest

import spear
from spear.errors import InvalidArgumentError, StaleObjectError

CUBE = "/Engine/BasicShapes/Cube"


def drop_cube(world: spear.UWorld, height: float) -> spear.AStaticMeshActor:
    """A static floor with its top at z = 0 and a cube falling onto it from `height`."""
    floor = world.spawn_actor(uclass=spear.AStaticMeshActor, name="Floor", location=spear.FVector(Z=-0.5))
    floor.StaticMeshComponent.SetStaticMesh(NewMesh=CUBE)
    floor.StaticMeshComponent.SetRelativeScale3D(NewScale3D=spear.FVector(20, 20, 1))
    floor.StaticMeshComponent.SetMobility(NewMobility=spear.EComponentMobility.Static)
    cube = world.spawn_actor(uclass=spear.AStaticMeshActor, name="Cube", location=spear.FVector(Z=height))
    cube.StaticMeshComponent.SetStaticMesh(NewMesh=CUBE)
    cube.StaticMeshComponent.SetSimulatePhysics(bSimulate=True)
    return cube


def test_created_worlds_tick_with_the_game_world_and_do_not_share_actors(instance: spear.Instance) -> None:
    game = instance.get_game()
    a = instance.create_world(name="EnvA")
    b = instance.create_world(name="EnvB")
    assert instance.get_worlds() == [game, a, b]
    with instance.begin_frame():
        assert a.GetName() == "EnvA"
        only = a.spawn_actor(uclass=spear.AActor, name="Only")
    with instance.end_frame():
        assert a.find_actor_by_name(name="Only") == only
        assert b.find_actor_by_name(name="Only") is None
        assert game.find_actor_by_name(name="Only") is None
        assert [world.get_frame_count() for world in instance.get_worlds()] == [1, 1, 1]


def test_physics_is_per_world_and_identical_worlds_replay_identically(instance: spear.Instance) -> None:
    worlds = [instance.create_world(name=f"Env{i}") for i in range(3)]
    with instance.begin_frame():
        cubes = [drop_cube(world, height) for world, height in zip(worlds, (2.0, 2.0, 4.0))]
    with instance.end_frame():
        pass
    instance.step(num_frames=30)
    with instance.begin_frame():
        heights = [cube.GetActorLocation().Z for cube in cubes]
    with instance.end_frame():
        pass
    assert heights[0] == heights[1]  # same scene, same steps: bit for bit
    assert heights[2] > heights[0] + 1.0  # dropped from higher, still falling apart from the others
    assert 0.5 < heights[0] < 2.0


def test_each_world_renders_its_own_scene(instance: spear.Instance) -> None:
    worlds = [instance.create_world(name=f"Env{i}") for i in range(2)]
    cameras = []
    with instance.begin_frame():
        for i, world in enumerate(worlds):
            if i == 1:  # a wall in front of the second world's camera only
                wall = world.spawn_actor(uclass=spear.AStaticMeshActor, name="Wall", location=spear.FVector(X=3))
                wall.StaticMeshComponent.SetStaticMesh(NewMesh=CUBE)
                wall.SetActorScale3D(NewScale3D=spear.FVector(0.1, 10, 10))
            camera = world.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera").CameraSensor
            camera.Width, camera.Height = 16, 12
            camera.Modalities = [spear.ECameraModality.Depth]
            cameras.append(camera)
    with instance.end_frame():
        empty, walled = (camera.read_pixels()["depth"] for camera in cameras)
    assert np.all(empty == 0.0)  # nothing in view: background
    assert np.allclose(walled, 2.95, atol=1e-3)  # the wall's front face, 3 m - 0.05 m


def shadowed_scene(world: spear.UWorld, height: float) -> spear.UCameraSensorComponent:
    """drop_cube() under a shadow-casting sun, and a 32 x 24 camera looking down at it."""
    drop_cube(world, height)
    sun = world.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(Pitch=-50.0, Yaw=30.0))
    sun.LightComponent.Intensity = 3.0
    camera = world.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera", location=spear.FVector(X=-4.0, Z=3.0),
                               rotation=spear.FRotator(Pitch=-30.0)).CameraSensor
    camera.Width, camera.Height = 32, 24
    camera.Modalities = [spear.ECameraModality.FinalColor, spear.ECameraModality.Depth,
                         spear.ECameraModality.ObjectIds]
    return camera


def test_a_worlds_images_do_not_depend_on_the_worlds_drawn_with_it(
    make_instance: Callable[..., spear.Instance],
) -> None:
    # The worlds' cameras are drawn as one batch (shared framebuffers and shadow-map layers): a world's frames
    # equal, bit for bit, those of the same world alone in an engine of its own, as its cube falls and its
    # shadow moves.
    def frames(instance: spear.Instance, heights: tuple[float, ...]) -> list[list[dict[str, NDArray[Any]]]]:
        worlds = [instance.create_world(name=f"Env{i}") for i in range(len(heights))]
        with instance.begin_frame():
            cameras = [shadowed_scene(world, height) for world, height in zip(worlds, heights)]
        shot = []
        for _ in range(4):
            with instance.end_frame():
                shot.append([{name: np.asarray(image) for name, image in camera.read_pixels().items()}
                             for camera in cameras])
            with instance.begin_frame():
                pass
        with instance.end_frame():
            pass
        return shot

    together = frames(make_instance(), (1.5, 2.5, 3.5))
    alone = frames(make_instance(), (2.5,))
    for frame, (batched, single) in enumerate(zip(together, alone)):
        for name in ("final_color", "depth", "object_ids"):
            assert np.array_equal(batched[1][name], single[0][name]), f"{name}, frame {frame}"
    assert not np.array_equal(together[3][0]["final_color"], together[3][2]["final_color"])  # other scenes
    assert not np.array_equal(together[0][1]["final_color"], together[3][1]["final_color"])  # the cube fell


def test_worlds_share_the_uploads_of_built_in_shapes_and_count_their_own_frames(instance: spear.Instance) -> None:
    # The engine's worlds render with one GL context and renderer: the cube's mesh is uploaded once, by the
    # world that drew it first, and each world's statistics are its own.
    worlds = [instance.create_world(name=f"Env{i}") for i in range(3)]
    cameras = []
    with instance.begin_frame():
        for world in worlds:
            cube = world.spawn_actor(uclass=spear.AStaticMeshActor, name="Cube", location=spear.FVector(X=3))
            cube.StaticMeshComponent.SetStaticMesh(NewMesh=CUBE)
            camera = world.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera").CameraSensor
            camera.Width, camera.Height = 16, 12
            camera.Modalities = [spear.ECameraModality.Depth]
            cameras.append(camera)
    with instance.end_frame():
        depths = [camera.read_pixels()["depth"] for camera in cameras]
    instance.step(num_frames=2)
    with instance.begin_frame():
        stats = [camera.GetRenderStats() for camera in cameras]
    with instance.end_frame():
        pass
    for depth in depths:
        assert np.isclose(depth[6, 8], 2.5, atol=1e-3)  # the cube's front face, 3 m - 0.5 m, in every world
    assert [s.Frames for s in stats] == [3, 3, 3]
    assert stats[0].MeshUploads >= 1
    assert [s.MeshUploads for s in stats[1:]] == [0, 0]
    assert [s.Readbacks for s in stats] == [1, 1, 1]


def test_world_names_are_unique_and_only_created_worlds_are_destroyed(instance: spear.Instance) -> None:
    world = instance.create_world(name="Env")
    with pytest.raises(InvalidArgumentError, match=r"^create_world\(\): a world named 'Env' exists already$"):
        instance.create_world(name="Env")
    with pytest.raises(InvalidArgumentError, match=r"^create_world\(\): name must not be empty$"):
        instance.create_world(name="")
    with pytest.raises(InvalidArgumentError, match=r"^create_world\(\): name must be a str, got int$"):
        instance.create_world(name=1)  # type: ignore[arg-type]
    with pytest.raises(InvalidArgumentError, match=r"^destroy_world\(\): world must be a UWorld, got NoneType$"):
        instance.destroy_world(world=None)  # type: ignore[arg-type]
    with instance.begin_frame():
        actor = world.spawn_actor(uclass=spear.AActor)
        with pytest.raises(InvalidArgumentError, match=r"^destroy_world\(\): 'World' is not a world create_world\(\) "
                                                       r"made; the game and editor worlds live as long as the engine$"):
            instance.destroy_world(world=instance.get_game())
        with pytest.raises(InvalidArgumentError, match=r"^destroy_world\(\): world must be a UWorld, got AActor$"):
            instance.destroy_world(world=actor)  # type: ignore[arg-type]
        instance.destroy_world(world=world)
        assert not actor.is_valid() and not world.is_valid()
        with pytest.raises(StaleObjectError, match=r"^UWorld.spawn_actor\(\): object \(handle \d+:\d+\) was destroyed$"):
            world.spawn_actor(uclass=spear.AActor)
    with instance.end_frame():
        pass
    assert instance.get_worlds() == [instance.get_game()]
    instance.create_world(name="Env")  # the name is free again


def test_cameras_of_many_worlds_are_read_in_one_stacked_call(instance: spear.Instance) -> None:
    worlds = [instance.create_world(name=f"Env{i}") for i in range(3)]
    cameras = []
    with instance.begin_frame():
        for i, world in enumerate(worlds):  # a wall 2 + i metres in front of each camera
            wall = world.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(X=2.05 + i))
            wall.StaticMeshComponent.SetStaticMesh(NewMesh=CUBE)
            wall.SetActorScale3D(NewScale3D=spear.FVector(0.1, 10, 10))
            camera = world.spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor
            camera.Width, camera.Height = 16, 12
            camera.Modalities = [spear.ECameraModality.FinalColor, spear.ECameraModality.Depth]
            cameras.append(camera)
    with instance.end_frame():
        stacked = spear.UCameraSensorComponent.read_pixels_stacked(Cameras=cameras)
        one_by_one = [camera.read_pixels() for camera in cameras]  # the same frame, read again
        frames = [camera.GetPixelsFrame() for camera in cameras]
    assert sorted(stacked) == ["depth", "final_color"]
    assert stacked["depth"].shape == (3, 12, 16) and stacked["final_color"].shape == (3, 12, 16, 4)
    for i in range(3):
        assert np.allclose(stacked["depth"][i], 2.0 + i, atol=1e-3)
        assert np.array_equal(stacked["depth"][i], one_by_one[i]["depth"])
        assert np.array_equal(stacked["final_color"][i], one_by_one[i]["final_color"])
    assert frames == [1, 1, 1]


def test_stacked_reads_need_one_size_and_one_set_of_modalities(instance: spear.Instance) -> None:
    worlds = [instance.create_world(name=f"Env{i}") for i in range(2)]
    with instance.begin_frame():
        a, b = (world.spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor for world in worlds)
        a.Width, a.Height, b.Width, b.Height = 16, 12, 8, 6
        b.Latency = 1
    with instance.end_frame():
        # b renders with one frame of latency: nothing is due for it yet, so nothing is read for either.
        assert spear.UCameraSensorComponent.read_pixels_stacked(Cameras=[a, b]) == {}
    with instance.begin_frame():
        pass
    with instance.end_frame():
        with pytest.raises(InvalidArgumentError, match=r"^UCameraSensorComponent.read_pixels_stacked\(\): Cameras\[1\] "
                                                       r"shows 8x6 images, Cameras\[0\] 16x12; stacked cameras need one size$"):
            spear.UCameraSensorComponent.read_pixels_stacked(Cameras=[a, b])
        with pytest.raises(InvalidArgumentError, match=r"^UCameraSensorComponent.read_pixels_stacked\(\): Cameras is empty$"):
            a.read_pixels_stacked(Cameras=[])  # called on an object: that object's engine runs it
        b.Width, b.Height = 16, 12
        b.Modalities = [spear.ECameraModality.Depth]
    instance.step(num_frames=2)
    with instance.begin_frame():
        pass
    with instance.end_frame():
        with pytest.raises(InvalidArgumentError, match=r"^UCameraSensorComponent.read_pixels_stacked\(\): Cameras\[1\] "
                                                       r"renders other modalities than Cameras\[0\] \(depth against final_color\)$"):
            spear.UCameraSensorComponent.read_pixels_stacked(Cameras=[a, b])


def test_a_world_destroyed_with_its_camera_leaves_the_others_rendering(instance: spear.Instance) -> None:
    worlds = [instance.create_world(name=f"Env{i}") for i in range(2)]
    with instance.begin_frame():
        cameras = [world.spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor for world in worlds]
        for camera in cameras:
            camera.Width, camera.Height = 8, 6
    with instance.end_frame():
        assert all("final_color" in camera.read_pixels() for camera in cameras)
    instance.destroy_world(world=worlds[0])  # its renderer goes, between frames
    with instance.begin_frame():
        pass
    with instance.end_frame():
        assert cameras[1].read_pixels()["final_color"].shape == (6, 8, 4)
        assert not cameras[0].is_valid()


def test_batched_locations_span_worlds(instance: spear.Instance) -> None:
    # One actor per world, moved and read in one call each: rows are a leading world axis.
    worlds = [instance.create_world(name=f"Env{i}") for i in range(3)]
    with instance.begin_frame():
        actors = [world.spawn_actor(uclass=spear.AStaticMeshActor, name="Agent") for world in worlds]
        targets = np.array([[i, 2.0 * i, 0.5] for i in range(3)])
        worlds[0].set_actor_locations(actors=actors, locations=targets)
    with instance.end_frame():
        assert np.array_equal(worlds[2].get_actor_locations(actors=actors), targets)
        assert np.array_equal(worlds[2].get_actor_locations(actors=tuple(actors)), targets)  # any sequence
        assert np.array_equal(worlds[2].get_actor_locations(actors=collections.UserList(actors)), targets)
        agents = [world.find_actor_by_name(name="Agent") for world in worlds]
        assert [agent.GetActorLocation().Y for agent in agents if agent is not None] == [0.0, 2.0, 4.0]
