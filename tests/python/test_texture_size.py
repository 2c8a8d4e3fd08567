"""FMaterialDesc.TextureSize: textures repeating every so many metres on the object's own scaled box axes
(core/render/box_uv.h), as UE's WorldAlignedTexture but attached to the object. Checked against where each
pixel's point is (the position modality), in the rasteriser and the path tracer, on both transports."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from numpy.typing import NDArray
from PIL import Image  # type: ignore[import]  # Debian ships no Pillow stubs

import spear
from test_camera import path_trace, spawn_camera, spawn_wall

M = spear.ECameraModality
ROOT = Path(__file__).resolve().parents[2]
SIZE = 0.8  # metres per repeat: a 2 x 2 checker, cells of 0.4 m
DARK, LIGHT = 0.2, 0.9  # the checker's linear albedos


@pytest.fixture(scope="module")
def checker(tmp_path_factory: pytest.TempPathFactory) -> str:
    """A 64 x 64 sRGB PNG: 2 x 2 cells, light in the top-left and bottom-right ones."""
    path = tmp_path_factory.mktemp("textures") / "checker.png"
    row, col = np.mgrid[0:64, 0:64]
    light = ((row // 32 + col // 32) % 2) == 0
    linear = np.where(light, LIGHT, DARK)
    srgb = np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * linear ** (1 / 2.4) - 0.055)
    pixels = np.repeat(np.round(srgb * 255).astype(np.uint8)[..., None], 3, axis=2)
    Image.fromarray(pixels, "RGB").save(path)
    return str(path)


def expected_light(position: NDArray[np.float32], centre: tuple[float, float, float]) -> tuple[NDArray[np.bool_], NDArray[np.bool_]]:
    """Where the checker is light on the -X face of a box centred at `centre` (u = -y, v = -z in metres from
    the centre, box_uv.h), and where a pixel is far enough from a cell's edge to be only one cell."""
    u = -(position[..., 1].astype(np.float64) - centre[1]) / SIZE
    v = -(position[..., 2].astype(np.float64) - centre[2]) / SIZE
    cu, cv = np.floor(2 * u), np.floor(2 * v)  # the cell, in half repeats
    light = (cu + cv) % 2 == 0
    margin = 0.06  # of a repeat: bilinear filtering and mip levels blend within it
    clear = (np.abs(2 * u - np.round(2 * u)) > 2 * margin) & (np.abs(2 * v - np.round(2 * v)) > 2 * margin)
    return light, clear


def textured_wall(game: spear.UWorld, texture: str, width: float = 10.0, size: float = SIZE) -> spear.AStaticMeshActor:
    library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Library")
    library.SetMaterial(Name="Checker", Material=spear.FMaterialDesc(
        BaseColor=spear.FLinearColor(R=1.0, G=1.0, B=1.0, A=1.0), Roughness=1.0, BaseColorTexture=texture,
        TextureSize=size))
    wall = spawn_wall(game, 5.0, material="Checker")
    wall.SetActorScale3D(NewScale3D=spear.FVector(X=0.1, Y=width, Z=10.0))
    return wall


def _base_color(instance: spear.Instance, texture: str, width: float) -> tuple[NDArray[np.float32], NDArray[np.float32]]:
    game = instance.get_game()
    with instance.begin_frame():
        textured_wall(game, texture, width)
        camera = spawn_camera(game, [M.BaseColor, M.Position], 48, 36, 60.0)
    with instance.end_frame():
        pixels = camera.read_pixels()
    return pixels["base_color"].astype(np.float32), pixels["position"].astype(np.float32)


