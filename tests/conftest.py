"""Fixtures shared across test folders: a short scenario, and tools for the tests that install kreisel the way a user does."""

import importlib.util
import pathlib
import shutil
import signal
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]


@pytest.fixture(scope="session")
def racket_toml():
    """A short rigid-body scenario, TOML text: the bundled tennis racket's body and spin, 10 s in 101 samples.

    Tests make their variants with ``str.replace`` of whole lines.
    """
    return """\
title = "short tennis racket"
[body]
moments = [1.0, 2.0, 3.0]
[initial]
omega = [0.01, 1.0, 0.01]
[integration]
t_end = 10.0
n_samples = 101
"""


@pytest.fixture(scope="session")
def interrupt():
    """``interrupt(process, timeout)``: stop a child as Ctrl+C does, killing it if it has not exited within ``timeout`` s."""

    def stop(process, timeout):
        process.send_signal(signal.SIGINT)
        try:
            process.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()

    return stop


@pytest.fixture(scope="session")
def repository_copy(tmp_path_factory):
    """A copy of the repository's files as a clone has them (tracked or about to be), without build products.

    pip builds an installed kreisel from it, so the working tree gets no ``build/`` or ``*.egg-info``.
    """
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        pytest.skip("needs a git checkout to know the repository's files")
    target = tmp_path_factory.mktemp("repository") / "kreisel"
    listed = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"], cwd=ROOT,
                            capture_output=True, text=True, check=True).stdout.split("\n")
    for name in filter(None, listed):
        source = ROOT / name
        if source.is_file():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target / name)
    return target


def _glyphs_module():
    spec = importlib.util.spec_from_file_location("_glyphs", ROOT / "tests" / "_glyphs.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="session")
def glyphs():
    """tests/_glyphs.py: ``glyphs.cjk_glyphs(page)`` checks that chromium draws every CJK character of a page."""
    return _glyphs_module()


@pytest.fixture(scope="module")
def playwright_chromium(glyphs):
    """Playwright, for Debian's chromium (``glyphs.launch(playwright_chromium)``); skips where either is missing.

    Module-scoped: Playwright's synchronous API runs one instance at a time, and other test modules start their own.
    """
    if not glyphs.CHROMIUM.exists():
        pytest.skip("needs Debian's chromium at /usr/bin/chromium (.ci/run installs it with apt-get)")
    sync_api = pytest.importorskip("playwright.sync_api")
    with sync_api.sync_playwright() as playwright:
        yield playwright


@pytest.fixture(scope="module")
def chromium(glyphs, playwright_chromium):
    """Debian's headless chromium (a Playwright browser) with the machine's fonts."""
    browser = glyphs.launch(playwright_chromium)
    try:
        yield browser
    finally:
        browser.close()
