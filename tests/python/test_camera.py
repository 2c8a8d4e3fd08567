"""The camera sensor end to end through the Python API, rendered on whatever EGL device the machine has
(Mesa llvmpipe without a GPU): geometry against analytic values, object ids, the intrinsic
decomposition, latency, pass selection, lifetime and errors."""

from __future__ import annotations

import math
import pickle
import time
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
import pytest

import spear

M = spear.ECameraModality


def spawn_wall(game: spear.UWorld, x_front: float, name: str = "Wall", material: str = "White") -> spear.AStaticMeshActor:
    """A 10 x 10 m slab whose front face is the plane X = x_front, facing the camera at the origin."""
    wall = game.spawn_actor(uclass=spear.AStaticMeshActor, name=name, location=spear.FVector(X=x_front + 0.05))
    wall.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
    wall.StaticMeshComponent.SetMaterial(ElementIndex=0, Material=material)
    wall.SetActorScale3D(NewScale3D=spear.FVector(X=0.1, Y=10.0, Z=10.0))
    return wall


def aces_srgb(exposed: NDArray[np.float64]) -> NDArray[np.float64]:
    """final_color's RGB in 0..255 from exposed linear radiance: the ACES fit, then the exact sRGB OETF."""
    x = np.clip(exposed, 0.0, None)
    aces = np.clip(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0)
    srgb: NDArray[np.float64] = np.where(aces < 0.0031308, aces * 12.92, 1.055 * aces ** (1 / 2.4) - 0.055) * 255
    return srgb


def spawn_ground_and_crate(game: spear.UWorld, ground_size: float, crate_x: float = 0.0) -> None:
    """A square plane of ground_size metres at the origin and a 1 m cube standing on it at X = crate_x."""
    ground = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground")
    ground.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Plane")
    ground.SetActorScale3D(NewScale3D=spear.FVector(ground_size, ground_size, 1.0))
    crate = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Crate", location=spear.FVector(X=crate_x, Z=0.5))
    crate.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")


def spawn_camera(
    game: spear.UWorld, modalities: list[spear.ECameraModality], width: int = 32, height: int = 24, fov: float = 60.0
) -> spear.UCameraSensorComponent:
    camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera").CameraSensor
    camera.Width, camera.Height, camera.FOV = width, height, fov
    camera.Modalities = modalities
    return camera


def path_trace(camera: spear.UCameraSensorComponent, samples: int, max_bounces: int) -> spear.UCameraSensorComponent:
    """`camera`, switched to the path tracer with `samples` per pixel and at most `max_bounces` bounces."""
    camera.Renderer = spear.ECameraRenderer.PathTraced
    camera.SamplesPerPixel = samples
    camera.MaxBounces = max_bounces
    return camera


@pytest.mark.parametrize("every", [False, True], ids=["three", "all 14"])
def test_depth_position_normal_of_a_plane_match_the_geometry(instance: spear.Instance, every: bool) -> None:
    # With all 14 modalities a software rasteriser computes position from depth and the camera (one pass, no
    # attribute pass); with three it rasterises it. The geometry is the same either way.
    game = instance.get_game()
    distance, width, height, fov = 5.0, 40, 30, 60.0
    with instance.begin_frame():
        spawn_wall(game, distance)
        camera = spawn_camera(game, list(M) if every else [M.Depth, M.Position, M.Normal], width, height, fov)
    with instance.end_frame():
        px = camera.read_pixels()
    assert len(px) == 14 if every else sorted(px) == ["depth", "normal", "position"]
    depth, position, normal = px["depth"], px["position"], px["normal"]
    assert depth.dtype == np.float32 and depth.shape == (height, width)
    assert position.dtype == np.float32 and position.shape == (height, width, 3)
    # Depth is the distance along the optical axis: the same for every pixel of a fronto-parallel plane.
    assert np.max(np.abs(depth - distance) / distance) < 1e-4
    # Positions lie on the back-projected pixel rays (u right = -Y, v down = -Z, centres at +0.5).
    f = (width / 2) / math.tan(math.radians(fov) / 2)
    u = np.arange(width) + 0.5 - width / 2
    v = np.arange(height) + 0.5 - height / 2
    expected_y = -u[None, :] / f * distance
    expected_z = -v[:, None] / f * distance
    assert np.max(np.abs(position[..., 0] - distance)) < 1e-3
    assert np.max(np.abs(position[..., 1] - expected_y)) < 1e-3
    assert np.max(np.abs(position[..., 2] - expected_z)) < 1e-3
    assert np.allclose(normal, [-1.0, 0.0, 0.0], atol=1e-4)


