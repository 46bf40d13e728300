"""Compiled per-pose kernels of :mod:`kreisel.se3`, broadcast as lazy gufuncs.

A pose is stored as a unit quaternion ``q`` (scalar first) and a translation
``t``: the displacement ``r -> R(q) r + t`` of seed 一.3. Everything here
works on one pose and is broadcast by :func:`numba.guvectorize`; the scalar
quaternion algebra comes from :mod:`kreisel.so3._kernels`.
"""

from __future__ import annotations

from ..so3 import _kernels as k
from ..so3._gufunc import gufunc

_F8 = "f8[:]"


def _signature(n_arrays):
    return ["void(" + ", ".join([_F8] * n_arrays) + ")"]


def split(pose):
    """Views ``(q, t)`` of packed poses ``(..., 7)``."""
    return pose[..., :4], pose[..., 4:]


# Results are packed as [q, t] in one (7,) core: one output array per call.
@gufunc(_signature(6), "(4),(3),(4),(3),(7)->(7)")
def _compose(q1, t1, q2, t2, carrier, out):
    k.qmul(q1, q2, out[:4])
    k.qrotate(q1, t2, out[4:])
    out[4] += t1[0]
    out[5] += t1[1]
    out[6] += t1[2]


@gufunc(_signature(4), "(4),(3),(7)->(7)")
def _invert(q, t, carrier, out):
    out[0] = q[0]
    out[1] = -q[1]
    out[2] = -q[2]
    out[3] = -q[3]
    k.qrotate_inverse(q, t, out[4:])
    out[4] = -out[4]
    out[5] = -out[5]
    out[6] = -out[6]


def compose(q1, t1, q2, t2):
    """(q1, t1)(q2, t2) = (q1 q2, R(q1) t2 + t1): apply pose 2, then pose 1."""
    return split(_compose(q1, t1, q2, t2))


def invert(q, t):
    """(q, t)⁻¹ = (q*, -R(q)ᵀ t)."""
    return split(_invert(q, t))


@gufunc(_signature(4), "(4),(3),(3)->(3)")
def apply(q, t, p, out):
    """r_P = R r′_CP + r_C (seed 一.3, Chasles)."""
    k.qrotate(q, p, out)
    out[0] += t[0]
    out[1] += t[1]
    out[2] += t[2]


@gufunc(_signature(4), "(4),(3),(3)->(3)")
def apply_inverse(q, t, p, out):
    """r′_CP = Rᵀ (r_P - r_C): space point back to body components."""
    d0 = p[0] - t[0]
    d1 = p[1] - t[1]
    d2 = p[2] - t[2]
    # qrotate_inverse reads v[i] only before it writes out[i]: safe in place,
    # and no per-pose temporary is allocated.
    out[0] = d0
    out[1] = d1
    out[2] = d2
    k.qrotate_inverse(q, out, out)
