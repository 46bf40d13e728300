"""The per-pose kernels of :mod:`kreisel.se3` and their declarations.

A pose is stored packed, ``[q0, q1, q2, q3, t0, t1, t2]``: a unit quaternion
``q`` (scalar first) and a translation ``t``, the displacement
``r -> R(q) r + t`` of Theory §1.3. Each operation is a kernel on one pose's
numbers and its declaration (:mod:`kreisel._compiled.elementwise`), which
broadcasts it over batches; the quaternion algebra comes from
:mod:`kreisel._compiled.kernels`. Packed, a pose is one input and a new pose
one output: the result of ``a * b`` is read by the next operation as it is,
where separate quaternions and translations cut out of one result would be
strided views that every loop copies first.
"""

from __future__ import annotations

import math

from numba import types

from .._compiled import dexp, kernels
from .._compiled.checks import POSE, POSE_MATRIX, TWIST, UNIT_DUAL_QUATERNION, VECTOR
from .._compiled.elementwise import Input, Parameter, declare, kernel
from ..so3.jacobians import SINGULAR_TOL

_TRANSFORM = Input("transform", (7,), POSE)


@kernel
def _turned(q0: float, q1: float, q2: float, q3: float, x: float, y: float, z: float,
            inverse: bool) -> tuple[float, float, float]:
    # R(q) v, or Rᵀ v = R(q*) v
    if inverse:
        return kernels.rotated(q0, -q1, -q2, -q3, x, y, z)
    return kernels.rotated(q0, q1, q2, q3, x, y, z)


@kernel
def _moved(q0: float, q1: float, q2: float, q3: float, t0: float, t1: float, t2: float, x: float, y: float,
           z: float, inverse: bool) -> tuple[float, float, float]:
    # r_P = R r′_CP + r_C (Theory §1.3, Chasles), or back: r′_CP = Rᵀ (r_P - r_C)
    if inverse:
        return _turned(q0, q1, q2, q3, x - t0, y - t1, z - t2, True)
    a, b, c = _turned(q0, q1, q2, q3, x, y, z, False)
    return a + t0, b + t1, c + t2


@kernel
def _vector_turned(q0: float, q1: float, q2: float, q3: float, t0: float, t1: float, t2: float, x: float, y: float,
                   z: float, inverse: bool) -> tuple[float, float, float]:
    # free vectors (directions, velocities, forces) turn with the pose and are not shifted
    return _turned(q0, q1, q2, q3, x, y, z, inverse)


@kernel
def _compose(p0: float, p1: float, p2: float, p3: float, s0: float, s1: float, s2: float, q0: float, q1: float,
             q2: float, q3: float, t0: float, t1: float, t2: float) -> tuple[float, ...]:
    # (p, s)(q, t) = (p q, R(p) t + s): (q, t) first, then (p, s)
    return kernels.quat_product(p0, p1, p2, p3, q0, q1, q2, q3) + _moved(p0, p1, p2, p3, s0, s1, s2, t0, t1, t2, False)


@kernel
def _based_at(q0: float, q1: float, q2: float, q3: float, t0: float, t1: float, t2: float, x: float, y: float,
              z: float) -> tuple[float, ...]:
    # the same R about the body point r′_CA = (x, y, z), which is at r_A = R r′_CA + r_C
    return (q0, q1, q2, q3) + _moved(q0, q1, q2, q3, t0, t1, t2, x, y, z, False)


@kernel
def _inverse(q0: float, q1: float, q2: float, q3: float, t0: float, t1: float, t2: float) -> tuple[float, ...]:
    # (q, t)⁻¹ = (q*, -R(q)ᵀ t)
    x, y, z = kernels.rotated(q0, -q1, -q2, -q3, t0, t1, t2)
    return q0, -q1, -q2, -q3, -x, -y, -z


@kernel
def _matrix(q0: float, q1: float, q2: float, q3: float, t0: float, t1: float, t2: float) -> tuple[float, ...]:
    # [[R(q), t], [0, 0, 0, 1]] row by row
    r00, r01, r02, r10, r11, r12, r20, r21, r22 = kernels.quat_matrix(q0, q1, q2, q3)
    return r00, r01, r02, t0, r10, r11, r12, t1, r20, r21, r22, t2, 0.0, 0.0, 0.0, 1.0


@kernel
def _pose_of_matrix(m00: float, m01: float, m02: float, m03: float, m10: float, m11: float, m12: float, m13: float,
                    m20: float, m21: float, m22: float, m23: float, m30: float, m31: float, m32: float,
                    m33: float) -> tuple[float, ...]:
    # Shepperd's quaternion (for a block within the tolerance, the nearest rotation's) and the last column
    return kernels.matrix_entries_quat(m00, m01, m02, m10, m11, m12, m20, m21, m22) + (m03, m13, m23)


@kernel
def _exp(w0: float, w1: float, w2: float, v0: float, v1: float, v2: float) -> tuple[float, ...]:
    # exp(ξ^) = (exp ω, J_l(ω) v), J_l the dexp map ψ̇ -> ω of Theory §3.4
    return kernels.rotvec_quat(w0, w1, w2) + dexp.jacobian_times(w0, w1, w2, v0, v1, v2, 1.0)


