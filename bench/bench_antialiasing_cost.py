"""What each anti-aliasing setting costs a rasterised frame: the default scene (the apartment) at one pose,
final_color only, with each AntiAliasingMethod and with SpatialSampleCount 2, 4, 8 and 16 (FXAA on top, as
a user keeping the default would have it). The settings take turns frame by frame, so that a busy machine
slows them alike; printed is each one's median frame time (begin_frame to the pixels read) and its ratio to
AAM_None's.

    PYTHONPATH=python /usr/bin/python3 bench/bench_antialiasing_cost.py [--width 1920 --height 1080]
        [--rounds 5] [--server launch]
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

import spear

APARTMENT = Path(__file__).resolve().parent.parent / "assets" / "scenes" / "apartment.json"
A = spear.EAntiAliasingMethod
# Label, AntiAliasingMethod, SpatialSampleCount.
SETTINGS = [("AAM_None", A.AAM_None, 1), ("AAM_FXAA", A.AAM_FXAA, 1), ("AAM_MSAA", A.AAM_MSAA, 1)] + [
    (f"SpatialSampleCount {n} + FXAA", A.AAM_FXAA, n) for n in (2, 4, 8, 16)]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--width", type=int, default=1920)
    parser.add_argument("--height", type=int, default=1080)
    parser.add_argument("--rounds", type=int, default=5, help="frames timed for each setting")
    parser.add_argument("--server", default=None, help="'launch' to run the engine in a spear-server process")
    args = parser.parse_args()

    with spear.Instance(server=args.server) as instance:
        game = instance.get_game()
        with instance.begin_frame():
            game.load_scene(path=str(APARTMENT))
            camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera",
                                      location=spear.FVector(-2.6, -1.6, 1.7),
                                      rotation=spear.FRotator(Pitch=-18.0, Yaw=22.0)).CameraSensor
            camera.Width, camera.Height, camera.FOV = args.width, args.height, 75.0
            camera.Modalities = [spear.ECameraModality.FinalColor]
        with instance.end_frame():
            pass
        times: dict[str, list[float]] = {label: [] for label, _, _ in SETTINGS}
        for round_ in range(args.rounds + 1):  # the first round warms up: programs compiled, targets made
            for label, method, samples in SETTINGS:
                with instance.begin_frame():
                    camera.AntiAliasingMethod = method
                    camera.SpatialSampleCount = samples
                with instance.end_frame():
                    pass
                start = time.perf_counter()
                with instance.begin_frame():
                    pass
                with instance.end_frame():
                    assert "final_color" in camera.read_pixels()
                if round_ > 0:
                    times[label].append(time.perf_counter() - start)
            print(f"round {round_ + 1} of {args.rounds + 1} done", flush=True)
    base = statistics.median(times["AAM_None"])
    print(f"\n| setting ({args.width}x{args.height}, the apartment, final_color) | median frame (ms) | x AAM_None |")
    print("|---|---:|---:|")
    for label, _, _ in SETTINGS:
        median = statistics.median(times[label])
        print(f"| {label} | {1000 * median:.1f} | {median / base:.2f} |")


if __name__ == "__main__":
    main()
