"""A house of many lamps: a view of one room, the lamps of the other rooms out of its sight.

A camera sees a room lit by a sun and 2 lamps; the world holds N more lamps (4 m apart, 5 m range) behind the
camera, in rooms it does not see. The floor is the same view in a world without those lamps: a view shades
the lamps whose range reaches it (core/render/README.md, "Shadows" and the lights), so the ratio should stay
near 1 whatever N, on both transports.

    PYTHONPATH=python /usr/bin/python3 bench/bench_lights.py [--lamps 16 64 256] [--frames 40] [--server launch]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402


def frame_ms(server: str | None, elsewhere: int, frames: int, width: int, height: int) -> tuple[float, int]:
    """Mean ms a frame (read_pixels of final_color included) with `elsewhere` lamps out of sight, and the
    lights the view left out past the 16 it shades."""
    instance = spear.Instance(server=server)
    try:
        game = instance.get_game()
        with instance.begin_frame():
            floor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Floor")
            floor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Plane")
            floor.SetActorScale3D(NewScale3D=spear.FVector(400.0, 400.0, 1.0))
            side = 16
            for i in range(elsewhere):  # rooms behind the camera, which looks along +X
                lamp = game.spawn_actor(uclass=spear.APointLight, location=spear.FVector(
                    X=-20.0 - 4.0 * (i // side), Y=4.0 * (i % side - side // 2), Z=1.5))
                lamp.LightComponent.AttenuationRadius = 5.0
            for j in range(2):  # the room in view
                lamp = game.spawn_actor(uclass=spear.APointLight,
                                        location=spear.FVector(X=4.0 + 3.0 * j, Y=1.0 - 2.0 * j, Z=1.5))
                lamp.LightComponent.AttenuationRadius = 5.0
            game.spawn_actor(uclass=spear.ADirectionalLight, rotation=spear.FRotator(Pitch=-40.0, Yaw=20.0))
            camera = game.spawn_actor(uclass=spear.ACameraSensorActor, location=spear.FVector(X=-2.0, Z=3.0),
                                      rotation=spear.FRotator(Pitch=-30.0)).CameraSensor
            camera.Width, camera.Height, camera.FOV = width, height, 60.0
        with instance.end_frame():
            pass
        start = 0.0
        for k in range(5 + frames):
            if k == 5:
                start = time.perf_counter()
            with instance.begin_frame():
                pass
            with instance.end_frame():
                camera.read_pixels()
        elapsed = (time.perf_counter() - start) / frames * 1e3
        with instance.begin_frame():
            pass
        with instance.end_frame():
            left_out = camera.GetRenderStats().LightsLeftOut
        return elapsed, left_out
    finally:
        instance.close()


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lamps", type=int, nargs="+", default=[16, 64, 256], help="lamps out of sight")
    parser.add_argument("--frames", type=int, default=40)
    parser.add_argument("--size", default="1920x1080", help="WxH")
    parser.add_argument("--server", default=None, help='None: in-process; "launch" for spear-server')
    args = parser.parse_args()
    width, height = (int(part) for part in args.size.split("x"))
    floor, _ = frame_ms(args.server, 0, args.frames, width, height)
    print(f"{args.size}, {'in-process' if args.server is None else 'RPC'}, {args.frames} frames")
    print("| lamps out of sight | ms/frame | floor: none out of sight, ms/frame | ratio | lights left out |")
    print("|---:|---:|---:|---:|---:|")
    for lamps in args.lamps:
        ms, left_out = frame_ms(args.server, lamps, args.frames, width, height)
        print(f"| {lamps} | {ms:.1f} | {floor:.1f} | {ms / floor:.2f} | {left_out} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
