"""One yard under four skies, side by side in one PNG: what the sky does to an outdoor image.

The same ground, house, shed and crate under the same sun, each in its own world, lit by:
  1. the renderer's default uniform sky (no sky light): the faces the sun does not reach are nearly black;
  2. an ASkyAtmosphere: the analytic daylight sky for the sun (Preetham, Shirley and Smits 1999), which is
     the background and lights those faces;
  3. the same atmosphere with a low, hazy sun (--low-sun-pitch, Turbidity 6);
  4. an HDR panorama: a sky light with SourceType SLS_SpecifiedCubemap and the CC0 park map shipped in
     assets/environments/ (any equirectangular .exr or .hdr works).
It prints, for each, the mean brightness of the faces in the sun's shadow and of the background.

    PYTHONPATH=python /usr/bin/python3 examples/sky_and_environment.py [--out out/sky_and_environment.png]
        [--width 480 --height 320] [--low-sun-pitch -8] [--server launch]
"""

# Debian 12's Pillow (9.4) has no annotations: strict pyright would flag every use of it.
# pyright: reportUnknownVariableType=false

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from PIL import Image, ImageDraw  # type: ignore[import]  # Debian ships no Pillow stubs

import spear

PANORAMA = "assets/environments/park.exr"


def box(game: spear.UWorld, name: str, location: tuple[float, float, float], scale: tuple[float, float, float],
        material: str) -> None:
    actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name=name, location=spear.FVector(*location))
    actor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
    actor.StaticMeshComponent.SetRelativeScale3D(NewScale3D=spear.FVector(*scale))
    actor.StaticMeshComponent.SetMaterial(ElementIndex=0, Material=material)


def yard(game: spear.UWorld, sky: str, sun_pitch: float, width: int, height: int) -> spear.UCameraSensorComponent:
    """The yard under `sky` ("uniform", "atmosphere", "hazy" or "panorama"); its camera."""
    library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Library")
    for name, (r, g, b) in {"Grass": (0.25, 0.3, 0.18), "Plaster": (0.75, 0.7, 0.62),
                            "Brick": (0.55, 0.25, 0.15), "Crate": (0.45, 0.35, 0.2)}.items():
        library.SetMaterial(Name=name, Material=spear.FMaterialDesc(
            BaseColor=spear.FLinearColor(R=r, G=g, B=b, A=1.0), Roughness=0.9))
    box(game, "Ground", (0.0, 0.0, -0.05), (60.0, 60.0, 0.1), "Grass")
    box(game, "House", (3.0, 1.0, 1.5), (4.0, 3.0, 3.0), "Plaster")
    box(game, "Shed", (0.5, -3.0, 0.75), (1.5, 1.5, 1.5), "Brick")
    box(game, "Crate", (-0.5, -0.5, 0.3), (0.6, 0.6, 0.6), "Crate")
    sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun",
                           rotation=spear.FRotator(Pitch=sun_pitch, Yaw=-60.0))
    sun.LightComponent.Intensity = 3.0
    if sky in ("atmosphere", "hazy"):
        atmosphere = game.spawn_actor(uclass=spear.ASkyAtmosphere, name="Atmosphere").SkyAtmosphereComponent
        atmosphere.Turbidity = 6.0 if sky == "hazy" else 2.5
    elif sky == "panorama":
        light = game.spawn_actor(uclass=spear.ASkyLight, name="Sky").SkyLightComponent
        light.SourceType = spear.ESkyLightSourceType.SLS_SpecifiedCubemap
        light.Cubemap = PANORAMA
        light.Intensity = 1.0  # the panorama as it is
    camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera", location=spear.FVector(-7.0, -5.0, 2.0),
                              rotation=spear.FRotator(Pitch=-8.0, Yaw=35.0)).CameraSensor
    camera.Width, camera.Height, camera.FOV = width, height, 75.0
    camera.Modalities = [spear.ECameraModality.FinalColor, spear.ECameraModality.HdrColor,
                         spear.ECameraModality.ObjectIds]
    camera.ShadowResolution = 2048
    camera.Exposure = 0.6 if sky == "panorama" else 1.0
    return camera


def luminance(hdr: NDArray[np.float16]) -> NDArray[np.float64]:
    rgb = hdr[..., :3].astype(np.float64)
    result: NDArray[np.float64] = 0.2126 * rgb[..., 0] + 0.7152 * rgb[..., 1] + 0.0722 * rgb[..., 2]
    return result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--out", default="out/sky_and_environment.png", help="where to write the four images")
    parser.add_argument("--width", type=int, default=480)
    parser.add_argument("--height", type=int, default=320)
    parser.add_argument("--sun-pitch", type=float, default=-35.0, help="the sun's pitch, degrees (negative: down)")
    parser.add_argument("--low-sun-pitch", type=float, default=-8.0, help="the hazy sky's sun")
    parser.add_argument("--server", default=None, help="'launch' to run the engine in a spear-server process")
    args = parser.parse_args()

    skies = [("uniform", "default uniform sky", args.sun_pitch), ("atmosphere", "ASkyAtmosphere", args.sun_pitch),
             ("hazy", "ASkyAtmosphere, low hazy sun", args.low_sun_pitch),
             ("panorama", "HDR panorama (park.exr)", args.sun_pitch)]
    sheet = Image.new("RGB", (2 * args.width, 2 * args.height))
    draw = ImageDraw.Draw(sheet)
    with spear.Instance(server=args.server) as instance:
        cameras: list[spear.UCameraSensorComponent] = []
        with instance.begin_frame():
            for i, (sky, _, pitch) in enumerate(skies):
                game = instance.get_game() if i == 0 else instance.create_world(name=f"Yard{i}")
                cameras.append(yard(game, sky, pitch, args.width, args.height))
        with instance.end_frame():
            images = [camera.read_pixels() for camera in cameras]
        for i, ((sky, label, _), pixels) in enumerate(zip(skies, images)):
            assert "final_color" in pixels and "hdr_color" in pixels and "object_ids" in pixels
            lum = luminance(pixels["hdr_color"])
            geometry = pixels["object_ids"] != 0
            # The faces in the sun's shadow: the darkest 2 % of the geometry's pixels.
            shade = float(np.percentile(lum[geometry], 2)) if geometry.any() else 0.0
            background = float(lum[~geometry].mean()) if (~geometry).any() else 0.0
            print(f"{label:32s} shaded faces {shade:.3f}, background {background:.3f} (hdr_color luminance)")
            x, y = (i % 2) * args.width, (i // 2) * args.height
            sheet.paste(Image.fromarray(np.ascontiguousarray(pixels["final_color"][..., :3])), (x, y))
            draw.text((x + 6, y + 4), label, fill=(255, 255, 255))
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(out)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
