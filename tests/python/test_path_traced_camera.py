"""The path-traced camera (UCameraSensorComponent.Renderer = PathTraced): global illumination from the
reference path tracer (core/pathtrace) behind the same sensor, both transports. Its colour accumulates
while nothing in view changes; the geometric modalities stay the rasteriser's."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

import spear
from test_camera import aces_srgb, path_trace, spawn_camera

M = spear.ECameraModality


def _sphere_in_sky(game: spear.UWorld, base: float) -> spear.AStaticMeshActor:
    """A unit sphere of a grey dielectric `base` at the origin, in a white sky that is also the background."""
    library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Library")
    library.SetMaterial(Name="Grey", Material=spear.FMaterialDesc(
        BaseColor=spear.FLinearColor(R=base, G=base, B=base, A=1.0), Roughness=0.6))
    sky = game.spawn_actor(uclass=spear.ASkyLight, name="Sky")
    sky.SkyLightComponent.Intensity = 1.0
    sky.SkyLightComponent.BackgroundColor = spear.FLinearColor(R=1.0, G=1.0, B=1.0, A=1.0)
    sphere = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Sphere")
    sphere.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Sphere")
    sphere.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Grey")
    return sphere


def _traced_camera(game: spear.UWorld, modalities: list[spear.ECameraModality], samples: int
                   ) -> spear.UCameraSensorComponent:
    """A path-traced 16 x 16 camera 3 m from the origin along -X, its 8 degree view filled by the sphere."""
    camera = path_trace(spawn_camera(game, modalities, 16, 16, 8.0), samples, 2)
    camera.GetOwner().SetActorLocation(NewLocation=spear.FVector(X=-3.0))  # type: ignore[union-attr]
    return camera


def test_a_diffuse_sphere_in_a_white_sky_reflects_its_base_colour(
    make_instance: Callable[..., spear.Instance]
) -> None:
    # Furnace: a convex dielectric in a uniform sky of radiance 1 shows base x 1 from its diffuse lobe plus
    # a specular share that is the same for any base (F0 = 0.04), so two bases differ by their difference.
    means = []
    for base in (1.0, 0.5):
        instance = make_instance()
        game = instance.get_game()
        with instance.begin_frame():
            _sphere_in_sky(game, base)
            camera = _traced_camera(game, [M.HdrColor], 128)
        with instance.end_frame():
            hdr = camera.read_pixels()["hdr_color"]
            assert camera.GetAccumulatedSamples() == 128
        assert hdr.dtype == np.float16 and hdr.shape == (16, 16, 4)
        means.append(hdr[..., :3].astype(np.float64).mean())
    assert means[0] - means[1] == pytest.approx(0.5, abs=0.02)


def test_a_still_view_accumulates_and_a_change_restarts(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _sphere_in_sky(game, 0.8)
        camera = _traced_camera(game, [M.FinalColor, M.HdrColor], 2)
    with instance.end_frame():
        pass
    samples = []
    for frame in range(4):
        with instance.begin_frame():
            if frame == 2:  # the camera moves: its image starts again
                camera.GetOwner().SetActorLocation(NewLocation=spear.FVector(X=-3.0, Y=0.01))  # type: ignore[union-attr]
        with instance.end_frame():
            pixels = camera.read_pixels()
            samples.append(camera.GetAccumulatedSamples())
    assert samples == [4, 6, 2, 4]  # the spawning frame rendered the first 2
    # final_color is hdr_color through the camera's tone curve (ACES, exposure 1) and sRGB.
    expected = aces_srgb(pixels["hdr_color"][..., :3].astype(np.float64))
    assert np.abs(pixels["final_color"][..., :3] - expected).max() <= 1.5  # float16 rounding of hdr_color
    assert (pixels["final_color"][..., 3] == 255).all()



def test_approximate_caustics_is_off_by_default_and_restarts_the_image_when_set(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _sphere_in_sky(game, 0.8)
        camera = _traced_camera(game, [M.HdrColor], 2)
        assert camera.bPathTracingApproximateCaustics is False  # the unbiased reference
    with instance.end_frame():
        pass
    samples = []
    for frame in range(3):
        with instance.begin_frame():
            if frame == 1:  # another estimate: the samples so far no longer count
                camera.bPathTracingApproximateCaustics = True
        with instance.end_frame():
            pixels = camera.read_pixels()
            samples.append(camera.GetAccumulatedSamples())
            assert camera.bPathTracingApproximateCaustics is (frame >= 1)
    assert samples == [4, 2, 4]
    assert np.isfinite(pixels["hdr_color"].astype(np.float64)).all()

def test_geometric_modalities_are_the_rasterisers(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        _sphere_in_sky(game, 0.8)
        raster = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Raster",
                                  location=spear.FVector(X=-3.0)).CameraSensor
        raster.Width, raster.Height, raster.FOV = 16, 16, 30.0
        raster.Modalities = [M.Depth, M.ObjectIds, M.FinalColor]
        traced = _traced_camera(game, [M.Depth, M.ObjectIds, M.FinalColor], 1)
        traced.FOV = 30.0
    with instance.end_frame():
        a, b = raster.read_pixels(), traced.read_pixels()
        assert raster.GetAccumulatedSamples() == 0 and traced.GetAccumulatedSamples() == 1
    np.testing.assert_array_equal(a["depth"], b["depth"])
    np.testing.assert_array_equal(a["object_ids"], b["object_ids"])


@pytest.mark.parametrize(("name", "value", "words"), [
    ("SamplesPerPixel", 0, "SamplesPerPixel must be in [1, 65536], got 0"),
    ("MaxBounces", 65, "MaxBounces must be in [0, 64], got 65"),
])
def test_bad_path_tracing_settings_are_refused(instance: spear.Instance, name: str, value: int, words: str) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = spawn_camera(game, [M.FinalColor])
        with pytest.raises(spear.InvalidArgumentError, match=words.replace("[", r"\[").replace("]", r"\]")):
            setattr(camera, name, value)
    with instance.end_frame():
        pass


def test_path_traced_intrinsics_include_indirect_light_and_sum_to_hdr(instance: spear.Instance) -> None:
    # In a white sky a white Lambertian surface anywhere on the sphere reflects 1 (diffuse_illumination),
    # so diffuse_only is the base colour; the specular residual is the rest of hdr_color.
    game = instance.get_game()
    with instance.begin_frame():
        _sphere_in_sky(game, 0.5)
        camera = _traced_camera(game, [M.HdrColor, M.DiffuseIllumination, M.DiffuseOnly, M.SpecularResidual], 128)
    with instance.end_frame():
        pixels = camera.read_pixels()
    hdr = pixels["hdr_color"][..., :3].astype(np.float32)
    illumination = pixels["diffuse_illumination"].astype(np.float32)
    diffuse = pixels["diffuse_only"].astype(np.float32)
    residual = pixels["specular_residual"].astype(np.float32)
    assert illumination.shape == diffuse.shape == residual.shape == (16, 16, 3)
    assert illumination.mean() == pytest.approx(1.0, abs=0.03)
    assert diffuse.mean() == pytest.approx(0.5, abs=0.02)
    assert residual.mean() > 0.0  # the dielectric's specular lobe
    # hdr = diffuse_only + specular_residual, to the float16 rounding of the stored images.
    np.testing.assert_allclose(diffuse + residual, hdr, rtol=2e-3, atol=2e-3)


def test_depth_of_field_blurs_what_is_out_of_focus(instance: spear.Instance) -> None:
    # A thin lens (ApertureFNumber, FocusDistance): a sphere whose front is in focus keeps the pinhole
    # image's sharp silhouette; focused far behind it, its silhouette spreads over several pixels.
    game = instance.get_game()
    with instance.begin_frame():
        _sphere_in_sky(game, 0.2)
        camera = _traced_camera(game, [M.HdrColor, M.Depth], 64)
        camera.Width, camera.Height, camera.FOV = 64, 64, 20.0
        with pytest.raises(spear.InvalidArgumentError, match=r"ApertureFNumber must be 0 \(a pinhole\) or a finite "
                                                            r"f-number >= 0.5, got 0.2"):
            camera.ApertureFNumber = 0.2
        with pytest.raises(spear.InvalidArgumentError, match=r"FocusDistance must be > 0 and finite, got 0"):
            camera.FocusDistance = 0.0
    with instance.end_frame():
        pass
    images = {}
    for name, f_number, focus in [("pinhole", 0.0, 10.0), ("focused", 1.0, 2.5), ("far", 1.0, 30.0)]:
        with instance.begin_frame():
            camera.ApertureFNumber, camera.FocusDistance = f_number, focus
        with instance.end_frame():
            pixels = camera.read_pixels()
        images[name] = pixels["hdr_color"][..., :3].astype(np.float64).mean(axis=-1)
        depth = pixels["depth"]
    # The silhouette: pixels within 3 of the sphere's edge in the (always sharp) depth image.
    inside = depth > 0
    edge = np.zeros_like(inside)
    for dy in range(-3, 4):
        for dx in range(-3, 4):
            edge |= np.roll(inside, (dy, dx), axis=(0, 1)) != inside

    def blur(name: str) -> float:
        return float(np.abs(images[name] - images["pinhole"])[edge].mean())
    assert blur("far") > 4 * blur("focused"), (blur("far"), blur("focused"))
    assert blur("far") > 0.05  # sky 1 against a sphere of about 0.2, spread over the edge
