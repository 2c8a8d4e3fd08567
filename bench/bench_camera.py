"""Camera sensor throughput through the Python API, with MuJoCo's own renderer as a peer in the same run.

Scene (the same in both, and as in core/render/bench/render_bench.cpp): a 40 x 40 m ground plane, N boxes
of 0.6 m, a shadowed sun and a shadowed spot light, 2048-texel shadow maps, no MSAA, 60 degree horizontal
FOV. For spear, one frame is `with instance.begin_frame(): pass` + `with instance.end_frame():
camera.read_pixels()`: world tick, render-scene sync, render, readback and the numpy dict, at 256x256
and 1920x1080, final_color only and all 14 modalities, for latency 0, 1 and 2. For MuJoCo,
mjr_render + mjr_readPixels (RGB, and RGB + depth) on an EGL context of the same device.

    PYTHONPATH=python /usr/bin/python3 bench/bench_camera.py [--build-dir build] [--boxes 64] [--frames 10]
"""

from __future__ import annotations

import argparse
import math
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402

M = spear.ECameraModality


def build_scene(game: spear.UWorld, boxes: int) -> None:
    ground = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Ground")
    ground.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Plane")
    ground.SetActorScale3D(NewScale3D=spear.FVector(40.0, 40.0, 1.0))
    library = game.spawn_actor(uclass=spear.AMaterialLibrary, name="Materials")
    library.SetMaterial(Name="Ground", Material=spear.FMaterialDesc(BaseColor=spear.FLinearColor(0.55, 0.55, 0.5, 1.0), Roughness=0.9))
    ground.StaticMeshComponent.SetMaterial(ElementIndex=0, Material="Ground")
    side = max(1, math.ceil(math.sqrt(boxes)))
    for i in range(boxes):
        name = f"Box{i}"
        library.SetMaterial(Name=name, Material=spear.FMaterialDesc(
            BaseColor=spear.FLinearColor(0.2 + 0.6 * ((i * 37) % 11) / 10, 0.2 + 0.6 * ((i * 17) % 7) / 6,
                                         0.2 + 0.6 * ((i * 53) % 5) / 4, 1.0),
            Roughness=0.2 + 0.7 * (i % 4) / 3, Metallic=1.0 if i % 5 == 0 else 0.0))
        box = game.spawn_actor(
            uclass=spear.AStaticMeshActor, name=name,
            location=spear.FVector(1.2 * (i % side) - 0.6 * side, 1.2 * (i // side) - 0.6 * side, 0.3 + 0.4 * (i % 3)),
            rotation=spear.FRotator(Yaw=math.degrees(0.3 * i)),
        )
        box.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        box.StaticMeshComponent.SetMaterial(ElementIndex=0, Material=name)
        box.SetActorScale3D(NewScale3D=spear.FVector(0.6, 0.6, 0.6))
    sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(
        Pitch=-math.degrees(math.atan2(1.0, math.hypot(0.5, 0.3))), Yaw=math.degrees(math.atan2(-0.3, -0.5))))
    sun.LightComponent.Intensity = 3.0
    spot = game.spawn_actor(uclass=spear.ASpotLight, name="Spot", location=spear.FVector(0.0, 0.0, 6.0), rotation=spear.FRotator(
        Pitch=-math.degrees(math.atan2(1.0, math.hypot(0.2, 0.1))), Yaw=math.degrees(math.atan2(0.1, 0.2))))
    spot.LightComponent.Intensity = 30.0
    spot.LightComponent.AttenuationRadius = 0.0
    sky = game.spawn_actor(uclass=spear.ASkyLight, name="Sky")
    sky.SkyLightComponent.SkyColor = spear.FLinearColor(0.1, 0.12, 0.15, 1.0)
    sky.SkyLightComponent.Intensity = 1.0
    sky.SkyLightComponent.BackgroundColor = spear.FLinearColor(0.3, 0.35, 0.45, 1.0)


def spear_rows(boxes: int, frames: int) -> list[str]:
    instance = spear.Instance()
    game = instance.get_game()
    extent = 0.6 * math.ceil(math.sqrt(boxes)) + 2.0
    position = (-1.4 * extent, -1.1 * extent, 0.9 * extent)
    with instance.begin_frame():
        build_scene(game, boxes)
        camera = game.spawn_actor(
            uclass=spear.ACameraSensorActor, name="Camera", location=spear.FVector(*position),
            rotation=spear.FRotator(Pitch=-math.degrees(math.atan2(position[2], math.hypot(position[0], position[1]))),
                                    Yaw=math.degrees(math.atan2(-position[1], -position[0]))),
        ).CameraSensor
        camera.FOV, camera.ShadowResolution = 60.0, 2048
        device = camera.get_render_device_info()
    with instance.end_frame():
        pass
    rows = [f"spear on EGL {device.Kind}: {device.Renderer}; {boxes} boxes, shadow maps 2048, "
            f"{frames} timed frames after 3 warm-up frames"]
    for width, height in ((256, 256), (1920, 1080)):
        for label, modalities in (("final_color", [M.FinalColor]), ("all (14)", list(M))):
            for latency in (0, 1, 2):
                with instance.begin_frame():
                    camera.Width, camera.Height, camera.Modalities, camera.Latency = width, height, modalities, latency
                with instance.end_frame():
                    camera.read_pixels()
                elapsed = 0.0
                for frame in range(frames + 3):
                    start = time.perf_counter()
                    with instance.begin_frame():
                        pass
                    with instance.end_frame():
                        px = camera.read_pixels()
                    if frame >= 3:
                        elapsed += time.perf_counter() - start
                assert len(px) == len(modalities)
                rows.append(f"spear  {width:4d}x{height:<4d} {label:<11} latency {latency}  {1000 * elapsed / frames:8.2f} ms/frame")
    instance.close()
    return rows


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--build-dir", type=Path, default=ROOT / "build")
    parser.add_argument("--boxes", type=int, default=64)
    parser.add_argument("--frames", type=int, default=10)
    args = parser.parse_args()
    for row in spear_rows(args.boxes, args.frames):
        print(row, flush=True)
    peer = args.build_dir / "bench" / "spear_mujoco_peer"
    if not peer.exists():
        print(f"MuJoCo peer not built ({peer}): install libmujoco-dev and rebuild")
        return
    result = subprocess.run([str(peer), "--boxes", str(args.boxes), "--frames", str(args.frames)],
                            capture_output=True, text=True, check=False)
    print(result.stdout.rstrip())
    if result.returncode:
        print(f"MuJoCo peer failed: {result.stderr.strip()}")


if __name__ == "__main__":
    main()
