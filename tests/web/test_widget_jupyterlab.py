"""``traj.show()`` in a real JupyterLab: a notebook cell run in headless chromium draws the 3D scene.

The test starts ``jupyter lab`` on a free local port with a token and its own home, configuration,
runtime and data directories, opens a notebook whose cell shows a trajectory, runs the cell once the
notebook's kernel is idle, and screenshots the widget's canvas (non-blank, many colours, as for the viewer).

The kernel (jupyter_client starts the ``python3`` kernel spec with this interpreter) compiles into this
process's numba cache, which the fixture fills first by running the cell's code here: compiled from
cold inside the kernel, the cell took ~20 s of CPU, minutes of wall time on a loaded machine, and the
canvas missed its deadline in a fresh clone. When a step fails, the page's screenshot, the browser
console, the server log and the kernel's state are written to a directory that the message names.
"""

import contextlib
import json
import os
import pathlib
import secrets
import shutil
import socket
import subprocess
import sys
import time
from io import BytesIO

import pytest

import kreisel

from .test_browser import ARGS, ARTIFACTS, CHROMIUM

nbformat = pytest.importorskip("nbformat")
pytest.importorskip("jupyterlab")
pytest.importorskip("anywidget")
pytestmark = pytest.mark.skipif(not CHROMIUM.exists(), reason="needs Debian's chromium at /usr/bin/chromium")

CELL = """import numpy as np
import kreisel as kr
traj = kr.EulerTop(1.0, 2.0, 3.0).solve(np.linspace(0.0, 20.0, 401), [0.01, 2.0, 0.01])
traj.show()"""

#: Seconds for each step: the server to answer, the notebook to open, its kernel to be idle, the canvas to appear.
STEP_SECONDS = 120

#: JavaScript: the notebook's kernel status, or null before JupyterLab has one.
KERNEL_STATUS = "() => window.jupyterapp?.shell.currentWidget?.sessionContext?.session?.kernel?.status ?? null"

#: JavaScript: false while the cell runs, else how it ended: "canvas", or what went wrong instead.
OUTCOME = """() => {
  const area = document.querySelector('.jp-NotebookPanel .jp-OutputArea');
  if (area?.querySelector('.jp-OutputArea-output canvas')) return 'canvas';
  const stderr = [...(area?.querySelectorAll('[data-mime-type="application/vnd.jupyter.stderr"]') ?? [])];
  const text = stderr.map((output) => output.innerText).join(' ');
  if (text.includes('Traceback')) return 'the cell raised: ' + text;   // a warning alone is no failure
  if (area?.innerText.includes('Error displaying widget')) return 'the widget did not display: ' + area.innerText;
  const dialog = document.querySelector('.jp-Dialog');
  if (dialog) return 'JupyterLab opened a dialog: ' + dialog.innerText;
  const status = window.jupyterapp?.shell.currentWidget?.sessionContext?.session?.kernel?.status;
  if (status === 'dead' || status === 'autorestarting') return 'the kernel is ' + status;
  return false;
}"""

#: JavaScript: what the page shows of the notebook, for the diagnostics.
PAGE_STATE = """() => {
  const panel = window.jupyterapp?.shell.currentWidget;
  const session = panel?.sessionContext;
  return {app_exposed: !!window.jupyterapp, current_widget: panel?.title?.label ?? null,
          kernel_name: session?.kernelDisplayName ?? null, kernel_status: session?.session?.kernel?.status ?? null,
          prompt: document.querySelector('.jp-NotebookPanel .jp-InputPrompt')?.innerText ?? null,
          dialog: document.querySelector('.jp-Dialog')?.innerText ?? null,
          output_text: document.querySelector('.jp-NotebookPanel .jp-OutputArea')?.innerText ?? null,
          output_html: document.querySelector('.jp-NotebookPanel .jp-OutputArea')?.innerHTML.slice(0, 5000) ?? null};
}"""


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _lab_environment(home):
    """This process's environment for the server and its kernel, with every Jupyter directory under ``home``."""
    import numba

    # a JUPYTER_* or IPYTHONDIR set by the developer would point the server at other settings and extensions
    env = {key: value for key, value in os.environ.items() if not key.startswith(("JUPYTER", "IPYTHON"))}
    env.update(HOME=str(home), JUPYTER_CONFIG_DIR=str(home / "config"), JUPYTER_DATA_DIR=str(home / "data"),
               JUPYTER_RUNTIME_DIR=str(home / "runtime"), JUPYTERLAB_SETTINGS_DIR=str(home / "settings"),
               JUPYTERLAB_WORKSPACES_DIR=str(home / "workspaces"), IPYTHONDIR=str(home / "ipython"), MPLBACKEND="Agg",
               # the kernel imports the kreisel under test
               PYTHONPATH=os.pathsep.join([str(pathlib.Path(kreisel.__file__).parents[1]),
                                           os.environ.get("PYTHONPATH", "")]))
    if numba.config.CACHE_DIR:   # a source checkout's cache (kreisel._compiled): the kernel reuses this process's code
        env["NUMBA_CACHE_DIR"] = numba.config.CACHE_DIR
    return env


