"""The browser inspector's cost and speed (issue #53), on the default apartment scene with a 640x480 camera, in
headless chromium over loopback:

1. Viewer frames per second: the page running frames itself (Run) and showing each one, against the floor of a
   Python loop doing the same over the same transport (a frame, then read_pixels of the camera).
2. The engine's frame time while a Python script drives it (a frame and a read_pixels a frame, as a data
   generator does) with a browser attached and watching the camera, against none attached (goal <= 1.05x), and
   with the inspector started against not started at all (what serving it costs nobody watching).

    PYTHONPATH=python /usr/bin/python3 bench/bench_inspector.py [--server launch|inprocess] [--seconds 10] [--frames 300]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import threading
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python"))

import spear  # noqa: E402

W, H = 640, 480
SCENE = "/Game/scenes/apartment"


def make(server: str | None, inspect: bool) -> tuple[spear.Instance, spear.ACameraSensorActor, str]:
    instance = spear.Instance(server=server, scene=SCENE)
    game = instance.get_game()
    with instance.begin_frame():
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Viewer",
                                  location=spear.FVector(-1.5, 0.0, 1.5), rotation=spear.FRotator(Pitch=-15.0))
        camera.CameraSensor.Width = W
        camera.CameraSensor.Height = H
    with instance.end_frame():
        pass
    return instance, camera, instance.inspect(port=0) if inspect else ""


def browser() -> Any:
    from selenium import webdriver

    options = webdriver.ChromeOptions()
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1400,900"):
        options.add_argument(argument)  # type: ignore[no-untyped-call]  # unannotated in Debian's selenium 4.8
    return webdriver.Chrome(options=options)


def serving(instance: spear.Instance, done: threading.Event) -> None:
    """In-process the engine answers its browsers only when this thread lets it: while the browser works."""
    while not done.is_set():
        instance.serve_inspector(seconds=0.05)


def in_thread(instance: spear.Instance, work: Any) -> Any:
    result: list[Any] = []
    done = threading.Event()

    def run() -> None:
        try:
            result.append(work())
        finally:
            done.set()

    thread = threading.Thread(target=run)
    thread.start()
    serving(instance, done)
    thread.join()
    return result[0]


def open_page(driver: Any, url: str) -> None:
    from selenium.webdriver.support.wait import WebDriverWait

    driver.get(url)
    WebDriverWait(driver, 60).until(lambda d: d.execute_script("return document.body.dataset.ready") == "true")


def viewer_fps(instance: spear.Instance, driver: Any, url: str, seconds: float) -> tuple[float, float]:
    """(images shown per second, frames run per second) while the page runs frames itself."""
    from selenium.webdriver.common.by import By

    def run() -> tuple[float, float]:
        open_page(driver, url)
        count = "return [window.spearInspector.viewport.draws, Number(document.getElementById('frame-count').textContent)]"
        driver.find_element(By.ID, "run-button").click()
        time.sleep(1.0)  # past the first frames
        draws0, frames0 = driver.execute_script(count)
        start = time.perf_counter()
        time.sleep(seconds)
        draws1, frames1 = driver.execute_script(count)
        elapsed = time.perf_counter() - start
        driver.find_element(By.ID, "run-button").click()  # pause
        time.sleep(0.5)
        return (draws1 - draws0) / elapsed, (frames1 - frames0) / elapsed

    return in_thread(instance, run)  # type: ignore[no-any-return]


def python_fps(instance: spear.Instance, camera: spear.ACameraSensorActor, frames: int) -> float:
    start = time.perf_counter()
    for _ in range(frames):
        with instance.begin_frame():
            pass
        with instance.end_frame():
            camera.CameraSensor.read_pixels()
    return frames / (time.perf_counter() - start)


def settle(instance: spear.Instance, seconds: float = 2.0) -> None:
    """Lets the browser finish what a page change started (loading, a first read of the scene) before a block of
    frames is timed; in-process the engine answers it meanwhile."""
    instance.serve_inspector(seconds=seconds) if instance.transport == "inprocess" else time.sleep(seconds)


def frame_times(instance: spear.Instance, camera: spear.ACameraSensorActor, frames: int) -> list[float]:
    times = []
    for _ in range(frames):
        start = time.perf_counter()
        with instance.begin_frame():
            pass
        with instance.end_frame():
            camera.CameraSensor.read_pixels()
        times.append(time.perf_counter() - start)
    return times


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--server", choices=["launch", "inprocess"], default="launch")
    parser.add_argument("--seconds", type=float, default=10.0, help="how long the page runs frames")
    parser.add_argument("--frames", type=int, default=300, help="frames a Python loop runs, each measurement")
    parser.add_argument("--rounds", type=int, default=4, help="turns of none / watching in measurement 2")
    args = parser.parse_args()
    server = None if args.server == "inprocess" else "launch"
    print(f"bench_inspector: {args.server}, apartment scene, a {W}x{H} camera (final_color), headless chromium")

    instance, camera, url = make(server, inspect=True)
    # An engine with no inspector at all, beside it (idle while the other runs), for the cost of serving one.
    plain, plain_camera, _ = make(server, inspect=False)
    driver = browser()
    try:
        print("[1/2] the page running frames and showing each ...", flush=True)
        shown, ran = viewer_fps(instance, driver, url, args.seconds)
        floor = python_fps(instance, camera, args.frames)
        print(f"  viewer: {shown:.1f} images/s shown ({ran:.1f} frames/s run); Python loop (frame + read_pixels, "
              f"same transport): {floor:.1f} frames/s; ratio {shown / floor:.2f}x")

        print("[2/2] a Python loop with a browser watching the camera, with none, and with no inspector, in turns ...",
              flush=True)
        # In turns (none, watching, none, ...), each a block of frames: on a machine of two cores, slow drifts
        # (llvmpipe's threads, the browser's own work) would otherwise fall on one side.
        alone: list[float] = []
        watched: list[float] = []
        never: list[float] = []
        frame_times(plain, plain_camera, 200)  # as many frames behind it as the other (a fresh engine runs slower)
        shown = 0
        for round_ in range(args.rounds):
            driver.get("about:blank")  # none attached
            settle(instance)
            frame_times(plain, plain_camera, 10)
            block = args.frames // args.rounds
            if round_ % 2 == 0:  # in turns, which goes first: the first block after a change runs slower
                never += frame_times(plain, plain_camera, block)
                alone += frame_times(instance, camera, block)
            else:
                alone += frame_times(instance, camera, block)
                never += frame_times(plain, plain_camera, block)
            in_thread(instance, lambda: open_page(driver, url))  # attached, showing the camera, polling
            settle(instance)  # past the page's loading and first look at the scene
            before = driver.execute_script("return window.spearInspector.viewport.draws")
            watched += frame_times(instance, camera, args.frames // args.rounds)
            shown += driver.execute_script("return window.spearInspector.viewport.draws") - before
        a, w = statistics.median(alone), statistics.median(watched)
        print(f"  frame time, median: {a * 1e3:.2f} ms alone, {w * 1e3:.2f} ms watched: {w / a:.3f}x (goal <= 1.05x); "
              f"means {statistics.mean(alone) * 1e3:.2f} / {statistics.mean(watched) * 1e3:.2f} ms; the page showed "
              f"{shown / (sum(watched)):.1f} images/s meanwhile")
        n = statistics.median(never)
        print(f"  frame time, median: {n * 1e3:.2f} ms with no inspector started: serving one nobody watches costs "
              f"{a / n:.3f}x")
    finally:
        driver.quit()
        instance.close()
        plain.close()


if __name__ == "__main__":
    main()
