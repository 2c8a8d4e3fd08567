"""Anti-aliasing of final_color (UCameraSensorComponent.AntiAliasingMethod): FXAA by default and MSAA, each
closer to a supersampled view than no anti-aliasing; SpatialSampleCount (supersampling) closer still; the
exact modalities untouched, and bad settings refused; anisotropic texture filtering (MaxAnisotropy) and the
textures' mip bias (MipMapLODBias); both transports."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

import spear

M = spear.ECameraModality
A = spear.EAntiAliasingMethod


def _scene(game: spear.UWorld) -> None:
    """Boxes on a ground under a sun: silhouettes at every slope."""
    game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun",
                     rotation=spear.FRotator(Pitch=-50.0, Yaw=30.0)).LightComponent.Intensity = 3.0
    for name, location, scale, yaw in [("Ground", (0.0, 0.0, -0.05), (20.0, 20.0, 0.1), 0.0),
                                       ("Box", (0.5, 0.3, 0.5), (1.0, 1.0, 1.0), 27.0),
                                       ("Post", (-0.6, -0.9, 0.8), (0.2, 0.2, 1.6), 10.0)]:
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name=name, location=spear.FVector(*location),
                                 rotation=spear.FRotator(Yaw=yaw))
        actor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        actor.StaticMeshComponent.SetRelativeScale3D(NewScale3D=spear.FVector(*scale))


def _camera(game: spear.UWorld, name: str, scale: int, method: spear.EAntiAliasingMethod | None
            ) -> spear.UCameraSensorComponent:
    camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name=name, location=spear.FVector(-4.0, -2.0, 2.0),
                              rotation=spear.FRotator(Pitch=-20.0, Yaw=25.0)).CameraSensor
    camera.Width, camera.Height, camera.FOV = 96 * scale, 64 * scale, 60.0
    camera.Modalities = [M.FinalColor, M.Depth, M.ObjectIds]
    if method is not None:
        camera.AntiAliasingMethod = method
    return camera


def _linear(final: NDArray[Any]) -> NDArray[np.float64]:
    c = final[..., :3].astype(np.float64) / 255.0
    result: NDArray[np.float64] = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return result


def test_fxaa_is_the_default_and_brings_final_color_closer_to_a_supersampled_view(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _scene(game)
        default = _camera(game, "Default", 1, None)
        plain = _camera(game, "Plain", 1, A.AAM_None)
        large = _camera(game, "Large", 4, A.AAM_None)
        assert default.AntiAliasingMethod == A.AAM_FXAA
    with instance.end_frame():
        filtered, aliased, big = default.read_pixels(), plain.read_pixels(), large.read_pixels()

    # The exact modalities are the unfiltered camera's, bit for bit.
    assert np.array_equal(filtered["depth"], aliased["depth"])
    assert np.array_equal(filtered["object_ids"], aliased["object_ids"])
    # final_color: the 4 x 4 supersampled view averaged down in linear light is the reference.
    reference = _linear(big["final_color"]).reshape(64, 4, 96, 4, 3).mean(axis=(1, 3))
    error = [float(np.abs(_linear(p["final_color"]) - reference).mean()) for p in (aliased, filtered)]
    assert error[1] < 0.8 * error[0], error
    assert not np.array_equal(filtered["final_color"], aliased["final_color"])


def test_msaa_comes_closest_to_a_supersampled_view(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _scene(game)
        cameras = {method: _camera(game, method.name, 1, method) for method in A}
        cameras[A.AAM_MSAA].Modalities = [M.FinalColor, M.Depth, M.ObjectIds, M.HdrColor]
        large = _camera(game, "Large", 4, A.AAM_None)
    with instance.end_frame():
        pixels = {method: camera.read_pixels() for method, camera in cameras.items()}
        big = large.read_pixels()
    reference = _linear(big["final_color"]).reshape(64, 4, 96, 4, 3).mean(axis=(1, 3))
    error = {method: float(np.abs(_linear(p["final_color"]) - reference).mean()) for method, p in pixels.items()}
    assert error[A.AAM_MSAA] < 0.6 * error[A.AAM_None], error
    assert error[A.AAM_MSAA] < error[A.AAM_FXAA], error
    none, msaa = pixels[A.AAM_None], pixels[A.AAM_MSAA]
    assert np.array_equal(msaa["object_ids"], none["object_ids"])
    assert np.allclose(msaa["depth"], none["depth"], rtol=0, atol=0)
    assert msaa["hdr_color"].dtype == np.float16 and msaa["hdr_color"].shape == (64, 96, 4)


def test_spatial_samples_come_closest_to_a_supersampled_view(instance: spear.Instance) -> None:
    """Against the view 17 x 17 times larger averaged down: finer than any pattern, and sharing none of their
    points (a 4 x 4 grid holds MSAA's four and would favour it)."""
    game = instance.get_game()
    with instance.begin_frame():
        _scene(game)
        cameras = {n: _camera(game, f"Sampled{n}", 1, A.AAM_None) for n in (1, 4, 16)}
        for n, camera in cameras.items():
            camera.SpatialSampleCount = n
        cameras[16].Modalities = [M.FinalColor, M.Depth, M.ObjectIds, M.HdrColor]
        msaa = _camera(game, "Msaa", 1, A.AAM_MSAA)
        large = _camera(game, "Large", 17, A.AAM_None)
        assert cameras[1].SpatialSampleCount == 1
    with instance.end_frame():
        pixels = {n: camera.read_pixels() for n, camera in cameras.items()}
        multisampled, big = msaa.read_pixels(), large.read_pixels()
    reference = _linear(big["final_color"]).reshape(64, 17, 96, 17, 3).mean(axis=(1, 3))
    error = {n: float(np.abs(_linear(p["final_color"]) - reference).mean()) for n, p in pixels.items()}
    error_msaa = float(np.abs(_linear(multisampled["final_color"]) - reference).mean())
    assert error[16] < error[4] < error_msaa < error[1], (error, error_msaa)
    assert error[16] < 0.5 * error_msaa, (error, error_msaa)
    none, ss = pixels[1], pixels[16]
    assert np.array_equal(ss["object_ids"], none["object_ids"])
    assert np.array_equal(ss["depth"], none["depth"])
    assert ss["final_color"].shape == (64, 96, 4) and ss["hdr_color"].shape == (64, 96, 4)


def test_bad_settings_are_refused(instance: spear.Instance) -> None:
    with instance.begin_frame():
        camera = _camera(instance.get_game(), "Camera", 1, None)
        with pytest.raises(TypeError, match="AntiAliasingMethod"):
            camera.AntiAliasingMethod = 2  # type: ignore[assignment]
        assert camera.AntiAliasingMethod == A.AAM_FXAA
        with pytest.raises(spear.InvalidArgumentError, match=r"MSAASampleCount must be 2, 4 or 8, got 3"):
            camera.MSAASampleCount = 3
        assert camera.MSAASampleCount == 4
        with pytest.raises(spear.InvalidArgumentError, match=r"SpatialSampleCount must be 1, 2, 4, 8 or 16, got 3"):
            camera.SpatialSampleCount = 3
        with pytest.raises(TypeError, match="SpatialSampleCount"):
            camera.SpatialSampleCount = 4.0  # type: ignore[assignment]
        assert camera.SpatialSampleCount == 1
        camera.MSAASampleCount = 8  # more than llvmpipe offers: its most
        camera.AntiAliasingMethod = A.AAM_MSAA
        camera.SpatialSampleCount = 2  # each sample's pass multisampled
    with instance.end_frame():
        assert camera.read_pixels()["final_color"].shape == (64, 96, 4)


def test_anisotropic_textures_come_closer_to_a_supersampled_floor(instance: spear.Instance) -> None:
    """The default scene's planks seen along the floor: MaxAnisotropy 8, and the default (0: anisotropic
    everywhere, in the sampler on a GPU, in the shader on a software rasteriser), nearer a 4 x 4 supersampled
    view than trilinear filtering (1); the exact modalities are the same with each."""
    from pathlib import Path

    game = instance.get_game()
    with instance.begin_frame():
        game.load_scene(path=str(Path(__file__).resolve().parents[2] / "assets" / "scenes" / "apartment.json"))
        cameras = {}
        for name, scale, anisotropy in [("Default", 1, 0), ("Trilinear", 1, 1), ("Anisotropic", 1, 8),
                                        ("Large", 4, 1)]:
            camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name=name,
                                      location=spear.FVector(-2.5, 0.5, 0.4),
                                      rotation=spear.FRotator(Pitch=-8.0, Yaw=0.0)).CameraSensor
            camera.Width, camera.Height, camera.FOV = 96 * scale, 64 * scale, 70.0
            camera.Modalities = [M.FinalColor, M.Depth, M.ObjectIds]
            camera.AntiAliasingMethod = A.AAM_None
            camera.GlobalIlluminationQuality = spear.EGlobalIlluminationQuality.Off
            camera.MaxAnisotropy = anisotropy
            cameras[name] = camera
        assert cameras["Default"].MaxAnisotropy == 0 and cameras["Anisotropic"].MaxAnisotropy == 8
    with instance.end_frame():
        pixels = {name: camera.read_pixels() for name, camera in cameras.items()}
    reference = _linear(pixels["Large"]["final_color"]).reshape(64, 4, 96, 4, 3).mean(axis=(1, 3))
    error = {name: float(np.abs(_linear(pixels[name]["final_color"]) - reference).mean())
             for name in ("Trilinear", "Anisotropic", "Default")}
    assert error["Anisotropic"] < 0.9 * error["Trilinear"], error
    assert error["Default"] < 0.9 * error["Trilinear"], error
    for key in ("depth", "object_ids"):
        assert np.array_equal(pixels["Anisotropic"][key], pixels["Trilinear"][key])
        assert np.array_equal(pixels["Default"][key], pixels["Trilinear"][key])