@pytest.fixture(scope="module")
def lab(tmp_path_factory, interrupt):
    """A running JupyterLab serving a folder with ``show.ipynb``: (base URL, token, server log)."""
    import httpx

    root = tmp_path_factory.mktemp("lab")
    home = tmp_path_factory.mktemp("home")
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(CELL)])
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nbformat.write(nb, root / "show.ipynb")
    token, port = secrets.token_hex(16), _free_port()
    log = home / "lab.log"   # a file, not a pipe: nothing reads the server's log while the test runs
    with log.open("w") as sink:   # the server keeps its own copy of the file
        server = subprocess.Popen(
            [sys.executable, "-m", "jupyterlab", "--no-browser", f"--port={port}", "--ip=127.0.0.1",
             f"--IdentityProvider.token={token}", f"--ServerApp.root_dir={root}", "--ServerApp.port_retries=0",
             "--allow-root",  # containers run the tests as root
             "--LabApp.expose_app_in_browser=True",   # window.jupyterapp: the kernel's status for the test
             "--LabApp.news_url=", "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate"],
            cwd=root, env=_lab_environment(home), stdout=subprocess.DEVNULL, stderr=sink)
    url = f"http://127.0.0.1:{port}"
    try:
        # while the server starts, and before any kernel: compile what the cell runs into the shared cache
        exec(CELL, {})
        deadline = time.monotonic() + STEP_SECONDS
        while True:
            assert server.poll() is None, f"jupyter lab exited: {log.read_text()[-3000:]}"
            try:
                if httpx.get(f"{url}/api/status", params={"token": token}, timeout=5).status_code == 200:
                    break
            except httpx.TransportError:
                pass
            assert time.monotonic() < deadline, f"no answer within {STEP_SECONDS} s: {log.read_text()[-3000:]}"
            time.sleep(0.5)
        yield url, token, log
    finally:
        interrupt(server, 30)


class Witness:
    """A timeline of the test's steps and the browser's console; on a failed step, everything seen, in ``folder``."""

    def __init__(self, page, lab, folder):
        self.page, self.lab, self.folder = page, lab, folder
        self.start, self.events = time.monotonic(), []
        page.on("console", lambda message: self.note(f"console.{message.type}: {message.text}"))
        page.on("pageerror", lambda error: self.note(f"page error: {error}"))

    def note(self, text):
        self.events.append(f"{time.monotonic() - self.start:7.1f} s  {text}")

    @contextlib.contextmanager
    def step(self, name):
        """Run the block as step ``name``; if it raises, fail with the diagnostics."""
        self.note(f"step: {name}")
        try:
            yield
            return
        except Exception as exc:
            failure = f"{name}: {exc}"
        pytest.fail(f"{failure}\n{self.dump()}", pytrace=False)   # outside the handler: no chained traceback

    def dump(self):
        """Write the screenshot, timeline, server log and kernel state; a summary naming the folder."""
        import httpx

        url, token, log = self.lab
        state = {}
        with contextlib.suppress(Exception):
            self.page.screenshot(path=str(self.folder / "page.png"), timeout=30_000)
        with contextlib.suppress(Exception):
            state["page"] = self.page.evaluate(PAGE_STATE)
        for api in ("sessions", "kernels"):
            with contextlib.suppress(Exception):
                state[api] = httpx.get(f"{url}/api/{api}", params={"token": token}, timeout=10).json()
        (self.folder / "state.json").write_text(json.dumps(state, indent=1))
        (self.folder / "timeline.txt").write_text("\n".join(self.events) + "\n")
        shutil.copy(log, self.folder / "lab.log")
        tail = log.read_text(errors="replace").splitlines()[-15:]
        status = state.get("page", {}).get("kernel_status")
        return "\n".join([f"diagnostics (page.png, timeline.txt with the browser console, lab.log, state.json) in "
                          f"{self.folder}", f"kernel status in the page: {status}",
                          "timeline (last 15):", *self.events[-15:], "server log (last 15 lines):", *tail])


def test_show_renders_in_jupyterlab(lab, tmp_path):
    sync_api = pytest.importorskip("playwright.sync_api")
    url, token, _ = lab
    timeout = STEP_SECONDS * 1000
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=str(CHROMIUM), args=ARGS, timeout=timeout)
        try:
            page = browser.new_page(viewport={"width": 1200, "height": 900})
            witness = Witness(page, lab, tmp_path)
            with witness.step("open the notebook"):
                page.goto(f"{url}/lab/tree/show.ipynb?token={token}", wait_until="load", timeout=timeout)
                editor = page.locator(".jp-NotebookPanel .jp-Cell .cm-content").first
                editor.wait_for(timeout=timeout)
            # a cell run before the notebook has its kernel may be dropped or ask which kernel to start
            with witness.step("wait for the notebook's kernel to be idle"):
                page.wait_for_function(f"({KERNEL_STATUS})() === 'idle'", timeout=timeout)
            with witness.step("run the cell"):
                editor.click()
                page.keyboard.press("Shift+Enter")
                outcome = page.wait_for_function(OUTCOME, timeout=timeout, polling=250).json_value()
                assert outcome == "canvas", outcome
            with witness.step("inspect the widget"):
                slider = page.locator(".jp-OutputArea-output input[type=range]").first
                assert slider.get_attribute("max") == "400"
                page.wait_for_timeout(500)
                ARTIFACTS.mkdir(exist_ok=True)
                canvas = page.locator(".jp-OutputArea-output canvas").first
                shot = canvas.screenshot(path=str(ARTIFACTS / "widget_jupyterlab.png"))
                legend = page.locator(".jp-OutputArea-output").first.inner_text()
        finally:
            browser.close()
    from matplotlib.image import imread

    pixels = imread(BytesIO(shot), format="png")[..., :3]
    assert pixels.std() > 0.02, "the 3D canvas is blank"
    assert len({tuple(c) for c in (pixels[::8, ::8].reshape(-1, 3) * 255).astype(int)}) > 20
    assert "invariable plane" in legend and "polhode" in legend
