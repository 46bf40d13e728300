"""Test-session set-up shared by tests/ and the doctests in src/kreisel.

Numba's on-disk cache is keyed on the file of each compiled function, not on
the files of the functions it calls, so after an edit to a shared kernel a
cached caller elsewhere can keep running the old code; and two processes
compiling one function for different array layouts at the same moment can
leave an index that pairs one signature with the other's machine code. Tests
therefore compile into a cache of their own, keyed by the state of the source
tree and separate for each pytest-xdist worker. This runs before numba is
imported, which conftest.py at the root of the repository guarantees.
"""

import hashlib
import os
import pathlib
import shutil

_ROOT = pathlib.Path(__file__).parent
_CACHES = _ROOT / ".numba_cache"


def _source_state():
    digest = hashlib.sha1()
    for path in sorted((_ROOT / "src" / "kreisel").rglob("*.py")):
        stat = path.stat()
        digest.update(f"{path.relative_to(_ROOT)}:{stat.st_size}:{stat.st_mtime_ns}".encode())
    return digest.hexdigest()[:16]


# a cache directory the user chose is respected; ours (inherited by xdist workers) is re-derived per worker
if "NUMBA_CACHE_DIR" not in os.environ or os.environ.get("KREISEL_TEST_NUMBA_CACHE") == os.environ["NUMBA_CACHE_DIR"]:
    _state = _source_state()
    if os.environ.get("PYTEST_XDIST_WORKER") is None and _CACHES.is_dir():
        for stale in _CACHES.iterdir():  # caches of earlier source states are never valid again
            if stale.name != _state:
                shutil.rmtree(stale, ignore_errors=True)
    os.environ["NUMBA_CACHE_DIR"] = str(_CACHES / _state / os.environ.get("PYTEST_XDIST_WORKER", "main"))
    os.environ["KREISEL_TEST_NUMBA_CACHE"] = os.environ["NUMBA_CACHE_DIR"]
