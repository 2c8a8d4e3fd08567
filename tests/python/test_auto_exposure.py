"""Automatic exposure (UCameraSensorComponent.AutoExposure*): off by default; a dim and a bright room shown
alike; the first frame exposed for what it shows; adaptation at AutoExposureSpeedUp / SpeedDown f-stops per
second of world time; ResetAutoExposure() as a camera cut; the path tracer metered the same way; bad and
contradictory settings refused. Both transports."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import spear
from test_global_illumination import _closed_room

M = spear.ECameraModality
A = spear.EAutoExposureMethod


def _camera(game: spear.UWorld, name: str, method: spear.EAutoExposureMethod,
            quality: spear.EGlobalIlluminationQuality = spear.EGlobalIlluminationQuality.Medium
            ) -> spear.UCameraSensorComponent:
    """A camera in _closed_room's room, 64 x 48, final_color only."""
    camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name=name, location=spear.FVector(-1.8, -1.3, 1.8),
                              rotation=spear.FRotator(Pitch=-15.0, Yaw=30.0)).CameraSensor
    camera.Width, camera.Height = 64, 48
    camera.Modalities = [M.FinalColor]
    camera.AutoExposureMethod = method
    camera.GlobalIlluminationQuality = quality
    return camera


def _mean(camera: spear.UCameraSensorComponent) -> float:
    pixels = camera.read_pixels()
    assert "final_color" in pixels
    return float(pixels["final_color"][..., :3].astype(np.float64).mean())


