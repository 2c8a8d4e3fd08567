"""Emissive meshes as lights: the path tracer samples emissive surfaces directly (next-event estimation), so a
glowing panel lights a wall as a rect light of the same radiance does, from the first sample and with no
bounce needed, and bounce rays that find it are weighted against those samples (multiple importance
sampling) rather than counted twice. Both transports."""

from __future__ import annotations

import numpy as np
import pytest

import spear
from test_camera import path_trace, spawn_camera
from test_rect_light import INTENSITY, PANEL, PANEL_GAP, WALL_X, dark_room_wall, expected_illumination

M = spear.ECameraModality


def _glowing_panel_scene(game: spear.UWorld, radiance: float) -> None:
    """The rect light test's wall and panel, the panel a plane mesh emitting `radiance` (black otherwise)."""
    library = dark_room_wall(game)
    library.SetMaterial(Name="Glow", Material=spear.FMaterialDesc(
        BaseColor=spear.FLinearColor(R=0.0, G=0.0, B=0.0, A=1.0),
        Emissive=spear.FLinearColor(R=radiance, G=radiance, B=radiance, A=1.0)))
    # A plane faces +Z; pitched a quarter turn it faces the wall (emission is two-sided).
    panel = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Panel",
                             location=spear.FVector(X=WALL_X - PANEL_GAP, Y=0.3, Z=-0.2),
                             rotation=spear.FRotator(Pitch=90.0))
    panel.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Plane")
    panel.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Glow")
    panel.SetActorScale3D(NewScale3D=spear.FVector(X=PANEL[1], Y=PANEL[0], Z=1.0))


@pytest.mark.parametrize("bounces", [0, 2])
def test_an_emissive_panel_gives_a_wall_its_form_factor(instance: spear.Instance, bounces: int) -> None:
    # With no bounce at all the panel's light arrives only through the emitter samples; with bounces the
    # bounce rays that find the panel add their weighted share, and the sum stays the same.
    game = instance.get_game()
    with instance.begin_frame():
        _glowing_panel_scene(game, INTENSITY / (PANEL[0] * PANEL[1]))
        camera = path_trace(spawn_camera(game, [M.DiffuseIllumination, M.Position], 24, 18, 50.0), 256, bounces)
    with instance.end_frame():
        pixels = camera.read_pixels()
    position = pixels["position"]
    wall = np.abs(position[..., 0] - WALL_X) < 0.01  # not the panel, which the camera sees too
    assert wall.sum() > 300
    expected = expected_illumination(position, 0.3, -0.2)[wall]
    illumination = pixels["diffuse_illumination"][..., 0].astype(np.float64)[wall]
    assert illumination.mean() == pytest.approx(expected.mean(), rel=0.03)
    assert np.abs(illumination - expected).max() <= 0.2 * expected.max()


def test_a_small_bright_emitter_converges_without_fireflies(instance: spear.Instance) -> None:
    # A small lamp found only by bounce rays leaves a few pixels far too bright and most too dark; sampled
    # directly, 64 samples give every pixel of the lit wall within a fifth of its mean's neighbourhood.
    game = instance.get_game()
    with instance.begin_frame():
        _glowing_panel_scene(game, 400.0)
        panel = game.find_actor_by_name(name="Panel")
        assert panel is not None
        panel.SetActorScale3D(NewScale3D=spear.FVector(X=0.1, Y=0.1, Z=1.0))
        camera = path_trace(spawn_camera(game, [M.DiffuseIllumination, M.Position], 24, 18, 50.0), 64, 2)
    with instance.end_frame():
        pixels = camera.read_pixels()
    wall = np.abs(pixels["position"][..., 0] - WALL_X) < 0.01
    illumination = pixels["diffuse_illumination"][..., 0].astype(np.float64)
    # Away from the lamp the light falls off smoothly; the image's relative spread against a smooth fit
    # (its 3 x 3 median) is the noise.
    padded = np.pad(illumination, 1, mode="edge")
    smooth = np.median(np.lib.stride_tricks.sliding_window_view(padded, (3, 3)), axis=(-2, -1))
    inside = wall & (smooth > 0.05 * smooth.max())
    noise = np.abs(illumination[inside] - smooth[inside]) / smooth[inside]
    assert float(np.percentile(noise, 99)) < 0.2
