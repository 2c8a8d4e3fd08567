"""Sky and environment light (ASkyAtmosphere, USkyLightComponent.SourceType and Cubemap): faces away from the sun
lit by the sky, the sky or the panorama as the background, both renderers alike, and bad settings refused; both
transports."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

import spear

M = spear.ECameraModality
S = spear.ESkyLightSourceType

PARK = "assets/environments/park.exr"


def _outdoor(game: spear.UWorld, atmosphere: bool, source: spear.ESkyLightSourceType | None = None,
             ) -> spear.UCameraSensorComponent:
    """A white cube under a sun shining along +X; the camera, on the +X side, sees the face away from the sun
    and the sky above the horizon behind it."""
    game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun",
                     rotation=spear.FRotator(Pitch=-40.0, Yaw=0.0)).LightComponent.Intensity = 3.0
    cube = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Cube", location=spear.FVector(0.0, 0.0, 1.0))
    cube.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
    cube.StaticMeshComponent.SetRelativeScale3D(NewScale3D=spear.FVector(1.0, 2.0, 2.0))
    if atmosphere:
        game.spawn_actor(uclass=spear.ASkyAtmosphere, name="Atmosphere")
    if source is not None:
        sky = game.spawn_actor(uclass=spear.ASkyLight, name="Sky").SkyLightComponent
        if source == S.SLS_SpecifiedCubemap:
            sky.Intensity = 1.0  # the panorama as it is
        sky.SourceType = source
        if source == S.SLS_SpecifiedCubemap:
            sky.Cubemap = PARK
    camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera", location=spear.FVector(4.0, 0.0, 1.0),
                              rotation=spear.FRotator(Yaw=180.0)).CameraSensor
    camera.Width, camera.Height, camera.FOV = 48, 32, 70.0
    camera.Modalities = [M.HdrColor, M.ObjectIds]
    return camera


def _luminance(image: NDArray[Any]) -> NDArray[np.float64]:
    rgb = image[..., :3].astype(np.float64)
    result: NDArray[np.float64] = 0.2126 * rgb[..., 0] + 0.7152 * rgb[..., 1] + 0.0722 * rgb[..., 2]
    return result


def _linear(final: NDArray[Any]) -> NDArray[np.float64]:
    """final_color's sRGB-encoded values in linear light."""
    c = final[..., :3].astype(np.float64) / 255.0
    result: NDArray[np.float64] = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return result


def _render(instance: spear.Instance, atmosphere: bool, source: spear.ESkyLightSourceType | None = None,
            world: str | None = None) -> dict[str, NDArray[np.generic]]:
    with instance.begin_frame():
        game = instance.create_world(name=world) if world else instance.get_game()
        camera = _outdoor(game, atmosphere, source)
    with instance.end_frame():
        return dict(camera.read_pixels())


def test_the_sky_atmosphere_lights_the_faces_away_from_the_sun_and_is_the_background(
        instance: spear.Instance) -> None:
    lit = _render(instance, atmosphere=True)
    ids = lit["object_ids"]
    face, sky = ids != 0, ids == 0
    assert face.sum() > 200 and sky[:4].all()  # the cube's face in the middle, sky along the top rows
    face_with_sky = float(_luminance(lit["hdr_color"])[face].mean())
    background = lit["hdr_color"][:4].astype(np.float64)
    assert background[..., 2].mean() > background[..., 0].mean() > 0.0  # a blue sky

    unlit = _render(instance, atmosphere=False, world="Uniform")
    face_uniform = float(_luminance(unlit["hdr_color"])[unlit["object_ids"] != 0].mean())
    # The renderer's default uniform sky (0.03) against the sky a clear day gives a face in the shade.
    assert face_with_sky > 2.0 * face_uniform
    assert float(np.abs(unlit["hdr_color"][:4, :, :3].astype(np.float64)).max()) == 0.0  # black without a sky


def test_a_default_sky_light_captures_the_atmosphere_as_bright_as_it_is(instance: spear.Instance) -> None:
    # The sky light's Intensity (0.03 by default) is the uniform sky's radiance: it does not dim the sky the
    # atmosphere's sun makes, which the sky light captures as it is.
    alone = _render(instance, atmosphere=True)
    captured = _render(instance, atmosphere=True, source=S.SLS_CapturedScene, world="Captured")
    for pixels in (alone, captured):
        assert _luminance(pixels["hdr_color"])[pixels["object_ids"] == 0].mean() > 0.05
    assert np.array_equal(alone["hdr_color"], captured["hdr_color"])


