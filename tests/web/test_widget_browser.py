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


def test_widget_draws_the_body_and_scrubs_time():
    sync_api = pytest.importorskip("playwright.sync_api")
    tr = kr.EulerTop(1.0, 2.0, 3.0).solve(np.linspace(0.0, 20.0, 801), [0.01, 2.0, 0.01])
    data = widget_data(tr, max_samples=400)
    code = (pathlib.Path(STATIC) / "widget.js").read_text(encoding="utf-8")
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=str(CHROMIUM), args=ARGS, timeout=120_000)
        try:
            page = browser.new_page(viewport={"width": 800, "height": 600})
            errors = []
            page.on("pageerror", lambda exc: errors.append(str(exc)))
            page.set_content('<div id="cell"></div>')
            page.evaluate(MOUNT, [code, data])
            assert errors == []
            assert page.locator("#cell canvas").count() == 1, page.content()
            slider = page.locator("#cell input[type=range]")
            assert slider.get_attribute("max") == "399"
            slider.evaluate("(s) => { s.value = 250; s.dispatchEvent(new Event('input')); }")
            assert page.evaluate("window.widgetState.index") == 250
            assert page.locator("#cell span").inner_text() == f"t = {data['t'][250]:#.4g} s"   # JS toPrecision(4)
            ARTIFACTS.mkdir(exist_ok=True)
            shot = page.locator("#cell canvas").screenshot(path=str(ARTIFACTS / "widget.png"))
        finally:
            browser.close()
    from matplotlib.image import imread

    pixels = imread(BytesIO(shot), format="png")[..., :3]
    assert pixels.std() > 0.02, "the 3D canvas is blank"
    assert len({tuple(c) for c in (pixels[::8, ::8].reshape(-1, 3) * 255).astype(int)}) > 20
