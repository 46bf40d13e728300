"""End to end: the page in Debian's headless chromium (software WebGL) driven by Playwright."""

import os
import pathlib

import numpy as np
import pytest

from kreisel.web.app import STATIC

CHROMIUM = pathlib.Path("/usr/bin/chromium")
ARTIFACTS = pathlib.Path(__file__).resolve().parents[2] / "test-artifacts"
DOCS = pathlib.Path(__file__).resolve().parents[2] / "docs"
ARGS = ["--no-sandbox", "--headless=new", "--use-gl=angle", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
        "--disable-background-networking", "--disable-component-update", "--disable-sync", "--no-first-run"]

pytestmark = [
    pytest.mark.skipif(not CHROMIUM.exists(), reason="needs Debian's chromium at /usr/bin/chromium "
                                                     "(.ci/run installs it with apt-get)"),
    pytest.mark.skipif(not (STATIC / "viewer.js").exists(), reason="front end not built: run `make web`"),
]


def websockets_served():
    from kreisel.web.server import websocket_support

    return websocket_support()


@pytest.fixture(scope="module")
def playwright():
    sync_api = pytest.importorskip("playwright.sync_api")
    with sync_api.sync_playwright() as p:
        yield p


@pytest.fixture(scope="module")
def page(playwright, live_url):
    browser = playwright.chromium.launch(executable_path=str(CHROMIUM), args=ARGS, timeout=120_000)
    try:
        page = browser.new_page(viewport={"width": 1400, "height": 820})
        errors = []
        page.on("pageerror", lambda exc: errors.append(str(exc)))
        page.set_default_timeout(180_000)
        page.goto(live_url, wait_until="load", timeout=120_000)
        page.errors = errors
        yield page
    finally:
        browser.close()


def test_tennis_racket_preset_plays_with_constant_energy(page):
    # the first run may compile the integrator (numba), hence the long timeout
    page.wait_for_function("window.kreisel && window.kreisel.ready && window.kreisel.data.kind === 'rigid_body'",
                           timeout=240_000)
    assert page.evaluate("document.getElementById('preset').value") == "tennis_racket"
    # the run came over the WebSocket stream, chunk by chunk, and all of it arrived; a uvicorn without a
    # WebSocket library refuses the upgrade, and the page must then fall back to the one-shot JSON run
    page.wait_for_function("window.kreisel.done", timeout=240_000)
    arrived = page.evaluate("({streamed: window.kreisel.streamed, chunks: window.kreisel.chunks, "
                            "n_chunks: window.kreisel.data.n_chunks, n: window.kreisel.data.t.length})")
    assert arrived["n"] == 2001
    if websockets_served():
        assert arrived["streamed"] and arrived["chunks"] == arrived["n_chunks"] == 2
    else:
        assert not arrived["streamed"] and arrived["chunks"] == 0
    assert page.evaluate("window.kreisel.webgl"), "WebGL (SwiftShader) was not available"
    # the page says what the scene draws and what the racket does, and reports the model's first integrals
    legend = page.inner_text("#legend")
    for item in ("invariable plane", "herpolhode", "polhode", "ω, angular velocity", "J, angular momentum"):
        assert item in legend
    readout = page.inner_text("#readout")
    assert "spun near the middle axis (I2 = 2): unstable, it flips over every" in readout
    assert "first integrals" in readout and "T   = 1.0002" in readout and "drift" not in readout
    assert page.evaluate("document.querySelector('link[rel=icon]').href").endswith("/static/favicon.svg")
    page.evaluate("document.getElementById('speed').value = 1; document.getElementById('speed').oninput()")
    page.wait_for_function("window.kreisel.plotted.energy.length > 200", timeout=120_000)
    energy = np.array(page.evaluate("window.kreisel.plotted.energy"))
    omega = np.array(page.evaluate("window.kreisel.plotted.omega"))
    assert energy[0] == pytest.approx(1.0002, rel=1e-12)  # T = ½ Σ I ω² = ½ (1e-4 + 2 + 3e-4)
    assert np.ptp(energy) / energy[0] < 1e-9
    assert np.ptp(omega[1]) > 0.1, "omega_2 should move when the racket starts to flip"
    ARTIFACTS.mkdir(exist_ok=True)
    shot = page.locator("#scene").screenshot(path=str(ARTIFACTS / "viewer.png"))
    from io import BytesIO

    from matplotlib.image import imread

    pixels = imread(BytesIO(shot), format="png")[..., :3]
    assert pixels.std() > 0.02, "the 3D canvas is blank"
    assert len({tuple(c) for c in (pixels[::8, ::8].reshape(-1, 3) * 255).astype(int)}) > 20
    # the README's screenshot is refreshed on request only, so test runs leave the tree clean
    if os.environ.get("KREISEL_UPDATE_SCREENSHOT") == "1":
        page.screenshot(path=str(DOCS / "viewer.png"))
    assert page.errors == []


