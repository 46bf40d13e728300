"""Test-session set-up shared by tests/ and the doctests in src/kreisel.

Compiled code: a source checkout compiles into ``.numba_cache/<state>/``,
keyed by the state of the package sources (:mod:`kreisel._compiled.cache`).
The main process removes the caches of earlier source states, which are
never valid again.
"""

import os
import shutil


def _remove_stale_caches():
    from kreisel._compiled.cache import checkout_cache_root, source_state

    caches = checkout_cache_root()
    if caches is None or os.environ.get("NUMBA_CACHE_DIR") or not caches.is_dir():
        return
    state = source_state()
    for stale in caches.iterdir():
        if stale.name != state:
            shutil.rmtree(stale, ignore_errors=True)


def pytest_configure(config):
    if hasattr(config, "workerinput"):
        return
    _remove_stale_caches()
