"""The inspector end to end in a real browser (Debian's chromium, headless, driven by Selenium), on both transports:
the page and its token, the outliner, edits and refused edits, clicking a pixel to select what it shows, and each
modality's image against what read_pixels() returns to Python."""

from __future__ import annotations

import os
import shutil
import time
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

import spear

from inspector_client import served

webdriver = pytest.importorskip("selenium.webdriver", reason="python3-selenium is not installed (test.sh installs it)")
from selenium.common.exceptions import StaleElementReferenceException  # noqa: E402
from selenium.webdriver.common.action_chains import ActionChains  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402
from selenium.webdriver.common.keys import Keys  # noqa: E402
from selenium.webdriver.support.ui import Select, WebDriverWait  # noqa: E402

CHROMEDRIVER = shutil.which("chromedriver")
if CHROMEDRIVER is None and os.environ.get("CI") != "true":
    pytest.skip("no chromedriver (Debian's chromium-driver; test.sh installs it)", allow_module_level=True)

W, H = 160, 120


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    options = webdriver.ChromeOptions()
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1400,900",
                     "--disable-dev-shm-usage"):
        options.add_argument(argument)
    driver = webdriver.Chrome(options=options)
    yield driver
    driver.quit()


@pytest.fixture
def scene(make_instance: Callable[..., spear.Instance]) -> tuple[spear.Instance, spear.ACameraSensorActor, str]:
    """A floor, a crate and a camera looking at them, one frame run."""
    instance = make_instance()
    game = instance.get_game()
    with instance.begin_frame():
        floor = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Floor")
        floor.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        floor.SetActorScale3D(NewScale3D=spear.FVector(10.0, 10.0, 0.1))
        crate = game.spawn_actor(uclass=spear.AStaticMeshActor, name="Crate", location=spear.FVector(3.0, 0.0, 0.5),
                                 tags=["cargo"])
        crate.StaticMeshComponent.SetStaticMesh(NewMesh="/Engine/BasicShapes/Cube")
        game.spawn_actor(uclass=spear.ADirectionalLight, name="Sun", rotation=spear.FRotator(Pitch=-50.0))
        camera = game.spawn_actor(uclass=spear.ACameraSensorActor, name="Cam", location=spear.FVector(0.0, 0.0, 1.0),
                                  rotation=spear.FRotator(Pitch=-10.0))
        camera.CameraSensor.Width = W
        camera.CameraSensor.Height = H
        camera.CameraSensor.Modalities = [spear.ECameraModality.FinalColor, spear.ECameraModality.Depth,
                                          spear.ECameraModality.ObjectIds]
    with instance.end_frame():
        pass
    return instance, camera, instance.inspect(port=0)


def open_page(driver: Any, url: str) -> None:
    driver.get(url)
    WebDriverWait(driver, 30).until(lambda d: d.execute_script("return document.body.dataset.ready") == "true")


def type_over(element: Any, text: str) -> None:
    """Types `text` over an input's value and leaves it, as a user does: the page commits on change."""
    element.send_keys(Keys.CONTROL, "a")
    element.send_keys(text, Keys.TAB)


def canvas_rgb(driver: Any) -> NDArray[np.uint8]:
    data = driver.execute_script(
        "const c = document.getElementById('viewport-canvas');"
        "return [c.width, c.height, Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data)];")
    width, height, pixels = data
    return np.array(pixels, dtype=np.uint8).reshape(height, width, 4)[..., :3]


def show_modality(driver: Any, modality: str) -> None:
    Select(driver.find_element(By.ID, "modality-select")).select_by_value(modality)
    WebDriverWait(driver, 30).until(
        lambda d: d.find_element(By.ID, "viewport-canvas").get_attribute("data-modality") == modality)


def test_the_page_opens_with_its_token_only(browser: Any, scene: tuple[spear.Instance, Any, str]) -> None:
    instance, _, url = scene

    def look() -> tuple[str, str]:
        browser.get(url.split("?")[0])
        refused = browser.find_element(By.TAG_NAME, "body").text
        open_page(browser, url)
        return refused, browser.find_element(By.ID, "status").text

    refused, status = served(instance, look)
    assert "wrong or missing token" in refused
    assert status == "connected"


