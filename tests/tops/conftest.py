"""Independent numerical reference for the tops: scipy DOP853 at rtol 1e-13 on (ω′, q)."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp


def _quat_rotate_inverse(q, v):
    # R(q)^T v written out from the rotation matrix of Theory §2.4
    q0, q1, q2, q3 = q
    R = np.array(
        [
            [1 - 2 * (q2 * q2 + q3 * q3), 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2)],
            [2 * (q1 * q2 + q0 * q3), 1 - 2 * (q1 * q1 + q3 * q3), 2 * (q2 * q3 - q0 * q1)],
            [2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), 1 - 2 * (q1 * q1 + q2 * q2)],
        ]
    )
    return R.T @ v


def _integrate(moments, omega0, q0, t, weight=0.0, lever=(0.0, 0.0, 0.0), rtol=1e-13, atol=1e-14):
    """Euler's equations with a uniform gravity force −weight·e_z at body point ``lever``."""
    moments = np.asarray(moments, dtype=float)
    lever = np.asarray(lever, dtype=float)
    t = np.asarray(t, dtype=float)

    def rhs(_, y):
        w, q = y[:3], y[3:]
        torque = np.cross(lever, _quat_rotate_inverse(q, np.array([0.0, 0.0, -weight])))
        dw = (np.cross(moments * w, w) + torque) / moments
        p0, p1, p2, p3 = q
        w1, w2, w3 = w
        dq = 0.5 * np.array(
            [
                -p1 * w1 - p2 * w2 - p3 * w3,
                p0 * w1 + p2 * w3 - p3 * w2,
                p0 * w2 - p1 * w3 + p3 * w1,
                p0 * w3 + p1 * w2 - p2 * w1,
            ]
        )
        return np.concatenate([dw, dq])

    y0 = np.concatenate([np.asarray(omega0, float), np.asarray(q0, float)])
    sol = solve_ivp(rhs, (t[0], t[-1]), y0, method="DOP853", rtol=rtol, atol=atol, t_eval=t)
    assert sol.success
    return sol.y[:3].T, sol.y[3:].T


@pytest.fixture
def reference():
    """``reference(moments, omega0, q0, t, weight=0, lever=0)`` -> (omega (n,3), q (n,4))."""
    return _integrate
