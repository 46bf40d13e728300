"""Declared array operations: a new operation needs only a kernel and a declaration."""

import numpy as np
import pytest
from numba import types

from kreisel._compiled import elementwise
from kreisel._compiled.checks import QUATERNION, VECTOR
from kreisel._compiled.elementwise import PARALLEL_THRESHOLD, Input, Parameter, declare, elementwise as declared, kernel


@kernel
def _scaled_rotation(q0, q1, q2, q3, x, y, z, factor):
    # factor R(q) v: a kernel written for this test only
    n2 = q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3
    s = q0 * q0 - q1 * q1 - q2 * q2 - q3 * q3
    d = q1 * x + q2 * y + q3 * z
    c = (q2 * z - q3 * y, q3 * x - q1 * z, q1 * y - q2 * x)
    return (factor * (s * x + 2.0 * (d * q1 + q0 * c[0])) / n2,
            factor * (s * y + 2.0 * (d * q2 + q0 * c[1])) / n2,
            factor * (s * z + 2.0 * (d * q3 + q0 * c[2])) / n2)


@declared(_scaled_rotation, [Input("q", (4,), QUATERNION), Input("v", (3,), VECTOR)], (3,),
          [Parameter("factor", types.float64)])
def scaled_rotation(q, v, factor=1.0, *, out=None):
    """``factor R(q) v``.

    Examples
    --------
    >>> scaled_rotation([1.0, 0.0, 0.0, 0.0], [1.0, 2.0, 3.0], 2.0)
    array([2., 4., 6.])
    """


def _reference(q, v, factor):
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    w, u = q[..., :1], q[..., 1:]
    t = 2.0 * np.cross(u, v)
    return factor * (v + w * t + np.cross(u, t))


def test_a_new_operation_broadcasts_checks_and_takes_out():
    rng = np.random.default_rng(1)
    q, v = rng.normal(size=(5, 1, 4)), rng.normal(size=(3, 3))
    result = scaled_rotation(q, v, 2.0)
    assert result.shape == (5, 3, 3) and result.flags.owndata
    np.testing.assert_allclose(result, _reference(q, v, 2.0), rtol=1e-13, atol=1e-14)
    out = np.empty((5, 3, 3))
    assert scaled_rotation(q, v, factor=2.0, out=out) is out
    np.testing.assert_array_equal(out, result)
    with pytest.raises(ValueError, match="q must be nonzero quaternions"):
        scaled_rotation(np.zeros(4), v)
    with pytest.raises(ValueError, match="v must be finite"):
        scaled_rotation(q, [0.0, np.nan, 1.0])
    with pytest.raises(ValueError, match="q and v are out of range for scaled_rotation: the result overflows"):
        scaled_rotation([1.0, 0.0, 0.0, 0.0], [1e308, 0.0, 0.0], 10.0)
    with pytest.raises(ValueError, match=r"batch shapes \(2,\), \(3,\) do not broadcast"):
        scaled_rotation(np.ones((2, 4)), np.ones((3, 3)))
    assert elementwise.REGISTRY["scaled_rotation"] is scaled_rotation.__operation__
    assert "Returns" not in scaled_rotation.__doc__ and "out : ndarray, optional" in scaled_rotation.__doc__


def test_large_batches_give_the_bits_of_one_element_at_a_time():
    rng = np.random.default_rng(2)
    n = PARALLEL_THRESHOLD + 1001
    q, v = rng.normal(size=(n, 4)), rng.normal(size=(n, 3))
    batch = scaled_rotation(q, v, 0.5)
    for i in (0, 1, n // 2, n - 1):
        np.testing.assert_array_equal(batch[i], scaled_rotation(q[i], v[i], 0.5))
    # one rotation applied to many vectors is read in place, the same bits
    np.testing.assert_array_equal(scaled_rotation(q[7], v, 0.5)[11], scaled_rotation(q[7], v[11], 0.5))
    bad = v.copy()
    bad[n - 5, 1] = np.inf
    with pytest.raises(ValueError, match="v must be finite"):
        scaled_rotation(q, bad)


def test_out_may_be_an_input_and_a_refusal_leaves_it_untouched():
    rng = np.random.default_rng(3)
    v = rng.normal(size=(40, 3))
    q = rng.normal(size=(40, 4))
    expected = scaled_rotation(q, v)
    scaled_rotation(q, v, out=v)
    np.testing.assert_array_equal(v, expected)
    q[39] = 0.0
    kept = v.copy()
    with pytest.raises(ValueError, match="nonzero"):
        scaled_rotation(q, v, out=v)
    np.testing.assert_array_equal(v, kept)


def test_a_declaration_must_match_its_stub():
    with pytest.raises(TypeError, match=r"must take \(q, v, factor, \*, out=None\)"):
        declared(_scaled_rotation, [Input("q", (4,), QUATERNION), Input("v", (3,), VECTOR)], (3,),
                 [Parameter("factor", types.float64)])(lambda q, v, *, out=None: None)
    with pytest.raises(ValueError, match="declared already"):
        declare(_scaled_rotation, [Input("q", (4,), QUATERNION)], (3,), name="scaled_rotation")


def test_the_loops_are_generated_source_a_reader_can_print():
    source = scaled_rotation.__operation__.source
    assert "def scaled_rotation_serial(" in source and "def scaled_rotation_parallel(" in source
    assert "kernel(x0_0, x0_1, x0_2, x0_3, x1_0, x1_1, x1_2, p0)" in source


def test_the_single_element_path_gives_the_batch_bits_and_a_new_array():
    rng = np.random.default_rng(7)
    q, v = rng.normal(size=4), rng.normal(size=3)
    single = scaled_rotation(q, v, 0.5)
    assert single is not None and single.flags.owndata and single.shape == (3,)
    np.testing.assert_array_equal(single, scaled_rotation(q[None], v[None], 0.5)[0])
    # inputs the path does not take (a list, a strided view) go the general way to the same bits
    np.testing.assert_array_equal(scaled_rotation(list(q), v, 0.5), single)
    strided = np.empty(8)
    strided[::2] = q
    np.testing.assert_array_equal(scaled_rotation(strided[::2], v, 0.5), single)
    assert scaled_rotation.__operation__.single(strided[::2], v, 0.5) is None
    with pytest.raises(ValueError, match="q"):
        scaled_rotation(np.zeros(4), v, 0.5)
