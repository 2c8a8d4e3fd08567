"""Watch and poke the default apartment scene in the browser inspector while this script runs it.

Loads the built-in apartment scene, adds a camera and a few boxes that fall onto the floor, starts the inspector
(instance.inspect()) and prints the address to open, then runs frames for --seconds in real time: the page follows
them. On the page: find an actor in the outliner (name, class or tag), edit any property (a refused value shows
the engine's error), switch the camera's modality, click a pixel to select what it shows, pick the viewer camera
to orbit (drag, wheel, W A S D Q E), or Step and Run frames yourself. After the frames the script keeps answering
the page for --serve seconds.

With --screenshot PATH a headless chromium (Debian's chromium, chromium-driver and python3-selenium) opens the
page, selects the camera's sensor (its properties fill the panel) and saves the page as a PNG;
docs/images/inspector.png is made so.

    PYTHONPATH=python /usr/bin/python3 examples/inspect_scene.py [--seconds 30] [--serve 600] [--port 0]
        [--server launch] [--screenshot out/inspector.png]
"""

# Debian 12's Selenium (4.8) is partly annotated: strict pyright would flag its WebDriver's members at each use.
# pyright: reportUnknownMemberType=false, reportUnknownLambdaType=false

from __future__ import annotations

import argparse
import threading
import time
from pathlib import Path

import spear

DEFAULT_SCENE = "/Game/scenes/apartment"


def build(instance: spear.Instance) -> None:
    game = instance.get_game()
    with instance.begin_frame():
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Camera", location=spear.FVector(-1.6, -1.2, 1.6),
                                  rotation=spear.FRotator(Pitch=-18.0, Yaw=25.0), tags=["inspected"])
        camera.CameraSensor.Width, camera.CameraSensor.Height = 640, 480
        # Metered from what the camera sees, as render_image.py's: the sunlit room needs no hand-set Exposure.
        camera.CameraSensor.AutoExposureMethod = spear.EAutoExposureMethod.AEM_Histogram
        camera.CameraSensor.Modalities = [spear.ECameraModality.FinalColor, spear.ECameraModality.Depth,
                                          spear.ECameraModality.ObjectIds]
        for i, colour in enumerate(["Red", "Blue", "Yellow"]):
            box = game.spawn_actor(uclass=spear.AStaticMeshActor, name=f"Box{i}",
                                   location=spear.FVector(0.6 + 0.35 * i, -0.3 + 0.3 * i, 1.6 + 0.4 * i), tags=["falling"])
            box.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
            box.StaticMeshComponent.SetMaterial(ElementIndex=0, Material=colour)
            box.SetActorScale3D(NewScale3D=spear.FVector(0.25, 0.25, 0.25))
            box.StaticMeshComponent.SetSimulatePhysics(bSimulate=True)
    with instance.end_frame():
        pass


def screenshot(url: str, out: Path, done: threading.Event) -> None:
    """Opens the page headless, selects the camera's sensor, and saves the page (run beside the engine's thread)."""
    from selenium import webdriver
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.wait import WebDriverWait

    options = webdriver.ChromeOptions()
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1500,820"):
        options.add_argument(argument)  # type: ignore[no-untyped-call]  # unannotated in Debian's selenium 4.8
    driver = webdriver.Chrome(options=options)
    try:
        driver.get(url)
        WebDriverWait(driver, 60).until(lambda d: d.execute_script("return document.body.dataset.ready") == "true")
        driver.find_element(By.ID, "outliner-search").send_keys("inspected")  # the camera, by its tag
        driver.find_element(By.CSS_SELECTOR, '#outliner-tree .item[data-name="CameraSensor"]').click()
        WebDriverWait(driver, 60).until(lambda d: d.find_elements(By.CSS_SELECTOR, "#property-list .property"))
        time.sleep(1.5)  # the camera's next image
        out.parent.mkdir(parents=True, exist_ok=True)
        driver.save_screenshot(str(out))
        print(f"inspect_scene: the page's screenshot is {out}")
    finally:
        driver.quit()
        done.set()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--seconds", type=float, default=30.0, help="how long to run frames (real time)")
    parser.add_argument("--serve", type=float, default=0.0, help="how long to answer the page after the frames")
    parser.add_argument("--port", type=int, default=0, help="the inspector's port on 127.0.0.1 (0: a free one)")
    parser.add_argument("--server", default=None, help='"launch", "unix:PATH" or "tcp:HOST:PORT" (default: in-process)')
    parser.add_argument("--screenshot", type=Path, default=None, help="save the page, opened headless, as this PNG")
    args = parser.parse_args()

    instance = spear.Instance(server=args.server, scene=DEFAULT_SCENE if args.server in (None, "launch") else None)
    build(instance)
    url = instance.inspect(port=args.port)
    print(f"inspect_scene: open {url}", flush=True)

    done = threading.Event()
    browser = None
    if args.screenshot is not None:
        browser = threading.Thread(target=screenshot, args=(url, args.screenshot, done))
        browser.start()
    start = time.monotonic()
    frames = 0
    while time.monotonic() - start < args.seconds or (browser is not None and not done.is_set()):
        # 30 frames a second of simulated time, no faster than real time: a person is watching.
        due = start + frames / 30.0
        if due > time.monotonic():
            instance.serve_inspector(seconds=due - time.monotonic())
        instance.step()
        frames += 1
    print(f"inspect_scene: ran {frames} frames in {time.monotonic() - start:.1f} s")
    if browser is not None:
        browser.join()
    if args.serve > 0:
        print(f"inspect_scene: answering the page for {args.serve:g} s more (Ctrl+C ends it)", flush=True)
        try:
            instance.serve_inspector(seconds=args.serve)
        except KeyboardInterrupt:
            pass
    instance.close()


if __name__ == "__main__":
    main()
