"""Instantaneous motion: screw axis (Chasles/Mozzi), planar instantaneous centre and centrodes (Theory §3.8).

At any instant a rigid motion with angular velocity ω and reference-point
velocity v_C is a translation (ω = 0), a rotation about an instantaneous
axis (ω ≠ 0, ω·v_C = 0) or a screw motion (ω·v_C ≠ 0). The axis passes
through ``r_A = r_C + ω × v_C / |ω|²`` along ω, and the pitch is
``h = ω·v_C / |ω|²`` (axial displacement per radian).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled.checks import VECTOR, vector_array
from .._compiled.elementwise import Input, declare, kernel, uses
from .._compiled.outputs import takes_out
from .._validation import as_float_array, out_of_range
from ._checks import batch_shape
from .._norms import norm

__all__ = ["ScrewAxis", "screw_axis", "instantaneous_centre", "Centrodes", "centrodes"]

#: a quantity given as a function of the sample times (vectorised over t)
_TimeFunction = Callable[[NDArray[np.float64]], ArrayLike]


class ScrewAxis(NamedTuple):
    """Instantaneous screw axis of a twist.

    Examples
    --------
    A drill bit turning at 10 rad/s about z while advancing 0.02 m/s along it,
    seen from a reference point 1 m off the axis: the axis is found again,
    with pitch 2 mm per radian:

    >>> s = screw_axis([0.0, 0.0, 10.0], [0.0, 10.0, 0.02], [1.0, 0.0, 0.0])
    >>> s.kind, (s.point.round(12) + 0.0).tolist(), round(float(s.pitch), 12)
    ('screw', [0.0, 0.0, 0.0], 0.002)
    >>> s.direction.tolist(), s.axial_velocity.round(12).tolist()
    ([0.0, 0.0, 1.0], [0.0, 0.0, 0.02])
    """

    kind: NDArray[np.str_] | str  #: "translation", "rotation" or "screw" (str for a single twist)
    point: NDArray[np.float64]  #: point of the axis nearest the reference point (NaN for a translation)
    direction: NDArray[np.float64]  #: unit vector along ω (along v for a translation; NaN at rest)
    pitch: NDArray[np.float64]  #: h = ω·v/|ω|², metres per radian (0 for a rotation, inf for a translation)
    axial_velocity: NDArray[np.float64]  #: velocity of the points on the axis, h ω (v itself for a translation)


def _vectors(x: ArrayLike, name: str) -> NDArray[np.float64]:
    """Finite ``(..., 3)`` float64 array, C-contiguous, so that a strided view gives bit for bit the result of a
    plain array (numpy's reductions sum in another order over other layouts)."""
    return np.ascontiguousarray(vector_array(x, name))


def screw_axis(omega: ArrayLike, velocity: ArrayLike, point: ArrayLike = 0.0, rtol: float = 1e-12,
               omega_atol: float = 0.0) -> ScrewAxis:
    """Classify the instantaneous motion and find its screw axis (Theory §3.8, Chasles/Mozzi).

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity.
    velocity : array_like, shape (..., 3)
        Velocity v_C of the reference point C.
    point : array_like, shape (..., 3)
        Position r_C of the reference point (default origin).
    rtol : float
        A motion with |ω·v| ≤ rtol |ω| |v| counts as a pure rotation.
    omega_atol : float
        A motion with |ω| ≤ omega_atol counts as a translation (default:
        exactly ω = 0).

    Returns
    -------
    ScrewAxis

    Examples
    --------
    A wheel of radius 1 in the xz plane rolling along x at unit speed (its
    centre at height 1, ω = (0, 1, 0)) turns about its contact line:

    >>> s = screw_axis([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0])
    >>> str(s.kind), s.point.round(15) + 0.0, float(s.pitch)
    ('rotation', array([0., 0., 0.]), 0.0)
    """
    omega = _vectors(omega, "omega")
    velocity = _vectors(velocity, "velocity")
    point = _vectors(np.broadcast_to(np.asarray(point, dtype=float), (3,)) if np.ndim(point) == 0 else point, "point")
    shape = batch_shape(("omega", omega, 1), ("velocity", velocity, 1), ("point", point, 1))
    if not (0.0 <= rtol < 1.0):
        raise ValueError(f"rtol must be in [0, 1), got {rtol!r}")
    if not omega_atol >= 0.0:
        raise ValueError(f"omega_atol must be >= 0, got {omega_atol!r}")
    # through the unit vector ω̂ = ω/|ω| and norms scaled before squaring: no product of two
    # large or two small magnitudes is formed, so any finite ω, v within range give finite results
    wn = norm(omega)
    vn = norm(velocity)
    translation = np.broadcast_to(wn <= omega_atol, shape)
    rotating = ~translation
    w_safe = np.where(rotating, wn, 1.0)[..., None]
    w_hat = omega / w_safe
    wv = np.einsum("...i,...i->...", w_hat, velocity)  # ω̂·v
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        pitch = np.where(rotating, wv / w_safe[..., 0], np.inf)
        axis_point = point + np.where(rotating[..., None], np.cross(w_hat, velocity) / w_safe, np.nan)
        along_v = velocity / vn[..., None]
        direction = np.where(translation[..., None], along_v, w_hat)
        axial = np.where(translation[..., None], velocity, wv[..., None] * w_hat)
    if not (np.isfinite(pitch[rotating]).all() and np.isfinite(axis_point[rotating]).all()):
        raise ValueError("omega is out of range: |v|/|ω| overflows double precision (treat tiny ω as a "
                         "translation with omega_atol)")
    rotation = rotating & (np.abs(wv) <= rtol * vn)
    pitch = np.where(rotation, 0.0, pitch)
    axial = np.where(rotation[..., None], 0.0, axial)
    kinds = np.where(translation, "translation", np.where(rotation, "rotation", "screw"))
    kind = str(kinds) if kinds.ndim == 0 else kinds
    return ScrewAxis(kind, axis_point, direction, pitch, axial)


@kernel
def _centre(w: float, vx: float, vy: float, px: float, py: float) -> tuple[float, float]:
    # r_C + (−v_y, v_x)/ω; at infinity (NaN) for a translation
    inv = math.nan if w == 0.0 else 1.0 / w
    return px + -vy * inv, py + vx * inv


_centres = declare(_centre, [Input("omega", (), VECTOR), Input("velocity", (2,), VECTOR), Input("point", (2,), VECTOR)],
                   (2,), name="instantaneous_centre", singular=True)


@uses(_centres)
@takes_out
def instantaneous_centre(omega: ArrayLike, velocity: ArrayLike, point: ArrayLike = 0.0, *,
                         out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Instantaneous centre of a planar motion (Theory §3.8).

    For ω ≠ 0 the point with zero velocity is unique:
    ``r_I = r_C + ẑ × v_C / ω = r_C + (−v_y, v_x)/ω``.

    Parameters
    ----------
    omega : array_like, shape (...)
        Angular velocity about the plane normal (counter-clockwise positive).
    velocity : array_like, shape (..., 2)
        Velocity of the reference point C.
    point : array_like, shape (..., 2)
        Position of C (default origin).

    Returns
    -------
    ndarray, shape (..., 2)
        The centre; NaN where ω = 0 (translation: the centre is at infinity).

    Examples
    --------
    Wheel of radius 0.5 rolling to the right at 1 m/s (turning clockwise at 2 rad/s):

    >>> instantaneous_centre(-2.0, [1.0, 0.0], [3.0, 0.5])
    array([3., 0.])
    """
    omega = as_float_array(omega, "omega", finite=False)
    velocity = as_float_array(velocity, "velocity", (2,), finite=False)
    point = as_float_array(np.broadcast_to(np.asarray(point, dtype=float), (2,)) if np.ndim(point) == 0 else point,
                           "point", (2,), finite=False)
    batch_shape(("omega", omega, 0), ("velocity", velocity, 1), ("point", point, 1))
    return _centres(omega, velocity, point, out=out)


class Centrodes(NamedTuple):
    """Space and body centrodes (空间极迹, 本体极迹) of a planar motion.

    Examples
    --------
    A wheel of radius 1 rolling along x (centre (s, 1), angle -s): the space
    centrode is the road y = 0, the body centrode the rim:

    >>> t = np.linspace(0.0, 3.0, 7)
    >>> c = centrodes(t, lambda t: -t, lambda t: np.stack([t, np.ones_like(t)], -1))
    >>> c.space.shape, bool(np.allclose(c.space[:, 1], 0.0, atol=1e-9))
    ((7, 2), True)
    >>> bool(np.allclose(np.linalg.norm(c.body, axis=-1), 1.0))
    True
    """

    t: NDArray[np.float64]  #: sample times, (n,)
    space: NDArray[np.float64]  #: instantaneous centre in the fixed plane, (..., n, 2)
    body: NDArray[np.float64]  #: the same points in body coordinates (origin C, axes turned by the angle), (..., n, 2)


def _richardson_derivative(f: _TimeFunction, t: NDArray[np.float64], h: float) -> NDArray[np.float64]:
    # central differences at h, h/2, h/4 combined to cancel the h² and h⁴ terms
    def central(step: float) -> NDArray[np.float64]:
        difference: NDArray[np.float64] = np.asarray(f(t + step), dtype=float) - np.asarray(f(t - step), dtype=float)
        return difference / (2.0 * step)

    d1, d2, d4 = central(h), central(h / 2), central(h / 4)
    e2 = (4.0 * d2 - d1) / 3.0
    e4 = (4.0 * d4 - d2) / 3.0
    derivative: NDArray[np.float64] = (16.0 * e4 - e2) / 15.0
    return derivative


def _sampled(value: ArrayLike | _TimeFunction, rate: ArrayLike | _TimeFunction | None, t: NDArray[np.float64], name: str,
             time_axis: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Values and rates at t from arrays (rates by np.gradient) or callables (Richardson)."""
    v: ArrayLike
    if callable(value):
        v = np.asarray(value(t), dtype=float)
        if rate is None:
            h = 1e-3 * max(1.0, float(np.ptp(t)))
            rate = _richardson_derivative(value, t, h)
    else:
        v = value
    r: ArrayLike | None = rate(t) if callable(rate) else rate
    v = as_float_array(v, name)
    if v.ndim <= time_axis or v.shape[time_axis if time_axis < 0 else time_axis] != t.size:
        raise ValueError(f"{name} must have {t.size} samples along its time axis, got shape {v.shape}")
    if r is None:
        if t.size < 3:
            raise ValueError(f"{name} needs at least 3 samples to be differentiated")
        # np.gradient multiplies three spacings: times are scaled by a power of two first (exact), so that
        # spans of 1e155 s do not overflow nor 1e-155 s underflow where the rate itself is representable
        e = int(np.frexp(np.max(np.abs(t)))[1])
        with out_of_range(f"t and {name}", f"the rate of {name}") as guard:
            r = guard.check(np.ldexp(np.gradient(v, np.ldexp(t, -e), axis=time_axis, edge_order=2), -e))
    r = as_float_array(r, f"{name} rate")
    if r.shape != v.shape:
        raise ValueError(f"the rate of {name} must have the shape of {name} {v.shape}, got {r.shape}")
    return v, r


def centrodes(t: ArrayLike, angle: ArrayLike | _TimeFunction, position: ArrayLike | _TimeFunction,
              angle_rate: ArrayLike | _TimeFunction | None = None,
              velocity: ArrayLike | _TimeFunction | None = None) -> Centrodes:
    """Space and body centrodes (polodes) of a planar motion (Theory §3.8).

    The body pose at time t is its angle θ(t) (counter-clockwise) and the
    position r_C(t) of a body reference point; the instantaneous centre
    r_I(t) traces the space centrode, and ``R(θ)ᵀ (r_I − r_C)`` the body
    centrode. During the motion the body centrode rolls without slipping on
    the space centrode.

    Parameters
    ----------
    t : array_like, shape (n,)
        Sample times, strictly increasing.
    angle : array_like (..., n) or callable
        θ at the times t, or a function θ(t) (vectorised over t).
    position : array_like (..., n, 2) or callable
        r_C at the times t, or a function r_C(t) returning (..., n, 2).
    angle_rate, velocity : array_like or callable, optional
        θ̇ and v_C; when omitted they are differentiated numerically:
        second-order ``np.gradient`` for samples, sixth-order Richardson
        central differences (relative error ~1e-11) for callables.

    Returns
    -------
    Centrodes
        ``t``, ``space`` and ``body`` points, NaN where θ̇ = 0.

    Examples
    --------
    A ladder of length 2 sliding down a wall: its ends are (0, 2 sin θ) and
    (2 cos θ, 0); the space centrode is the circle of radius 2 about the
    corner, the body centrode the circle of radius 1 about the midpoint.

    >>> t = np.linspace(0.2, 1.2, 5)
    >>> c = centrodes(t, lambda t: -t, lambda t: np.stack([np.cos(t), np.sin(t)], -1))
    >>> np.allclose(np.linalg.norm(c.space, axis=-1), 2.0), np.allclose(np.linalg.norm(c.body, axis=-1), 1.0)
    (True, True)
    """
    t = as_float_array(t, "t")
    if t.ndim != 1 or t.size < 1 or np.any(np.diff(t) <= 0):
        raise ValueError("t must be a strictly increasing 1-D array of times")
    theta, theta_rate = _sampled(angle, angle_rate, t, "angle", -1)
    r_c, v_c = _sampled(position, velocity, t, "position", -2)
    if r_c.shape[-1] != 2:
        raise ValueError(f"position must have shape (..., n, 2), got {r_c.shape}")
    batch_shape(("angle", theta, 0), ("position", r_c, 1))
    space = instantaneous_centre(theta_rate, v_c, r_c)
    d = space - r_c
    c, s = np.cos(theta), np.sin(theta)
    body = np.stack([c * d[..., 0] + s * d[..., 1], -s * d[..., 0] + c * d[..., 1]], axis=-1)
    return Centrodes(t, space, body)