def test_changes_made_in_begin_frame_show_in_the_same_frame(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        wall = spawn_wall(game, 3.0)
        camera = spawn_camera(game, [M.Depth])
    with instance.end_frame():
        pass
    for step in range(3):
        with instance.begin_frame():
            wall.SetActorLocation(NewLocation=spear.FVector(X=3.0 + step + 0.05))
        with instance.end_frame():
            assert np.allclose(camera.read_pixels()["depth"], 3.0 + step, rtol=1e-4)
            assert camera.GetPixelsFrame() == game.get_frame_count()


def test_attached_camera_follows_its_parent(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        spawn_wall(game, 6.0)
        body = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Body", location=spear.FVector(X=-1.0))
        camera = spawn_camera(game, [M.Depth])
        camera.AttachToComponent(Parent=body.StaticMeshComponent)
        camera.SetRelativeLocation(NewLocation=spear.FVector(X=2.0))
    with instance.end_frame():
        assert np.allclose(camera.read_pixels()["depth"], 5.0, rtol=1e-4)  # camera at X = -1 + 2
    with instance.begin_frame():
        body.SetActorLocation(NewLocation=spear.FVector(X=0.5))
    with instance.end_frame():
        assert np.allclose(camera.read_pixels()["depth"], 3.5, rtol=1e-4)


TWO_SLOT_OBJ = """\
# Two quads facing -X in the plane X = 0: the left one (+Y) is material slot 0, the right one slot 1.
v 0 0 -1
v 0 1 -1
v 0 1 1
v 0 0 1
v 0 -1 -1
v 0 0 -1
v 0 0 1
v 0 -1 1
usemtl Left
f 1 2 3
f 1 3 4
usemtl Right
f 5 6 7
f 5 7 8
"""


def test_object_ids_are_per_component_and_slot_stable_and_map_back(instance: spear.Instance, tmp_path: Path) -> None:
    game = instance.get_game()
    mesh_file = tmp_path / "two_slots.obj"
    mesh_file.write_text(TWO_SLOT_OBJ)
    with instance.begin_frame():
        spawn_wall(game, 8.0, name="Back", material="Grey")
        pair = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Pair", location=spear.FVector(X=4.0, Z=1.5))
        pair.StaticMeshComponent.StaticMesh = str(mesh_file)
        pair.StaticMeshComponent.Materials = ["Red", "Blue"]
        ball = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ball", location=spear.FVector(X=4.0, Z=-1.0))
        ball.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Sphere")
        ball.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Red")  # same material, other component
        camera = spawn_camera(game, [M.ObjectIds, M.MaterialIds], 64, 64, 90.0)
    with instance.end_frame():
        px = camera.read_pixels()
        ids, materials = px["object_ids"], px["material_ids"]
        assert ids.dtype == np.uint32 and ids.shape == (64, 64)
        left, right = camera.GetObjectId(Component=pair.StaticMeshComponent, MaterialSlot=0), camera.GetObjectId(
            Component=pair.StaticMeshComponent, MaterialSlot=1
        )
        ball_id = camera.GetObjectId(Component=ball.StaticMeshComponent)
        back_id = camera.GetObjectId(Component=game.find_actor_by_name(name="Back").StaticMeshComponent)  # type: ignore[union-attr]
        assert len({left, right, ball_id, back_id}) == 4 and 0 not in {left, right, ball_id, back_id}
        assert set(np.unique(ids)) - {0} == {left, right, ball_id, back_id}
        # The two slots of one component and two components with one material all differ in object_ids,
        # while material_ids groups by material.
        assert materials[ids == ball_id][0] == materials[ids == left][0] == camera.GetMaterialId(Name="Red")
        assert camera.GetMaterialId(Name="Blue") == materials[ids == right][0] != materials[ids == left][0]
        info = camera.GetObjectIdInfo(ObjectId=right)
        assert info.ReturnValue and info.Actor == pair and info.Component == pair.StaticMeshComponent
        assert (info.MaterialSlot, info.MaterialName) == (1, "Blue")
        info = camera.GetObjectIdInfo(ObjectId=ball_id)
        assert (info.Actor, info.MaterialSlot, info.MaterialName) == (ball, 0, "Red")
        background = camera.GetObjectIdInfo(ObjectId=0)
        assert not background.ReturnValue and background.Actor is None and background.MaterialSlot == -1
    # Stable across frames and camera moves; a destroyed component's id goes and is never reused.
    with instance.begin_frame():
        owner = camera.GetOwner()
        assert owner is not None
        owner.SetActorLocation(NewLocation=spear.FVector(Y=0.3, Z=0.2))
        game.destroy_actor(actor=ball)
    with instance.end_frame():
        ids2 = camera.read_pixels()["object_ids"]
        assert camera.GetObjectId(Component=pair.StaticMeshComponent, MaterialSlot=1) == right
        assert set(np.unique(ids2)) - {0} == {left, right, back_id}
        assert not camera.GetObjectIdInfo(ObjectId=ball_id).ReturnValue
    with instance.begin_frame():
        again = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ball2", location=spear.FVector(X=4.0, Z=-1.0))
        again.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Sphere")
    with instance.end_frame():
        new_id = camera.GetObjectId(Component=again.StaticMeshComponent)
        assert new_id not in {left, right, ball_id, back_id} and new_id in camera.read_pixels()["object_ids"]


def lit_room(game: spear.UWorld) -> None:
    spawn_wall(game, 6.0, material="Plaster")
    for i, material in enumerate(["Red", "Metal", "Gold", "Plastic"]):
        ball = game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(X=4.0, Y=1.5 - i, Z=0.0))
        ball.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Sphere")
        ball.StaticMeshComponent.SetMaterial(ElementIndex=0, Material=material)
    sun = game.spawn_actor(uclass=spear.ADirectionalLight, rotation=spear.FRotator(Pitch=-40.0, Yaw=20.0))
    sun.LightComponent.Intensity = 3.0
    lamp = game.spawn_actor(uclass=spear.APointLight, location=spear.FVector(X=2.0, Y=1.0, Z=1.0))
    lamp.LightComponent.Intensity = 5.0
    sky = game.spawn_actor(uclass=spear.ASkyLight)
    sky.SkyLightComponent.Intensity = 0.2


def test_a_world_of_many_lamps_shades_in_each_view_those_that_reach_it(instance: spear.Instance) -> None:
    # 40 lamps of 4 m range, 35 behind the camera or far to its sides, then 5 before it: a view shades the
    # lamps whose range reaches it (16 at most), whatever their number and order in the world, so the 35
    # change nothing, and destroying them leaves the image as it was, bit for bit; destroying one it sees
    # does not.
    game = instance.get_game()
    with instance.begin_frame():
        floor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Floor")
        floor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Plane")
        floor.SetActorScale3D(NewScale3D=spear.FVector(200.0, 200.0, 1.0))
        seen, unseen = [], []
        for i in range(40):
            if i < 35:
                location = spear.FVector(X=-20.0 - 8.0 * (i % 5), Y=-60.0 + 20.0 * (i // 5), Z=1.5)
            else:
                j = i - 35
                location = spear.FVector(X=3.0 + 2.5 * j, Y=1.5 * (j % 3 - 1), Z=1.5)
            lamp = game.spawn_actor(uclass=spear.APointLight, location=location)
            lamp.LightComponent.AttenuationRadius = 4.0
            (unseen if i < 35 else seen).append(lamp)
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, location=spear.FVector(X=-2.0, Z=3.0),
                                  rotation=spear.FRotator(Pitch=-30.0)).CameraSensor
        camera.Width, camera.Height, camera.FOV = 64, 48, 60.0
        camera.Modalities = [M.FinalColor, M.HdrColor]
    with instance.end_frame():
        pass
    images = []
    for destroyed in (None, unseen, seen[:1]):
        with instance.begin_frame():
            for lamp in destroyed or []:
                game.destroy_actor(actor=lamp)
        with instance.end_frame():
            images.append(camera.read_pixels())
            assert camera.GetRenderStats().LightsLeftOut == 0
    for key in ("final_color", "hdr_color"):
        assert np.array_equal(images[0][key], images[1][key]), key
        assert not np.array_equal(images[1][key], images[2][key]), key


def test_intrinsic_decomposition_holds_per_pixel(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        lit_room(game)
        camera = spawn_camera(game, [M.HdrColor, M.BaseColor, M.Metallic, M.DiffuseIllumination, M.DiffuseOnly,
                                     M.SpecularResidual], 48, 32)
    with instance.end_frame():
        px = camera.read_pixels()
    assert px["hdr_color"].dtype == np.float16 and px["hdr_color"].shape == (32, 48, 4)
    hdr = px["hdr_color"][..., :3].astype(np.float32)
    diffuse = px["diffuse_only"].astype(np.float32)
    residual = px["specular_residual"].astype(np.float32)
    # hdr = diffuse_only + specular_residual to float16 rounding of the three stored images.
    tolerance = 1e-3 * (np.abs(hdr) + np.abs(diffuse) + np.abs(residual)) + 1e-6
    assert np.all(np.abs(hdr - (diffuse + residual)) <= tolerance)
    # diffuse_only = base_color * (1 - metallic) * diffuse_illumination, as the renderer defines it.
    reflectance = px["base_color"].astype(np.float32) * (1.0 - px["metallic"].astype(np.float32))[..., None]
    product = reflectance * px["diffuse_illumination"].astype(np.float32)
    assert np.all(np.abs(diffuse - product) <= 2e-3 * np.abs(product) + 1e-4)
    assert np.max(hdr) > 0.1 and np.max(residual) > 0.01  # lit, with visible specular on the metals


@pytest.mark.parametrize("latency", [0, 1, 2])
def test_latency_returns_the_promised_frame(instance: spear.Instance, latency: int) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        wall = spawn_wall(game, 2.0)
    with instance.end_frame():
        pass
    for k in range(6):
        with instance.begin_frame():
            wall.SetActorLocation(NewLocation=spear.FVector(X=2.0 + 0.5 * k + 0.05))
            if k == 0:  # the camera's first frame is k = 0
                camera = spawn_camera(game, [M.Depth])
                camera.Latency = latency
        with instance.end_frame():
            px = camera.read_pixels()
            frame = game.get_frame_count()
            if k < latency:  # priming: no frame rendered `latency` frames ago yet
                assert px == {} and camera.GetPixelsFrame() == -1
                continue
            assert camera.GetPixelsFrame() == frame - latency
            shown = k - latency  # the wall position of frame - latency
            assert np.allclose(px["depth"], 2.0 + 0.5 * shown, rtol=1e-4), (k, frame)
            assert np.array_equal(camera.read_pixels()["depth"], px["depth"])  # reading twice: same frame


def test_read_pixels_in_begin_frame_returns_the_frame_last_rendered_and_says_which(instance: spear.Instance) -> None:
    # The rule: read_pixels() returns the camera's due frame whenever it is called. Nothing is rendered between
    # end_frame and the next begin_frame, so in begin_frame of frame k+1 that is still frame k's (what a
    # controller acting on its last observation reads); before the camera's first frame it is {} (as while
    # priming). GetPixelsFrame() names the frame either way.
    game = instance.get_game()
    with instance.begin_frame():
        wall = spawn_wall(game, 2.0)
        camera = spawn_camera(game, [M.Depth])
        assert camera.read_pixels() == {} and camera.GetPixelsFrame() == -1
    with instance.end_frame():
        rendered = camera.read_pixels()["depth"]
        frame = game.get_frame_count()
    with instance.begin_frame():
        again = camera.read_pixels()
        assert camera.GetPixelsFrame() == frame
        np.testing.assert_array_equal(again["depth"], rendered)
        wall.SetActorLocation(NewLocation=spear.FVector(X=3.05))  # shows in the frame this one renders
    with instance.end_frame():
        assert np.allclose(camera.read_pixels()["depth"], 3.0, rtol=1e-4)
        assert camera.GetPixelsFrame() == frame + 1


def test_render_now_shows_the_world_as_it_stands_without_a_frame(instance: spear.Instance) -> None:
    # RenderNow() renders between frames (the inspector's viewer of a paused world): the next read_pixels()
    # returns it, it shows the frame count as it stands, and nothing ticks.
    game = instance.get_game()
    with instance.begin_frame():
        wall = spawn_wall(game, 2.0)
        camera = spawn_camera(game, [M.Depth])
        camera.RenderNow()  # before the camera's first frame, too
        assert np.allclose(camera.read_pixels()["depth"], 2.0, rtol=1e-4)
        assert camera.GetPixelsFrame() == 0
    with instance.end_frame():
        frame = game.get_frame_count()
    with instance.begin_frame():
        wall.SetActorLocation(NewLocation=spear.FVector(X=3.05))
        camera.RenderNow()
        assert np.allclose(camera.read_pixels()["depth"], 3.0, rtol=1e-4)
        assert camera.GetPixelsFrame() == frame and game.get_frame_count() == frame
    with instance.end_frame():
        camera.read_pixels()
        assert camera.GetPixelsFrame() == frame + 1  # the frame's own render comes after


def test_final_color_without_alpha_is_rgb_of_the_same_pixels(instance: spear.Instance) -> None:
    # bFinalColorAlpha = False: (H, W, 3), the RGB of the (H, W, 4) image, for a model that takes RGB as it is;
    # stacked reads too, and cameras that disagree are refused.
    game = instance.get_game()
    with instance.begin_frame():
        spawn_wall(game, 3.0)
        cameras = [spawn_camera(game, [M.FinalColor, M.Depth], 24, 16)]
        cameras.append(game.spawn_actor(uclass=spear.ACameraSensorActor, name="Second").CameraSensor)
        cameras[1].Width, cameras[1].Height, cameras[1].FOV = 24, 16, 60.0
        cameras[1].Modalities = [M.FinalColor, M.Depth]
    with instance.end_frame():
        rgba = cameras[0].read_pixels()["final_color"]
    with instance.begin_frame():
        for camera in cameras:
            camera.bFinalColorAlpha = False
    with instance.end_frame():
        rgb = cameras[0].read_pixels()["final_color"]
        stacked = spear.UCameraSensorComponent.read_pixels_stacked(Cameras=cameras)["final_color"]
    assert rgba.shape == (16, 24, 4) and rgb.shape == (16, 24, 3) and rgb.dtype == np.uint8
    np.testing.assert_array_equal(rgb, rgba[..., :3])
    assert stacked.shape == (2, 16, 24, 3)
    np.testing.assert_array_equal(stacked[0], rgb)
    with instance.begin_frame():
        cameras[1].bFinalColorAlpha = True
    with instance.end_frame():
        with pytest.raises(spear.InvalidArgumentError, match=(
                r"read_pixels_stacked\(\): Cameras\[1\] has bFinalColorAlpha True, Cameras\[0\] False")):
            spear.UCameraSensorComponent.read_pixels_stacked(Cameras=cameras)


def test_copies_of_one_mesh_are_drawn_in_one_call_with_their_own_ids(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        cubes = []
        for i, material in enumerate(["Red", "Metal", "Gold", "Plastic"] * 2):
            cube = game.spawn_actor(uclass=spear.AStaticMeshActor,
                                    location=spear.FVector(X=4.0, Y=1.75 - 0.5 * i, Z=0.0))
            cube.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
            cube.StaticMeshComponent.SetRelativeScale3D(NewScale3D=spear.FVector(0.3, 0.3, 0.3))
            cube.StaticMeshComponent.SetMaterial(ElementIndex=0, Material=material)
            cubes.append(cube.StaticMeshComponent)
        camera = spawn_camera(game, [M.ObjectIds], 96, 48)
    with instance.end_frame():
        ids = camera.read_pixels()["object_ids"]
        stats = camera.GetRenderStats()
        expected = {camera.GetObjectId(Component=cube) for cube in cubes}
    assert stats.DrawnInstances == 8 and stats.DrawCalls == 1  # eight cubes, one instanced draw
    assert set(np.unique(ids)) - {0} == expected  # each cube's pixels carry its own id


def test_normals_are_turned_by_the_rasterisers_facing_where_the_mesh_and_its_scale_allow(
        instance: spear.Instance) -> None:
    # A cube's normals are its faces' own, under any scale; a sphere stretched four times along one axis leans
    # its smooth normals past what its triangles' windings vouch for, so its fragments take screen derivatives.
    game = instance.get_game()
    with instance.begin_frame():
        shapes = (("Cube", 0.6, spear.FVector(0.3, 0.5, 0.2)), ("Sphere", -0.6, spear.FVector(0.3, 1.2, 0.3)))
        for shape, y, scale in shapes:
            actor = game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(X=4.0, Y=y, Z=0.0))
            actor.StaticMeshComponent.CollisionPrimitive = spear.ECollisionPrimitive.NoCollision  # a stretched sphere
            actor.StaticMeshComponent.SetStaticMesh(NewMesh=f"/Engine/BasicShapes/{shape}")
            actor.StaticMeshComponent.SetRelativeScale3D(NewScale3D=scale)
        camera = spawn_camera(game, [M.FinalColor, M.Normal], 96, 48)
    with instance.end_frame():
        pixels = camera.read_pixels()
        stats = camera.GetRenderStats()
    assert stats.DrawnInstances == 2 and stats.WindingFacedInstances == 1, stats
    normal = pixels["normal"]
    # Both face the camera, which looks along +X (+Y is left: the cube is left of the centre, the sphere right).
    assert normal[24, 35, 0] < -0.9 and normal[24, 61, 0] < -0.9, (normal[24, 35], normal[24, 61])


@pytest.mark.parametrize("distance", [1.0, 3.0, 8.0, 20.0])
def test_a_round_shape_drawn_at_a_coarser_level_of_detail_keeps_its_outline(instance: spear.Instance,
                                                                            distance: float) -> None:
    # Far spheres are drawn with fewer triangles; the level is chosen so that the outline stays within half
    # a pixel of the true one. Pixels more than a pixel inside the sphere's exact disc show it, pixels more
    # than a pixel outside show the background, at every distance (so at every level).
    game = instance.get_game()
    size, radius = 256, 0.15
    with instance.begin_frame():
        ball = game.spawn_actor(uclass=spear.AStaticMeshActor, location=spear.FVector(X=distance))
        ball.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Sphere")
        ball.SetActorScale3D(NewScale3D=spear.FVector(X=2 * radius, Y=2 * radius, Z=2 * radius))
        camera = spawn_camera(game, [M.ObjectIds], size, size, 60.0)
    with instance.end_frame():
        ids = camera.read_pixels()["object_ids"]
    focal = size / 2 / math.tan(math.radians(30.0))
    disc = focal * math.tan(math.asin(radius / distance))  # the silhouette cone's image, in pixels
    v, u = np.mgrid[0:size, 0:size] + 0.5
    r = np.hypot(u - size / 2, v - size / 2)
    assert np.all(ids[r < disc - 1.0] != 0), f"holes inside the outline at {distance} m"
    assert np.all(ids[r > disc + 1.0] == 0), f"sphere outside the outline at {distance} m"


def test_an_object_falling_far_out_of_view_leaves_the_shadowed_image_as_it_was(instance: spear.Instance) -> None:
    """The sun's shadow map covers what the camera sees: an object far out of view (one that fell off the ground
    in a long run) neither coarsens the shadows in the image nor changes a pixel as it keeps falling."""
    game = instance.get_game()
    with instance.begin_frame():
        spawn_ground_and_crate(game, 8.0)
        # Shining towards the camera, so the crate's shadow falls on the ground in view.
        sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(Pitch=-50.0, Yaw=-160.0))
        sun.LightComponent.Intensity = 3.0
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera", location=spear.FVector(-5.0, -2.0, 3.0),
                                  rotation=spear.FRotator(Pitch=-28.0, Yaw=20.0)).CameraSensor
        camera.Width, camera.Height, camera.FOV = 64, 48, 60.0
        camera.ShadowResolution = 256
        camera.Modalities = [M.FinalColor]
    with instance.end_frame():
        before = camera.read_pixels()["final_color"]
    ground_rows = before[before.shape[0] // 2:, :, :3].astype(np.float64).mean(axis=2)  # the ground, no sky
    assert ground_rows.max() > 180 and ground_rows.min() < 100, "the crate's shadow darkens part of the ground"
    with instance.begin_frame():
        fallen = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Fallen",
                                  location=spear.FVector(-150.0, 80.0, -400.0))
        fallen.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Sphere")
    for step in range(2):
        with instance.end_frame():
            after = camera.read_pixels()["final_color"]
        np.testing.assert_array_equal(after, before, err_msg=f"step {step}")
        with instance.begin_frame():
            fallen.SetActorLocation(NewLocation=spear.FVector(-150.0, 80.0, -430.0 - 30.0 * step))


def test_what_no_shadow_reaches_is_shaded_without_shadow_lookups_on_a_software_rasteriser(
        instance: spear.Instance) -> None:
    """A wide floor with a crate on it and a ball high above it, under the sun: on llvmpipe the floor is shaded in
    parts (shadow-map lookups only around the crate's shadow) and the ball without lookups; a GPU does neither.
    The images are the same either way (core/render tests compare them bit for bit)."""
    game = instance.get_game()
    with instance.begin_frame():
        spawn_ground_and_crate(game, 40.0, crate_x=2.0)
        ball = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ball", location=spear.FVector(X=6.0, Z=3.0))
        ball.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(Pitch=-50.0, Yaw=30.0))
        sun.LightComponent.Intensity = 3.0
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera", location=spear.FVector(-6.0, 0.0, 4.0),
                                  rotation=spear.FRotator(Pitch=-20.0)).CameraSensor
        camera.Width, camera.Height, camera.FOV = 640, 360, 70.0
        camera.Modalities = [M.FinalColor]
    with instance.end_frame():
        colour = camera.read_pixels()["final_color"]
        stats = camera.GetRenderStats()
        device = camera.get_render_device_info()
    assert colour.shape == (360, 640, 4)
    if "llvmpipe" in device.Renderer:
        assert stats.SplitInstances == 1, stats  # the floor
        assert stats.UnshadowedInstances >= 1, stats  # the box in the air, at least
    else:
        assert stats.SplitInstances == 0 and stats.UnshadowedInstances == 0, (device.Renderer, stats)