def test_exposure_is_manual_by_default_and_applied_as_set(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _closed_room(game, sun=False)
        camera = _camera(game, "Camera", A.AEM_Manual)
        default = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Default").CameraSensor
        assert default.AutoExposureMethod == A.AEM_Manual
        assert camera.GetAppliedExposure() == 0.0  # no frame read yet
        camera.Exposure = 0.25
    with instance.end_frame():
        _mean(camera)
        assert camera.GetAppliedExposure() == 0.25


@pytest.mark.parametrize("method", [A.AEM_Histogram, A.AEM_Basic])
def test_a_dim_and_a_bright_room_show_alike(make_instance: object, method: spear.EAutoExposureMethod) -> None:
    # A lamp 16 times brighter: with Exposure as set the image is far brighter; metered, the first frame of
    # each is exposed for what it shows, 4 stops apart, and the images match.
    results = []
    for intensity in (10.0, 160.0):
        instance = make_instance()  # type: ignore[operator]
        assert isinstance(instance, spear.Instance)
        game = instance.get_game()
        with instance.begin_frame():
            _closed_room(game, sun=False).LightComponent.Intensity = intensity
            metered = _camera(game, "Metered", method)
            manual = _camera(game, "Manual", A.AEM_Manual)
        with instance.end_frame():
            results.append((_mean(metered), metered.GetAppliedExposure(), _mean(manual)))
    (dim, dim_exposure, dim_manual), (bright, bright_exposure, bright_manual) = results
    assert bright_manual > dim_manual + 8.0
    assert 90.0 < dim < 190.0  # around middle grey (0.18 before the tone curve is 141 after it)
    assert bright == pytest.approx(dim, abs=2.0)
    assert dim_exposure / bright_exposure == pytest.approx(16.0, rel=0.05)


def test_bias_brightens_by_stops_and_the_path_tracer_meters_alike(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _closed_room(game, sun=False)
        plain = _camera(game, "Plain", A.AEM_Histogram)
        biased = _camera(game, "Biased", A.AEM_Histogram)
        biased.AutoExposureBias = 1.0
        traced = _camera(game, "Traced", A.AEM_Histogram)
        traced.Renderer = spear.ECameraRenderer.PathTraced
        traced.SamplesPerPixel = 32
    with instance.end_frame():
        cameras = {"Plain": plain, "Biased": biased, "Traced": traced}
        means = {name: _mean(c) for name, c in cameras.items()}
        exposures = {name: c.GetAppliedExposure() for name, c in cameras.items()}
    assert exposures["Biased"] == pytest.approx(2.0 * exposures["Plain"], rel=1e-4)
    assert means["Biased"] > means["Plain"] + 15.0
    # The rasteriser with global illumination and the path tracer see the same light, and meter it alike.
    assert exposures["Traced"] == pytest.approx(exposures["Plain"], rel=0.1)
    assert means["Traced"] == pytest.approx(means["Plain"], abs=8.0)


def test_adapts_at_its_speeds_and_resets_at_a_cut(instance: spear.Instance) -> None:
    # Global illumination off, so that the room's light follows the lamp at once (the probes take frames).
    game = instance.get_game()
    with instance.begin_frame():
        lamp = _closed_room(game, sun=False)
        camera = _camera(game, "Camera", A.AEM_Histogram, spear.EGlobalIlluminationQuality.Off)
    with instance.end_frame():
        _mean(camera)
        dim = camera.GetAppliedExposure()
    with instance.begin_frame():
        lamp.LightComponent.Intensity = 160.0  # 4 stops brighter: this frame still shows the old light's
    with instance.end_frame():
        _mean(camera)
        # (metered from the first frame's final_color, within its 8 bits of what the cut metered in HDR)
        assert camera.GetAppliedExposure() == pytest.approx(dim, rel=0.01)
    # One frame (1/60 s) later the exposure moved 4 * (1 - 2^(-3/60)) stops down (SpeedUp 3 stops a second).
    with instance.begin_frame():
        pass
    with instance.end_frame():
        _mean(camera)
        stops = math.log2(dim / camera.GetAppliedExposure())
    assert stops == pytest.approx(4.0 * (1.0 - 2.0 ** (-3.0 / 60.0)), abs=0.03)
    for _ in range(150):  # 2.5 s: within 4 * 2^-7.5 stops of the bright room's exposure
        with instance.begin_frame():
            pass
        with instance.end_frame():
            _mean(camera)
            bright = camera.GetAppliedExposure()
    with instance.begin_frame():  # what a new camera there is exposed at
        reference = _camera(game, "Reference", A.AEM_Histogram, spear.EGlobalIlluminationQuality.Off)
    with instance.end_frame():
        _mean(reference)
        cut = reference.GetAppliedExposure()
    assert math.log2(dim / cut) == pytest.approx(4.0, abs=0.15)
    assert math.log2(cut / bright) == pytest.approx(0.0, abs=0.03)
    # Darker again: SpeedDown, 1 stop a second, is half the way after 1 s.
    with instance.begin_frame():
        lamp.LightComponent.Intensity = 10.0
    with instance.end_frame():
        _mean(camera)
    for _ in range(60):
        with instance.begin_frame():
            pass
        with instance.end_frame():
            _mean(camera)
            adapted = camera.GetAppliedExposure()
    assert math.log2(adapted / bright) == pytest.approx(2.0, abs=0.1)
    # A cut: the next frame is exposed for what it shows.
    with instance.begin_frame():
        camera.ResetAutoExposure()
    with instance.end_frame():
        _mean(camera)
        assert camera.GetAppliedExposure() == pytest.approx(dim, rel=1e-3)


def test_contradictory_settings_are_refused_when_the_camera_renders(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _closed_room(game, sun=False)
        camera = _camera(game, "Camera", A.AEM_Histogram)
    with instance.end_frame():
        _mean(camera)
    with pytest.raises(spear.InvalidArgumentError, match=re.escape(
            "UCameraSensorComponent 'CameraSensor': AutoExposureMinBrightness (5) must not exceed "
            "AutoExposureMaxBrightness (4)")):
        with instance.begin_frame():
            camera.AutoExposureMinBrightness, camera.AutoExposureMaxBrightness = 5.0, 4.0
    with instance.end_frame():
        pass
    with pytest.raises(spear.InvalidArgumentError, match=re.escape(
            "AutoExposureLowPercent (60) must be below AutoExposureHighPercent (50)")):
        with instance.begin_frame():
            camera.AutoExposureMinBrightness = -10.0
            camera.AutoExposureLowPercent, camera.AutoExposureHighPercent = 60.0, 50.0
    with instance.end_frame():
        pass
    with instance.begin_frame():
        camera.AutoExposureLowPercent = 10.0
    with instance.end_frame():
        assert _mean(camera) > 0.0  # the engine rendered on
