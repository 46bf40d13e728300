"""Test-session set-up shared by tests/ and the doctests in src/kreisel.

Each pytest-xdist worker gets its own numba cache directory. Two processes
compiling the same function for different array layouts at the same moment
can leave numba's on-disk index pairing one signature with the other's
machine code (a crash, not a wrong number, but a crash all the same); separate
caches make the parallel test run immune to that race. This must run before
numba is imported, which conftest.py at the root does.
"""

import os
import pathlib

_worker = os.environ.get("PYTEST_XDIST_WORKER")
if _worker and "NUMBA_CACHE_DIR" not in os.environ:
    os.environ["NUMBA_CACHE_DIR"] = str(pathlib.Path(__file__).parent / ".numba_cache" / _worker)