def test_a_still_scene_with_several_lights_renders_its_shadow_maps_once(instance: spear.Instance) -> None:
    """Lights keep their order from frame to frame: a still scene's shadow maps (the sun's one, six for each
    lamp) are drawn once and reused, and every frame is the same image."""
    game = instance.get_game()
    with instance.begin_frame():
        spawn_ground_and_crate(game, 8.0, crate_x=2.0)
        game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(Pitch=-50.0, Yaw=30.0))
        game.spawn_actor(uclass=spear.APointLight, name="Lamp", location=spear.FVector(X=1.0, Y=1.0, Z=2.0))
        game.spawn_actor(uclass=spear.APointLight, name="Fill", location=spear.FVector(X=3.0, Y=-1.0, Z=1.0))
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera", location=spear.FVector(-3.0, 0.0, 2.0),
                                  rotation=spear.FRotator(Pitch=-20.0)).CameraSensor
        camera.Width, camera.Height = 64, 48
        camera.Modalities = [M.FinalColor]
    frames = []
    for _ in range(4):
        with instance.end_frame():
            frames.append(camera.read_pixels()["final_color"])
            stats = camera.GetRenderStats()
        with instance.begin_frame():
            pass
    with instance.end_frame():
        pass
    assert stats.ShadowPasses == 1 + 6 + 6 and stats.ShadowReuses == 3, stats
    for frame in frames[1:]:
        np.testing.assert_array_equal(frame, frames[0])