def test_find_an_actor_and_edit_a_property(browser: Any, scene: tuple[spear.Instance, Any, str]) -> None:
    instance, _, url = scene
    crate = instance.get_game()

    def edit() -> str:
        open_page(browser, url)
        browser.find_element(By.ID, "outliner-search").send_keys("cargo")  # by its tag
        items = browser.find_elements(By.CSS_SELECTOR, "#outliner-tree .item")
        names = [item.get_attribute("data-name") for item in items]
        assert names == ["World", "Crate", "StaticMeshComponent"]  # the world, its actor, the actor's component
        items[2].click()
        WebDriverWait(browser, 30).until(
            lambda d: d.find_elements(By.CSS_SELECTOR, '[data-property="RelativeLocation"] input'))
        x = browser.find_element(By.CSS_SELECTOR, '[data-property="RelativeLocation"] input[type=number]')
        type_over(x, "2.5")
        return str(browser.find_element(By.ID, "selected-name").text)

    assert served(instance, edit) == "StaticMeshComponent"
    with instance.begin_frame():
        actor = crate.find_actor_by_name(name="Crate")
        assert actor is not None
        assert actor.StaticMeshComponent.RelativeLocation.X == 2.5
    with instance.end_frame():
        pass


def test_a_refused_value_shows_the_engines_error(browser: Any, scene: tuple[spear.Instance, Any, str]) -> None:
    instance, camera, url = scene
    with instance.begin_frame():
        with pytest.raises(spear.errors.InvalidArgumentError) as refused:
            camera.CameraSensor.Width = 0
    with instance.end_frame():
        pass

    def refuse() -> tuple[str, str]:
        open_page(browser, url)
        browser.find_element(By.CSS_SELECTOR, '#outliner-tree .item[data-name="CameraSensor"]').click()
        width = WebDriverWait(browser, 30).until(
            lambda d: d.find_element(By.CSS_SELECTOR, '[data-property="Width"] input'))
        type_over(width, "0")
        error = browser.find_element(By.CSS_SELECTOR, '[data-property="Width"] .property-error')
        WebDriverWait(browser, 30).until(lambda d: error.is_displayed())
        WebDriverWait(browser, 30).until(lambda d: width.get_attribute("value") == str(W))  # the engine's again
        return str(error.text), str(width.get_attribute("value"))

    shown, value = served(instance, refuse)
    assert shown == f"InvalidArgumentError: {refused.value}"
    assert value == str(W)


def python_pixels(instance: spear.Instance, camera: Any) -> tuple[int, spear.FCameraPixels]:
    """The camera's images as Python reads them at the end of a frame: the frame the page shows after it."""
    with instance.begin_frame():
        pass
    with instance.end_frame():
        pixels = camera.CameraSensor.read_pixels()
        frame = camera.CameraSensor.GetPixelsFrame()
    return frame, pixels


def id_colors(ids: NDArray[np.uint32]) -> NDArray[np.uint8]:
    """The page's colours of ids (inspector/src/colors.ts: idColor): Knuth's multiplicative hash's bytes."""
    h = (ids.astype(np.uint64) * 2654435761) & 0xFFFFFFFF
    rgb = np.stack([h & 0xFF, (h >> 8) & 0xFF, (h >> 16) & 0xFF], axis=-1).astype(np.uint8)
    rgb[ids == 0] = 0
    return rgb


def ramp(depth: NDArray[np.float32]) -> NDArray[np.uint8]:
    """The page's false colours of a scalar image (colors.ts: ramp over the finite values' range)."""
    stops = np.array([[13, 8, 135], [84, 2, 163], [185, 50, 137], [249, 142, 9], [240, 249, 33]], dtype=np.float64)
    finite = np.isfinite(depth)
    lo, hi = depth[finite].min(), depth[finite].max()
    t = np.clip((depth.astype(np.float64) - lo) / (hi - lo if hi > lo else 1.0), 0, 1) * 4
    i = np.minimum(np.floor(t).astype(int), 3)
    f = (t - i)[..., None]
    out = np.round(stops[i] + (stops[i + 1] - stops[i]) * f)
    out[~finite] = 0
    return out.astype(np.uint8)


