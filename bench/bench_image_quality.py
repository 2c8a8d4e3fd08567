"""Image quality of the rasteriser against the project's own path tracer, on the default scene and two more.

For each scene, one pose: the rasterised final_color (each global-illumination quality asked for) against a
path-traced reference of --reference samples per pixel at the same pose and exposure. Printed per scene and
quality, over the pixels that show geometry (depth > 0):
  - mean luminance ratio (raster / reference) and mean relative luminance error;
  - SSIM of final_color (scikit-image, Debian's python3-skimage);
  - crushed pixels (every channel below 8/255) in raster and in the reference;
and, once per scene, the path tracer's relative RMSE at 64 spp against the reference, raw and denoised
(bPathTracingEnableDenoiser), and the rasteriser's aliasing with each AntiAliasingMethod, and with
SpatialSampleCount 4, 8 and 16 (supersampling): the mean and 99th-percentile difference of
final_color against the same view supersampled 4 x 4, and 17 x 17 (which holds none of the settings' sample
points, as 4 x 4 holds MSAA's; --aliasing-grids).

    PYTHONPATH=python /usr/bin/python3 bench/bench_image_quality.py [--width 320 --height 240]
        [--reference 1024] [--qualities Off,Medium] [--ambient-occlusion 0.5] [--scenes apartment,yard,closed_room,sky_yard,park_yard] [--out out/iq]
        [--aliasing-grids 4,17] [--aliasing-only] [--max-anisotropy 8] [--mip-bias -1] [--reference-cache DIR]

--max-anisotropy sets the raster cameras' MaxAnisotropy (0: the renderer's default, anisotropic: 8 samples in a
GPU's sampler, 4 reads in the shader on llvmpipe; 1: trilinear). --mip-bias sets their MipMapLODBias (0 by default; the
supersampled views of the aliasing measure stay at 0). --reference-cache keeps each scene's path-traced
reference in DIR (one .npy per scene, size and sample count) and reads it back in later runs: a 4,096-sample
reference takes about 18 minutes on two cores. It is the caller's to clear when the scene or the path tracer
changes.
"""

from __future__ import annotations

import argparse
import importlib
import sys
import time
from pathlib import Path
from typing import Callable

import numpy as np
from numpy.typing import NDArray

import spear

# The anti-aliasing settings whose aliasing is measured: label, AntiAliasingMethod, SpatialSampleCount.
ALIASING_SETTINGS = [(m.name, m, 1) for m in spear.EAntiAliasingMethod] + [
    (f"SpatialSampleCount {n}", spear.EAntiAliasingMethod.AAM_None, n) for n in (4, 8, 16)]

ROOT = Path(__file__).resolve().parent.parent
APARTMENT = ROOT / "assets" / "scenes" / "apartment.json"
CUBE = "/Engine/BasicShapes/Cube"

Pose = tuple[spear.FVector, spear.FRotator]


def box(game: spear.UWorld, name: str, location: tuple[float, float, float], scale: tuple[float, float, float],
        color: tuple[float, float, float], roughness: float = 0.8) -> None:
    library = game.find_actor_by_name(name="Materials")
    if library is None:
        library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Materials")
    assert isinstance(library, spear.AMaterialLibrary)
    library.SetMaterial(Name=name, Material=spear.FMaterialDesc(BaseColor=spear.FLinearColor(*color, 1.0),
                                                                Roughness=roughness))
    actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name=name, location=spear.FVector(*location))
    mesh = actor.StaticMeshComponent
    mesh.SetStaticMesh(NewMesh=CUBE)
    mesh.SetRelativeScale3D(NewScale3D=spear.FVector(*scale))
    mesh.SetMaterial(ElementIndex=0, Material=name)


def apartment(game: spear.UWorld) -> Pose:
    game.load_scene(path=str(APARTMENT))
    return spear.FVector(-2.6, -1.6, 1.7), spear.FRotator(Pitch=-18.0, Yaw=22.0)