@kernel
def _log(q0: float, q1: float, q2: float, q3: float, t0: float, t1: float, t2: float) -> tuple[float, ...]:
    # (ω, J_l(ω)⁻¹ t) with |ω| <= π, where the inverse dexp map of Theory §3.5 has no pole
    w0, w1, w2 = kernels.quat_rotvec(q0, q1, q2, q3)
    return (w0, w1, w2) + dexp.jacobian_inverse_times(w0, w1, w2, t0, t1, t2, 1.0, SINGULAR_TOL)


@kernel
def _power(q0: float, q1: float, q2: float, q3: float, t0: float, t1: float, t2: float, p: float) -> tuple[float, ...]:
    # exp(p log T)
    w0, w1, w2, v0, v1, v2 = _log(q0, q1, q2, q3, t0, t1, t2)
    return _exp(p * w0, p * w1, p * w2, p * v0, p * v1, p * v2)


@kernel
def _dual_quat(q0: float, q1: float, q2: float, q3: float, t0: float, t1: float, t2: float) -> tuple[float, ...]:
    # [q_r, q_d] = [q, ½ (0, t) q]
    d0, d1, d2, d3 = kernels.quat_product(0.0, t0, t1, t2, q0, q1, q2, q3)
    return q0, q1, q2, q3, 0.5 * d0, 0.5 * d1, 0.5 * d2, 0.5 * d3


@kernel
def _pose_of_dual_quat(r0: float, r1: float, r2: float, r3: float, d0: float, d1: float, d2: float,
                       d3: float) -> tuple[float, ...]:
    # projected onto the unit dual quaternions (q_r / |q_r|, and q_d / |q_r| less its part along q_r),
    # then t = 2 vec(q_d q_r*)
    n = math.sqrt(r0 * r0 + r1 * r1 + r2 * r2 + r3 * r3)
    along = (r0 * d0 + r1 * d1 + r2 * d2 + r3 * d3) / (n * n)
    r0, r1, r2, r3 = r0 / n, r1 / n, r2 / n, r3 / n
    _, x, y, z = kernels.quat_product(d0 / n - along * r0, d1 / n - along * r1, d2 / n - along * r2,
                                      d3 / n - along * r3, r0, -r1, -r2, -r3)
    return r0, r1, r2, r3, 2.0 * x, 2.0 * y, 2.0 * z


@kernel
def _adjoint(q0: float, q1: float, q2: float, q3: float, t0: float, t1: float, t2: float) -> tuple[float, ...]:
    # [[R, 0], [hat(t) R, R]] row by row (the columns of hat(t) R are t × those of R)
    a, b, c, d, e, f, g, h, i = kernels.quat_matrix(q0, q1, q2, q3)
    return (
        a, b, c, 0.0, 0.0, 0.0,
        d, e, f, 0.0, 0.0, 0.0,
        g, h, i, 0.0, 0.0, 0.0,
        -t2 * d + t1 * g, -t2 * e + t1 * h, -t2 * f + t1 * i, a, b, c,
        t2 * a - t0 * g, t2 * b - t0 * h, t2 * c - t0 * i, d, e, f,
        -t1 * a + t0 * d, -t1 * b + t0 * e, -t1 * c + t0 * f, g, h, i,
    )  # fmt: skip


#: Points moved by poses (``inverse``: moved back), ``(..., 3)``.
move = declare(_moved, [_TRANSFORM, Input("points", (3,), VECTOR)], (3,), [Parameter("inverse", types.boolean)],
               name="pose_apply")
#: Vectors turned by poses (``inverse``: turned back), ``(..., 3)``.
turn = declare(_vector_turned, [_TRANSFORM, Input("vectors", (3,), VECTOR)], (3,),
               [Parameter("inverse", types.boolean)], name="pose_apply_vector")
#: Products ``a b`` of poses: ``b`` first.
compose = declare(_compose, [Input("a", (7,), POSE), Input("b", (7,), POSE)], (7,), name="pose_compose")
#: The poses about the body points ``offset`` (:func:`kreisel.se3.change_base_point`).
based_at = declare(_based_at, [_TRANSFORM, Input("offset", (3,), VECTOR)], (7,), name="pose_base_point")
invert = declare(_inverse, [_TRANSFORM], (7,), name="pose_inverse")
as_matrix = declare(_matrix, [_TRANSFORM], (4, 4), name="pose_as_matrix")
from_matrix = declare(_pose_of_matrix, [Input("matrix", (4, 4), POSE_MATRIX)], (7,), name="pose_from_matrix")
#: Poses ``exp(ξ^)`` of twists ``(ω, v)``.
exp = declare(_exp, [Input("exp_coords", (6,), TWIST)], (7,), name="pose_exp")
#: Twists ``(ω, v)`` with ``|ω| <= π`` of poses.
log = declare(_log, [_TRANSFORM], (6,), name="pose_log")
#: Powers ``exp(p log T)``; the caller refuses ``|p|`` times an angle beyond 1e8 rad.
power = declare(_power, [_TRANSFORM, Input("p", (), VECTOR)], (7,), name="pose_power")
as_dual_quat = declare(_dual_quat, [_TRANSFORM], (8,), name="pose_as_dual_quat")
from_dual_quat = declare(_pose_of_dual_quat, [Input("dual_quat", (8,), UNIT_DUAL_QUATERNION)], (7,),
                         name="pose_from_dual_quat")
adjoint = declare(_adjoint, [_TRANSFORM], (6, 6), name="pose_adjoint")
