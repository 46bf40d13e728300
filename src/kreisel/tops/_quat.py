"""Vectorised quaternion helpers the tops need (scalar first, Hamilton, body -> space).

Thin numpy versions operating on whole time series; they follow the
conventions of :mod:`kreisel.so3` (seed 二.4).
"""

from __future__ import annotations

import numpy as np


def qmul(p, q):
    """Hamilton product p q, broadcast over leading axes."""
    p0, p1, p2, p3 = np.moveaxis(np.asarray(p), -1, 0)
    q0, q1, q2, q3 = np.moveaxis(np.asarray(q), -1, 0)
    return np.stack(
        [
            p0 * q0 - p1 * q1 - p2 * q2 - p3 * q3,
            p0 * q1 + p1 * q0 + p2 * q3 - p3 * q2,
            p0 * q2 - p1 * q3 + p2 * q0 + p3 * q1,
            p0 * q3 + p1 * q2 - p2 * q1 + p3 * q0,
        ],
        axis=-1,
    )


def qconj(q):
    """Conjugate (= inverse of a unit quaternion)."""
    return np.asarray(q) * np.array([1.0, -1.0, -1.0, -1.0])


def rotate(q, v):
    """R(q) v for unit quaternions, broadcast."""
    q = np.asarray(q)
    u = q[..., 1:]
    t = 2.0 * np.cross(u, v)
    return v + q[..., :1] * t + np.cross(u, t)


def rotate_inverse(q, v):
    """R(q)^T v for unit quaternions, broadcast."""
    return rotate(qconj(q), v)


def rotvec_to_quat(psi):
    """exp of a rotation vector: (cos |ψ|/2, sin(|ψ|/2) ψ/|ψ|)."""
    psi = np.asarray(psi, dtype=np.float64)
    angle = np.linalg.norm(psi, axis=-1, keepdims=True)
    half = 0.5 * angle
    # sin(x/2)/x written as 0.5 sinc to stay finite at the identity
    scale = 0.5 * np.sinc(half / np.pi)
    return np.concatenate([np.cos(half), scale * psi], axis=-1)


def zxz_to_quat(phi, theta, psi):
    """Quaternion of R = Rz(φ) Rx(θ) Rz(ψ) (seed 二.3 mechanics angles)."""
    phi, theta, psi = np.broadcast_arrays(
        np.asarray(phi, dtype=np.float64),
        np.asarray(theta, dtype=np.float64),
        np.asarray(psi, dtype=np.float64),
    )
    return half_angles_zxz_to_quat(np.cos(0.5 * theta), np.sin(0.5 * theta), 0.5 * (phi + psi), 0.5 * (phi - psi))


def half_angles_zxz_to_quat(cos_half_theta, sin_half_theta, half_sum, half_difference):
    """ZXZ quaternion from cos/sin of θ/2 and (φ ± ψ)/2, for callers with θ from atan2."""
    return np.stack(
        [
            cos_half_theta * np.cos(half_sum),
            sin_half_theta * np.cos(half_difference),
            sin_half_theta * np.sin(half_difference),
            cos_half_theta * np.sin(half_sum),
        ],
        axis=-1,
    )


def matrix_to_quat(R):
    """Quaternion of one proper rotation matrix (Shepperd's branch choice)."""
    R = np.asarray(R, dtype=np.float64)
    diag = np.array([np.trace(R), R[0, 0], R[1, 1], R[2, 2]])
    k = int(np.argmax(diag))
    if k == 0:
        w = 0.5 * np.sqrt(1.0 + diag[0])
        q = [w, (R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w), (R[1, 0] - R[0, 1]) / (4 * w)]
    else:
        i = k - 1
        j, l = (i + 1) % 3, (i + 2) % 3
        x = 0.5 * np.sqrt(1.0 + 2.0 * R[i, i] - np.trace(R))
        v = np.empty(3)
        v[i] = x
        v[j] = (R[j, i] + R[i, j]) / (4 * x)
        v[l] = (R[l, i] + R[i, l]) / (4 * x)
        q = [(R[l, j] - R[j, l]) / (4 * x), *v]
    q = np.asarray(q)
    return q if q[0] >= 0 else -q
