"""The rasteriser's global illumination (UCameraSensorComponent.GlobalIlluminationQuality): off by default, a
closed room lit from inside as bright as the path tracer says, no sunlight leaking through its walls, a moved
lamp reaching the image, and bad values refused; screen-space ambient occlusion (AmbientOcclusionIntensity,
off by default); both transports."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.typing import NDArray

import spear
from test_camera import spawn_camera

M = spear.ECameraModality
Q = spear.EGlobalIlluminationQuality


def _closed_room(game: spear.UWorld, sun: bool) -> spear.APointLight:
    """A closed white room (inside 4 x 3 x 2.5 m, walls 0.2 m) with a lamp inside; optionally a sun outside."""
    library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Library")
    library.SetMaterial(Name="White", Material=spear.FMaterialDesc(
        BaseColor=spear.FLinearColor(R=0.8, G=0.8, B=0.8, A=1.0), Roughness=1.0))
    t = 0.2
    for name, location, scale in [("Floor", (0.0, 0.0, -t / 2), (4.4, 3.4, t)),
                                  ("Ceiling", (0.0, 0.0, 2.5 + t / 2), (4.4, 3.4, t)),
                                  ("WallN", (2.0 + t / 2, 0.0, 1.25), (t, 3.0, 2.5)),
                                  ("WallS", (-2.0 - t / 2, 0.0, 1.25), (t, 3.0, 2.5)),
                                  ("WallW", (0.0, 1.5 + t / 2, 1.25), (4.4, t, 2.5)),
                                  ("WallE", (0.0, -1.5 - t / 2, 1.25), (4.4, t, 2.5))]:
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name=name, location=spear.FVector(*location))
        actor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        actor.StaticMeshComponent.SetRelativeScale3D(NewScale3D=spear.FVector(*scale))
        actor.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="White")
    lamp = game.spawn_actor(uclass=spear.APointLight, name="Lamp", location=spear.FVector(0.5, 0.3, 2.2))
    lamp.LightComponent.Intensity = 10.0
    if sun:
        game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun",
                         rotation=spear.FRotator(Pitch=-60.0, Yaw=30.0)).LightComponent.Intensity = 100.0
    return lamp


def _room_camera(game: spear.UWorld, quality: spear.EGlobalIlluminationQuality | None, name: str = "Camera"
                 ) -> spear.UCameraSensorComponent:
    """A camera in the closed room seeing diffuse_illumination; quality None leaves the camera's default."""
    camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name=name, location=spear.FVector(-1.8, -1.3, 1.8),
                              rotation=spear.FRotator(Pitch=-15.0, Yaw=30.0)).CameraSensor
    camera.Width, camera.Height, camera.FOV = 48, 32, 90.0
    camera.Modalities = [M.DiffuseIllumination]
    if quality is not None:
        camera.GlobalIlluminationQuality = quality
    return camera


def _mean_illumination(camera: spear.UCameraSensorComponent) -> float:
    pixels = camera.read_pixels()
    assert "diffuse_illumination" in pixels
    return float(pixels["diffuse_illumination"].astype(np.float64).mean())


def test_global_illumination_is_on_by_default(instance: spear.Instance) -> None:
    # Medium, as Unreal's cameras have global illumination on (core/render/README.md): a default camera in the
    # closed room lit from inside sees the indirect light a camera asking for Medium sees.
    game = instance.get_game()
    with instance.begin_frame():
        _closed_room(game, sun=False)
        default = _room_camera(game, None, "Default")
        assert default.GlobalIlluminationQuality == Q.Medium
        cameras = {q: _room_camera(game, q, q.name) for q in (Q.Off, Q.Medium)}
    with instance.end_frame():
        seen = _mean_illumination(default)
        means = {q: _mean_illumination(c) for q, c in cameras.items()}
    assert seen == means[Q.Medium]
    assert seen > 1.3 * means[Q.Off], (seen, means)


