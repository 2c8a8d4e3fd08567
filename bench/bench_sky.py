"""What a sky costs a frame: a still sun against one that turns every frame, under an analytic sky.

A world with a sun, an ASkyAtmosphere and one small camera (final_color): with the sun still the sky is made
once; turned every frame, the sky, its spherical harmonics, prefiltered chain and sampling density are made
and uploaded every frame (core/render/README.md, "Sky and environment light"). The floor is the same world
with a uniform sky light, where nothing is made. Alternating runs, ms a frame, read_pixels included.

    PYTHONPATH=python /usr/bin/python3 bench/bench_sky.py [--frames 30] [--rounds 2] [--server launch]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402


def frame_ms(instance: spear.Instance, sun: spear.ADirectionalLight, camera: spear.UCameraSensorComponent,
             frames: int, turning: bool) -> float:
    start = time.perf_counter()
    for i in range(frames):
        with instance.begin_frame():
            if turning:
                sun.SetActorRotation(NewRotation=spear.FRotator(Pitch=-40.0 + 0.5 * (i % 20), Yaw=float(i)))
        with instance.end_frame():
            camera.read_pixels()
    return (time.perf_counter() - start) / frames * 1000.0


def world(instance: spear.Instance, name: str, atmosphere: bool
          ) -> tuple[spear.ADirectionalLight, spear.UCameraSensorComponent]:
    with instance.begin_frame():
        game = instance.create_world(name=name)
        sun = game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(Pitch=-40.0))
        if atmosphere:
            game.spawn_actor(uclass=spear.ASkyAtmosphere, name="Sky")
        else:
            game.spawn_actor(uclass=spear.ASkyLight, name="Sky")
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera").CameraSensor
        camera.Width, camera.Height = 64, 48
        camera.Modalities = [spear.ECameraModality.FinalColor]
    with instance.end_frame():
        camera.read_pixels()
    return sun, camera


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--frames", type=int, default=30)
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--server", default=None, help="'launch' to measure over RPC")
    args = parser.parse_args()
    instance = spear.Instance(server=args.server)
    try:
        rows: dict[str, list[float]] = {}
        for name, atmosphere in (("uniform sky light", False), ("ASkyAtmosphere", True)):
            sun, camera = world(instance, name.replace(" ", ""), atmosphere)
            for _ in range(args.rounds):
                for turning in (False, True):
                    key = f"{name}, sun {'turning every frame' if turning else 'still'}"
                    rows.setdefault(key, []).append(frame_ms(instance, sun, camera, args.frames, turning))
            with instance.begin_frame():
                camera.Modalities = []  # this world's camera renders nothing more
            with instance.end_frame():
                pass
        print("| world | ms a frame |")
        print("|---|---:|")
        for key, values in rows.items():
            print(f"| {key} | {' / '.join(f'{v:.1f}' for v in values)} |")
    finally:
        instance.close()


if __name__ == "__main__":
    main()
