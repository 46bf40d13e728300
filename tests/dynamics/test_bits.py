"""Bit-level contracts of the fixed-step drivers: RK4 against a plain-Python transcription; dense = end state.

The drivers keep their state in registers on some paths and in arrays on
others, and store samples from inside their loops; rewriting them must not
move a bit. Classical RK4 uses only correctly rounded operations (+, ×, ÷, √),
so a transcription in Python floats with the same order of operations gives
the same bits on any IEEE machine.
"""

import math

import numpy as np
import pytest

import kreisel as kr
from kreisel.dynamics import _integrators
from kreisel.dynamics.torques import ConstantTorque, LinearDamping

MOMENTS = np.array([[1.0, 2.0, 2.85], [1.1, 2.05, 2.9], [0.7, 1.3, 1.9]])
OMEGA = np.array([[0.1, 1.0, 0.1], [0.3, -0.8, 0.2], [1.5, 0.05, -0.4]])
Q0 = np.array([0.9, 0.1, -0.3, 0.2]) / np.linalg.norm([0.9, 0.1, -0.3, 0.2])


def _unit(q0, q1, q2, q3):
    n = math.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    return q0 / n, q1 / n, q2 / n, q3 / n


def _rates(i, m, y):
    """Euler's equations and ½ q ⊗ (0, ω′), in the order of operations of the compiled right-hand side."""
    w0, w1, w2, q0, q1, q2, q3 = y
    i0, i1, i2 = i
    d0 = q0 * 0.0 - q1 * w0 - q2 * w1 - q3 * w2
    d1 = (q0 * w0 + q1 * 0.0) + (q2 * w2 - q3 * w1)
    d2 = (q0 * w1 + q2 * 0.0) + (q3 * w0 - q1 * w2)
    d3 = (q0 * w2 + q3 * 0.0) + (q1 * w1 - q2 * w0)
    return [((i1 - i2) * w1 * w2 + m[0]) / i0, ((i2 - i0) * w2 * w0 + m[1]) / i1,
            ((i0 - i1) * w0 * w1 + m[2]) / i2, 0.5 * d0, 0.5 * d1, 0.5 * d2, 0.5 * d3]


def _rk4_samples(i, m, y, steps):
    """Classical RK4 with a constant body torque ``m``, q renormalised every step; the samples (ω′, q/|q|)."""
    samples = [list(y[:3]) + list(_unit(*y[3:]))]
    for h in steps:
        k1 = _rates(i, m, y)
        k2 = _rates(i, m, [a + 0.5 * h * b for a, b in zip(y, k1)])
        k3 = _rates(i, m, [a + 0.5 * h * b for a, b in zip(y, k2)])
        k4 = _rates(i, m, [a + h * b for a, b in zip(y, k3)])
        y = [y[c] + h / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c]) for c in range(7)]
        y[3:] = _unit(*y[3:])
        samples.append(y[:3] + list(_unit(*y[3:])))
    return np.array(samples)


@pytest.mark.parametrize("torque", [None, ConstantTorque([0.1, -0.05, 0.2])])
def test_rk4_gives_the_bits_of_its_transcription(torque):
    t = np.linspace(0.0, 0.6, 61)  # one step per output interval (the steps differ in the last bits), all stored
    m = (0.0, 0.0, 0.0) if torque is None else (0.1, -0.05, 0.2)
    expected = np.stack([_rk4_samples(i, m, list(w) + list(Q0), np.diff(t)) for i, w in zip(MOMENTS, OMEGA)])
    dense = kr.simulate_batch(MOMENTS, t, OMEGA, q0=Q0, torque=torque, method="rk4", dt=0.01)
    sparse = kr.simulate_batch(MOMENTS, t, OMEGA, q0=Q0, torque=torque, method="rk4", dt=0.01, every=20)
    one = kr.simulate(MOMENTS[2], t, OMEGA[2], q0=Q0, torque=torque, method="rk4", dt=0.01)
    six = kr.simulate_6dof(MOMENTS[2], t, OMEGA[2], q0=Q0, velocity0=[1.0, 0.0, 0.5], torque=torque, method="rk4",
                           dt=0.01)
    for got, want in ((dense, expected), (sparse, expected[:, ::20]), (one, expected[2]), (six, expected[2])):
        np.testing.assert_array_equal(got.omega, want[..., :3])
        np.testing.assert_array_equal(got.q, want[..., 3:])


@pytest.mark.parametrize("method", ["splitting", "splitting4", "dmv", "rkmk4", "midpoint", "rk4"])
@pytest.mark.parametrize("torque", [None, ConstantTorque([0.1, 0.0, 0.2]) + LinearDamping(0.01)])
def test_dense_samples_are_the_end_states_of_shorter_runs(method, torque):
    # steps of 1/8 on a grid of exact binary times: the run to t[k] takes the dense run's first k steps
    if torque is None and method.startswith("splitting"):
        pytest.skip("free splitting merges the half flows on either side of a sample: equal to round-off only")
    t = np.arange(9) / 8.0
    dense = kr.simulate_batch(MOMENTS, t, OMEGA, q0=Q0, torque=torque, method=method, dt=0.125)
    six = kr.simulate_6dof(MOMENTS[0], t, OMEGA[0], q0=Q0, velocity0=[1.0, 0.0, 0.5], torque=torque,
                           method=method, dt=0.125)
    for k in (1, 2, 5, 8):
        end = kr.simulate_batch(MOMENTS, t[[0, k]], OMEGA, q0=Q0, torque=torque, method=method, dt=0.125)
        np.testing.assert_array_equal(end.omega[:, -1], dense.omega[:, k])
        np.testing.assert_array_equal(end.q[:, -1], dense.q[:, k])
        end6 = kr.simulate_6dof(MOMENTS[0], t[[0, k]], OMEGA[0], q0=Q0, velocity0=[1.0, 0.0, 0.5], torque=torque,
                                method=method, dt=0.125)
        for name in ("omega", "q", "position", "velocity"):
            np.testing.assert_array_equal(getattr(end6, name)[-1], getattr(six, name)[k], err_msg=name)


def test_the_register_drivers_finite_test_rejects_exactly_the_non_finite_numbers():
    # one sum of x - x stands for fourteen isfinite tests, the largest finite numbers included
    finite = [1e308, -1e308, 5e-324, -0.0, 0.0, 1.0, -2.5, 1.7976931348623157e308, -1.7976931348623157e308, 3.0,
              1e-300, 7.0, -7.0, 2.0]
    assert _integrators._finite(tuple(finite[:7]), tuple(finite[7:]))
    for position in range(14):
        for bad in (math.inf, -math.inf, math.nan):
            values = list(finite)
            values[position] = bad
            assert not _integrators._finite(tuple(values[:7]), tuple(values[7:]))