def test_refused_run_shows_the_reason(page):
    page.wait_for_function("window.kreisel && window.kreisel.ready", timeout=240_000)
    samples = page.input_value("#nsamp")
    page.fill("#nsamp", "50000000")
    page.click("#run")
    page.wait_for_function("window.kreisel.error !== null", timeout=60_000)
    assert "at most" in page.inner_text("#status")
    # a refused run leaves nothing to play: run again as it was, for the tests that share this page
    page.fill("#nsamp", samples)
    page.click("#run")
    page.wait_for_function("window.kreisel.ready", timeout=240_000)


def test_without_webgl_the_page_says_so(playwright, live_url):
    browser = playwright.chromium.launch(executable_path=str(CHROMIUM), args=ARGS + ["--disable-webgl"],
                                         timeout=120_000)
    try:
        page = browser.new_page()
        page.goto(live_url, wait_until="load", timeout=120_000)
        page.wait_for_function("window.kreisel && window.kreisel.webgl === false", timeout=120_000)
        assert page.locator("#nowebgl").is_visible()
        assert "WebGL is not available" in page.inner_text("#nowebgl")
        # the numbers still come: the plots and readouts do not need WebGL
        page.wait_for_function("window.kreisel.ready", timeout=240_000)
        assert "first integrals" in page.inner_text("#readout")
    finally:
        browser.close()


def test_uploaded_recording_is_fitted_and_replayed(page):
    """A gyroscope recording uploaded in the page is fitted, and the fitted body's ω′ follows the data."""
    import kreisel as kr

    page.wait_for_function("window.kreisel && window.kreisel.ready", timeout=240_000)
    page.set_input_files("#recording", str(kr.io.recording_path("phone_toss")))
    page.click("#fit")
    page.wait_for_function("window.kreisel.data && window.kreisel.data.fit", timeout=120_000)
    assert "I_x = 0.81" in page.inner_text("#readout")
    page.wait_for_function("window.kreisel.plotted.omega.length === 6 && window.kreisel.plotted.omega[0].length > 50",
                           timeout=120_000)
    plotted = page.evaluate("window.kreisel.plotted.omega")
    n = min(len(s) for s in plotted)
    measured, fitted = np.array([s[:n] for s in plotted[:3]]), np.array([s[:n] for s in plotted[3:]])
    assert np.sqrt(np.mean((measured - fitted) ** 2)) < 0.1
    # during the replay the preset box names the recording and the form holds the fitted body
    shown = page.evaluate("({preset: document.getElementById('preset').selectedOptions[0].text, "
                          "moments: ['I1', 'I2', 'I3'].map((id) => parseFloat(document.getElementById(id).value)), "
                          "omega: ['w1', 'w2', 'w3'].map((id) => parseFloat(document.getElementById(id).value)), "
                          "fitted: window.kreisel.data.form, method: document.getElementById('method').value})")
    assert shown["preset"] == f"recording: {kr.io.recording_path('phone_toss').name}"
    np.testing.assert_allclose(shown["moments"], shown["fitted"]["moments"], rtol=1e-9)
    np.testing.assert_allclose(shown["omega"], shown["fitted"]["omega"], rtol=1e-9)
    assert shown["method"] == "exact"
    # the next run is not the recording's: its entry goes
    page.select_option("#preset", "tennis_racket")
    page.wait_for_function("window.kreisel.ready && !window.kreisel.data.fit", timeout=240_000)
    assert page.locator("#preset option[data-recording]").count() == 0
    assert not page.errors, page.errors


@pytest.fixture(scope="module")
def attitude_page(playwright):
    """The page of ``kreisel serve --recording broad_07``: the bundled BROAD trial's attitude replay."""
    import kreisel as kr
    from kreisel.web import create_app
    from kreisel.web.server import bind, url_of

    from .conftest import RELAXED, start_server

    sock = bind("127.0.0.1", 0)
    app = create_app(port=sock.getsockname()[1], limits=RELAXED,
                     recording=kr.io.read_imu(kr.io.recording_path("broad_07")))
    server, thread = start_server(app, sock)
    browser = playwright.chromium.launch(executable_path=str(CHROMIUM), args=ARGS, timeout=120_000)
    try:
        page = browser.new_page(viewport={"width": 1400, "height": 820})
        page.errors = []
        page.on("pageerror", lambda exc: page.errors.append(str(exc)))
        page.set_default_timeout(180_000)
        page.goto(f"{url_of(sock)}?token={app.state.viewer.token}", wait_until="load", timeout=120_000)
        yield page
    finally:
        browser.close()
        server.should_exit = True
        thread.join(timeout=30)
        sock.close()
        app.state.viewer.runner.close()


