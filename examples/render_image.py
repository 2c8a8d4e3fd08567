"""Render every camera modality of the default apartment scene and write one labelled contact sheet.

By default the built-in scene assets/scenes/apartment.json is loaded (UWorld.load_scene); --scene picks
another scene file, and --room builds a small room from basic shapes here instead. A camera renders all
14 modalities in one frame; each is visualised (ids in random colours, depth and normals mapped, HDR
images tone-mapped) and tiled into one PNG.

    PYTHONPATH=python /usr/bin/python3 examples/render_image.py [--out out/render_image.png] [--server launch]
"""

# Debian 12's Pillow (9.4) has no annotations: strict pyright would flag every use of it.
# pyright: reportUnknownVariableType=false

from __future__ import annotations

import argparse
from collections.abc import Mapping
from pathlib import Path
from typing import cast

import numpy as np
from numpy.typing import NDArray
from PIL import Image, ImageDraw  # type: ignore[import]  # Debian ships no Pillow stubs

import spear
import spear.images

WIDTH, HEIGHT = 480, 360
# By asset name: found in the working directory, SPEAR_ASSET_PATH or spear's own assets (a checkout or the
# installed package), so the example runs from anywhere.
DEFAULT_SCENE = "/Game/scenes/apartment"


def box(
    game: spear.UWorld, name: str, centre: tuple[float, float, float], size: tuple[float, float, float], material: str,
    mesh: str = "Cube",
) -> None:
    actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name=name, location=spear.FVector(*centre))
    actor.StaticMeshComponent.SetStaticMesh(NewMesh=f"/Engine/BasicShapes/{mesh}")
    actor.StaticMeshComponent.SetMaterial(ElementIndex=0, Material=material)
    actor.SetActorScale3D(NewScale3D=spear.FVector(*size))


def build_room(game: spear.UWorld) -> None:
    """A 6 x 5 m room open to the sky, with a table, boxes, a ball, a rug, a lamp and a window of sun."""
    library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Materials")
    library.SetMaterial(Name="DarkWood", Material=spear.FMaterialDesc(BaseColor=spear.FLinearColor(0.12, 0.06, 0.03, 1.0), Roughness=0.45))
    library.SetMaterial(Name="Tiles", Material=spear.FMaterialDesc(BaseColor=spear.FLinearColor(0.55, 0.5, 0.42, 1.0), Roughness=0.3))
    library.SetMaterial(Name="LampShade", Material=spear.FMaterialDesc(BaseColor=spear.FLinearColor(0.9, 0.85, 0.7, 1.0), Emissive=spear.FLinearColor(3.0, 2.6, 1.8, 1.0)))

    box(game, "Floor", (0.0, 0.0, -0.05), (6.0, 5.0, 0.1), "Tiles")
    box(game, "BackWall", (3.05, 0.0, 1.4), (0.1, 5.0, 2.8), "Plaster")
    box(game, "LeftWall", (0.0, 2.55, 1.4), (6.0, 0.1, 2.8), "Plaster")
    box(game, "Rug", (0.6, -0.2, 0.005), (2.4, 1.8, 0.01), "Fabric")
    box(game, "TableTop", (1.0, 0.0, 0.74), (1.4, 0.8, 0.04), "DarkWood")
    for i, (x, y) in enumerate([(0.4, 0.32), (0.4, -0.32), (1.6, 0.32), (1.6, -0.32)]):
        box(game, f"TableLeg{i}", (x, y, 0.36), (0.05, 0.05, 0.72), "DarkWood", mesh="Cylinder")
    box(game, "Shelf", (2.8, 1.5, 0.9), (0.4, 1.6, 1.8), "Wood")
    box(game, "RedBox", (0.8, 0.15, 0.86), (0.2, 0.2, 0.2), "Red")
    box(game, "BlueBox", (1.25, -0.15, 0.835), (0.3, 0.2, 0.15), "Blue")
    box(game, "Crate", (1.8, -1.4, 0.25), (0.5, 0.5, 0.5), "Yellow")
    box(game, "Crate2", (1.75, -1.35, 0.65), (0.3, 0.3, 0.3), "Green")
    box(game, "Ball", (1.2, 0.2, 0.86), (0.2, 0.2, 0.2), "Gold", mesh="Sphere")
    box(game, "Vase", (2.8, 1.2, 1.95), (0.15, 0.15, 0.3), "Metal", mesh="Cylinder")
    box(game, "LampPole", (2.5, -2.1, 0.75), (0.04, 0.04, 1.5), "Black", mesh="Cylinder")
    box(game, "LampShade", (2.5, -2.1, 1.55), (0.3, 0.3, 0.25), "LampShade", mesh="Cylinder")

    sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(Pitch=-50.0, Yaw=-30.0))
    sun.LightComponent.Intensity = 4.0
    sun.LightComponent.LightColor = spear.FLinearColor(1.0, 0.95, 0.85, 1.0)
    lamp = game.spawn_actor(uclass=spear.APointLight, name="Lamp", location=spear.FVector(2.4, -1.9, 1.3))
    lamp.LightComponent.Intensity = 3.0
    lamp.LightComponent.LightColor = spear.FLinearColor(1.0, 0.8, 0.55, 1.0)
    spot = game.spawn_actor(uclass=spear.ASpotLight, name="Spot", location=spear.FVector(1.0, 0.0, 2.6), rotation=spear.FRotator(Pitch=-90.0))
    spot.LightComponent.Intensity = 4.0
    sky = game.spawn_actor(uclass=spear.ASkyLight, name="Sky")
    sky.SkyLightComponent.SkyColor = spear.FLinearColor(0.6, 0.75, 1.0, 1.0)
    sky.SkyLightComponent.Intensity = 0.5
    sky.SkyLightComponent.BackgroundColor = spear.FLinearColor(0.35, 0.5, 0.8, 1.0)