def yard(game: spear.UWorld, sky: str = "uniform") -> Pose:
    """Outdoors: a sun low enough to leave faces in shade, a ground and a few blocks, under a uniform blue sky
    light, the analytic sky (ASkyAtmosphere) or an HDR panorama (assets/environments/park.exr)."""
    box(game, "Ground", (0.0, 0.0, -0.05), (40.0, 40.0, 0.1), (0.35, 0.33, 0.3), 0.95)
    box(game, "House", (3.0, 1.0, 1.5), (4.0, 3.0, 3.0), (0.75, 0.7, 0.62))
    box(game, "Shed", (0.5, -3.0, 0.75), (1.5, 1.5, 1.5), (0.55, 0.25, 0.15))
    box(game, "Wall", (-1.0, 2.5, 0.5), (0.2, 4.0, 1.0), (0.6, 0.6, 0.6))
    box(game, "Crate", (-0.5, -0.5, 0.3), (0.6, 0.6, 0.6), (0.4, 0.5, 0.3))
    sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun",
                           rotation=spear.FRotator(Pitch=-35.0, Yaw=-60.0))
    sun.LightComponent.Intensity = 3.0
    if sky == "atmosphere":
        game.spawn_actor(uclass=spear.ASkyAtmosphere, name="Atmosphere")
    else:
        light = game.spawn_actor(uclass=spear.ASkyLight, name="Sky").SkyLightComponent
        light.Intensity = 1.0
        if sky == "panorama":
            light.SourceType = spear.ESkyLightSourceType.SLS_SpecifiedCubemap
            light.Cubemap = "assets/environments/park.exr"
        else:
            light.SkyColor = spear.FLinearColor(0.35, 0.45, 0.6, 1.0)
            light.BackgroundColor = spear.FLinearColor(0.35, 0.45, 0.6, 1.0)
    return spear.FVector(-7.0, -5.0, 2.5), spear.FRotator(Pitch=-12.0, Yaw=35.0)


def closed_room(game: spear.UWorld) -> Pose:
    """A closed white room lit by one lamp, with a sun outside that must not leak in."""
    t = 0.2
    for name, location, scale in [("Floor", (0.0, 0.0, -t / 2), (4.4, 3.4, t)),
                                  ("Ceiling", (0.0, 0.0, 2.5 + t / 2), (4.4, 3.4, t)),
                                  ("WallN", (2.0 + t / 2, 0.0, 1.25), (t, 3.0, 2.5)),
                                  ("WallS", (-2.0 - t / 2, 0.0, 1.25), (t, 3.0, 2.5)),
                                  ("WallW", (0.0, 1.5 + t / 2, 1.25), (4.4, t, 2.5)),
                                  ("WallE", (0.0, -1.5 - t / 2, 1.25), (4.4, t, 2.5))]:
        box(game, name, location, scale, (0.8, 0.8, 0.8), 1.0)
    box(game, "Block", (0.6, 0.4, 0.4), (0.8, 0.8, 0.8), (0.7, 0.2, 0.15))
    lamp = game.spawn_actor(uclass=spear.APointLight, name="Lamp", location=spear.FVector(-0.5, -0.3, 2.2))
    lamp.LightComponent.Intensity = 10.0
    sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun",
                           rotation=spear.FRotator(Pitch=-50.0, Yaw=30.0))
    sun.LightComponent.Intensity = 30.0
    return spear.FVector(-1.8, -1.3, 1.8), spear.FRotator(Pitch=-20.0, Yaw=35.0)


SCENES: dict[str, Callable[[spear.UWorld], Pose]] = {
    "apartment": apartment, "yard": yard, "closed_room": closed_room,
    "sky_yard": lambda game: yard(game, "atmosphere"), "park_yard": lambda game: yard(game, "panorama")}
# Each scene's one exposure for both renderers: the apartment's is what automatic exposure (AEM_Histogram)
# meters for its view, so that neither image is clipped.
EXPOSURE = {"apartment": 0.07, "yard": 1.0, "closed_room": 1.0, "sky_yard": 1.0, "park_yard": 0.5}


def luminance(rgb: NDArray[np.float64]) -> NDArray[np.float64]:
    result: NDArray[np.float64] = 0.2126 * rgb[..., 0] + 0.7152 * rgb[..., 1] + 0.0722 * rgb[..., 2]
    return result


def srgb_to_linear(image: NDArray[np.uint8]) -> NDArray[np.float64]:
    c = image[..., :3].astype(np.float64) / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