def test_a_cubemap_lights_the_world_and_is_its_background(instance: spear.Instance) -> None:
    pixels = _render(instance, atmosphere=False, source=S.SLS_SpecifiedCubemap)
    hdr, ids = pixels["hdr_color"].astype(np.float64), pixels["object_ids"]
    background = _luminance(pixels["hdr_color"])[ids == 0]
    assert background.min() > 0.0 and background.std() > 0.01  # a photograph, not a colour
    assert float(_luminance(pixels["hdr_color"])[ids != 0].mean()) > 0.05
    assert np.isfinite(hdr).all()


def test_a_radiance_hdr_panorama_is_read(instance: spear.Instance, tmp_path: Path) -> None:
    # A flat RGBE file of 16 x 8 texels of radiance 0.5 (mantissa 128, exponent 128): the background is 0.5.
    path = tmp_path / "grey.hdr"
    path.write_bytes(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 16\n" + bytes([128, 128, 128, 128]) * 128)
    with instance.begin_frame():
        camera = _outdoor(instance.get_game(), atmosphere=False)
        sky = instance.get_game().spawn_actor(uclass=spear.ASkyLight, name="Panorama").SkyLightComponent
        sky.SourceType, sky.Intensity, sky.Cubemap = S.SLS_SpecifiedCubemap, 1.0, str(path)
    with instance.end_frame():
        pixels = camera.read_pixels()
    background = pixels["hdr_color"][..., :3][pixels["object_ids"] == 0].astype(np.float64)
    assert background == pytest.approx(np.full_like(background, 0.5), abs=1e-3)


def test_the_sky_lights_a_convex_object_alike_in_both_renderers(instance: spear.Instance) -> None:
    with instance.begin_frame():
        raster = _outdoor(instance.get_game(), atmosphere=True)
        traced = instance.get_game().spawn_actor(
            uclass=spear.ACameraSensorActor, name="Traced", location=spear.FVector(4.0, 0.0, 1.0),
            rotation=spear.FRotator(Yaw=180.0)).CameraSensor
        traced.Width, traced.Height, traced.FOV = raster.Width, raster.Height, raster.FOV
        for camera in (raster, traced):
            camera.Modalities = [M.HdrColor, M.FinalColor, M.ObjectIds]
            camera.Exposure = 1.5  # the same exposure: the same final_color (the tone curve is shared)
        traced.Renderer = spear.ECameraRenderer.PathTraced
        traced.SamplesPerPixel = 64
    with instance.end_frame():
        a, b = raster.read_pixels(), traced.read_pixels()
    face = a["object_ids"] != 0
    ratio = _luminance(a["hdr_color"])[face].mean() / _luminance(b["hdr_color"])[face].mean()
    assert ratio == pytest.approx(1.0, abs=0.08)
    final = [_luminance(_linear(p["final_color"]))[face].mean() for p in (a, b)]
    assert final[0] / final[1] == pytest.approx(1.0, abs=0.08)
    sky = a["object_ids"] == 0
    assert _luminance(a["hdr_color"])[sky].mean() == pytest.approx(_luminance(b["hdr_color"])[sky].mean(), rel=0.03)


def test_sky_settings_out_of_range_are_refused(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        atmosphere = game.spawn_actor(uclass=spear.ASkyAtmosphere, name="Atmosphere").SkyAtmosphereComponent
        with pytest.raises(spear.InvalidArgumentError,
                           match=r"USkyAtmosphereComponent.Turbidity must be in \[1.7, 10\], got 12"):
            atmosphere.Turbidity = 12.0
        assert atmosphere.Turbidity == 3.0
        with pytest.raises(spear.InvalidArgumentError, match=r"GroundAlbedo must be in \[0, 1\] per channel"):
            atmosphere.GroundAlbedo = spear.FLinearColor(R=2.0, G=0.5, B=0.5, A=1.0)
        sky = game.spawn_actor(uclass=spear.ASkyLight, name="Sky").SkyLightComponent
        with pytest.raises(spear.InvalidArgumentError, match=r"USkyLightComponent.Intensity must be >= 0, got -1"):
            sky.Intensity = -1.0
        with pytest.raises(spear.NotFoundError, match=r"USkyLightComponent.Cubemap: no file 'missing.exr'"):
            sky.Cubemap = "missing.exr"
        with pytest.raises(spear.InvalidArgumentError,
                           match=r"Cubemap must be an OpenEXR \(.exr\) or Radiance HDR \(.hdr\) file, got 'a.png'"):
            sky.Cubemap = "a.png"
        with pytest.raises(TypeError, match="SourceType"):
            sky.SourceType = 5  # type: ignore[assignment]
        assert sky.Intensity == pytest.approx(0.03) and sky.Cubemap == "" and sky.SourceType == S.SLS_CapturedScene
    with instance.end_frame():
        pass