# -- visualisation: every modality to uint8 RGB -----------------------------------------------------------


def srgb(linear: NDArray[np.float32]) -> NDArray[np.uint8]:
    x = np.clip(linear.astype(np.float32), 0.0, 1.0)
    encoded = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    result: NDArray[np.uint8] = (encoded * 255 + 0.5).astype(np.uint8)
    return result


def tonemap(hdr: NDArray[np.float32]) -> NDArray[np.uint8]:
    x = np.maximum(hdr[..., :3].astype(np.float32), 0.0)
    return srgb(x / (1.0 + x))


def grey(values: NDArray[np.float32], lo: float = 0.0, hi: float = 1.0) -> NDArray[np.uint8]:
    x = np.clip((values.astype(np.float32) - lo) / (hi - lo), 0.0, 1.0)
    return np.repeat((x * 255 + 0.5).astype(np.uint8)[..., None], 3, axis=2)


def position_image(position: NDArray[np.float32]) -> NDArray[np.uint8]:
    lo, hi = position.reshape(-1, 3).min(axis=0), position.reshape(-1, 3).max(axis=0)
    result: NDArray[np.uint8] = ((position - lo) / np.maximum(hi - lo, 1e-6) * 255).astype(np.uint8)
    return result


def visualise(name: str, image: NDArray[np.generic]) -> NDArray[np.uint8]:
    if name == "final_color":
        return image[..., :3].astype(np.uint8)
    if name in ("hdr_color", "diffuse_illumination", "diffuse_only", "specular_residual"):
        return tonemap(image.astype(np.float32))
    if name == "depth":
        return spear.images.depth_grey(image.astype(np.float32))
    if name == "position":
        return position_image(image.astype(np.float32))
    if name == "normal":
        normal: NDArray[np.uint8] = ((image.astype(np.float32) * 0.5 + 0.5) * 255).clip(0, 255).astype(np.uint8)
        return normal
    if name in ("object_ids", "material_ids"):
        return spear.images.id_colours(image.astype(np.uint32))
    if name == "base_color":
        return srgb(image.astype(np.float32))
    return grey(image.astype(np.float32))  # roughness, metallic, material_ao


def contact_sheet(pixels: spear.FCameraPixels, order: list[str], columns: int = 4) -> Image.Image:
    label_height = 22
    rows = (len(order) + columns - 1) // columns
    sheet = Image.new("RGB", (columns * WIDTH, rows * (HEIGHT + label_height)), 0x181818)  # packed dark grey
    draw: ImageDraw.ImageDraw = ImageDraw.Draw(sheet)
    images: Mapping[str, object] = pixels  # indexed by run-time names below
    for i, name in enumerate(order):
        image = cast("NDArray[np.generic]", images[name])
        x, y = (i % columns) * WIDTH, (i // columns) * (HEIGHT + label_height)
        sheet.paste(Image.fromarray(visualise(name, image)), (x, y + label_height))
        draw.text((x + 6, y + 5), f"{name}  {image.dtype} {image.shape}", fill=(235, 235, 235))
    return sheet


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--out", default="out/render_image.png", help="where to write the contact sheet")
    parser.add_argument("--scene", default=DEFAULT_SCENE, help="the scene file to render (default: %(default)s)")
    parser.add_argument("--room", action="store_true", help="build a room from basic shapes here instead")
    parser.add_argument("--server", default=None, help='"launch", "unix:PATH" or "tcp:HOST:PORT" (default: in-process)')
    args = parser.parse_args()

    instance = spear.Instance(server=args.server)
    game = instance.get_game()
    with instance.begin_frame():
        if args.room:
            build_room(game)
        else:
            game.load_scene(path=args.scene)
        camera_actor = game.spawn_actor(
            uclass=spear.ACameraSensorActor, name="Camera", location=spear.FVector(-2.6, -1.6, 1.7),
            rotation=spear.FRotator(Pitch=-18.0, Yaw=22.0),
        )
        camera = camera_actor.CameraSensor
        camera.Width, camera.Height, camera.FOV = WIDTH, HEIGHT, 75.0
        camera.Modalities = list(spear.ECameraModality)  # all 14
        camera.ShadowResolution = 2048
        # Metered from the view (the first frame is exposed for what it shows): the sunlit walls, the lamp
        # and the shade need no hand-set Exposure.
        camera.AutoExposureMethod = spear.EAutoExposureMethod.AEM_Histogram
        device = camera.get_render_device_info()
        print(f"rendering on EGL {device.Kind}: {device.Renderer} ({device.Vendor}, OpenGL {device.Version})")

    with instance.end_frame():
        pixels = camera.read_pixels()
        order = camera.GetModalityNames()
        assert "object_ids" in pixels and "depth" in pixels  # all 14 modalities were asked for
        ids = pixels["object_ids"]
        visible = [int(i) for i in np.unique(ids) if i != 0]
        names = sorted({camera.GetObjectIdInfo(ObjectId=i).Actor.GetName() for i in visible})  # type: ignore[union-attr]
        print(f"{len(visible)} object ids visible: {', '.join(names)}")
        print(f"depth range {pixels['depth'][pixels['depth'] > 0].min():.2f} .. {pixels['depth'].max():.2f} m")
        print(f"automatic exposure: {camera.GetAppliedExposure():.3f}")

    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    contact_sheet(pixels, order).save(out)
    print(f"wrote {out.resolve()}")
    instance.close()


if __name__ == "__main__":
    main()
