"""Shared references for the dynamics tests: an independent numpy right-hand side."""

from types import SimpleNamespace

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation


def euler_rhs(inertia, torque=None):
    """Full-tensor Euler equations + quaternion kinematics, written independently of kreisel."""
    inertia = np.asarray(inertia, dtype=float)
    tensor = np.diag(inertia) if inertia.shape == (3,) else inertia
    inverse = np.linalg.inv(tensor)

    def f(t, y):
        w, q = y[:3], y[3:7]
        m = np.zeros(3) if torque is None else torque(t, q / np.linalg.norm(q), w)
        dw = inverse @ (m - np.cross(w, tensor @ w))
        dq = 0.5 * np.concatenate([[-q[1:] @ w], q[0] * w + np.cross(q[1:], w)])
        return np.concatenate([dw, dq])

    return f


def reference(inertia, t, omega0, q0=(1.0, 0, 0, 0), torque=None):
    """Tight DOP853 reference (rtol 1e-13) -> (omega (n,3), q (n,4))."""
    y0 = np.concatenate([omega0, q0]).astype(float)
    sol = solve_ivp(euler_rhs(inertia, torque), (t[0], t[-1]), y0, method="DOP853", t_eval=t,
                    rtol=1e-13, atol=1e-15)
    assert sol.success
    q = sol.y[3:].T
    return sol.y[:3].T, q / np.linalg.norm(q, axis=1, keepdims=True)


def rotation_matrix(q):
    return Rotation.from_quat(np.asarray(q), scalar_first=True).as_matrix()


def quat_distance(p, q):
    """Sign-independent distance between unit quaternions."""
    return np.minimum(np.linalg.norm(p - q, axis=-1), np.linalg.norm(p + q, axis=-1))


@pytest.fixture(scope="session")
def tools():
    """The helpers above, for test modules (conftest is not importable under importlib mode)."""
    return SimpleNamespace(euler_rhs=euler_rhs, reference=reference, rotation_matrix=rotation_matrix,
                           quat_distance=quat_distance)
