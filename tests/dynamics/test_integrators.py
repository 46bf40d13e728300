"""Compiled building blocks of the integrators, against independent references."""

import math

import mpmath
import numpy as np

from kreisel.dynamics._integrators import _SINCOS_SERIES_BELOW, _sin_cos

ULP = 2.0**-53  # unit round-off of float64


def test_sub_flow_sine_and_cosine_are_as_accurate_as_the_library():
    # the splittings' exact sub-flows take sin and cos of the half angle from a series below the
    # switch-over: it must be within about an ulp of the true values (60-digit mpmath)
    rng = np.random.default_rng(3)
    small = 10.0 ** rng.uniform(-12.0, math.log10(_SINCOS_SERIES_BELOW), 400) * rng.choice([-1.0, 1.0], 400)
    points = np.concatenate([small, rng.uniform(-_SINCOS_SERIES_BELOW, _SINCOS_SERIES_BELOW, 400),
                             np.nextafter(_SINCOS_SERIES_BELOW, 0.0) * np.array([-1.0, 1.0]),
                             [_SINCOS_SERIES_BELOW, 1.0, -3.0, 100.0]])
    with mpmath.workdps(60):
        for x in points:
            s, c = _sin_cos(float(x))
            exact_s, exact_c = mpmath.sin(mpmath.mpf(float(x))), mpmath.cos(mpmath.mpf(float(x)))
            assert abs(float((s - exact_s) / exact_s)) <= 1.5 * ULP, x
            assert abs(float((c - exact_c) / exact_c)) <= 1.5 * ULP, x
    assert _sin_cos(0.0) == (0.0, 1.0)
