"""kreisel's compiled layer: the one home of the numba machinery every package shares.

It sits below :mod:`kreisel.so3` (every package may import it; it imports no
other kreisel package, only the private helpers ``kreisel._validation`` and
``kreisel._norms``) and holds

- :mod:`.elementwise`: array operations declared once, a scalar kernel and a
  declaration that generates the checks, broadcasting, the serial and
  multi-core loops and ``out=``;
- :mod:`.checks`: the input checks and the kinds of input they belong to;
- :mod:`.outputs`: the ``out=`` checks and the ``out`` entry of every docstring;
- :mod:`.kernels`: the scalar quaternion kernels (product, rotation, matrix,
  exp/log);
- :mod:`.dexp`: the scalar kernels of the exponential map's differential
  (rate maps, Jacobians, Bortz coefficient);
- :mod:`.series`: Maclaurin coefficients from exact rationals, for the
  functions that lose digits to cancellation at small angles;
- :mod:`.dop853`: the one adaptive Dormand–Prince 8(5,3) integrator;
- :mod:`.chunks`: long runs in chunks (Ctrl-C, step budgets, progress);
- :mod:`.cache`: where compiled code is cached and how processes share it.

The decorator flavours below and :data:`.elementwise.kernel` are the only
ways kreisel compiles a function (besides user callables, compiled per call).
Importing kreisel changes nothing in numba: not its configuration, its locks
nor its thread count; every cached function gets a cache object of
:mod:`.cache` of its own.

Cache rules
    Everything is compiled with ``cache=True`` except the element kernels
    (compiled into the loops that call them) and what takes another compiled
    function as an argument (:data:`generic`: numba would add a new, never
    reused cache entry per process). Such routines are inlined into a cached
    caller with a fixed module-level right-hand side.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

from numba import njit

from .cache import attach, checkout_cache_root, source_state

# to type checkers a flavour returns the function it compiles (numba has no annotations for njit)
_Function = TypeVar("_Function", bound=Callable[..., Any])


def _flavour(**options: Any) -> Callable[[_Function], _Function]:
    # compiled without numba's own cache, which would create its directories next to the sources
    compile = njit(**options)
    return lambda function: attach(compile(function))


#: Cached, GIL-free scalar or array kernel: the default flavour.
cached: Callable[[_Function], _Function] = _flavour(nogil=True)
#: As :data:`cached`, inlined into its callers at the numba IR level (small
#: models called in the innermost loop of an integrator).
inlined: Callable[[_Function], _Function] = _flavour(nogil=True, inline="always")
#: As :data:`cached`, with numpy's error model: a division by zero gives inf
#: or nan instead of raising, so a loop that divides needs no test per element
#: and vectorises.
vectorised: Callable[[_Function], _Function] = _flavour(nogil=True, error_model="numpy")
#: Routines compiled anew for each argument type (a compiled function, a tuple
#: of any length): never cached on their own, always inlined into a cached caller.
generic: Callable[[_Function], _Function] = njit(nogil=True, inline="always")
#: Cached multi-core loop (``prange``), on numba's thread count.
parallel: Callable[[_Function], _Function] = _flavour(parallel=True)

__all__ = ["cached", "checkout_cache_root", "generic", "inlined", "parallel", "source_state", "vectorised"]
