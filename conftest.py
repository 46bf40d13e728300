"""Test-session set-up shared by tests/ and the doctests in src/kreisel.

Compiled code: a source checkout compiles into ``.numba_cache/<state>/shared``,
keyed by the state of the package sources (:mod:`kreisel._compiled` sets this
up on import, for tests and every other run alike). Here, the main process
removes the caches of earlier source states, which are never valid again, and
every process checks at the end that no shared kernel of the compiled layer
was compiled for more than one signature (``kreisel._compiled.signatures``);
pytest-xdist workers hand their findings to the main process.
"""

import json
import os
import shutil
import sys

import pytest

_SIGNATURES = "kreisel_signature_violations"


def _remove_stale_caches():
    from kreisel._compiled import checkout_cache_root, source_state

    caches = checkout_cache_root()
    if caches is None or os.environ.get("NUMBA_CACHE_DIR") or not caches.is_dir():
        return
    state = source_state()
    for stale in caches.iterdir():
        if stale.name != state:
            shutil.rmtree(stale, ignore_errors=True)


def _violations():
    if "kreisel._compiled" not in sys.modules:
        return {}
    from kreisel._compiled.signatures import violations

    return violations()


class _WorkerReports:
    """Collects the violations found by pytest-xdist workers (main process only)."""

    def __init__(self):
        self.found = {}

    @pytest.hookimpl(optionalhook=True)
    def pytest_testnodedown(self, node, error):
        self.found.update(json.loads(getattr(node, "workeroutput", {}).get(_SIGNATURES, "{}")))


def pytest_configure(config):
    if hasattr(config, "workerinput"):
        return
    _remove_stale_caches()
    config._kreisel_workers = _WorkerReports()
    config.pluginmanager.register(config._kreisel_workers)


def pytest_sessionfinish(session, exitstatus):
    found = _violations()
    config = session.config
    if hasattr(config, "workeroutput"):
        config.workeroutput[_SIGNATURES] = json.dumps(found)
        return
    found.update(config._kreisel_workers.found)
    if found:
        lines = [f"  {name}: {', '.join(signatures)}" for name, signatures in sorted(found.items())]
        sys.stderr.write(
            "\nShared compiled kernels with more than one signature (one layout per shared kernel,"
            " see kreisel._compiled):\n" + "\n".join(lines) + "\n"
        )
        session.exitstatus = pytest.ExitCode.TESTS_FAILED
