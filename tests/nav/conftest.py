"""Quaternion helpers for the nav tests, written in plain numpy (independent of the kernels)."""

import numpy as np
import pytest


def qmul(p, q):
    p0, p1, p2, p3 = np.moveaxis(np.asarray(p, float), -1, 0)
    q0, q1, q2, q3 = np.moveaxis(np.asarray(q, float), -1, 0)
    return np.stack([p0 * q0 - p1 * q1 - p2 * q2 - p3 * q3,
                     p0 * q1 + p1 * q0 + p2 * q3 - p3 * q2,
                     p0 * q2 - p1 * q3 + p2 * q0 + p3 * q1,
                     p0 * q3 + p1 * q2 - p2 * q1 + p3 * q0], axis=-1)


def qconj(q):
    return np.asarray(q, float) * np.array([1.0, -1.0, -1.0, -1.0])


def qlog(q):
    """Rotation vector of unit quaternions, |ψ| <= π."""
    q = np.asarray(q, float) * np.where(np.asarray(q)[..., :1] < 0, -1.0, 1.0)
    v = np.linalg.norm(q[..., 1:], axis=-1)
    angle = 2.0 * np.arctan2(v, q[..., 0])
    scale = np.where(v > 1e-300, angle / np.where(v > 1e-300, v, 1.0), 2.0 / q[..., 0])
    return q[..., 1:] * scale[..., None]


def body_error(q_true, q_est):
    """δ with q_est = q_true ⊗ exp(δ/2): the attitude error in body components."""
    return qlog(qmul(qconj(q_true), q_est))


@pytest.fixture
def quat():
    class Q:
        mul = staticmethod(qmul)
        conj = staticmethod(qconj)
        log = staticmethod(qlog)
        error = staticmethod(body_error)
    return Q
