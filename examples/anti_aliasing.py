"""One view with each anti-aliasing method beside a supersampled one: what AntiAliasingMethod does to edges.

Thin posts, a slanted box and a fence against a bright sky, seen by six cameras at one pose: AAM_None, AAM_FXAA
(the default), AAM_MSAA (MSAASampleCount 4), SpatialSampleCount 4 and 16 (supersampling: that many passes, each
pixel sampling another point of its square) and, as the reference, AAM_None rendered 17 x 17 times larger and
averaged down in linear light (finer than any method's samples, and sharing none of their points: a 4 x 4
reference holds MSAA's four points and would favour it). It writes a sheet of the six (each crop magnified so
that the pixels show) and prints each method's mean and 99th-percentile difference from the reference, in
8-bit steps. Depth and ids are the same under every method: only the colour is anti-aliased.

    PYTHONPATH=python /usr/bin/python3 examples/anti_aliasing.py [--out out/anti_aliasing.png]
        [--width 320 --height 240] [--server launch]
"""

# Debian 12's Pillow (9.4) has no annotations: strict pyright would flag every use of it.
# pyright: reportUnknownVariableType=false, reportUnknownMemberType=false

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from PIL import Image, ImageDraw  # type: ignore[import]  # Debian ships no Pillow stubs

import spear

A = spear.EAntiAliasingMethod
# The reference is the view rendered this many times larger along each axis and averaged down.
REFERENCE_GRID = 17


def scene(game: spear.UWorld) -> None:
    """A ground, a slanted box, a row of thin fence posts and a sun, under an analytic sky."""
    game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun",
                     rotation=spear.FRotator(Pitch=-40.0, Yaw=-50.0)).LightComponent.Intensity = 3.0
    game.spawn_actor(uclass=spear.ASkyAtmosphere, name="Atmosphere")
    library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Library")
    for material, (r, g, b) in {"Grass": (0.2, 0.3, 0.12), "Brick": (0.55, 0.22, 0.12),
                                "Wood": (0.3, 0.2, 0.12)}.items():
        library.SetMaterial(Name=material, Material=spear.FMaterialDesc(
            BaseColor=spear.FLinearColor(R=r, G=g, B=b, A=1.0), Roughness=0.85))
    parts = [("Ground", (0.0, 0.0, -0.05), (30.0, 30.0, 0.1), 0.0, "Grass"),
             ("Box", (1.0, 0.6, 0.6), (1.2, 1.2, 1.2), 33.0, "Brick")]
    parts += [(f"Post{i}", (-0.5 + 0.45 * i, -1.4, 0.6), (0.04, 0.04, 1.2), 0.0, "Wood") for i in range(7)]
    parts += [("Rail", (0.85, -1.4, 1.1), (2.9, 0.03, 0.05), 0.0, "Wood")]
    for name, location, scale, yaw, material in parts:
        actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name=name, location=spear.FVector(*location),
                                 rotation=spear.FRotator(Yaw=yaw))
        actor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        actor.StaticMeshComponent.SetRelativeScale3D(NewScale3D=spear.FVector(*scale))
        actor.StaticMeshComponent.SetMaterial(ElementIndex=0, Material=material)


def camera(game: spear.UWorld, name: str, width: int, height: int, method: spear.EAntiAliasingMethod,
           spatial_samples: int = 1) -> spear.UCameraSensorComponent:
    sensor = game.spawn_actor(uclass=spear.ACameraSensorActor, name=name, location=spear.FVector(-1.6, -3.6, 1.3),
                              rotation=spear.FRotator(Pitch=-6.0, Yaw=55.0)).CameraSensor
    sensor.Width, sensor.Height, sensor.FOV = width, height, 60.0
    sensor.Exposure = 0.5
    sensor.Modalities = [spear.ECameraModality.FinalColor, spear.ECameraModality.ObjectIds]
    sensor.AntiAliasingMethod = method
    sensor.MSAASampleCount = 4
    sensor.SpatialSampleCount = spatial_samples
    return sensor


def linear(image: NDArray[np.uint8]) -> NDArray[np.float64]:
    c = image[..., :3].astype(np.float64) / 255.0
    result: NDArray[np.float64] = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return result


def encode(values: NDArray[np.float64]) -> NDArray[np.uint8]:
    c = np.where(values <= 0.0031308, 12.92 * values, 1.055 * np.maximum(values, 0.0) ** (1 / 2.4) - 0.055)
    result: NDArray[np.uint8] = np.round(255.0 * np.clip(c, 0.0, 1.0)).astype(np.uint8)
    return result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--out", default="out/anti_aliasing.png", help="where to write the sheet")
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=240)
    parser.add_argument("--server", default=None, help="'launch' to run the engine in a spear-server process")
    args = parser.parse_args()
    width, height = args.width, args.height

    settings = [("AAM_None", A.AAM_None, 1), ("AAM_FXAA", A.AAM_FXAA, 1), ("AAM_MSAA", A.AAM_MSAA, 1),
                ("SpatialSampleCount 4", A.AAM_None, 4), ("SpatialSampleCount 16", A.AAM_None, 16)]
    n = REFERENCE_GRID
    with spear.Instance(server=args.server) as instance:
        game = instance.get_game()
        with instance.begin_frame():
            scene(game)
            cameras = [camera(game, f"Camera{i}", width, height, method, samples)
                       for i, (_, method, samples) in enumerate(settings)]
            large = camera(game, "Supersampled", n * width, n * height, A.AAM_None)
        with instance.end_frame():
            pixels = [c.read_pixels() for c in cameras]
            big = large.read_pixels()
    assert "final_color" in big and "object_ids" in pixels[0]
    reference = encode(linear(big["final_color"]).reshape(height, n, width, n, 3).mean(axis=(1, 3)))
    plain_ids = pixels[0]["object_ids"]
    images: list[NDArray[np.uint8]] = []
    for (label, _, _), p in zip(settings, pixels):
        assert "final_color" in p and "object_ids" in p
        color = p["final_color"][..., :3]
        difference = np.abs(color.astype(np.float64) - reference.astype(np.float64))
        same_ids = np.array_equal(p["object_ids"], plain_ids)
        print(f"{label:20s} mean {difference.mean():.2f}, 99th percentile {np.percentile(difference, 99):.1f} "
              f"(/255, against {n}x{n} supersampled); ids as without anti-aliasing: {same_ids}")
        images.append(np.ascontiguousarray(color))
    images.append(reference)

    # The middle third of each image, magnified 3 x, side by side with its label.
    crop = (slice(height // 3, 2 * height // 3), slice(width // 3, 2 * width // 3))
    zoom = 3
    tile_w, tile_h = (width // 3) * zoom, (height // 3) * zoom
    sheet = Image.new("RGB", (len(images) * tile_w, tile_h))
    draw = ImageDraw.Draw(sheet)
    for i, (image, label) in enumerate(zip(images, [label for label, _, _ in settings] + [f"{n}x{n} supersampled"])):
        tile = Image.fromarray(np.ascontiguousarray(image[crop])).resize((tile_w, tile_h), Image.NEAREST)
        sheet.paste(tile, (i * tile_w, 0))
        draw.text((i * tile_w + 6, 4), label, fill=(255, 255, 255))
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(out)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
