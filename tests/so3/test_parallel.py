"""The multi-core loops for large batches agree with the serial loops bit for bit.

Lowering ``PARALLEL_THRESHOLD`` sends small batches through the multi-core
loops (in pieces of ``PIECE`` elements), so they are compared with the serial
loops without allocating 10^4 rotations.
"""

import numpy as np
import pytest

import kreisel as kr
from kreisel._compiled import elementwise

N = 37  # odd, so the multi-core loop sees a ragged last piece


@pytest.fixture
def parallel(monkeypatch):
    monkeypatch.setattr(elementwise, "PARALLEL_THRESHOLD", 1)
    monkeypatch.setattr(elementwise, "PIECE", 5)


@pytest.fixture(scope="module")
def data():
    rng = np.random.default_rng(7)
    q = rng.normal(size=(N, 4))
    p = rng.normal(size=(N, 4))
    psi = rng.normal(size=(N, 3)) * 2.0
    R = kr.quat_to_matrix(q)
    return q, p, psi, R, rng.normal(size=(N, 3))


CASES = {
    "quat_to_matrix": lambda q, p, psi, R, v: kr.quat_to_matrix(q),
    "matrix_to_quat": lambda q, p, psi, R, v: kr.matrix_to_quat(R),
    "rotvec_to_matrix": lambda q, p, psi, R, v: kr.rotvec_to_matrix(psi),
    "matrix_to_rotvec": lambda q, p, psi, R, v: kr.matrix_to_rotvec(R),
    "rotvec_to_quat": lambda q, p, psi, R, v: kr.rotvec_to_quat(psi),
    "quat_to_rotvec": lambda q, p, psi, R, v: kr.quat_to_rotvec(q),
    "euler_to_matrix": lambda q, p, psi, R, v: kr.euler_to_matrix("ZXZ", psi),
    "euler_to_quat": lambda q, p, psi, R, v: kr.euler_to_quat("xyz", psi),
    "quat_to_euler": lambda q, p, psi, R, v: kr.quat_to_euler("yxz", q),
    "matrix_to_euler": lambda q, p, psi, R, v: kr.matrix_to_euler("ZYX", R),
    "quat_multiply": lambda q, p, psi, R, v: kr.quat_multiply(p, q),
    "quat_apply": lambda q, p, psi, R, v: kr.quat_apply(q, v, inverse=True),
    "quat_normalize": lambda q, p, psi, R, v: kr.quat_normalize(q),
    "quat_inverse": lambda q, p, psi, R, v: kr.quat_inverse(q),
}


@pytest.mark.parametrize("name", list(CASES))
def test_parallel_matches_serial(name, data, monkeypatch):
    serial = CASES[name](*data)
    monkeypatch.setattr(elementwise, "PARALLEL_THRESHOLD", 1)
    monkeypatch.setattr(elementwise, "PIECE", 5)
    assert np.array_equal(CASES[name](*data), serial)
    # Non-contiguous inputs are copied into the flat arrays the loops read.
    assert np.array_equal(CASES[name](*(np.asfortranarray(x) for x in data)), serial)


def test_parallel_keeps_leading_shape(data, parallel):
    q = data[0][:36].reshape(4, 9, 4)
    R = kr.quat_to_matrix(q)
    assert R.shape == (4, 9, 3, 3)
    np.testing.assert_array_equal(R[2, 5], kr.quat_to_matrix(q[2, 5]))


def test_parallel_broadcast_reads_one_element_in_place(data, parallel):
    q, p = data[0], data[1]
    np.testing.assert_array_equal(kr.quat_multiply(p[0], q), kr.quat_multiply(np.broadcast_to(p[0], q.shape).copy(), q))


