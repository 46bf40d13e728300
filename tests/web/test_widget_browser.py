"""kreisel.show's front end in headless chromium: the widget module renders the 3D scene and scrubs time.

The page is a minimal notebook stand-in: it imports the widget's ES module as a notebook would
and hands it a model with anywidget's interface (get, set, save_changes, on).
"""

import pathlib
from io import BytesIO

import numpy as np
import pytest

import kreisel as kr
from kreisel.notebook import widget_data
from kreisel.web.app import STATIC

from .test_browser import ARGS, ARTIFACTS, CHROMIUM

pytestmark = [
    pytest.mark.skipif(not CHROMIUM.exists(), reason="needs Debian's chromium at /usr/bin/chromium"),
    pytest.mark.skipif(not (STATIC / "widget.js").exists(), reason="front end not built: run `make web`"),
]

MOUNT = """async ([code, data]) => {
  const state = {data, index: 0}, saved = [];
  const model = {get: (k) => state[k], set: (k, v) => { state[k] = v; }, save_changes: () => saved.push(state.index),
                 on: () => {}, off: () => {}};
  const url = URL.createObjectURL(new Blob([code], {type: "text/javascript"}));
  const widget = (await import(url)).default;
  widget.render({model, el: document.getElementById("cell")});
  window.widgetState = state;
  window.widgetSaved = saved;
}"""


FREE_SCENE = ["ω, angular velocity", "J, angular momentum", "invariable plane", "herpolhode", "polhode",
              "inertia ellipsoid", "principal axis 1", "principal axis 2", "principal axis 3"]


def _pixels(shot):
    from matplotlib.image import imread

    return imread(BytesIO(shot), format="png")[..., :3]


def _colours(pixels):
    return {tuple(c) for c in (pixels[::4, ::4].reshape(-1, 3) * 255).astype(int)}


def test_widget_draws_the_scene_and_scrubs_time():
    sync_api = pytest.importorskip("playwright.sync_api")
    tr = kr.EulerTop(1.0, 2.0, 3.0).solve(np.linspace(0.0, 20.0, 801), [0.01, 2.0, 0.01])
    data = widget_data(tr, max_samples=400)
    top = kr.LagrangeTop(1.0, 0.5, 1.0)
    heavy = widget_data(top.solve(np.linspace(0.0, 6.0, 301), [0.0, 0.6, 0.0], [0.0, 0.0, 8.0]),
                        gravity=(top.mgl, [0.0, 0.0, 1.0]))
    code = (pathlib.Path(STATIC) / "widget.js").read_text(encoding="utf-8")
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=str(CHROMIUM), args=ARGS, timeout=120_000)
        try:
            page = browser.new_page(viewport={"width": 800, "height": 700})
            errors = []
            page.on("pageerror", lambda exc: errors.append(str(exc)))
            page.set_content('<div id="cell"></div>')
            page.evaluate(MOUNT, [code, data])
            assert errors == []
            assert page.locator("#cell canvas").count() == 1, page.content()
            legend = page.locator("#cell canvas + div + div").inner_text()
            for item in FREE_SCENE:
                assert item in legend, (item, legend)
            slider = page.locator("#cell input[type=range]")
            assert slider.get_attribute("max") == "399"
            slider.evaluate("(s) => { s.value = 250; s.dispatchEvent(new Event('input')); }")
            assert page.evaluate("window.widgetState.index") == 250
            assert page.locator("#cell span").inner_text() == f"t = {data['t'][250]:#.4g} s"   # JS toPrecision(4)
            ARTIFACTS.mkdir(exist_ok=True)
            canvas = page.locator("#cell canvas")
            space = canvas.screenshot(path=str(ARTIFACTS / "widget.png"))
            slider.evaluate("(s) => { s.value = 120; s.dispatchEvent(new Event('input')); }")
            earlier = canvas.screenshot()
            camera = page.locator("#cell button", has_text="camera")
            assert camera.inner_text() == "camera: space"
            camera.click()
            assert camera.inner_text() == "camera: body"
            riding = canvas.screenshot()
            # a heavy top: pivot, gravity and the path of the apex instead of the Poinsot construction
            page.set_content('<div id="cell"></div>')
            page.evaluate(MOUNT, [code, heavy])
            heavy_legend = page.locator("#cell canvas + div + div").inner_text()
            heavy_shot = page.locator("#cell canvas").screenshot(path=str(ARTIFACTS / "widget_heavy.png"))
            assert errors == []
        finally:
            browser.close()
    pixels = _pixels(space)
    assert pixels.std() > 0.02, "the 3D canvas is blank"
    assert len(_colours(pixels)) > 20
    # scrubbing moves the body and the trails; the body camera turns the scene
    assert np.abs(_pixels(earlier) - pixels).mean() > 1e-3
    assert np.abs(_pixels(riding) - _pixels(earlier)).mean() > 1e-3
    assert "path of the apex" in heavy_legend and "gravity" in heavy_legend and "invariable plane" not in heavy_legend
    assert _pixels(heavy_shot).std() > 0.02