def test_each_modality_is_what_read_pixels_returns(browser: Any, scene: tuple[spear.Instance, Any, str]) -> None:
    instance, camera, url = scene
    frame, pixels = python_pixels(instance, camera)

    def views() -> dict[str, Any]:
        open_page(browser, url)
        shown = {}
        for modality in ("final_color", "object_ids", "depth"):
            show_modality(browser, modality)
            canvas = browser.find_element(By.ID, "viewport-canvas")
            shown[modality] = (int(canvas.get_attribute("data-frame")), canvas_rgb(browser))
        return shown

    shown = served(instance, views)
    for modality, (shown_frame, _) in shown.items():
        assert shown_frame == frame, modality
    np.testing.assert_array_equal(shown["final_color"][1], pixels["final_color"][..., :3])
    np.testing.assert_array_equal(shown["object_ids"][1], id_colors(pixels["object_ids"]))
    # The ramp's float arithmetic differs in the last place between numpy and JavaScript: one step at most.
    difference = np.abs(shown["depth"][1].astype(int) - ramp(pixels["depth"]).astype(int))
    assert difference.max() <= 1


def test_clicking_a_pixel_selects_the_actor_it_shows(browser: Any, scene: tuple[spear.Instance, Any, str]) -> None:
    instance, camera, url = scene
    _, pixels = python_pixels(instance, camera)
    ids = pixels["object_ids"]
    with instance.begin_frame():
        crate = instance.get_game().find_actor_by_name(name="Crate")
        assert crate is not None
        crate_id = camera.CameraSensor.GetObjectId(Component=crate.StaticMeshComponent)
    with instance.end_frame():
        pass
    ys, xs = np.nonzero(ids == crate_id)
    assert len(xs) > 0, "the crate is in view"
    x, y = int(np.median(xs)), int(np.median(ys))
    assert ids[y, x] == crate_id

    def click() -> tuple[str, str]:
        open_page(browser, url)
        show_modality(browser, "final_color")
        canvas = browser.find_element(By.ID, "viewport-canvas")
        ActionChains(browser).move_to_element_with_offset(canvas, x - W // 2, y - H // 2).click().perform()
        WebDriverWait(browser, 30).until(lambda d: d.find_element(By.ID, "selected-name").text == "Crate")
        return str(canvas.get_attribute("data-picked-id")), str(browser.find_element(By.ID, "selected-class").text)

    picked, class_name = served(instance, click)
    assert int(picked) == crate_id
    assert class_name == "AStaticMeshActor"


def test_the_viewer_orbits_and_renders_a_paused_world(browser: Any, scene: tuple[spear.Instance, Any, str]) -> None:
    instance, _, url = scene
    frames = instance.frame_count

    def orbit() -> tuple[NDArray[np.uint8], NDArray[np.uint8], str]:
        open_page(browser, url)
        Select(browser.find_element(By.ID, "camera-select")).select_by_value("viewer")
        canvas = browser.find_element(By.ID, "viewport-canvas")
        WebDriverWait(browser, 60).until(lambda d: canvas.get_attribute("width") == "640")  # the viewer's image
        before = canvas_rgb(browser)
        drawn = browser.execute_script("return window.spearInspector.viewport.draws")
        ActionChains(browser).click_and_hold(canvas).move_by_offset(60, 0).move_by_offset(60, 10).release().perform()
        WebDriverWait(browser, 60).until(
            lambda d: d.execute_script("return window.spearInspector.viewport.draws") > drawn + 1)
        time.sleep(0.5)  # the last move's image
        return before, canvas_rgb(browser), str(canvas.get_attribute("data-frame"))

    before, after, shown = served(instance, orbit)
    assert before.shape == (480, 640, 3)
    assert np.abs(before.astype(int) - after.astype(int)).mean() > 5, "the view turned"
    assert int(shown) == frames and instance.frame_count == frames  # rendered without a frame
    with instance.begin_frame():
        viewers = instance.get_game().find_actors_by_tag(tag="spear.inspector")
        assert [v.GetName() for v in viewers] == ["InspectorViewer"]
    with instance.end_frame():
        pass

    def again() -> int:  # a page opened later takes the same viewer
        open_page(browser, url)
        Select(browser.find_element(By.ID, "camera-select")).select_by_value("viewer")
        WebDriverWait(browser, 60).until(
            lambda d: d.execute_script("return window.spearInspector.viewport.draws") > 0)
        return int(browser.execute_script("return window.spearInspector.viewport.draws"))

    assert served(instance, again) > 0
    with instance.begin_frame():
        assert len(instance.get_game().find_actors_by_tag(tag="spear.inspector")) == 1
    with instance.end_frame():
        pass


def test_lists_and_ranges_have_editors_of_their_own(browser: Any, scene: tuple[spear.Instance, Any, str]) -> None:
    instance, camera, url = scene

    def edit() -> tuple[str, str]:
        open_page(browser, url)
        browser.find_element(By.CSS_SELECTOR, '#outliner-tree .item[data-name="CameraSensor"]').click()
        modalities = WebDriverWait(browser, 30).until(
            lambda d: d.find_element(By.CSS_SELECTOR, '[data-property="Modalities"] .list'))
        items = modalities.find_elements(By.CSS_SELECTOR, ".item select")
        assert [Select(i).first_selected_option.text for i in items] == ["FinalColor", "Depth", "ObjectIds"]
        modalities.find_element(By.CSS_SELECTOR, 'button[title="add an item"]').click()  # FinalColor, the first
        WebDriverWait(browser, 30).until(
            lambda d: len(d.find_elements(By.CSS_SELECTOR, '[data-property="Modalities"] .item')) == 4)
        def choose_normal(d: Any) -> bool:  # the list is drawn again once the engine's value comes back
            Select(d.find_elements(By.CSS_SELECTOR, '[data-property="Modalities"] .item select')[-1]
                   ).select_by_visible_text("Normal")
            return True

        WebDriverWait(browser, 30, ignored_exceptions=(StaleElementReferenceException,)).until(choose_normal)
        WebDriverWait(browser, 30).until(lambda d: Select(
            d.find_elements(By.CSS_SELECTOR, '[data-property="Modalities"] .item select')[-1]
        ).first_selected_option.text == "Normal")
        width = browser.find_element(By.CSS_SELECTOR, '[data-property="Width"] .range')
        vignette = browser.find_element(By.CSS_SELECTOR, '[data-property="VignetteIntensity"] input[type=range]')
        return str(width.get_attribute("title")), str(vignette.get_attribute("max"))

    title, vignette_max = served(instance, edit)
    assert title == "in [1, 16384]" and vignette_max == "1"  # ClampMin / ClampMax from the reflected header
    with instance.begin_frame():
        assert camera.CameraSensor.Modalities == [spear.ECameraModality.FinalColor, spear.ECameraModality.Depth,
                                                  spear.ECameraModality.ObjectIds, spear.ECameraModality.Normal]
    with instance.end_frame():
        pass


def test_the_outliner_shows_every_world(browser: Any, scene: tuple[spear.Instance, Any, str]) -> None:
    instance, _, url = scene
    second = instance.create_world(name="Second")
    with instance.begin_frame():
        second.spawn_actor(uclass=spear.AStaticMeshActor, name="Elsewhere")
    with instance.end_frame():
        pass

    def worlds() -> list[str]:
        open_page(browser, url)
        return [str(e.get_attribute("data-name")) for e in browser.find_elements(By.CSS_SELECTOR, "#outliner-tree .world")]

    assert served(instance, worlds) == ["World", "Second"]

    def found() -> list[str]:
        browser.find_element(By.ID, "outliner-search").send_keys("Elsewhere")
        return [str(e.get_attribute("data-name")) for e in browser.find_elements(By.CSS_SELECTOR, "#outliner-tree .item")]

    assert served(instance, found) == ["World", "Second", "Elsewhere", "StaticMeshComponent"]
