"""The compiled layer's shared kernels: sincos and the DOP853 dense output."""

import platform

import numba
import numpy as np
import pytest

from kreisel._compiled import dop853, kernels


# ---------------------------------------------------------------------------- sincos

def _ulps(got, want):
    """|got - want| in units of the last place of ``want`` rounded to a double (want: long double or mpmath)."""
    w = np.asarray(want, dtype=np.float64)
    ulp = np.where(w == 0.0, 5e-324, np.spacing(np.abs(w)))
    return np.abs(np.asarray(got, dtype=np.longdouble) - np.asarray(want, dtype=np.longdouble)) / ulp


def test_sincos_is_within_a_quarter_ulp_of_libm_and_below_0_8_ulp():
    """The vectorisable sine and cosine against references, at random arguments over the whole range
    (long double: 11 more bits than a double) and where they are hardest (mpmath): the doubles nearest
    to multiples of π/2 (|r| down to 2^-60.5 at 45.553093477052), tiny arguments, the range's end.
    Measured on 2·10^6 random arguments: at most 0.78 ulp (sin) and 0.75 ulp (cos); libm 0.52."""
    mpmath = pytest.importorskip("mpmath")
    if np.finfo(np.longdouble).nmant < 63:
        pytest.skip("long double is not the x87 extended format here")
    rng = np.random.default_rng(23)
    n = 50_000
    x = np.concatenate([
        np.exp(rng.uniform(np.log(1e-300), np.log(kernels.SINCOS_RANGE), n)) * rng.choice([-1.0, 1.0], n),
        rng.uniform(-8.0, 8.0, n),
        rng.integers(-2**26, 2**26, n) * (np.pi / 2) * (1 + rng.uniform(-1e-15, 1e-15, n)),
    ])
    got = np.array([kernels.sincos(v) for v in x])
    libm = np.stack([np.sin(x), np.cos(x)], axis=-1)
    want = np.stack([np.sin(x.astype(np.longdouble)), np.cos(x.astype(np.longdouble))], axis=-1)
    error, libm_error = _ulps(got, want).max(axis=0), _ulps(libm, want).max(axis=0)
    assert np.all(error <= 0.8) and np.all(error <= libm_error + 0.3), (error, libm_error)
    # hard cases in mpmath: nearest doubles to k π/2 (k = 29 is the closest approach below 1e8), tiny, the end
    with mpmath.workdps(60):
        hard = [float(k * mpmath.pi / 2) for k in [1, 2, 3, 29, 355, 2**20 + 7, 41_000_000, *rng.integers(1, 2**26, 40)]]
        hard += [1e-300, 5e-324, 1e-8, 0.785398163397448, -0.785398163397449, kernels.SINCOS_RANGE, 0.0]
        for v in hard:
            s, c = kernels.sincos(v)
            for got_value, exact in ((s, mpmath.sin(v)), (c, mpmath.cos(v))):
                ulp = np.spacing(abs(float(exact))) if float(exact) else 5e-324
                assert float(abs(mpmath.mpf(got_value) - exact)) / ulp <= 0.8, (v, got_value, exact)


# ---------------------------------------------------------------------------- DOP853 dense output

@pytest.mark.parametrize("count", [1, 7, dop853.LANES, 13, 20, dop853.BLOCK])
@pytest.mark.parametrize("scale", [1.0, 1e-200, 1e200])
@pytest.mark.parametrize("unit", [3, -1])
def test_samples_interpolated_together_are_those_of_the_one_sample_interpolant(scale, unit, count):
    # bit for bit the per-sample interpolant and quat_unit, including quat_unit's rescaling of quaternions
    # whose squares would underflow or overflow (scale), and y_new itself at the step's end; counts that
    # are not a whole number of SIMD registers are padded, and the padding never reaches the samples
    rng = np.random.default_rng(7)
    ny, block = 7, np.full((9, dop853.BLOCK), np.nan)
    y, y_new, dense = rng.normal(size=ny), rng.normal(size=ny), 1e-2 * rng.normal(size=(7, ny))
    for a in (y, y_new, dense.T):
        a[3:7] *= scale
    t, h = 2.0, 0.3
    t_new = t + h
    times = np.concatenate([np.sort(rng.uniform(t, t_new, count - 1)), [t_new]])
    block[ny, :count] = times
    dop853.interpolate_samples(dense, y, y_new, t, t_new, h, count, unit, block)
    expected = np.empty((count, ny))
    for s in range(count):
        if times[s] == t_new:
            expected[s] = y_new
        else:
            dop853.interpolate(dense, y, (times[s] - t) / h, expected[s])
        if unit >= 0:
            expected[s, 3:7] = kernels.quat_unit(*expected[s, 3:7])
    np.testing.assert_array_equal(block[:ny, :count].T, expected)
    if unit >= 0:
        np.testing.assert_allclose(np.linalg.norm(block[3:7, :count], axis=0), 1.0, rtol=1e-15)


@pytest.mark.skipif(platform.machine().lower() not in ("x86_64", "amd64"), reason="x86 packed instructions")
def test_the_sample_normalisation_vectorises():
    # the reason interpolate_samples works on components of many samples: packed square roots and divisions
    normalise = numba.njit(nogil=True, error_model="numpy")(dop853._normalise.py_func)
    q = np.ones((5, 8))
    normalise(q, 0, 4, 8)
    np.testing.assert_array_equal(q[:4], 0.5)
    assembly = "".join(normalise.inspect_asm().values())
    assert "sqrtpd" in assembly and "divpd" in assembly


@numba.njit
def _faulty_oscillator(t, y, args, dy, offset):
    # y'' = -y, whose slope turns non-finite (args[2]) in stage args[0] of every step past t = args[1] only
    dy[offset] = y[1]
    dy[offset + 1] = -y[0]
    if offset == args[0] * y.size and t > args[1]:
        dy[offset] = args[2]


@pytest.mark.parametrize("bad", [np.inf, np.nan])
@pytest.mark.parametrize("stage", [1, 2, 3, 4, 13, 14, 15])
@pytest.mark.parametrize("dense_output", [True, False])
def test_a_non_finite_middle_stage_is_refused_not_interpolated_around(stage, bad, dense_output):
    # the dense output leaves stages 1-4 out of its sums (zero weights), so a non-finite one no longer spreads
    # into the samples as 0·inf; the step's own sums still weigh it and reject the step, so the run stops
    # (no finite wrong sample); a non-finite extra stage (13-15) would reach the samples only: refused too
    t_out = np.linspace(0.0, 2.0, 41) if dense_output else np.array([0.0, 2.0])
    atol = np.full(2, 1e-12)
    out = np.full((t_out.size, 2), 7.0)
    status = dop853.integrate(_faulty_oscillator, np.array([float(stage), 1.0, bad]), t_out, np.array([1.0, 0.0]),
                              1e-12, atol, np.inf, dop853.tableau(), out, False)
    clean = np.full((t_out.size, 2), 7.0)
    assert dop853.integrate(_faulty_oscillator, np.array([float(stage), 1e300, bad]), t_out, np.array([1.0, 0.0]),
                            1e-12, atol, np.inf, dop853.tableau(), clean, False) == dop853.OK
    np.testing.assert_allclose(clean[:, 0], np.cos(t_out), atol=1e-11)
    if stage > 12 and not dense_output:
        # end state only: the extra stages shape no sample, the run is right
        assert status == dop853.OK and np.array_equal(out, clean)
    else:
        assert status in (dop853.STEP_TOO_SMALL, dop853.NOT_FINITE)
