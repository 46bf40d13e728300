"""The committed front-end bundle is the build of web/, and a non-editable install serves it without Node.js."""

import hashlib
import json
import os
import pathlib
import re
import shutil
import site
import subprocess
import sys
import time

import pytest

from kreisel.web.app import STATIC

ROOT = pathlib.Path(__file__).resolve().parents[2]
WEB = ROOT / "web"


def source_hash(files):
    """The hash web/build.mjs stores in BUILD.json: each file's name and LF-normalised text."""
    digest = hashlib.sha256()
    for name in files:
        digest.update(name.encode() + b"\0")
        digest.update((WEB / name).read_bytes().decode("utf-8").replace("\r\n", "\n").encode())
        digest.update(b"\0")
    return digest.hexdigest()


def test_bundle_was_built_from_the_current_sources():
    build = json.loads((STATIC / "BUILD.json").read_text(encoding="utf-8"))
    sources = ["build.mjs", "package-lock.json", *sorted(f"src/{p.name}" for p in (WEB / "src").glob("*.js"))]
    assert build["files"] == sources, "web/ has files the bundle was not built from: run `make web`"
    assert build["sha256"] == source_hash(sources), "web/ changed since the bundle was built: run `make web`"


def test_three_js_is_shipped_once():
    """The page's script imports the scene from the widget module, which alone carries three.js."""
    viewer = (STATIC / "viewer.js").read_text(encoding="utf-8")
    widget = (STATIC / "widget.js").read_text(encoding="utf-8")
    assert len(viewer) < 50_000 and "Three.js Authors" not in viewer and "Three.js Authors" in widget
    imported = re.search(r'import\{([^}]*)\}from"\./widget\.js"', viewer)
    exported = re.search(r"export\{([^}]*)\}\s*;?\s*(/\*.*)?$", widget, re.S)
    assert imported and exported
    names = lambda text, k: {part.split(" as ")[k].strip() for part in text.split(",")}
    assert names(imported.group(1), 0) <= names(exported.group(1), 1) and "default" in names(exported.group(1), 1)
    assert not re.search(r"\bimport\b\s*[{*\w]|\bimport\s*\(", widget.split("/*! Bundled license")[0]), \
        "the widget module must be self-contained: anywidget loads it from one string"


@pytest.mark.skipif(shutil.which("node") is None or not (WEB / "node_modules" / "esbuild").is_dir(),
                    reason="needs Node.js and web/node_modules (npm ci in web/)")
def test_rebuilding_gives_the_committed_bundle(tmp_path):
    subprocess.run(["node", str(WEB / "build.mjs")], check=True, env={**os.environ, "KREISEL_WEB_OUT": str(tmp_path)},
                   timeout=300)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["BUILD.json", "viewer.js", "widget.js"]
    for name in ("viewer.js", "widget.js", "BUILD.json"):
        assert (tmp_path / name).read_bytes() == (STATIC / name).read_bytes(), name


def test_static_files_are_package_data():
    import tomllib

    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    patterns = config["tool"]["setuptools"]["package-data"]["kreisel.web"]
    for name in ("viewer.js", "widget.js", "index.html", "favicon.svg", "BUILD.json"):
        assert any(pathlib.PurePath(f"static/{name}").match(p) for p in patterns), name


@pytest.fixture(scope="module")
def installed(tmp_path_factory, repository_copy):
    """A fresh virtual environment with kreisel installed from a copy of the repository, not editable.

    The environment sees this interpreter's packages (numpy, fastapi, ...), so only the build backend is
    fetched (or taken from pip's cache); its own site-packages, where kreisel goes, comes first on its path.
    """
    base = tmp_path_factory.mktemp("install")
    venv = base / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True, timeout=300)
    python = venv / "bin" / "python"
    # this interpreter's packages after the environment's own (a .pth line adds a directory without
    # running the .pth files in it, so an editable kreisel installed here stays out)
    own = subprocess.run([str(python), "-c", "import site; print(site.getsitepackages()[0])"], capture_output=True,
                         text=True, check=True, timeout=300).stdout.strip()
    pathlib.Path(own, "dependencies.pth").write_text("\n".join(site.getsitepackages()) + "\n", encoding="utf-8")
    # pip builds the wheel in an isolated environment with the setuptools pyproject.toml asks for, as a
    # user's `pip install` does (the runtime dependencies come from this interpreter's packages)
    subprocess.run([str(python), "-m", "pip", "install", "--quiet", "--no-deps", str(repository_copy)], check=True,
                   timeout=900, cwd=base)
    where = subprocess.run([str(python), "-c", "import kreisel.web.app as a; print(a.STATIC)"],
                           capture_output=True, text=True, timeout=300, cwd=base,
                           env={k: v for k, v in os.environ.items() if k != "PYTHONPATH"})
    assert str(venv) in where.stdout, f"kreisel was not imported from the new environment: {where}"
    return python, base


@pytest.fixture(scope="module")
def served(installed, interrupt):
    """``kreisel serve`` from the fresh environment, as a user starts it: the URL it prints (with its token)."""
    python, base = installed
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    server = subprocess.Popen([str(python), "-m", "kreisel", "serve", "--port", "0", "--no-browser"], cwd=base,
                              env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        deadline = time.monotonic() + 300
        url = None
        while url is None and time.monotonic() < deadline:
            line = server.stdout.readline()
            if not line:
                break
            found = re.search(r"http://127\.0\.0\.1:\d+/\?token=[\w-]+", line)
            url = found.group(0) if found else None
        assert url, "kreisel serve did not print its URL"
        yield url
    finally:
        interrupt(server, 60)  # Ctrl+C: the server stops its run workers on the way out


def test_installed_viewer_serves_the_page_and_its_script(served):
    import httpx

    base = served.partition("?")[0]
    with httpx.Client(timeout=60) as browser:  # keeps the cookie the page sets, as a browser does
        page = browser.get(served)
        assert page.status_code == 200 and '<script type="module" src="/static/viewer.js">' in page.text
        script = browser.get(base + "static/viewer.js")
        assert script.status_code == 200 and 'from"./widget.js"' in script.text
        scene = browser.get(base + "static/widget.js")
        assert scene.status_code == 200 and len(scene.content) > 100_000
        assert browser.get(base + "favicon.ico").headers["content-type"].startswith("image/svg+xml")


@pytest.mark.skipif(not pathlib.Path("/usr/bin/chromium").exists(), reason="needs chromium at /usr/bin/chromium")
def test_installed_viewer_renders_in_chromium(served):
    sync_api = pytest.importorskip("playwright.sync_api")
    from .test_browser import ARGS

    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS, timeout=120_000)
        try:
            page = browser.new_page(viewport={"width": 1400, "height": 820})
            errors = []
            page.on("pageerror", lambda exc: errors.append(str(exc)))
            page.goto(served, wait_until="load", timeout=120_000)
            # the script ran: presets and integrators came from the API and WebGL drew the scene
            page.wait_for_function("document.getElementById('preset').options.length >= 8 && "
                                   "document.getElementById('method').options.length > 3 && "
                                   "window.kreisel && window.kreisel.webgl === true", timeout=120_000)
            assert errors == []
        finally:
            browser.close()
