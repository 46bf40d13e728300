"""Reference paths and differentiation for the kinematics tests.

References are independent of kreisel: rotations from scipy, derivatives
from closed forms or Richardson-extrapolated central differences.
"""

from __future__ import annotations

import itertools
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.spatial.transform import Rotation as ScipyRotation

SEQUENCES = [
    "".join(s) for s in itertools.product("XYZ", repeat=3) if s[0] != s[1] and s[1] != s[2]
]
ALL_SEQUENCES = SEQUENCES + [s.lower() for s in SEQUENCES]
assert len(ALL_SEQUENCES) == 24


def hat(v):
    v = np.asarray(v, dtype=float)
    z = np.zeros(v.shape[:-1])
    return np.stack(
        [
            np.stack([z, -v[..., 2], v[..., 1]], -1),
            np.stack([v[..., 2], z, -v[..., 0]], -1),
            np.stack([-v[..., 1], v[..., 0], z], -1),
        ],
        -2,
    )


def vee(A):
    return 0.5 * np.stack([A[..., 2, 1] - A[..., 1, 2], A[..., 0, 2] - A[..., 2, 0], A[..., 1, 0] - A[..., 0, 1]], -1)


def derivative(f, t, h=1e-2):
    """First derivative by central differences at h, h/2, h/4 with Richardson extrapolation (error O(h⁶))."""

    def central(s):
        return (np.asarray(f(t + s)) - np.asarray(f(t - s))) / (2 * s)

    d1, d2, d4 = central(h), central(h / 2), central(h / 4)
    return (16 * (4 * d4 - d2) / 3 - (4 * d2 - d1) / 3) / 15


def second_derivative(f, t, h=4e-2):
    """Second derivative by central differences with Richardson extrapolation (error O(h⁶))."""

    def central(s):
        return (np.asarray(f(t + s)) - 2 * np.asarray(f(t)) + np.asarray(f(t - s))) / (s * s)

    d1, d2, d4 = central(h), central(h / 2), central(h / 4)
    return (16 * (4 * d4 - d2) / 3 - (4 * d2 - d1) / 3) / 15


class ExpPath:
    """R(t) = exp(t a) exp(t² b): R, Ṙ, R̈ by the product rule, ω, ω′, ε in closed form."""

    def __init__(self, a, b):
        self.a = np.asarray(a, dtype=float)
        self.b = np.asarray(b, dtype=float)

    def parts(self, t):
        return ScipyRotation.from_rotvec(t * self.a).as_matrix(), ScipyRotation.from_rotvec(t * t * self.b).as_matrix()

    def R(self, t):
        R1, R2 = self.parts(t)
        return R1 @ R2

    def Rdot(self, t):
        R1, R2 = self.parts(t)
        A, B = hat(self.a), hat(self.b)
        return A @ R1 @ R2 + R1 @ (2 * t * B) @ R2

    def Rddot(self, t):
        R1, R2 = self.parts(t)
        A, B = hat(self.a), hat(self.b)
        return A @ A @ R1 @ R2 + 2 * (A @ R1) @ (2 * t * B @ R2) + R1 @ (2 * B + 4 * t * t * B @ B) @ R2

    def omega(self, t):
        R1, _ = self.parts(t)
        return self.a + R1 @ (2 * t * self.b)

    def omega_body(self, t):
        return self.R(t).T @ self.omega(t)

    def epsilon(self, t):
        R1, _ = self.parts(t)
        return np.cross(self.a, R1 @ (2 * t * self.b)) + 2 * R1 @ self.b

    def epsilon_body(self, t):
        return self.R(t).T @ self.epsilon(t)

    def quat(self, t):
        """Scalar-first quaternion, sign kept continuous along the path (q0 > 0 for the paths used)."""
        x, y, z, w = ScipyRotation.from_matrix(self.R(t)).as_quat()
        q = np.array([w, x, y, z])
        return q if w >= 0 else -q

    def rotvec(self, t):
        return ScipyRotation.from_matrix(self.R(t)).as_rotvec()


PATHS = [
    ExpPath([0.3, -0.5, 0.4], [0.2, 0.6, -0.1]),
    ExpPath([-0.9, 0.2, 0.1], [0.05, -0.3, 0.7]),
    ExpPath([1e-3, 2e-3, -1e-3], [1e-3, 0.0, 2e-3]),
]


@pytest.fixture(params=range(len(PATHS)), ids=["generic", "tumbling", "small-angle"])
def path(request):
    return PATHS[request.param]


@pytest.fixture
def ref():
    return SimpleNamespace(
        hat=hat,
        vee=vee,
        derivative=derivative,
        second_derivative=second_derivative,
        ExpPath=ExpPath,
        sequences=ALL_SEQUENCES,
        Rotation=ScipyRotation,
    )