@pytest.mark.parametrize("position", [0, N // 2, N - 1])
def test_parallel_checks_find_bad_entries_anywhere(data, parallel, position):
    q, _, psi, R, _ = data
    bad_q, bad_psi, bad_R = q.copy(), psi.copy(), R.copy()
    bad_q[position, 2] = np.nan
    bad_psi[position, 1] = np.inf
    bad_R[position, 0, 0] = 1.5
    for function in (kr.quat_to_matrix, kr.quat_normalize, kr.quat_inverse):  # the last two check as they compute
        with pytest.raises(ValueError, match="q must be finite"):
            function(bad_q)
    for function in (kr.rotvec_to_matrix, kr.rotvec_to_quat):
        with pytest.raises(ValueError, match="psi must be finite"):
            function(bad_psi)
    with pytest.raises(ValueError, match="R must be rotation matrices"):
        kr.matrix_to_quat(bad_R)
    zero_q = q.copy()
    zero_q[position] = 0.0
    for function in (kr.quat_to_matrix, kr.quat_normalize, kr.quat_inverse):
        with pytest.raises(ValueError, match="nonzero"):
            function(zero_q)
    tiny_q = q.copy()
    tiny_q[position] = [1e-309, 0.0, 0.0, 0.0]
    with pytest.raises(ValueError, match="overflows"):
        kr.quat_inverse(tiny_q)
    flipped = R.copy()
    flipped[position] *= -1.0
    with pytest.raises(ValueError, match="det > 0"):
        kr.matrix_to_euler("ZXZ", flipped)
    nan_R = R.copy()
    nan_R[position, 2, 1] = np.nan
    with pytest.raises(ValueError, match="R must be finite"):
        kr.matrix_to_rotvec(nan_R)


def _awkward(width, decades=150):
    # non-unit, tiny and huge rows: the kernels rescale before squaring
    rng = np.random.default_rng(3)
    return rng.normal(size=(N, width)) * 10.0 ** rng.integers(-decades, decades, size=(N, 1))


def _three_ways(function, *inputs):
    """``function(*inputs)`` new, into a fresh ``out=`` and into an ``out=`` that is an input of the result's shape."""
    shape = function(*inputs).shape
    aliased = [x.copy() for x in inputs]
    return (function(*inputs), function(*inputs, out=np.empty(shape)),
            function(*aliased, out=next(x for x in aliased if x.shape == shape)))


@pytest.mark.parametrize("name", ["quat_normalize", "quat_inverse", "quat_apply", "quat_apply inverse", "quat_multiply"])
def test_out_gives_the_bits_of_the_serial_loop(name, monkeypatch):
    # a fresh result, an out= that overlaps no input and an out= that is an input, on all cores
    function = {
        "quat_normalize": kr.quat_normalize, "quat_inverse": kr.quat_inverse, "quat_apply": kr.quat_apply,
        "quat_apply inverse": lambda q, v, out=None: kr.quat_apply(q, v, inverse=True, out=out),
        "quat_multiply": kr.quat_multiply,
    }[name]
    # R(q) v is computed as (q v q*) / |q|²: |q|² |v| must stay below the largest double
    rotated = (_awkward(4, 70), _awkward(3))
    inputs = {"quat_apply": rotated, "quat_apply inverse": rotated,
              "quat_multiply": (_awkward(4), _awkward(4)[::-1])}.get(name, (_awkward(4),))
    with np.errstate(all="ignore"):
        serial = function(*inputs)
        monkeypatch.setattr(elementwise, "PARALLEL_THRESHOLD", 1)
        monkeypatch.setattr(elementwise, "PIECE", 5)
        for result in _three_ways(function, *inputs):
            assert result.tobytes() == serial.tobytes()


@pytest.mark.parametrize("position", [0, N // 2, N - 1])
def test_products_refuse_as_when_checked_first(data, parallel, position):
    q, p, _, _, v = data
    nan_p, inf_q, zero_q, nan_v = p.copy(), q.copy(), q.copy(), v.copy()
    nan_p[position, 3] = np.nan
    inf_q[N - 1 - position, 0] = -np.inf
    zero_q[position] = 0.0
    nan_v[position, 1] = np.nan
    refusals = [
        (lambda: kr.quat_multiply(nan_p, inf_q), "p must be finite"),
        (lambda: kr.quat_multiply(p, inf_q), "q must be finite"),
        (lambda: kr.quat_multiply(nan_p, np.zeros((N, 3))), "p must be finite"),  # p's refusal before q's shape
        (lambda: kr.quat_apply(inf_q, nan_v), "q must be finite"),
        (lambda: kr.quat_apply(zero_q, nan_v), "q must be nonzero"),
        (lambda: kr.quat_apply(q, nan_v, inverse=True), "v must be finite"),
        (lambda: kr.quat_apply(zero_q, np.zeros((N, 2))), "q must be nonzero"),
    ]
    for call, message in refusals:
        with pytest.raises(ValueError, match=message):
            call()
    assert np.array_equal(kr.quat_multiply(p, zero_q), kr.quat_multiply(p, zero_q, out=np.empty((N, 4))))