def test_a_closed_room_lit_from_inside_is_as_bright_as_the_path_tracer_says(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _closed_room(game, sun=False)
        cameras = {q: _room_camera(game, q, q.name) for q in (Q.Off, Q.Medium)}
        traced = _room_camera(game, Q.Off, "Traced")
        traced.Renderer = spear.ECameraRenderer.PathTraced
        traced.SamplesPerPixel = 64
        traced.MaxBounces = 4  # the probes' 3 bounces after the surface they see, and that one
    with instance.end_frame():
        means = {q: _mean_illumination(c) for q, c in cameras.items()}
        reference = _mean_illumination(traced)
    assert means[Q.Off] < 0.75 * reference  # direct light and a constant sky term fall short
    assert means[Q.Medium] == pytest.approx(reference, rel=0.08), (means, reference)


def test_sunlight_outside_a_closed_room_does_not_leak_in(make_instance: object) -> None:
    means = []
    for sun in (False, True):
        instance = make_instance()  # type: ignore[operator]
        assert isinstance(instance, spear.Instance)
        game = instance.get_game()
        with instance.begin_frame():
            _closed_room(game, sun)
            camera = _room_camera(game, Q.Medium)
        with instance.end_frame():
            means.append(_mean_illumination(camera))
    assert means[1] == pytest.approx(means[0], rel=0.05)


def test_a_moved_lamp_reaches_the_indirect_light_within_the_stated_frames(instance: spear.Instance) -> None:
    # Medium lights 32 probes a frame after a change; the room's grid (its box and a quarter of its longest side
    # around it, 0.5 m apart: 14 x 12 x 11 probes) has fewer than 32 x 64.
    game = instance.get_game()
    with instance.begin_frame():
        lamp = _closed_room(game, sun=False)
        camera = _room_camera(game, Q.Medium)
    with instance.end_frame():
        before = _mean_illumination(camera)
    with instance.begin_frame():
        lamp.LightComponent.Intensity = 40.0
    with instance.end_frame():
        pass
    for _ in range(64):
        with instance.begin_frame():
            pass
        with instance.end_frame():
            after = _mean_illumination(camera)
    assert after == pytest.approx(4.0 * before, rel=0.03)


def test_a_bad_quality_is_refused(instance: spear.Instance) -> None:
    with instance.begin_frame():
        camera = spawn_camera(instance.get_game(), [M.FinalColor])
        with pytest.raises(TypeError, match="GlobalIlluminationQuality"):
            camera.GlobalIlluminationQuality = 7  # type: ignore[assignment]
        assert camera.GlobalIlluminationQuality == Q.Medium  # the default, unchanged
    with instance.end_frame():
        pass


def test_the_path_tracer_denoiser_brings_few_samples_closer_to_many(instance: spear.Instance) -> None:
    # The closed room path traced at 4 samples per pixel, with and without bPathTracingEnableDenoiser, against
    # 512: the denoised hdr_color is less than 0.6x as far from it (0.42x when written), over all but the
    # brightest hundredth of the pixels: the lamp's hot spot on the ceiling, seen directly, whose pixels differ by
    # where their samples fell, direct light the filter keeps as it is. The intrinsic images stay unfiltered.
    # (Four samples: the lamp's light-vertex connections leave 16 of this room nearly as clean as a filter would.)
    game = instance.get_game()
    with instance.begin_frame():
        _closed_room(game, sun=False)
        cameras = []
        for name, samples, denoise in (("Raw", 4, False), ("Denoised", 4, True), ("Reference", 512, False)):
            camera = _room_camera(game, Q.Off, name)
            camera.Modalities = [M.HdrColor, M.DiffuseOnly]
            camera.Renderer = spear.ECameraRenderer.PathTraced
            camera.SamplesPerPixel = samples
            camera.bPathTracingEnableDenoiser = denoise
            cameras.append(camera)
    with instance.end_frame():
        raw, denoised, reference = (camera.read_pixels() for camera in cameras)
    assert "hdr_color" in raw and "hdr_color" in denoised and "hdr_color" in reference
    assert "diffuse_only" in raw and "diffuse_only" in denoised
    truth = reference["hdr_color"][..., :3].astype(np.float64)
    brightness = truth.mean(axis=2)
    indirect = brightness <= np.percentile(brightness, 99)

    def rmse(image: NDArray[np.float16]) -> float:
        return float(np.sqrt(((image[..., :3].astype(np.float64) - truth)[indirect] ** 2).mean()))

    assert rmse(denoised["hdr_color"]) < 0.6 * rmse(raw["hdr_color"])
    assert np.array_equal(raw["diffuse_only"], denoised["diffuse_only"])


def test_the_path_tracers_firefly_clamp_is_off_by_default_and_refuses_bad_values(instance: spear.Instance) -> None:
    with instance.begin_frame():
        camera = spawn_camera(instance.get_game(), [M.HdrColor])
        assert camera.PathTracingMaxPathIntensity == 0.0  # the unbiased reference
        for bad in (-1.0, float("nan")):
            with pytest.raises(spear.InvalidArgumentError,
                               match=r"UCameraSensorComponent.PathTracingMaxPathIntensity must be >= 0, got"):
                camera.PathTracingMaxPathIntensity = bad
        camera.PathTracingMaxPathIntensity = 10.0
        camera.Renderer = spear.ECameraRenderer.PathTraced
    with instance.end_frame():
        pixels = camera.read_pixels()
        assert camera.PathTracingMaxPathIntensity == 10.0
    assert np.isfinite(pixels["hdr_color"].astype(np.float64)).all()



def test_ambient_occlusion_darkens_a_crates_foot_and_is_off_by_default(instance: spear.Instance) -> None:
    # The sky light on a ground and a crate, no lights: with AmbientOcclusionIntensity the ground at the crate's
    # foot is darker, the ground far from it is not, and the exact modalities do not change; off by default;
    # bad values refused with the property's range.
    game = instance.get_game()
    with instance.begin_frame():
        ground = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground")
        ground.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Plane")
        ground.SetActorScale3D(NewScale3D=spear.FVector(20.0, 20.0, 1.0))
        crate = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Crate", location=spear.FVector(Z=0.5))
        crate.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        game.spawn_actor(uclass=spear.ASkyLight, name="Sky").SkyLightComponent.Intensity = 1.0
        cameras = []
        for name in ("Plain", "Occluded"):
            actor = game.spawn_actor(uclass=spear.ACameraSensorActor, name=name, location=spear.FVector(-3.0, -2.5, 2.2),
                                     rotation=spear.FRotator(Pitch=-30.0, Yaw=40.0))
            camera = actor.CameraSensor
            camera.Width, camera.Height, camera.FOV = 96, 72, 60.0
            camera.Modalities = [M.DiffuseIllumination, M.Position, M.ObjectIds, M.Depth]
            camera.GlobalIlluminationQuality = Q.Off  # the sky's uniform term alone: all it scales
            cameras.append(camera)
        plain, occluded = cameras
        assert plain.AmbientOcclusionIntensity == 0.0 and plain.AmbientOcclusionRadius == 0.5
        occluded.AmbientOcclusionIntensity = 1.0
        for prop, value, message in [("AmbientOcclusionIntensity", 1.5, r"AmbientOcclusionIntensity must be in \[0, 1\], got 1.5"),
                                     ("AmbientOcclusionIntensity", -0.5, r"must be in \[0, 1\], got -0.5"),
                                     ("AmbientOcclusionRadius", 0.0, r"AmbientOcclusionRadius must be in \(0, 100\] metres, got 0"),
                                     ("AmbientOcclusionRadius", 200.0, r"must be in \(0, 100\] metres, got 200")]:
            with pytest.raises(spear.InvalidArgumentError, match=message):
                setattr(occluded, prop, value)
        assert occluded.AmbientOcclusionIntensity == 1.0 and occluded.AmbientOcclusionRadius == 0.5
    with instance.end_frame():
        a, b = plain.read_pixels(), occluded.read_pixels()
    np.testing.assert_array_equal(a["position"], b["position"])
    np.testing.assert_array_equal(a["object_ids"], b["object_ids"])
    np.testing.assert_array_equal(a["depth"], b["depth"])
    ground_id = int(np.bincount(a["object_ids"].ravel()).argmax())  # the ground fills most of the view
    on_ground = a["object_ids"] == ground_id
    x, y = a["position"][..., 0], a["position"][..., 1]
    distance = np.hypot(np.maximum(np.abs(x) - 0.5, 0.0), np.maximum(np.abs(y) - 0.5, 0.0))
    ratio = b["diffuse_illumination"][..., 0].astype(np.float64) / a["diffuse_illumination"][..., 0].astype(np.float64)
    near, far = on_ground & (distance < 0.1), on_ground & (distance > 0.6)
    assert near.sum() > 5 and far.sum() > 1000
    assert ratio[near].mean() < 0.95  # a light ground: the light its neighbours reflect makes up for some
    assert ratio[far].min() > 0.99