@pytest.mark.parametrize("sides, sized", [((64, 48), 256), ((640, 360), 1024), ((300, 1030), 2048)])
def test_shadow_maps_are_sized_to_the_worlds_cameras_by_default(instance: spear.Instance,
                                                                sides: tuple[int, int], sized: int) -> None:
    """ShadowResolution 0 (the default) stands for the power of two at or above the longest side of the world's
    shadowed cameras, within [256, 4096]: the image equals the one rendered at that resolution, bit for bit."""
    game = instance.get_game()
    with instance.begin_frame():
        spawn_ground_and_crate(game, 8.0, crate_x=2.0)
        game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(Pitch=-50.0, Yaw=30.0))
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera", location=spear.FVector(-3.0, 0.0, 2.0),
                                  rotation=spear.FRotator(Pitch=-20.0)).CameraSensor
        camera.Width, camera.Height = sides
        camera.Modalities = [M.FinalColor]
        assert camera.ShadowResolution == 0
    with instance.end_frame():
        pass
    images = []
    for resolution in (0, sized, sized // 2):
        with instance.begin_frame():
            camera.ShadowResolution = resolution
        with instance.end_frame():
            images.append(camera.read_pixels()["final_color"])
    np.testing.assert_array_equal(images[0], images[1])
    assert not np.array_equal(images[0], images[2])  # the size shows in the image


def test_pass_timings_are_measurements(instance: spear.Instance) -> None:
    """ShadowMs, SurfaceMs and ReadbackMs add up per-pass times: none is negative or longer than the frames took
    (llvmpipe answers a new GL context's first timer query with the time since boot, which is dropped)."""
    started = time.perf_counter()
    game = instance.get_game()
    with instance.begin_frame():
        ground = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground")
        ground.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Plane")
        crate = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Crate", location=spear.FVector(Z=0.5))
        crate.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(Pitch=-50.0))
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera", location=spear.FVector(-5.0, 0.0, 2.0),
                                  rotation=spear.FRotator(Pitch=-20.0)).CameraSensor
        camera.Width, camera.Height, camera.Modalities = 32, 24, [M.FinalColor]
    with instance.end_frame():
        pass
    for step in range(3):
        with instance.begin_frame():
            crate.SetActorLocation(NewLocation=spear.FVector(Z=0.5 + 0.1 * step))
        with instance.end_frame():
            camera.read_pixels()
            stats = camera.GetRenderStats()
    elapsed_ms = 1000.0 * (time.perf_counter() - started)
    assert stats.ShadowPasses >= 1 and stats.SurfacePasses >= 3
    for name, value in [("ShadowMs", stats.ShadowMs), ("SurfaceMs", stats.SurfaceMs), ("ReadbackMs", stats.ReadbackMs)]:
        assert 0.0 <= value <= elapsed_ms, f"{name} = {value} ms in {elapsed_ms:.0f} ms of frames"