class Scene:
    """One scene in its own engine: a camera per quality and a path-traced one, all at one pose."""

    def __init__(self, name: str, width: int, height: int, qualities: list[spear.EGlobalIlluminationQuality],
                 ambient_occlusion: float = 0.0, max_anisotropy: int = 0, mip_bias: float = 0.0):
        self.instance = spear.Instance()
        self.game = self.instance.get_game()
        self.width, self.height, self.name = width, height, name
        with self.instance.begin_frame():
            self.pose = SCENES[name](self.game)
            for actor in self.game.find_actors_by_class(uclass=spear.AStaticMeshActor):
                if actor.StaticMeshComponent.bSimulatePhysics:  # still, for the path tracer to accumulate
                    actor.StaticMeshComponent.SetSimulatePhysics(bSimulate=False)
            self.cameras = {q: self.camera(f"Raster{q.name}", width, height, q, name) for q in qualities}
            for camera in self.cameras.values():
                camera.AmbientOcclusionIntensity = ambient_occlusion
                camera.MaxAnisotropy = max_anisotropy
                camera.MipMapLODBias = mip_bias
        with self.instance.end_frame():
            pass

    def camera(self, label: str, width: int, height: int, quality: spear.EGlobalIlluminationQuality,
               scene: str) -> spear.UCameraSensorComponent:
        actor = self.game.spawn_actor(uclass=spear.ACameraSensorActor, name=label, location=self.pose[0],
                                      rotation=self.pose[1])
        camera = actor.CameraSensor
        camera.Width, camera.Height, camera.FOV = width, height, 75.0
        camera.Modalities = [spear.ECameraModality.FinalColor, spear.ECameraModality.Depth]
        camera.ShadowResolution = 2048
        camera.Exposure = EXPOSURE[scene]
        camera.GlobalIlluminationQuality = quality
        return camera

    def frame(self) -> None:
        with self.instance.begin_frame():
            pass
        with self.instance.end_frame():
            pass

    def raster(self, camera: spear.UCameraSensorComponent) -> tuple[NDArray[np.uint8], NDArray[np.float32]]:
        """A frame, and the camera's images of it. The other raster cameras render nothing meanwhile: a world's
        probes are lit at the highest GlobalIlluminationQuality of the cameras that shade, so with them all
        shading every row would show the highest."""
        with self.instance.begin_frame():
            for other in self.cameras.values():
                other.Modalities = ([spear.ECameraModality.FinalColor, spear.ECameraModality.Depth]
                                    if other is camera else [])
        with self.instance.end_frame():
            pixels = camera.read_pixels()
        assert "final_color" in pixels and "depth" in pixels
        return pixels["final_color"], pixels["depth"]

    def aliasing(self, quality: spear.EGlobalIlluminationQuality,
                 grids: list[int]) -> dict[int, dict[str, tuple[float, float]]]:
        """final_color, with each anti-aliasing setting (ALIASING_SETTINGS), against the same view rendered n x n
        times larger without any and averaged down (in linear light), for each n of `grids`: the mean and
        99th-percentile difference over all pixels, in 8-bit steps. A grid holding a setting's sample points
        favours it (4 x 4 holds MSAA's four); 17 x 17 holds none of them."""
        camera = self.cameras[quality]
        # The supersampled views render alone: with another quality's camera shading beside them, the world's
        # probes would follow the highest quality, and the references would be lit otherwise than the view.
        with self.instance.begin_frame():
            for other in self.cameras.values():
                other.Modalities = []
        with self.instance.end_frame():
            pass
        references: dict[int, NDArray[np.float64]] = {}
        for n in grids:
            with self.instance.begin_frame():
                large = self.camera(f"Supersampled{n}", n * self.width, n * self.height, quality, self.name)
                large.AntiAliasingMethod = spear.EAntiAliasingMethod.AAM_None
                large.Modalities = [spear.ECameraModality.FinalColor]
            with self.instance.end_frame():
                pass
            with self.instance.begin_frame():
                pass
            with self.instance.end_frame():
                pixels = large.read_pixels()
            assert "final_color" in pixels
            linear = srgb_to_linear(pixels["final_color"]).reshape(self.height, n, self.width, n, 3).mean(axis=(1, 3))
            encoded = np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * linear ** (1 / 2.4) - 0.055)
            references[n] = np.round(255.0 * np.clip(encoded, 0.0, 1.0))
            with self.instance.begin_frame():
                large.Modalities = []  # its targets freed
            with self.instance.end_frame():
                pass
        with self.instance.begin_frame():
            default = camera.AntiAliasingMethod
        with self.instance.end_frame():
            pass
        result: dict[int, dict[str, tuple[float, float]]] = {n: {} for n in grids}
        for label, method, samples in ALIASING_SETTINGS:
            with self.instance.begin_frame():
                camera.AntiAliasingMethod = method
                camera.SpatialSampleCount = samples
            with self.instance.end_frame():
                pass
            color, _ = self.raster(camera)
            for n, reference in references.items():
                difference = np.abs(color[..., :3].astype(np.float64) - reference)
                result[n][label] = (float(difference.mean()), float(np.percentile(difference, 99)))
        with self.instance.begin_frame():
            camera.AntiAliasingMethod = default
            camera.SpatialSampleCount = 1
        with self.instance.end_frame():
            pass
        return result

    def traced(self, samples: int, label: str, denoise: bool = False, independent: bool = False) -> NDArray[np.uint8]:
        """final_color of a path-traced camera at the pose after `samples` samples per pixel. `independent`: with
        other random numbers than the other traced cameras (the path tracer seeds them from the view, so a
        reference traced like the image it measures would share that image's samples and flatter it)."""
        with self.instance.begin_frame():
            camera = self.camera(label, self.width, self.height, spear.EGlobalIlluminationQuality.Off, self.name)
            if independent:
                camera.NearClip = 0.0501  # the same image (nothing is that near), other random numbers
            camera.Modalities = [spear.ECameraModality.FinalColor]
            camera.Renderer = spear.ECameraRenderer.PathTraced
            camera.SamplesPerPixel = min(64, samples)
            camera.MaxBounces = 6
            camera.bPathTracingEnableDenoiser = denoise
        start = time.monotonic()
        with self.instance.end_frame():
            done = camera.GetAccumulatedSamples()
            pixels = camera.read_pixels()
        while done < samples:
            with self.instance.begin_frame():
                camera.SamplesPerPixel = min(64, samples - done)
            with self.instance.end_frame():
                done = camera.GetAccumulatedSamples()
                pixels = camera.read_pixels()
            print(f"  {label}: {done}/{samples} spp, {time.monotonic() - start:.0f} s", file=sys.stderr)
        with self.instance.begin_frame():
            camera.Modalities = []  # done: the next frames trace nothing more
        with self.instance.end_frame():
            pass
        assert "final_color" in pixels
        return pixels["final_color"]

    def close(self) -> None:
        self.instance.close()