def test_attitude_replay_shows_the_estimate_beside_the_reference(attitude_page):
    """Both sensors are drawn; scrubbed to a sample, the scene's attitudes are the API's and the error readout is
    kreisel.nav.attitude_error_angles' angle of that sample."""
    import kreisel as kr

    page = attitude_page
    page.wait_for_function("window.kreisel && window.kreisel.ready && window.kreisel.data.kind === 'attitude'",
                           timeout=240_000)
    assert page.evaluate("window.kreisel.webgl"), "WebGL (SwiftShader) was not available"
    legend = page.inner_text("#legend")
    assert "estimated attitude (kreisel's estimator)" in legend and "reference attitude (motion capture" in legend
    readout = page.inner_text("#readout")
    assert "estimated by kreisel's estimator from gyro, accelerometer and magnetometer at 285.71 Hz" in readout
    assert "error against the reference (RMSE over the movement)" in readout
    assert page.evaluate("document.getElementById('preset').selectedOptions[0].text") == \
        "recording: broad_07_fast_rotation_60s.npz"
    rec = kr.io.read_imu(kr.io.recording_path("broad_07"))
    estimate = kr.nav.estimate_attitude(rec.omega, rec.accel, rec.mag, rate=(rec.t.size - 1) / (rec.t[-1] - rec.t[0]))
    total, heading, inclination = np.degrees(kr.nav.attitude_error_angles(estimate.q, rec.reference))
    api = page.evaluate("fetch('/api/recording').then((r) => r.json())")
    for index in (12_000, 9_000):  # in the fast rotation: errors of 2.9° and 4.0°
        page.evaluate(f"(() => {{ const s = document.getElementById('scrub'); s.value = {index}; "
                      "s.dispatchEvent(new Event('input')); })()")
        page.wait_for_function(f"window.kreisel.shown && window.kreisel.shown.index === {index}", timeout=60_000)
        shown = page.evaluate("window.kreisel.shown")
        assert not page.evaluate("window.kreisel.playing")
        # the scene's two bodies hold the API's attitudes (three.js stores them as doubles, unchanged)
        assert shown["estimate"] == api["q"][index] and shown["reference"] == api["q_ref"][index]
        np.testing.assert_array_equal(shown["estimate"], estimate.q[index])
        np.testing.assert_array_equal(shown["reference"], rec.reference[index])
        readout = page.inner_text("#attitude-error")
        assert readout == (f"error {total[index]:.3f}° (heading {heading[index]:.3f}°, "
                           f"inclination {inclination[index]:.3f}°)"), readout
        assert f"t = {rec.t[index]:.3f} s" in page.inner_text("#hud")
    # where the motion capture lost the body only the estimate is drawn, and the readout says why
    page.evaluate("(() => { const s = document.getElementById('scrub'); s.value = 100; "
                  "s.dispatchEvent(new Event('input')); })()")
    page.wait_for_function("window.kreisel.shown.index === 100", timeout=60_000)
    assert page.evaluate("window.kreisel.shown.reference") is None
    assert page.inner_text("#attitude-error") == "error: the reference lost the body here"
    ARTIFACTS.mkdir(exist_ok=True)
    page.evaluate("(() => { const s = document.getElementById('scrub'); s.value = 12000; "
                  "s.dispatchEvent(new Event('input')); })()")
    page.wait_for_function("window.kreisel.shown.index === 12000", timeout=60_000)
    page.screenshot(path=str(ARTIFACTS / "viewer_attitude.png"))
    # the two sensors are drawn: the scene holds the estimate's orange and the reference's blue
    from io import BytesIO

    from matplotlib.image import imread

    pixels = (imread(BytesIO(page.locator("#scene").screenshot()), format="png")[..., :3] * 255).astype(int)
    orange = (np.abs(pixels - [224, 138, 48]).max(axis=-1) < 60) & (pixels[..., 0] > pixels[..., 2] + 80)
    blue = (np.abs(pixels - [74, 120, 200]).max(axis=-1) < 60) & (pixels[..., 2] > pixels[..., 0] + 60)
    assert orange.sum() > 500 and blue.sum() > 500, (orange.sum(), blue.sum())
    assert not page.errors, page.errors
