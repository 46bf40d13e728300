"""The multi-core loops of the rate maps agree bit for bit with the serial ones.

Lowering ``PARALLEL_THRESHOLD`` and ``PIECE`` sends a small batch through
the parallel loops in several pieces (shared kernel code, frame sign and
tolerance included).
"""

import warnings

import numpy as np
import pytest

import kreisel as kr
from kreisel._compiled import elementwise

N = 37


@pytest.fixture(scope="module")
def data():
    rng = np.random.default_rng(11)
    angles = rng.uniform(-3.0, 3.0, size=(N, 3))
    angles[3, 1] = 0.0  # gimbal lock of the proper Euler sequences: NaN entries must match too
    psi = rng.normal(size=(N, 3)) * 2.0
    psi[5] = [0.0, 0.0, 2.0 * np.pi]  # pole of dexp⁻¹
    return angles, psi, rng.normal(size=(N, 3))


CASES = {
    "euler_rates ZXZ body": lambda a, p, w: kr.euler_rates("ZXZ", a, w, frame="body"),
    "euler_rates xyz space": lambda a, p, w: kr.euler_rates("xyz", a, w),
    "angular_velocity_from_euler_rates zyz body": lambda a, p, w: kr.angular_velocity_from_euler_rates("zyz", a, w, frame="body"),
    "angular_velocity_from_euler_rates YXZ space": lambda a, p, w: kr.angular_velocity_from_euler_rates("YXZ", a, w),
    "rotvec_rate body": lambda a, p, w: kr.rotvec_rate(p, w, frame="body"),
    "rotvec_rate space": lambda a, p, w: kr.rotvec_rate(p, w),
    "angular_velocity_from_rotvec_rate body": lambda a, p, w: kr.angular_velocity_from_rotvec_rate(p, w, frame="body"),
}


@pytest.mark.parametrize("name", list(CASES))
def test_parallel_matches_serial(name, data, monkeypatch):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", kr.KinematicSingularityWarning)
        serial = CASES[name](*data)
        monkeypatch.setattr(elementwise, "PARALLEL_THRESHOLD", 1)
        monkeypatch.setattr(elementwise, "PIECE", 5)
        parallel = CASES[name](*data)
        strided = CASES[name](*(np.asfortranarray(x) for x in data))
    np.testing.assert_array_equal(parallel, serial)
    np.testing.assert_array_equal(strided, serial)


def test_parallel_keeps_leading_shape_and_warns(data, monkeypatch):
    angles, _, w = data
    monkeypatch.setattr(elementwise, "PARALLEL_THRESHOLD", 1)
    monkeypatch.setattr(elementwise, "PIECE", 5)
    with pytest.warns(kr.GimbalLockWarning):
        rates = kr.euler_rates("ZXZ", angles[:36].reshape(4, 9, 3), w[:36].reshape(4, 9, 3))
    assert rates.shape == (4, 9, 3)
    np.testing.assert_array_equal(rates[0, 3, [0, 2]], [np.nan, np.nan])