def test_a_texture_repeats_every_texture_size_metres_whatever_the_scale(make_instance, checker: str) -> None:  # type: ignore[no-untyped-def]
    # Two walls, 10 m and 20 m wide: the same metres of checker at the same places. Mesh uvs would stretch the
    # one texture over each wall, twice as wide on the wider one.
    base, position = _base_color(make_instance(), checker, 10.0)
    wider, _ = _base_color(make_instance(), checker, 20.0)
    np.testing.assert_allclose(wider, base, atol=2e-3)
    light, clear = expected_light(position, (5.05, 0.0, 0.0))
    assert clear.sum() > 0.5 * clear.size
    seen = base[..., 0] > (DARK + LIGHT) / 2
    assert np.array_equal(seen[clear], light[clear])
    assert 0.3 < light[clear].mean() < 0.7  # cells of both kinds are in view
    # The cells' own albedos (a pixel spans several texels: filtering blends those near a cell's edge).
    assert np.median(base[..., 0][clear & light]) == pytest.approx(LIGHT, abs=0.01)
    assert np.median(base[..., 0][clear & ~light]) == pytest.approx(DARK, abs=0.01)


def test_a_texture_stays_on_a_moving_box(instance: spear.Instance, checker: str) -> None:
    # The wall and the camera move together by a distance that is no multiple of the repeat: the picture is
    # the same (world-aligned textures would slide across the wall).
    game = instance.get_game()
    with instance.begin_frame():
        wall = textured_wall(game, checker)
        camera = spawn_camera(game, [M.BaseColor], 32, 24, 60.0)
    with instance.end_frame():
        before = camera.read_pixels()["base_color"].astype(np.float32)
    with instance.begin_frame():
        at = wall.GetActorLocation()
        wall.SetActorLocation(NewLocation=spear.FVector(X=at.X, Y=at.Y + 0.37, Z=at.Z - 0.23))
        owner = camera.GetOwner()
        assert owner is not None
        owner.SetActorLocation(NewLocation=spear.FVector(X=0.0, Y=0.37, Z=-0.23))
    with instance.end_frame():
        after = camera.read_pixels()["base_color"].astype(np.float32)
    np.testing.assert_allclose(after, before, atol=2e-3)


def test_the_path_tracer_projects_textures_as_the_rasteriser(instance: spear.Instance, checker: str) -> None:
    # A uniform white sky and no bounces: each pixel's radiance is its albedo times the sky, so the light and
    # dark cells are where the rasteriser's base colour has them.
    game = instance.get_game()
    with instance.begin_frame():
        textured_wall(game, checker)
        sky = game.spawn_actor(uclass=spear.ASkyLight, name="Sky")
        sky.SkyLightComponent.SkyColor = spear.FLinearColor(R=1.0, G=1.0, B=1.0, A=1.0)
        sky.SkyLightComponent.Intensity = 1.0
        # Pixels of 9 cm on the wall, so that most lie inside one cell (a traced pixel averages its area).
        camera = path_trace(spawn_camera(game, [M.HdrColor, M.Position], 64, 48, 60.0), 16, 0)
    with instance.end_frame():
        pixels = camera.read_pixels()
    hdr = pixels["hdr_color"][..., 0].astype(np.float64)
    light, clear = expected_light(pixels["position"].astype(np.float32), (5.05, 0.0, 0.0))
    threshold = math.sqrt(np.median(hdr[clear & light]) * np.median(hdr[clear & ~light]))
    assert np.median(hdr[clear & light]) > 3.0 * np.median(hdr[clear & ~light])
    assert np.mean((hdr > threshold)[clear] == light[clear]) > 0.98


@pytest.mark.parametrize("size, shown", [(-1.0, "-1"), (math.nan, "nan"), (math.inf, "inf"), (1e-9, "1e-09")])
def test_a_texture_size_out_of_range_is_refused(instance: spear.Instance, size: float, shown: str) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Library")
        with pytest.raises(spear.InvalidArgumentError, match=(
                r"AMaterialLibrary\.SetMaterial\(\): material 'Bad': TextureSize must be 0 \(the mesh's uvs\) or "
                rf"finite and >= 1e-6 m, got {shown}")):
            library.SetMaterial(Name="Bad", Material=spear.FMaterialDesc(TextureSize=size))
        with pytest.raises(spear.InvalidArgumentError, match=r"material 'Rough': Roughness must be in \[0, 1\], got 1\.5"):
            library.SetMaterial(Name="Rough", Material=spear.FMaterialDesc(Roughness=1.5))
        library.SetMaterial(Name="Good", Material=spear.FMaterialDesc(TextureSize=0.5))  # the engine goes on
        assert library.GetMaterial(Name="Good").TextureSize == 0.5
        assert library.GetMaterial(Name="Bad") == library.GetMaterial(Name="Default")


