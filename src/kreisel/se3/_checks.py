"""Input checks of :mod:`kreisel.se3`."""

from __future__ import annotations

import numpy as np

from .._validation import as_float_array


def finite_array(x, name, tail=(3,)):
    """Float64 array with trailing shape ``tail`` and finite entries, checked at the cost of one sum.

    A finite sum proves every entry finite (NaN and ±inf propagate); only
    when it is not (non-finite entries, or huge ones overflowing the sum)
    does the entrywise check run and name the argument.
    """
    a = as_float_array(x, name, tail, finite=False)
    with np.errstate(over="ignore", invalid="ignore"):
        total = np.sum(a)
    if not np.isfinite(total):
        as_float_array(a, name, tail)
    return a
