"""Rect lights (URectLightComponent, ARectLight): a one-sided Lambertian panel that both renderers light with
its whole area and shadows it, on both transports. The wall they light is checked against the exact form factor of a
rectangle parallel to it, so the rasteriser's closed form and the path tracer's samples are each held to
the same physics, not only to each other."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest
from numpy.typing import NDArray

import spear
from test_camera import path_trace, spawn_camera, spawn_wall

M = spear.ECameraModality

WALL_X = 5.0  # the wall's front face, seen by a camera at the origin looking along +X
PANEL = (1.2, 0.6)  # SourceWidth (along Y), SourceHeight (along Z)
PANEL_GAP = 0.8  # metres between the panel and the wall
INTENSITY = 6.0  # candela along the panel's normal


def _corner(x: NDArray[np.float64], y: NDArray[np.float64], c: float) -> NDArray[np.float64]:
    """The form factor to a point of a rectangle [0, x] x [0, y] on a parallel plane c above it, one corner
    over the point (odd in x and in y, so that rectangles add up by inclusion and exclusion)."""
    X, Y = x / c, y / c
    a, b = np.sqrt(1.0 + X * X), np.sqrt(1.0 + Y * Y)
    form: NDArray[np.float64] = (X / a * np.arctan(Y / a) + Y / b * np.arctan(X / b)) / (2.0 * math.pi)
    return form


def expected_illumination(position: NDArray[np.float32], centre_y: float, centre_z: float) -> NDArray[np.float64]:
    """diffuse_illumination (irradiance / pi) the panel gives the wall at each pixel's `position`: its
    radiance times the form factor of the rectangle."""
    width, height = PANEL
    radiance = INTENSITY / (width * height)
    y = position[..., 1].astype(np.float64) - centre_y
    z = position[..., 2].astype(np.float64) - centre_z
    y1, y2 = -width / 2 - y, width / 2 - y
    z1, z2 = -height / 2 - z, height / 2 - z
    form = _corner(y2, z2, PANEL_GAP) - _corner(y1, z2, PANEL_GAP) - _corner(y2, z1, PANEL_GAP) + _corner(y1, z1, PANEL_GAP)
    return radiance * form


def dark_room_wall(game: spear.UWorld) -> spear.AMaterialLibrary:
    """A matte white wall at WALL_X and no sky light; the library, for more materials."""
    library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Library")
    library.SetMaterial(Name="Matte", Material=spear.FMaterialDesc(
        BaseColor=spear.FLinearColor(R=1.0, G=1.0, B=1.0, A=1.0), Roughness=1.0))
    spawn_wall(game, WALL_X, material="Matte")
    sky = game.spawn_actor(uclass=spear.ASkyLight, name="Sky")
    sky.SkyLightComponent.Intensity = 0.0
    return library


def _panel_scene(game: spear.UWorld, yaw: float = 0.0) -> spear.ARectLight:
    """The dark room's wall and a rect light 0.8 m in front of it, off the camera's axis; yaw 0 faces the
    wall, 180 turns its back to it."""
    dark_room_wall(game)
    panel = game.spawn_actor(uclass=spear.ARectLight, name="Panel",
                             location=spear.FVector(X=WALL_X - PANEL_GAP, Y=0.3, Z=-0.2),
                             rotation=spear.FRotator(Yaw=yaw))
    light = panel.LightComponent
    light.SetSourceWidth(NewWidth=PANEL[0])
    light.SetSourceHeight(NewHeight=PANEL[1])
    light.Intensity = INTENSITY
    light.AttenuationRadius = 0.0
    return panel


def _camera(game: spear.UWorld, traced: bool) -> spear.UCameraSensorComponent:
    camera = spawn_camera(game, [M.DiffuseIllumination, M.Position], 24, 18, 50.0)
    camera.GlobalIlluminationQuality = spear.EGlobalIlluminationQuality.Off
    if traced:
        path_trace(camera, 256, 0)
    return camera


@pytest.mark.parametrize("traced", [False, True], ids=["raster", "path traced"])
def test_a_rect_light_gives_a_wall_its_form_factor(instance: spear.Instance, traced: bool) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _panel_scene(game)
        camera = _camera(game, traced)
    with instance.end_frame():
        pixels = camera.read_pixels()
    position = pixels["position"]
    illumination = pixels["diffuse_illumination"][..., 0].astype(np.float64)
    expected = expected_illumination(position, 0.3, -0.2)
    assert expected.max() > 1.0 and expected.min() < 0.2 * expected.max()  # a pool of light, not a wash
    if traced:  # 256 samples of the panel a pixel: a few per cent each, far less over the image
        assert illumination.mean() == pytest.approx(expected.mean(), rel=0.02)
        assert np.abs(illumination - expected).max() <= 0.15 * expected.max()
    else:  # closed form, to float16
        np.testing.assert_allclose(illumination, expected, rtol=0.01, atol=2e-3 * expected.max())


@pytest.mark.parametrize("traced", [False, True], ids=["raster", "path traced"])
def test_a_rect_light_shines_one_way(instance: spear.Instance, traced: bool) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _panel_scene(game, yaw=180.0)
        camera = _camera(game, traced)
    with instance.end_frame():
        illumination = camera.read_pixels()["diffuse_illumination"]
    assert float(np.abs(illumination.astype(np.float64)).max()) == 0.0


@pytest.mark.parametrize("roughness", [0.3, 0.5, 0.8])
def test_a_rect_lights_highlight_on_metal_has_the_path_tracers_energy(
    make_instance: Callable[..., spear.Instance], roughness: float
) -> None:
    # The rasteriser's specular term is an approximation (a representative point); over a glossy metal wall
    # seen at a slant, the light it reflects is the path tracer's within a few per cent.
    means = []
    for traced in (False, True):
        instance = make_instance()
        game = instance.get_game()
        with instance.begin_frame():
            _panel_scene(game)
            library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Metals")
            library.SetMaterial(Name="Metal", Material=spear.FMaterialDesc(
                BaseColor=spear.FLinearColor(R=0.8, G=0.8, B=0.8, A=1.0), Roughness=roughness, Metallic=1.0))
            wall = game.find_actor_by_name(name="Wall")
            assert isinstance(wall, spear.AStaticMeshActor)
            wall.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Metal")
            camera = _camera(game, traced)
            camera.Modalities = [M.HdrColor]
            camera.SamplesPerPixel = 512
            owner = camera.GetOwner()
            assert owner is not None
            owner.SetActorLocation(NewLocation=spear.FVector(X=1.0, Y=-1.5, Z=0.5))
            owner.SetActorRotation(NewRotation=spear.FRotator(Pitch=-5.0, Yaw=20.0))
        with instance.end_frame():
            means.append(float(camera.read_pixels()["hdr_color"][..., :3].astype(np.float64).mean()))
    assert means[0] == pytest.approx(means[1], rel=0.08)


@pytest.mark.parametrize("traced", [False, True], ids=["raster", "path traced"])
def test_a_rect_light_casts_shadows(instance: spear.Instance, traced: bool) -> None:
    # A board between the panel and the wall leaves a shadow on the wall: less light than the form factor
    # says (the path tracer's soft, from the whole panel; the rasteriser's from its centre's shadow map).
    game = instance.get_game()
    with instance.begin_frame():
        _panel_scene(game)
        board = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Board",
                                 location=spear.FVector(X=WALL_X - 0.4, Y=0.3, Z=-0.2))
        board.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        board.SetActorScale3D(NewScale3D=spear.FVector(X=0.02, Y=0.6, Z=0.6))
        camera = _camera(game, traced)
    with instance.end_frame():
        pixels = camera.read_pixels()
    expected = expected_illumination(pixels["position"], 0.3, -0.2)
    illumination = pixels["diffuse_illumination"][..., 0].astype(np.float64)
    # The board hides the wall right behind it from the camera too; around that its shadow still falls.
    wall = np.abs(pixels["position"][..., 0] - WALL_X) < 0.01
    lit = wall & (expected >= 0.5 * expected.max())
    assert lit.sum() >= 10
    assert illumination[lit].mean() < 0.8 * expected[lit].mean()  # unshadowed: 1.0 within 2 %


@pytest.mark.parametrize(("name", "value", "message"), [
    ("SetSourceWidth", 0.0, "URectLightComponent.SourceWidth must be >= 1e-6 m, got 0"),
    ("SetSourceHeight", math.nan, "URectLightComponent.SourceHeight must be >= 1e-6 m, got nan"),
])
def test_bad_rect_light_sizes_are_refused(instance: spear.Instance, name: str, value: float, message: str) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        light = game.spawn_actor(uclass=spear.ARectLight, name="Panel").LightComponent
        with pytest.raises(spear.InvalidArgumentError, match=message):
            if name == "SetSourceWidth":
                light.SetSourceWidth(NewWidth=value)
            else:
                light.SetSourceHeight(NewHeight=value)
        assert (light.SourceWidth, light.SourceHeight) == pytest.approx((0.64, 0.64))
    with instance.end_frame():
        pass


def test_a_spot_light_shadows_a_wall_of_few_triangles(instance: spear.Instance) -> None:
    # A spot light's shadow-map coordinates were interpolated from the vertices with an offset that grows
    # with the distance to the light: across a wall of two triangles per face, the far corners' offset carried
    # the points near the light past the board, and its shadow vanished. The ring of the wall around the
    # board that the camera sees is in the board's shadow (the spot is a point: dark, bar the 1.5-texel edge).
    game = instance.get_game()
    results = []
    for board in (False, True):
        with instance.begin_frame():
            if not board:
                _panel_scene(game).LightComponent.Intensity = 0.0
                spot = game.spawn_actor(uclass=spear.ASpotLight, name="Spot",
                                        location=spear.FVector(X=WALL_X - PANEL_GAP, Y=0.3, Z=-0.2))
                spot.LightComponent.OuterConeAngle, spot.LightComponent.InnerConeAngle = 80.0, 70.0
                camera = _camera(game, False)
                camera.Width, camera.Height = 48, 36
            else:
                blocker = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Board",
                                           location=spear.FVector(X=WALL_X - 0.4, Y=0.3, Z=-0.2))
                blocker.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
                blocker.SetActorScale3D(NewScale3D=spear.FVector(X=0.02, Y=0.6, Z=0.6))
        with instance.end_frame():
            results.append(camera.read_pixels())
    position = results[1]["position"]
    # The umbra reaches 0.6 m from the board's axis; 0.15 m short of that the offset plays no part.
    ring = ((np.abs(position[..., 0] - WALL_X) < 0.01) & (np.abs(position[..., 1] - 0.3) < 0.45)
            & (np.abs(position[..., 2] + 0.2) < 0.45))
    assert ring.sum() >= 30
    lit, shadowed = (r["diffuse_illumination"][..., 0].astype(np.float64)[ring] for r in results)
    assert shadowed.mean() < 0.1 * lit.mean()