def test_max_anisotropy_out_of_range_is_refused(instance: spear.Instance) -> None:
    with instance.begin_frame():
        camera = _camera(instance.get_game(), "Camera", 1, None)
        for bad in (-1, 17):
            with pytest.raises(spear.InvalidArgumentError,
                               match=rf"MaxAnisotropy must be 0 \(the renderer's default\) or in \[1, 16\], got {bad}"):
                camera.MaxAnisotropy = bad
        with pytest.raises(TypeError, match="MaxAnisotropy"):
            camera.MaxAnisotropy = 2.5  # type: ignore[assignment]
        assert camera.MaxAnisotropy == 0
    with instance.end_frame():
        pass


def test_a_finer_mip_level_brings_the_default_scenes_textures_closer_to_a_supersampled_view(
        instance: spear.Instance) -> None:
    """The default scene's plaster, planks and tiles: MipMapLODBias -1 nearer a 4 x 4 supersampled view (read at
    bias 0) than the default, 0; depth and ids the same."""
    from pathlib import Path

    game = instance.get_game()
    with instance.begin_frame():
        game.load_scene(path=str(Path(__file__).resolve().parents[2] / "assets" / "scenes" / "apartment.json"))
        cameras = {}
        for name, scale, bias in [("Default", 1, None), ("Finer", 1, -1.0), ("Large", 4, 0.0)]:
            camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name=name,
                                      location=spear.FVector(-2.6, -1.6, 1.7),
                                      rotation=spear.FRotator(Pitch=-18.0, Yaw=22.0)).CameraSensor
            camera.Width, camera.Height, camera.FOV = 96 * scale, 64 * scale, 75.0
            camera.Modalities = [M.FinalColor, M.Depth, M.ObjectIds]
            camera.AntiAliasingMethod = A.AAM_None
            camera.GlobalIlluminationQuality = spear.EGlobalIlluminationQuality.Off
            if bias is not None:
                camera.MipMapLODBias = bias
            cameras[name] = camera
        assert cameras["Default"].MipMapLODBias == 0.0 and cameras["Finer"].MipMapLODBias == -1.0
    with instance.end_frame():
        pixels = {name: camera.read_pixels() for name, camera in cameras.items()}
    reference = _linear(pixels["Large"]["final_color"]).reshape(64, 4, 96, 4, 3).mean(axis=(1, 3))
    error = {name: float(np.abs(_linear(pixels[name]["final_color"]) - reference).mean())
             for name in ("Default", "Finer")}
    assert error["Finer"] < 0.95 * error["Default"], error
    for key in ("depth", "object_ids"):
        assert np.array_equal(pixels["Finer"][key], pixels["Default"][key])


def test_mip_bias_out_of_range_is_refused(instance: spear.Instance) -> None:
    with instance.begin_frame():
        camera = _camera(instance.get_game(), "Camera", 1, None)
        for bad in (-2.5, 3.0, float("nan")):
            with pytest.raises(spear.InvalidArgumentError, match=r"MipMapLODBias must be \[-2, 2\], got "):
                camera.MipMapLODBias = bad
        with pytest.raises(TypeError, match="MipMapLODBias"):
            camera.MipMapLODBias = "sharp"  # type: ignore[assignment]
        assert camera.MipMapLODBias == 0.0
        camera.MipMapLODBias = -2  # an int is a float
        assert camera.MipMapLODBias == -2.0
    with instance.end_frame():
        pass