def test_textures_named_under_game_load_from_any_working_directory(
        instance: spear.Instance, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # The default scene names its maps /Game/textures/...: found in the built-in assets, not the working
    # directory (and a missing one leaves the material's factors, as any texture that cannot be read).
    monkeypatch.chdir(tmp_path)
    plaster = np.asarray(Image.open(ROOT / "assets" / "textures" / "plaster_color.png").convert("RGB"))
    expected = ((plaster.astype(np.float64) / 255 + 0.055) / 1.055) ** 2.4  # sRGB to linear, above the knee
    game = instance.get_game()
    with instance.begin_frame():
        textured_wall(game, "/Game/textures/plaster_color.png", size=1.0)
        camera = spawn_camera(game, [M.BaseColor], 16, 12, 30.0)
    with instance.end_frame():
        base = camera.read_pixels()["base_color"].astype(np.float64)
    np.testing.assert_allclose(base.mean(axis=(0, 1)), expected.mean(axis=(0, 1)), rtol=0.03)


@pytest.mark.parametrize("packed", [False, True], ids=["own file", "orm"])
def test_an_occlusion_texture_multiplies_material_ao_and_the_ambient_light(
        instance: spear.Instance, tmp_path: Path, packed: bool) -> None:
    # The checker's cells occlude 0.2 and 0.9 in R (linear bytes), its own file or an ORM map's R beside
    # roughness in G: material_ao is AmbientOcclusion times R, and under a sky light alone (all of it
    # ambient) the diffuse illumination follows it. With no occlusion map R is not read: material_ao is the
    # factor (the ORM map's file as RoughnessMetallicTexture only).
    row, col = np.mgrid[0:64, 0:64]
    occluded = np.where(((row // 32 + col // 32) % 2) == 0, 0.9, 0.2)
    rgb = np.stack([np.round(occluded * 255), np.full_like(occluded, 255), np.zeros_like(occluded)], axis=-1)
    path = tmp_path / "orm.png"
    Image.fromarray(rgb.astype(np.uint8), "RGB").save(path)
    game = instance.get_game()
    with instance.begin_frame():
        library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Library")
        for name, occlusion in (("Occluded", str(path)), ("Plain", "")):
            library.SetMaterial(Name=name, Material=spear.FMaterialDesc(
                BaseColor=spear.FLinearColor(R=1.0, G=1.0, B=1.0, A=1.0), Roughness=1.0, AmbientOcclusion=0.5,
                OcclusionTexture=occlusion, TextureSize=SIZE,
                RoughnessMetallicTexture=str(path) if packed or name == "Plain" else ""))
        wall = spawn_wall(game, 5.0, material="Occluded")
        sky = game.spawn_actor(uclass=spear.ASkyLight, name="Sky")
        sky.SkyLightComponent.SkyColor = spear.FLinearColor(R=1.0, G=1.0, B=1.0, A=1.0)
        camera = spawn_camera(game, [M.MaterialAo, M.DiffuseIllumination, M.Position], 48, 36, 60.0)
    with instance.end_frame():
        pixels = camera.read_pixels()
    ao = pixels["material_ao"].astype(np.float64)
    irradiance = pixels["diffuse_illumination"][..., 0].astype(np.float64)
    light, clear = expected_light(pixels["position"].astype(np.float32), (5.05, 0.0, 0.0))
    assert np.median(ao[clear & light]) == pytest.approx(0.5 * 230 / 255, abs=0.01)
    assert np.median(ao[clear & ~light]) == pytest.approx(0.5 * 51 / 255, abs=0.01)
    ratio = np.median(irradiance[clear & ~light]) / np.median(irradiance[clear & light])
    assert ratio == pytest.approx(51 / 230, rel=0.1)
    with instance.begin_frame():
        wall.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Plain")
    with instance.end_frame():
        plain = camera.read_pixels()["material_ao"].astype(np.float64)
    np.testing.assert_allclose(plain, 0.5, atol=2e-3)
