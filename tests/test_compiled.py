"""The compiled layer's own rules: one signature per shared kernel, a cache keyed by the sources."""

import os

import numba
import numpy as np

from kreisel._compiled import checkout_cache_root, signatures, source_state


def test_a_kernel_compiled_for_two_layouts_is_reported():
    @numba.njit
    def total(a):
        return a.sum()

    total(np.ones(3))
    assert signatures.violations({"total": total}) == {}
    total(np.ones(6)[::2])
    assert list(signatures.violations({"total": total})) == ["total"]


def test_the_shared_kernels_are_the_cached_ones():
    kernels = signatures.shared_kernels()
    assert "kreisel._compiled.kernels.qmul" in kernels and "kreisel._compiled.gufunc._all_finite" in kernels
    # routines taking a compiled right-hand side are compiled for each and never cached
    assert not any(name.endswith(".integrate") for name in kernels)


def test_a_source_checkout_compiles_into_a_cache_of_its_source_state():
    root = checkout_cache_root()
    assert root is not None and (root.parent / "pyproject.toml").is_file()
    expected = os.environ.get("NUMBA_CACHE_DIR") or str(root / source_state())  # a user's choice wins
    assert numba.config.CACHE_DIR.startswith(expected)