def test_only_the_needed_passes_run(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        lit_room(game)
        camera = spawn_camera(game, [M.Depth, M.ObjectIds])
    with instance.end_frame():
        before = camera.GetRenderStats()
    instance.step(num_frames=2)
    with instance.begin_frame():
        after = camera.GetRenderStats()
        assert after.SurfacePasses - before.SurfacePasses == 2 and after.AttributePasses == 0
        assert (after.LightingPasses, after.TonemapPasses, after.ShadowPasses) == (0, 0, 0)
        camera.Modalities = [M.FinalColor]
    with instance.end_frame():
        assert sorted(camera.read_pixels()) == ["final_color"]
        stats = camera.GetRenderStats()
        assert stats.LightingPasses == 1 and stats.TonemapPasses == 1 and stats.ShadowPasses >= 1
        camera.bShadows = False
    with instance.begin_frame():
        pass
    with instance.end_frame():
        assert camera.GetRenderStats().ShadowPasses == stats.ShadowPasses


def test_final_color_is_srgb_rgba8(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        lit_room(game)
        camera = spawn_camera(game, list(M), 40, 30)
    with instance.end_frame():
        px = camera.read_pixels()
        assert sorted(px) == sorted(camera.GetModalityNames()) and len(px) == 14
    color = px["final_color"]
    assert color.dtype == np.uint8 and color.shape == (30, 40, 4) and np.all(color[..., 3] == 255)
    assert color[..., :3].std() > 5  # not a flat image


def test_several_cameras_and_rigs(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        target = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Target")
        target.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        ring = game.spawn_actor(uclass=spear.AMultiViewCameraRig, name="Ring")
        ring.SetRing(NumViews=3, NewRadius=3.0)
        ring.ConfigureCameras(Width=15, Height=15, Modalities=[M.Depth])
        # A bad size is refused before any camera changes.
        with pytest.raises(spear.InvalidArgumentError,
                           match=r"^AMultiViewCameraRig.ConfigureCameras\(\): Width must be in \[1, 16384\], got -1$"):
            ring.ConfigureCameras(Width=-1, Height=-1, Modalities=[M.FinalColor])
        assert all((c.Width, c.Height, c.Modalities) == (15, 15, [M.Depth]) for c in ring.Cameras)
        stereo = game.spawn_actor(uclass=spear.AStereoCameraRig, name="Stereo", location=spear.FVector(X=-4.0))
        stereo.Baseline = 0.5
        for cam in (stereo.LeftCamera, stereo.RightCamera):
            cam.Width, cam.Height, cam.Modalities = 15, 15, [M.Position]
    with instance.end_frame():
        assert len(ring.Cameras) == 3
        # Every ring camera looks at the origin from 3 m: the centre pixel hits the cube's near side.
        for cam in ring.Cameras:
            depth = cam.read_pixels()["depth"][7, 7]
            assert 3.0 - 0.5 * math.sqrt(2) - 0.01 < depth < 2.51, depth  # a face or an edge of the cube
        assert stereo.LeftCamera.GetComponentLocation().Y == pytest.approx(0.25)
        left = stereo.LeftCamera.read_pixels()["position"][7, 7]
        right = stereo.RightCamera.read_pixels()["position"][7, 7]
        assert left[1] == pytest.approx(0.25, abs=0.02) and right[1] == pytest.approx(-0.25, abs=0.02)


def test_destroyed_camera_raises_stale_object_error(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        actor = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Gone")
        camera = actor.CameraSensor
        camera.Width, camera.Height = 8, 8
    with instance.end_frame():
        assert "final_color" in camera.read_pixels()
    with instance.begin_frame():
        game.destroy_actor(actor=actor)
    with instance.end_frame():
        with pytest.raises(spear.StaleObjectError, match=r"UCameraSensorComponent 'CameraSensor'.*was destroyed"):
            camera.read_pixels()


def test_bad_modality_names_and_settings_are_clear_errors(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = spawn_camera(game, [M.Depth])
        camera.SetModalityNames(Names=["final_color", "depth"])
        assert camera.Modalities == [M.FinalColor, M.Depth]
        with pytest.raises(
            spear.InvalidArgumentError,
            match=r"UCameraSensorComponent.SetModalityNames\(\): unknown modality 'dept' \(valid: final_color, hdr_color, depth,",
        ):
            camera.SetModalityNames(Names=["dept"])
        assert camera.GetModalityNames() == ["final_color", "depth"]
        with pytest.raises(AttributeError):
            _ = spear.ECameraModality.Dept  # type: ignore[attr-defined]
    with instance.end_frame():
        pass
    # Settings are checked when they are set (tests/python/test_set_time_validation.py has every one); the
    # error names the property and its range, and the old value stays.
    with instance.begin_frame():
        with pytest.raises(spear.InvalidArgumentError, match=r"UCameraSensorComponent.Latency must be 0, 1 or 2, got 3"):
            camera.Latency = 3
        assert camera.Latency == 0
    with instance.end_frame():
        pass
    with instance.begin_frame():
        pass  # the engine kept running
    with instance.end_frame():
        assert sorted(camera.read_pixels()) == ["depth", "final_color"]


def test_render_device_is_reported(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = spawn_camera(game, [M.Depth])
        info = camera.get_render_device_info()
    assert info.Kind in ("device", "surfaceless")
    assert info.Renderer and info.Version.startswith("4.")


def test_intrinsics_and_extrinsics_project_points_where_they_are_rendered(instance: spear.Instance) -> None:
    # K and the world-to-camera transform in OpenCV's convention: a small ball's projected centre is the
    # centroid of its pixels, and its camera-frame z is its depth (plus its radius).
    game = instance.get_game()
    centre = np.array([2.0, 0.7, 0.4])
    with instance.begin_frame():
        ball = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ball", location=spear.FVector(*centre))
        ball.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Sphere")
        ball.SetActorScale3D(NewScale3D=spear.FVector(X=0.3, Y=0.3, Z=0.3))  # radius 0.15 m
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera", location=spear.FVector(-1.0, -0.5, 1.2),
                                  rotation=spear.FRotator(Pitch=-12.0, Yaw=20.0, Roll=5.0)).CameraSensor
        camera.Width, camera.Height, camera.FOV = 96, 64, 70.0
        camera.Modalities = [M.ObjectIds, M.Depth]
    with instance.end_frame():
        pixels = camera.read_pixels()
        k, world_to_camera = camera.GetIntrinsicMatrix(), camera.GetWorldToCamera()
        ball_id = camera.GetObjectId(Component=ball.StaticMeshComponent)
    assert k.shape == (3, 3) and k.dtype == np.float64 and world_to_camera.shape == (4, 4)
    focal = 48 / math.tan(math.radians(35.0))
    np.testing.assert_allclose(k, [[focal, 0, 47.5], [0, focal, 31.5], [0, 0, 1]])
    np.testing.assert_allclose(world_to_camera[3], [0, 0, 0, 1])
    np.testing.assert_allclose(world_to_camera[:3, :3] @ world_to_camera[:3, :3].T, np.eye(3), atol=1e-12)
    point = (world_to_camera @ np.append(centre, 1.0))[:3]
    u, v = (k @ point)[:2] / point[2]
    rows, columns = np.nonzero(pixels["object_ids"] == ball_id)
    assert len(rows) > 20
    assert columns.mean() == pytest.approx(u, abs=0.5) and rows.mean() == pytest.approx(v, abs=0.5)
    nearest = pixels["depth"][int(round(v)), int(round(u))]
    assert point[2] - 0.15 <= nearest <= point[2] - 0.1  # the ball's near side


def test_photographic_settings_set_fov_and_exposure(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = spawn_camera(game, [M.FinalColor], 64, 48)
        assert camera.SensorWidth == 36.0  # full frame
        camera.SetFocalLength(FocalLength=18.0)  # 36 mm across at 18 mm: a 90 degree view
        assert camera.FOV == pytest.approx(90.0)
        assert camera.GetFocalLength() == pytest.approx(18.0)
        np.testing.assert_allclose(camera.GetIntrinsicMatrix()[0, 0], 32.0)  # (64 / 2) / tan(45 degrees)
        camera.SensorWidth = 23.6  # APS-C keeps the view; the same view is a shorter lens
        assert camera.FOV == pytest.approx(90.0) and camera.GetFocalLength() == pytest.approx(11.8)
        camera.SetExposureValue(EV100=0.0)
        assert camera.Exposure == pytest.approx(1 / 1.2)
        camera.SetPhysicalExposure(FNumber=16.0, ShutterSeconds=1 / 100, ISO=100.0)  # sunny 16: EV100 ~ 14.6
        assert camera.Exposure == pytest.approx(1 / (1.2 * 16.0**2 * 100), rel=1e-6)
        for call, words in [
            (lambda: camera.SetFocalLength(FocalLength=0.0), "FocalLength must be > 0 and finite, got 0"),
            (lambda: setattr(camera, "SensorWidth", -1.0), "SensorWidth must be > 0 and finite, got -1"),
            (lambda: camera.SetPhysicalExposure(FNumber=2.8, ShutterSeconds=0.0, ISO=100.0),
             "ShutterSeconds must be > 0 and finite, got 0"),
        ]:
            with pytest.raises(spear.InvalidArgumentError, match=words):
                call()
    with instance.end_frame():
        pass


def test_a_distorted_off_centre_lens_renders_points_where_opencvs_model_puts_them(instance: spear.Instance) -> None:
    # Brown-Conrady distortion and a principal point off the centre, in OpenCV's convention: each ball's
    # pixels centre where K, the coefficients and the world-to-camera transform project its centre, in every
    # modality alike; undistorting pixels inverts distorting them.
    game = instance.get_game()
    centres = [np.array([4.0, y, z]) for y in (-1.6, 0.0, 1.6) for z in (-1.0, 0.0, 1.0)]
    lens = spear.FLensDistortion(K1=-0.25, K2=0.06, K3=0.0, P1=0.004, P2=-0.003)
    with instance.begin_frame():
        balls = []
        for i, c in enumerate(centres):
            ball = game.spawn_actor(uclass=spear.AStaticMeshActor, name=f"Ball{i}", location=spear.FVector(*c))
            ball.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Sphere")
            ball.SetActorScale3D(NewScale3D=spear.FVector(X=0.24, Y=0.24, Z=0.24))
            balls.append(ball)
        camera = spawn_camera(game, [M.ObjectIds, M.Depth, M.FinalColor], 160, 120, 80.0)
        camera.LensDistortion = lens
        camera.PrincipalPointOffset = spear.FVector2D(X=6.0, Y=-4.0)
    with instance.end_frame():
        pixels = camera.read_pixels()
        k, world_to_camera = camera.GetIntrinsicMatrix(), camera.GetWorldToCamera()
        coefficients = camera.GetDistortionCoefficients()
        ids = [camera.GetObjectId(Component=ball.StaticMeshComponent) for ball in balls]
        grid = np.array([[u, v] for u in np.linspace(0.0, 159.0, 9) for v in np.linspace(0.0, 119.0, 7)])
        undistorted = camera.UndistortPixels(Points=grid)
        round_trip = camera.DistortPixels(Points=undistorted)
        with pytest.raises(spear.InvalidArgumentError, match=r"DistortPixels\(\): array 'Points' must have shape"):
            camera.DistortPixels(Points=np.zeros((3, 3)))
    np.testing.assert_allclose(coefficients, [-0.25, 0.06, 0.004, -0.003, 0.0])
    focal = 80 / math.tan(math.radians(40.0))
    np.testing.assert_allclose(k, [[focal, 0, 79.5 + 6.0], [0, focal, 59.5 - 4.0], [0, 0, 1]])
    np.testing.assert_allclose(round_trip, grid, atol=1e-9)
    assert np.abs(undistorted - grid).max() > 5.0  # the lens does bend the image
    assert pixels["object_ids"].shape == (120, 160) and pixels["final_color"].shape == (120, 160, 4)

    k1, k2, p1, p2, k3 = coefficients
    for centre, ball_id in zip(centres, ids):
        x, y, z = (world_to_camera @ np.append(centre, 1.0))[:3]
        a, b = x / z, y / z
        r2 = a * a + b * b
        radial = 1 + k1 * r2 + k2 * r2 * r2 + k3 * r2**3
        ad = a * radial + 2 * p1 * a * b + p2 * (r2 + 2 * a * a)
        bd = b * radial + p1 * (r2 + 2 * b * b) + 2 * p2 * a * b
        u, v = k[0, 0] * ad + k[0, 2], k[1, 1] * bd + k[1, 2]
        rows, columns = np.nonzero(pixels["object_ids"] == ball_id)
        assert len(rows) > 15, centre
        assert columns.mean() == pytest.approx(u, abs=0.6) and rows.mean() == pytest.approx(v, abs=0.6), centre
        # Depth is along the optical axis in every lens: the nearest point of the ball is its centre's z less
        # at most its radius.
        assert z - 0.12 - 0.01 <= pixels["depth"][rows, columns].min() <= z - 0.05, centre
        # The colour at a ball's pixels is the ball's, not the background's: modalities stay aligned.
        assert (pixels["final_color"][rows, columns, :3] > 0).any(axis=-1).all(), centre


def test_lens_settings_are_checked(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = spawn_camera(game, [M.Depth, M.ObjectIds, M.FinalColor], 64, 48, 90.0)
        spawn_wall(game, 3.0)
        with pytest.raises(spear.InvalidArgumentError, match=r"LensDistortion.K2 must be finite, got inf"):
            camera.LensDistortion = spear.FLensDistortion(K2=float("inf"))
        with pytest.raises(spear.InvalidArgumentError, match=r"PrincipalPointOffset.Y must be finite, got nan"):
            camera.PrincipalPointOffset = spear.FVector2D(Y=float("nan"))
        # A mild barrel past its fold: K1 = -0.1 folds over before the corners of a 90 degree view.
        camera.LensDistortion = spear.FLensDistortion(K1=-0.1)
    with instance.end_frame():
        pixels = camera.read_pixels()
        corner = camera.UndistortPixels(Points=np.array([[0.0, 0.0], [31.5, 23.5]]))
    assert np.isnan(corner[0]).all() and np.isfinite(corner[1]).all()
    for name in ("depth", "object_ids", "final_color"):  # the corners show no ray: empty in every modality
        assert not pixels[name][0, 0].any() and pixels[name][24, 32].any(), name  # type: ignore[literal-required]
    # Whether a lens can serve an image depends on its size and field of view too, so it is checked when
    # the camera renders (the frame's tick, at the end of the begin_frame block).
    with pytest.raises(spear.InvalidArgumentError, match=r"UCameraSensorComponent 'CameraSensor': the lens "
                       r"\(distortion and principal point\) needs a \d+x\d+ pinhole render to cover its 64x48 "
                       r"image .*; its rays reach too far from the axis"):
        with instance.begin_frame():
            camera.LensDistortion = spear.FLensDistortion()
            camera.PrincipalPointOffset = spear.FVector2D(X=5000.0)  # the image far off the axis
    with instance.end_frame():
        pass
    with instance.begin_frame():
        camera.PrincipalPointOffset = spear.FVector2D()
    with instance.end_frame():
        assert camera.read_pixels()["depth"].shape == (48, 64)  # the engine rendered on


@pytest.mark.parametrize("renderer", [spear.ECameraRenderer.Raster, spear.ECameraRenderer.PathTraced])
def test_white_balance_scales_linear_colour_before_the_tone_curve(
    instance: spear.Instance, renderer: spear.ECameraRenderer
) -> None:
    # Balancing for tungsten light (3200 K) raises blue and lowers red in final_color; hdr_color is radiance
    # and does not change. final_color = sRGB(ACES(hdr * exposure * gains)), on both renderers.
    game = instance.get_game()
    with instance.begin_frame():
        spawn_wall(game, 3.0)
        sky = game.spawn_actor(uclass=spear.ASkyLight, name="Sky")
        sky.SkyLightComponent.Intensity = 0.6
        sky.SkyLightComponent.BackgroundColor = spear.FLinearColor(R=0.5, G=0.5, B=0.5, A=1.0)
        camera = spawn_camera(game, [M.FinalColor, M.HdrColor], 24, 16, 90.0)
        camera.Renderer = renderer
        camera.SamplesPerPixel = 2
        assert camera.WhiteBalanceTemperature == 6500.0
        np.testing.assert_allclose(camera.GetWhiteBalanceGains(), [1.0, 1.0, 1.0], atol=1e-6)
        camera.WhiteBalanceTemperature = 3200.0
        gains = camera.GetWhiteBalanceGains()
        with pytest.raises(spear.InvalidArgumentError, match=r"WhiteBalanceTemperature must be in \[2000, 25000\] "
                                                            r"kelvin, got 1000"):
            camera.WhiteBalanceTemperature = 1000.0
    with instance.end_frame():
        pixels = camera.read_pixels()
    assert gains[2] > gains[1] > gains[0]
    assert float(gains @ [0.2126, 0.7152, 0.0722]) == pytest.approx(1.0)  # a grey keeps its luminance
    final = pixels["final_color"][..., :3].astype(np.float64)
    expected = aces_srgb(pixels["hdr_color"][..., :3].astype(np.float64) * gains)
    assert np.abs(final - expected).max() <= 1.5  # float16 rounding of hdr_color, the shader's sRGB fit
    assert final[..., 2].mean() > final[..., 0].mean() + 10  # a grey scene turns blue


@pytest.mark.parametrize("renderer", [spear.ECameraRenderer.Raster, spear.ECameraRenderer.PathTraced])
def test_vignetting_darkens_final_colour_by_the_cos4_law(
    instance: spear.Instance, renderer: spear.ECameraRenderer
) -> None:
    # final_color = sRGB(ACES(hdr * exposure * mix(1, cos^4 theta, VignetteIntensity))) at every pixel, the
    # background's included; hdr_color is radiance and is not vignetted.
    game = instance.get_game()
    with instance.begin_frame():
        spawn_wall(game, 3.0, name="Left").SetActorLocation(NewLocation=spear.FVector(X=3.05, Y=7.0))
        sky = game.spawn_actor(uclass=spear.ASkyLight, name="Sky")
        sky.SkyLightComponent.Intensity = 0.8
        sky.SkyLightComponent.BackgroundColor = spear.FLinearColor(R=0.6, G=0.6, B=0.6, A=1.0)
        camera = spawn_camera(game, [M.FinalColor, M.HdrColor, M.Depth], 32, 20, 100.0)
        camera.Renderer = renderer
        camera.SamplesPerPixel = 2
        camera.VignetteIntensity = 0.8
        with pytest.raises(spear.InvalidArgumentError, match=r"VignetteIntensity must be in \[0, 1\], got 1.5"):
            camera.VignetteIntensity = 1.5
    with instance.end_frame():
        pixels = camera.read_pixels()
    depth = pixels["depth"]
    assert (depth > 0).any() and (depth == 0).any()  # both the wall and the background are in view
    focal = 16 / math.tan(math.radians(50.0))
    v, u = np.mgrid[0:20, 0:32] + 0.5
    cos2 = 1 / (1 + ((u - 16) / focal) ** 2 + ((v - 10) / focal) ** 2)
    factor = 1 + (cos2**2 - 1) * 0.8
    final = pixels["final_color"][..., :3].astype(np.float64)
    expected = aces_srgb(pixels["hdr_color"][..., :3].astype(np.float64) * factor[..., None])
    assert np.abs(final - expected).max() <= 1.5
    background = final[depth == 0][:, 0]
    assert background.max() - background.min() > 40  # the uniform sky darkens towards the corners


def test_a_lens_applies_alike_to_path_traced_buffered_and_stacked_reads(instance: spear.Instance) -> None:
    # The remap follows each frame: a path-traced lens camera's images and a raster one's agree on geometry,
    # a buffered frame is read with the lens it was rendered with, and stacked reads equal single ones.
    game = instance.get_game()
    lens = spear.FLensDistortion(K1=-0.2, P2=0.01)
    with instance.begin_frame():
        spawn_wall(game, 3.0)
        ball = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ball", location=spear.FVector(X=2.0, Y=0.4))
        ball.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Sphere")
        cameras = []
        for name in ("Raster", "Traced", "Buffered"):
            camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name=name).CameraSensor
            camera.Width, camera.Height, camera.FOV = 40, 30, 80.0
            camera.Modalities = [M.Depth] if name == "Buffered" else [M.Depth, M.FinalColor]
            camera.LensDistortion, camera.PrincipalPointOffset = lens, spear.FVector2D(X=3.0, Y=-2.0)
            cameras.append(camera)
        raster, traced, buffered = cameras
        traced.Renderer, traced.SamplesPerPixel = spear.ECameraRenderer.PathTraced, 1
        buffered.Latency = 1
    with instance.end_frame():
        a, b = raster.read_pixels(), traced.read_pixels()
        stacked = spear.UCameraSensorComponent.read_pixels_stacked(Cameras=[raster, traced])
    assert a["final_color"].shape == b["final_color"].shape == (30, 40, 4)
    np.testing.assert_array_equal(a["depth"], b["depth"])
    np.testing.assert_array_equal(stacked["depth"][0], a["depth"])
    np.testing.assert_array_equal(stacked["final_color"][1], b["final_color"])
    with instance.begin_frame():
        buffered.LensDistortion = spear.FLensDistortion()  # the frame due now was rendered with the lens
        buffered.PrincipalPointOffset = spear.FVector2D()
    with instance.end_frame():
        np.testing.assert_array_equal(buffered.read_pixels()["depth"], a["depth"])


def test_a_modality_not_rendered_or_misspelt_is_a_key_error_that_says_which(instance: spear.Instance) -> None:
    """read_pixels() holds the modalities the camera renders; asking for another names what it holds and where
    that comes from, and a misspelt key names the fields, with the same words on both transports. The result
    is still a dict (`in`, get() and pickling work as on any dict)."""
    game = instance.get_game()
    with instance.begin_frame():
        camera = spawn_camera(game, [M.FinalColor, M.Depth], 8, 6)
    with instance.end_frame():
        pixels = camera.read_pixels()
    assert isinstance(pixels, dict) and sorted(pixels) == ["depth", "final_color"]
    with pytest.raises(KeyError, match=r"'normal' is not in this FCameraPixels \(it holds 'final_color', 'depth'\)\. "
                                       r"The images of one frame, .* the camera renders \(its Modalities\) are present"):
        pixels["normal"]
    with pytest.raises(KeyError, match=r"'normals' is not a field of FCameraPixels \(its fields: final_color, "
                                       r"hdr_color, depth, position, normal,"):
        pixels["normals"]  # type: ignore[typeddict-item]
    assert "normal" not in pixels and pixels.get("normal") is None
    copied = pickle.loads(pickle.dumps(pixels))
    assert np.array_equal(copied["depth"], pixels["depth"])
    with pytest.raises(KeyError, match="'normal' is not in this FCameraPixels"):
        copied["normal"]