def cached_reference(scene: Scene, samples: int, cache: str | None) -> NDArray[np.uint8]:
    """The scene's path-traced reference, from `cache` when it holds one of this size and sample count, else
    traced (and kept there, written whole: a temporary file renamed)."""
    if cache is None:
        return scene.traced(samples, "Reference", independent=True)
    path = Path(cache) / f"{scene.name}_{scene.width}x{scene.height}_{samples}spp.npy"
    if path.exists():
        print(f"  reference: {path}", file=sys.stderr)
        loaded: NDArray[np.uint8] = np.load(path)
        if loaded.shape[:2] != (scene.height, scene.width) or loaded.dtype != np.uint8:
            sys.exit(f"bench_image_quality.py: {path} holds a {loaded.dtype} image of shape {loaded.shape}, not "
                     f"a {scene.width}x{scene.height} final_color: remove it")
        return loaded
    reference = scene.traced(samples, "Reference", independent=True)
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_suffix(".partial.npy")
    np.save(temporary, reference)
    temporary.replace(path)
    return reference


def ssim(a: NDArray[np.uint8], b: NDArray[np.uint8]) -> float:
    structural_similarity = importlib.import_module("skimage.metrics").structural_similarity  # untyped
    return float(structural_similarity(a[..., :3], b[..., :3], channel_axis=2, data_range=255))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=240)
    parser.add_argument("--reference", type=int, default=1024, help="path-traced samples per pixel")
    parser.add_argument("--qualities", default="Off,Medium")
    parser.add_argument("--ambient-occlusion", type=float, default=0.0,
                        help="the raster cameras' AmbientOcclusionIntensity (0: off, the camera's default)")
    parser.add_argument("--max-anisotropy", type=int, default=0,
                        help="the raster cameras' MaxAnisotropy (0: the renderer's default)")
    parser.add_argument("--mip-bias", type=float, default=0.0, help="the raster cameras' MipMapLODBias")
    parser.add_argument("--reference-cache", default=None,
                        help="a folder to keep the path-traced references in and read them back from")
    parser.add_argument("--scenes", default="apartment,yard,closed_room,sky_yard,park_yard")
    parser.add_argument("--out", default=None, help="a folder for the images (PNG)")
    parser.add_argument("--aliasing-grids", default="4,17",
                        help="the supersampled references of the aliasing measure: n x n each")
    parser.add_argument("--aliasing-only", action="store_true", help="measure the aliasing alone (no path tracing)")
    args = parser.parse_args()
    grids = [int(n) for n in args.aliasing_grids.split(",")]
    try:
        importlib.import_module("skimage")
    except ImportError:
        sys.exit("bench_image_quality.py needs scikit-image: sudo apt-get install python3-skimage")
    qualities = [spear.EGlobalIlluminationQuality[q] for q in args.qualities.split(",")]
    rows: list[tuple[str, str, float, float, float, float, float, float]] = []
    noise: list[tuple[str, float, float]] = []
    aliasing: list[tuple[str, dict[int, dict[str, tuple[float, float]]]]] = []
    for name in args.scenes.split(","):
        print(f"{name}:", file=sys.stderr)
        scene = Scene(name, args.width, args.height, qualities, args.ambient_occlusion, args.max_anisotropy,
                      args.mip_bias)
        scene.frame()
        if args.aliasing_only:
            aliasing.append((name, scene.aliasing(qualities[0], grids)))
            scene.close()
            continue
        reference = cached_reference(scene, args.reference, args.reference_cache)
        noisy = scene.traced(64, "Traced64")
        denoised = scene.traced(64, "Traced64Denoised", denoise=True)
        ref_linear = srgb_to_linear(reference)
        ref_lum = luminance(ref_linear)
        for quality, camera in scene.cameras.items():
            start = time.monotonic()
            color, depth = scene.raster(camera)
            elapsed = time.monotonic() - start
            geometry = depth > 0
            lum = luminance(srgb_to_linear(color))
            ratio = float(lum[geometry].mean() / max(ref_lum[geometry].mean(), 1e-9))
            relative = float((np.abs(lum - ref_lum)[geometry] / np.maximum(ref_lum[geometry], 1e-3)).mean())
            crushed = float((color[..., :3].max(axis=2) < 8)[geometry].mean())
            crushed_ref = float((reference[..., :3].max(axis=2) < 8)[geometry].mean())
            rows.append((name, quality.name, ratio, relative, ssim(color, reference), crushed, crushed_ref,
                         elapsed))
            if args.out:
                from PIL import Image  # type: ignore[import]
                out = Path(args.out)
                out.mkdir(parents=True, exist_ok=True)
                Image.fromarray(np.ascontiguousarray(color[..., :3])).save(out / f"{name}_{quality.name}.png")
                Image.fromarray(np.ascontiguousarray(reference[..., :3])).save(out / f"{name}_reference.png")
        rmse = [float(np.sqrt(((luminance(srgb_to_linear(image)) - ref_lum) ** 2).mean()) / max(ref_lum.mean(), 1e-9))
                for image in (noisy, denoised)]
        print(f"  path tracer, 64 spp against {args.reference}: relative RMSE {rmse[0]:.3f}, denoised {rmse[1]:.3f}",
              file=sys.stderr)
        noise.append((name, rmse[0], rmse[1]))
        aliasing.append((name, scene.aliasing(qualities[0], grids)))
        scene.close()

    print("| scene | quality | luminance ratio | mean rel. error | SSIM | crushed raster | crushed ref. | frame s |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for n, q, ratio, rel, s, cr, crr, t in rows:
        print(f"| {n} | {q} | {ratio:.2f} | {rel:.2f} | {s:.3f} | {cr:.1%} | {crr:.1%} | {t:.2f} |")
    print()
    print(f"| scene | path tracer at 64 spp: relative RMSE against {args.reference} spp | denoised |")
    print("|---|---:|---:|")
    for n, raw, filtered in noise:
        print(f"| {n} | {raw:.3f} | {filtered:.3f} |")
    print()
    methods = [label for label, _, _ in ALIASING_SETTINGS]
    for grid in grids:
        print(f"\naliasing against the view supersampled {grid} x {grid}:")
        print("| scene | " + " | ".join(f"{m}: mean / p99 (/255)" for m in methods) + " |")
        print("|---|" + "---:|" * len(methods))
        for name, by_grid in aliasing:
            print(f"| {name} | " + " | ".join(f"{by_grid[grid][m][0]:.2f} / {by_grid[grid][m][1]:.1f}" for m in methods)
                  + " |")


if __name__ == "__main__":
    main()
