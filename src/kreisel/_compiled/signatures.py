"""The rule "one layout per shared kernel" (see :mod:`kreisel._compiled`), as a check.

The test suite calls :func:`violations` when it ends (root ``conftest.py``):
a shared kernel that finishes the run with more than one compiled signature
fails it.
"""

from __future__ import annotations

from numba.core.caching import NullCache
from numba.core.registry import CPUDispatcher

from . import dexp, dop853, gufunc, kernels
from .threads import ParallelLoop


def shared_kernels():
    """The cached kernels of the compiled layer, by qualified name.

    The :data:`~kreisel._compiled.generic` routines are left out: they take
    a compiled function as an argument, are compiled once for each and never
    cached.
    """
    found = {}
    for module in (dexp, dop853, gufunc, kernels):
        for obj in vars(module).values():
            obj = obj.dispatcher if isinstance(obj, ParallelLoop) else obj
            if isinstance(obj, CPUDispatcher) and not isinstance(obj._cache, NullCache):
                found[f"{module.__name__}.{obj.py_func.__name__}"] = obj
    return found


def compiled_signatures(dispatcher):
    """Signatures ``dispatcher`` holds in this process or in its on-disk cache index.

    The index counts too: a kernel that a cached caller loads from disk is
    not compiled in the process, but the signatures it was ever compiled for
    in this cache directory are listed in its index.
    """
    found = set(dispatcher.signatures)
    cache_file = getattr(dispatcher._cache, "_cache_file", None)
    if cache_file is not None:
        found.update(key[0] for key in cache_file._load_index())
    return sorted(str(signature) for signature in found)


def violations(dispatchers=None):
    """Kernels compiled for more than one signature: qualified name -> list of signatures.

    Parameters
    ----------
    dispatchers : dict, optional
        Name -> numba dispatcher; by default :func:`shared_kernels`.
    """
    dispatchers = shared_kernels() if dispatchers is None else dispatchers
    found = {name: compiled_signatures(d) for name, d in sorted(dispatchers.items())}
    return {name: signatures for name, signatures in found.items() if len(signatures) > 1}
