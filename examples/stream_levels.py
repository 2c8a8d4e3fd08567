"""Streaming levels: a long road of blocks, written as one persistent scene that declares three streaming
levels (one per block of buildings), driven along by a camera that loads the block ahead and unloads the
one behind with UGameplayStatics.LoadStreamLevel / UnloadStreamLevel, inside its frames. Writes the level
files, then a strip of the camera's views and how many actors the world held at each.

    PYTHONPATH=python /usr/bin/python3 examples/stream_levels.py [--server launch] [--out out/stream_levels]
"""

# Debian 12's Pillow (9.4) has no annotations: strict pyright would flag every use of it.
# pyright: reportUnknownVariableType=false, reportUnknownMemberType=false

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from PIL import Image  # type: ignore[import]  # Debian ships no Pillow stubs

import spear

BLOCK_LENGTH = 40.0  # metres of road per level
BLOCKS = 3
WIDTH, HEIGHT = 320, 180


def building(game: spear.UWorld, name: str, x: float, y: float, height: float, material: str) -> None:
    actor = game.spawn_actor(uclass=spear.AStaticMeshActor, name=name, location=spear.FVector(x, y, height / 2))
    actor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
    actor.StaticMeshComponent.SetMaterial(ElementIndex=0, Material=material)
    actor.SetActorScale3D(NewScale3D=spear.FVector(8.0, 8.0, height))


def write_levels(instance: spear.Instance, folder: Path) -> Path:
    """Each block's buildings in levels/block_N.json, and main.json: the road, lights, materials, and the
    "levels" list that declares the blocks (paths relative to main.json)."""
    game = instance.get_game()
    (folder / "levels").mkdir(parents=True, exist_ok=True)
    with instance.begin_frame():
        for block in range(BLOCKS):
            start = block * BLOCK_LENGTH
            for i in range(4):
                for side in (-1, 1):
                    height = 6.0 + 5.0 * ((block * 7 + i * 3 + (side + 1)) % 4)
                    material = ("Brick", "Concrete", "Glass")[(block + i + (side + 1) // 2) % 3]
                    building(game, f"Block{block}_{i}_{'L' if side > 0 else 'R'}", start + 5.0 + 10.0 * i,
                             side * 11.0, height, material)
            game.save_scene(path=str(folder / "levels" / f"block_{block}.json"))
            for actor in game.find_actors():
                game.destroy_actor(actor=actor)
        library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Materials")
        for name, colour in (("Road", (0.12, 0.12, 0.13)), ("Brick", (0.55, 0.25, 0.18)),
                             ("Concrete", (0.6, 0.6, 0.58)), ("Glass", (0.25, 0.35, 0.45))):
            library.SetMaterial(Name=name, Material=spear.FMaterialDesc(
                BaseColor=spear.FLinearColor(*colour, 1.0), Roughness=0.7))
        road = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Road",
                                location=spear.FVector(BLOCKS * BLOCK_LENGTH / 2, 0.0, 0.0))
        road.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Plane")
        road.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Road")
        road.SetActorScale3D(NewScale3D=spear.FVector(BLOCKS * BLOCK_LENGTH + 40.0, 60.0, 1.0))
        sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun",
                               rotation=spear.FRotator(Pitch=-65.0, Yaw=30.0))
        sun.LightComponent.Intensity = 3.0
        sky = game.spawn_actor(uclass=spear.ASkyLight, name="Sky")
        sky.SkyLightComponent.BackgroundColor = spear.FLinearColor(0.5, 0.6, 0.75, 1.0)
        game.save_scene(path=str(folder / "main.json"))
    with instance.end_frame():
        pass
    main = json.loads((folder / "main.json").read_text())
    main["levels"] = [{"name": f"Block{b}", "path": f"levels/block_{b}.json", "loaded": b == 0} for b in range(BLOCKS)]
    (folder / "main.json").write_text(json.dumps(main, indent=2) + "\n")
    return folder / "main.json"


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--server", default=None, help='"launch", "unix:PATH" or "tcp:HOST:PORT" (default: in-process)')
    parser.add_argument("--out", default="out/stream_levels", help="folder for the level files and the views")
    args = parser.parse_args()
    out = Path(args.out).resolve()

    instance = spear.Instance(server=args.server)
    scene = write_levels(instance, out)
    game = instance.get_game()
    statics = spear.UGameplayStatics
    with instance.begin_frame():
        game.load_scene(path=str(scene))  # Block0 is marked loaded in the scene, so it comes with it
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera")
        camera.CameraSensor.Width, camera.CameraSensor.Height, camera.CameraSensor.FOV = WIDTH, HEIGHT, 70.0
    with instance.end_frame():
        pass

    views: list[NDArray[np.uint8]] = []
    steps = int(BLOCKS * BLOCK_LENGTH / 5.0)
    for step in range(steps):
        x = 5.0 * step - 10.0
        block = int(max(x, 0.0) // BLOCK_LENGTH)
        with instance.begin_frame():
            # Keep the block the camera is in and the next one; let go of the one behind.
            for b in range(BLOCKS):
                name = f"Block{b}"
                wanted = block <= b <= block + 1
                loaded = statics.IsStreamingLevelLoaded(WorldContextObject=game, LevelName=name)
                if wanted and not loaded:
                    statics.LoadStreamLevel(WorldContextObject=game, LevelName=name)
                elif loaded and not wanted:
                    statics.UnloadStreamLevel(WorldContextObject=game, LevelName=name)
            camera.K2_SetActorLocationAndRotation(NewLocation=spear.FVector(x, 0.0, 3.0),
                                                  NewRotation=spear.FRotator(Pitch=-2.0))
            loaded_now = [n for n in statics.GetStreamingLevelNames(WorldContextObject=game)
                          if statics.IsStreamingLevelLoaded(WorldContextObject=game, LevelName=n)]
            count = game.get_actor_count()
        with instance.end_frame():
            if step % 6 == 0:
                pixels = camera.CameraSensor.read_pixels()
                if "final_color" not in pixels:
                    raise spear.InvalidStateError("stream_levels: the camera rendered no final_color")
                views.append(pixels["final_color"][:, :, :3].copy())
                print(f"step {step + 1}/{steps}: camera at x = {x:.0f} m, levels loaded: {', '.join(loaded_now)}; "
                      f"{count} actors", flush=True)
    instance.close()
    strip = np.concatenate(views, axis=1)
    Image.fromarray(strip).save(out / "views.png")
    print(f"wrote {out / 'views.png'} ({len(views)} views)")


if __name__ == "__main__":
    main()
