"""Chasles/Mozzi screws of finite displacements, and the change of base point.

Theory §1.3: a displacement is a rotation about a base point plus that point's
translation, and moving the base point leaves R unchanged. Theory §3.8 shows
that a suitable base point makes the velocity parallel to ω (screw axis);
the same holds for finite displacements (Chasles/Mozzi): every rigid
displacement is a rotation by ``angle`` about a line ``point + λ axis``
combined with a slide ``translation`` along that line.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled.checks import finite_array
from .._validation import as_float_array

__all__ = ["Screw"]


class Screw(NamedTuple):
    """Screw parameters of finite displacements (arrays with the transform's batch shape).

    Attributes
    ----------
    axis : ndarray (..., 3)
        Unit direction of the screw axis, oriented so that ``angle >= 0``.
        Pure translation: the direction of travel; identity: (0, 0, 1).
    point : ndarray (..., 3)
        Point of the axis closest to the origin (perpendicular to ``axis``);
        zero for pure translations, whose axis may be any parallel line.
    angle : ndarray (...)
        Rotation angle about the axis, in [0, π] (right-hand rule about ``axis``).
    translation : ndarray (...)
        Slide along ``axis`` (signed), metres.
    pitch : ndarray (...)
        ``translation / angle``; ``inf`` for pure translations, 0 for the identity.

    Examples
    --------
    A quarter turn about the vertical line through (1, 0, 0) combined with a
    0.5 m rise (Chasles): :meth:`RigidTransform.as_screw` finds the axis,
    angle, slide and pitch again:

    >>> from kreisel.se3 import RigidTransform
    >>> T = RigidTransform.from_screw([0, 0, 1], [1.0, 0, 0], np.pi / 2, 0.5)
    >>> s = T.as_screw()
    >>> s.axis.round(12).tolist(), (s.point.round(12) + 0.0).tolist()
    ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0])
    >>> round(float(s.angle), 12), round(float(s.translation), 12), round(float(s.pitch), 9)
    (1.570796326795, 0.5, 0.318309886)
    """

    axis: np.ndarray
    point: np.ndarray
    angle: np.ndarray
    translation: np.ndarray
    pitch: np.ndarray


def screw_parameters(quat: NDArray[np.float64], translation: NDArray[np.float64]) -> Screw:
    """:class:`Screw` of poses given as unit quaternions and translations.

    With ``q = (cos(θ/2), s)``, ``s = n sin(θ/2)`` (hemisphere ``q0 >= 0``),
    the axis point ``p ⊥ n`` solves ``(1 - R) p = t⊥`` (the part of ``t``
    across the axis), whose solution is ``p = ½ (t⊥ + cot(θ/2) n × t⊥)``,
    written as ``½ (t⊥ + q0 (s × t⊥)/|s|²)`` so that no angle is formed and
    nothing is lost near θ = π. Only an exactly zero rotation is treated as
    a pure translation; a tiny one gives a distant axis, as it should.
    """
    sign = np.where(quat[..., :1] < 0.0, -1.0, 1.0)
    w = np.abs(quat[..., 0])
    s = sign * quat[..., 1:]
    batch = np.broadcast_shapes(quat.shape[:-1], translation.shape[:-1])
    s = np.broadcast_to(s, batch + (3,))
    w = np.broadcast_to(w, batch)
    t = np.broadcast_to(translation, batch + (3,))

    s2 = np.sum(s * s, axis=-1)
    sn = np.sqrt(s2)
    angle = 2.0 * np.arctan2(sn, w)
    rotates = sn > 0.0
    t_norm = np.sqrt(np.sum(t * t, axis=-1))
    slides = ~rotates & (t_norm > 0.0)

    axis = np.zeros(batch + (3,))
    axis[..., 2] = 1.0
    axis = np.where(rotates[..., None], s / np.where(rotates, sn, 1.0)[..., None], axis)
    axis = np.where(slides[..., None], t / np.where(slides, t_norm, 1.0)[..., None], axis)

    along = np.sum(axis * t, axis=-1)
    across = t - along[..., None] * axis
    offset = w / np.where(rotates, s2, 1.0)
    point = np.where(rotates[..., None], 0.5 * (across + offset[..., None] * np.cross(s, across)), 0.0)

    with np.errstate(divide="ignore", invalid="ignore"):
        pitch = np.where(rotates, along / np.where(rotates, angle, 1.0), np.where(slides, np.inf, 0.0))
    return Screw(axis, point, angle, along, pitch)


def screw_pose(axis: ArrayLike, point: ArrayLike, angle: ArrayLike,
               translation: ArrayLike = 0.0) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Unit quaternions and translations of screw displacements (inverse of :func:`screw_parameters`).

    ``q = (cos(θ/2), n sin(θ/2))`` and ``t = (1 - R) p + d n``, with
    ``(1 - R) p = -2 q0 (s × p) - 2 s × (s × p)`` (no cancellation at
    small angles). ``point`` may be any point of the axis.
    """
    axis = finite_array(axis, "axis")
    point = finite_array(point, "point")
    angle = as_float_array(angle, "angle")
    translation = as_float_array(translation, "translation")
    norm = np.sqrt(np.sum(axis * axis, axis=-1))
    if axis.size and not np.min(norm) > 0.0:
        raise ValueError("axis must be nonzero vectors")
    n = axis / norm[..., None]
    half = 0.5 * angle
    s = np.sin(half)[..., None] * n
    w = np.cos(half)
    quat = np.empty(np.broadcast_shapes(w.shape, s.shape[:-1]) + (4,))
    quat[..., 0] = w
    quat[..., 1:] = s
    sp = np.cross(s, point)
    t = -2.0 * w[..., None] * sp - 2.0 * np.cross(s, sp) + translation[..., None] * n
    return quat, t

