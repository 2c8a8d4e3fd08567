"""Positive typing case: the camera sensor's pixels are typed per modality."""

from __future__ import annotations

from typing import assert_type

import numpy as np
from numpy.typing import NDArray

import spear


def camera_pixels(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor).CameraSensor
        assert_type(camera, spear.UCameraSensorComponent)
        camera.Modalities = [spear.ECameraModality.FinalColor, spear.ECameraModality.Depth]
        camera.ToneCurve = spear.ECameraToneCurve.Reinhard
        camera.AutoExposureMethod = spear.EAutoExposureMethod.AEM_Histogram
        camera.AutoExposureBias = 0.5
        camera.ResetAutoExposure()
        panel = game.spawn_actor(uclass=spear.ARectLight).LightComponent
        assert_type(panel, spear.URectLightComponent)
        panel.SetSourceWidth(NewWidth=1.2)
        panel.SourceHeight = 0.5
        rig = game.spawn_actor(uclass=spear.AStereoCameraRig)
        assert_type(rig.LeftCamera, spear.UCameraSensorComponent)
    with instance.end_frame():
        px = camera.read_pixels()
        assert_type(px, spear.FCameraPixels)
        # Only the rendered modalities are present: pyright asks for the check, mypy allows px["depth"] as is.
        assert "depth" in px and "final_color" in px and "object_ids" in px
        assert_type(px["depth"], NDArray[np.float32])
        assert_type(px["final_color"], NDArray[np.uint8])
        assert_type(px["object_ids"], NDArray[np.uint32])
        assert_type(px.get("hdr_color"), NDArray[np.float16] | None)
        info = camera.GetObjectIdInfo(ObjectId=int(px["object_ids"][0, 0]))
        assert_type(info.Actor, spear.AActor | None)
        assert_type(info.MaterialSlot, int)
        assert_type(camera.get_render_device_info().Renderer, str)
        assert_type(camera.GetAppliedExposure(), float)
