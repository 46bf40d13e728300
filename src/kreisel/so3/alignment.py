"""Attitude from vector observations: Wahba's problem, batched.

Given vectors ``b_k`` measured in one frame (body: sun, star, magnetometer,
gravity directions) and the same vectors ``a_k`` known in another (space),
find the rotation ``R`` with ``a_k ≈ R b_k`` that minimises Wahba's loss

.. math::

   L(R) = \\tfrac12 \\sum_k w_k \\,|a_k - R\\,b_k|^2 ,

which is the same as maximising ``tr(Rᵀ B)`` with the attitude profile
matrix ``B = Σ w_k a_k b_kᵀ``. This is the static counterpart of the
strapdown attitude of Theory §4.5: there the attitude is integrated from
rates, here it is fixed by two or more directions observed at one instant.

**TRIAD** (Black 1964) uses exactly two directions: it builds an orthonormal
triad from each pair, ``(a₁, a₁×a₂, a₁×(a₁×a₂))`` and the same from ``b``, and
``R`` maps one triad onto the other. The first vector is matched exactly, the
second only in the plane it spans with the first; the weights are ignored.
With one infinite weight, :func:`align_vectors` gives TRIAD's solution for
two vectors and its least-squares generalisation for more.

**Davenport's q-method** (1968) solves the weighted problem for any number of
vectors. For a unit quaternion ``q = (q0, v)`` (scalar first, active
``R(q)`` of Theory §2.4), ``tr(R(q)ᵀ B) = qᵀ K q`` with the symmetric 4×4

.. math::

   K = \\begin{pmatrix} \\operatorname{tr} B & z^\\mathsf{T} \\\\
       z & B + B^\\mathsf{T} - \\operatorname{tr} B\\, 1 \\end{pmatrix},
   \\qquad z = (B_{32} - B_{23},\\ B_{13} - B_{31},\\ B_{21} - B_{12}),

so the optimal ``q`` is the eigenvector of ``K`` with the largest eigenvalue
``λ_max``. Here it is found per problem by cyclic Jacobi rotations of the 4×4
matrix in compiled code (no SVD, no characteristic polynomial, accurate for
repeated eigenvalues too), which makes many small problems cheap. The SVD
form (Markley 1988, the Kabsch algorithm) gives the same ``R``; the tests
check one against the other.

The sensitivity matrix (Markley 1993) is scipy's: with the corrected singular
values ``s₁, s₂, s₃'`` of ``B`` (the eigenvalues of the symmetric ``Rᵀ B``),
``S = mean(w) (κ 1 + B Bᵀ) / ζ``, ``κ = s₁s₂ + s₂s₃' + s₃'s₁``,
``ζ = (s₁+s₂)(s₂+s₃')(s₃'+s₁)``; it is proportional to the covariance of
the small rotation vector (in frame A) that corrects the estimate.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray
from numba import prange

from .._compiled import cached, kernels, parallel
from .._compiled.elementwise import PARALLEL_THRESHOLD, PIECE
from .._validation import as_float_array

__all__ = ["align_vectors"]

#: Packed per-problem result: quaternion (4), rssd (1), sensitivity (9).
_WIDTH = 14


@cached
def _jacobi_top_eigenvector(K: NDArray[np.float64]) -> tuple[float, float, float, float]:
    """Unit eigenvector of the largest eigenvalue of the symmetric 4×4 ``K`` (overwritten).

    Cyclic Jacobi: each plane rotation zeroes one off-diagonal pair; the
    off-diagonal mass falls quadratically, so a few sweeps reach rounding.
    """
    V = np.eye(4)
    for _ in range(30):
        off = 0.0
        diag = 0.0
        for p in range(4):
            diag += K[p, p] * K[p, p]
            for q in range(p + 1, 4):
                off += K[p, q] * K[p, q]
        if off <= 1e-34 * diag or off == 0.0:
            break
        for p in range(3):
            for q in range(p + 1, 4):
                apq = K[p, q]
                if apq == 0.0:
                    continue
                theta = (K[q, q] - K[p, p]) / (2.0 * apq)
                if abs(theta) > 1e150:
                    t = 0.5 / theta
                else:
                    t = 1.0 / (abs(theta) + math.sqrt(theta * theta + 1.0))
                    if theta < 0.0:
                        t = -t
                c = 1.0 / math.sqrt(t * t + 1.0)
                s = t * c
                for m in range(4):
                    kmp, kmq = K[m, p], K[m, q]
                    K[m, p] = c * kmp - s * kmq
                    K[m, q] = s * kmp + c * kmq
                for m in range(4):
                    kpm, kqm = K[p, m], K[q, m]
                    K[p, m] = c * kpm - s * kqm
                    K[q, m] = s * kpm + c * kqm
                for m in range(4):
                    vmp, vmq = V[m, p], V[m, q]
                    V[m, p] = c * vmp - s * vmq
                    V[m, q] = s * vmp + c * vmq
    best = 0
    for p in range(1, 4):
        if K[p, p] > K[best, best]:
            best = p
    q0, q1, q2, q3 = kernels.quat_unit(V[0, best], V[1, best], V[2, best], V[3, best])
    if q0 < 0.0:
        return -q0, -q1, -q2, -q3
    return q0, q1, q2, q3


@cached
def _shortest_arc(ax: float, ay: float, az: float, bx: float, by: float, bz: float) -> tuple[float, float, float, float]:
    """Smallest rotation taking the unit vector b to the unit vector a (scipy's choice when antiparallel)."""
    # (1 + a·b, b × a) is 2 cos(θ/2) (cos(θ/2), n sin(θ/2)), the half-way quaternion.
    cx, cy, cz = by * az - bz * ay, bz * ax - bx * az, bx * ay - by * ax
    d = ax * bx + ay * by + az * bz
    if d >= 0.0:
        return kernels.quat_unit(1.0 + d, cx, cy, cz)
    # Obtuse: 1 + a·b would cancel. First a half turn about an axis u ⊥ a
    # (the direction of b × a, made exactly normal to a: near antiparallel
    # b × a is mostly rounding noise), then the short arc from the turned b,
    # whose scalar part 1 + a·b' = 1 - a·b >= 1 is exact.
    along = cx * ax + cy * ay + cz * az
    ux, uy, uz = cx - along * ax, cy - along * ay, cz - along * az
    norm = math.sqrt(ux * ux + uy * uy + uz * uz)
    if not norm > 1e-300:
        # Antiparallel: the axis e_i × a, e_i the coordinate axis least aligned with a (scipy's choice).
        if abs(ax) <= abs(ay) and abs(ax) <= abs(az):
            ux, uy, uz = 0.0, -az, ay
        elif abs(ay) <= abs(az):
            ux, uy, uz = az, 0.0, -ax
        else:
            ux, uy, uz = -ay, ax, 0.0
        norm = math.sqrt(ux * ux + uy * uy + uz * uz)
    ux, uy, uz = ux / norm, uy / norm, uz / norm
    ub = 2.0 * (ux * bx + uy * by + uz * bz)
    tx, ty, tz = ub * ux - bx, ub * uy - by, ub * uz - bz
    s0, s1, s2, s3 = kernels.quat_unit(
        1.0 + ax * tx + ay * ty + az * tz, ty * az - tz * ay, tz * ax - tx * az, tx * ay - ty * ax
    )
    return kernels.quat_product(s0, s1, s2, s3, 0.0, ux, uy, uz)


@cached
def _power_of_two(m: float) -> float:
    """The largest power of two at most ``m`` (1.0 for 0): dividing by it is exact, so no bit is lost."""
    if m == 0.0:
        return 1.0
    return math.ldexp(1.0, math.frexp(m)[1] - 1)


@cached
def _vector_scale(x: NDArray[np.float64], i: int) -> float:
    """Scale of the vectors of problem ``i``: a power of two within a factor 2 of their largest |component|."""
    m = 0.0
    for j in range(x.shape[1]):
        for r in range(3):
            m = max(m, abs(x[i, j, r]))
    return _power_of_two(m)


@cached
def _weight_scale(w: NDArray[np.float64], i: int) -> float:
    """Scale of the finite weights of problem ``i``: a power of two within a factor 2 of the largest."""
    m = 0.0
    for j in range(w.shape[1]):
        if w[i, j] != np.inf:
            m = max(m, w[i, j])
    return _power_of_two(m)


@cached
def _solve(a: NDArray[np.float64], b: NDArray[np.float64], w: NDArray[np.float64], i: int, primary: int, out: NDArray[np.float64]) -> None:
    """Problem ``i`` of the batch into ``out[i]``; ``primary`` is the index of the infinite weight or -1.

    The vectors and the finite weights enter divided by powers of two near their largest |entry|
    (``sa``, ``sb``, ``sw``):
    the rotation does not depend on these scales, the rssd and the sensitivity carry them as
    factors applied last, so no product of huge or tiny inputs over- or underflows.
    """
    n = a.shape[1]
    sa, sb, sw = _vector_scale(a, i), _vector_scale(b, i), _weight_scale(w, i)
    if primary < 0:
        B = _profile(a, b, w, i, sa, sb, sw)
        tr = B[0, 0] + B[1, 1] + B[2, 2]
        K = np.empty((4, 4))
        K[0, 0] = tr
        K[0, 1] = K[1, 0] = B[2, 1] - B[1, 2]
        K[0, 2] = K[2, 0] = B[0, 2] - B[2, 0]
        K[0, 3] = K[3, 0] = B[1, 0] - B[0, 1]
        for r in range(3):
            for c in range(3):
                K[r + 1, c + 1] = B[r, c] + B[c, r]
            K[r + 1, r + 1] -= tr
        q0, q1, q2, q3 = _jacobi_top_eigenvector(K)
    else:
        ax, ay, az = a[i, primary, 0], a[i, primary, 1], a[i, primary, 2]
        bx, by, bz = b[i, primary, 0], b[i, primary, 1], b[i, primary, 2]
        na = kernels.norm3(ax, ay, az)
        nb = kernels.norm3(bx, by, bz)
        ax, ay, az, bx, by, bz = ax / na, ay / na, az / na, bx / nb, by / nb, bz / nb
        p0, p1, p2, p3 = _shortest_arc(ax, ay, az, bx, by, bz)
        # Then the turn φ about a that best aligns the secondary vectors
        # c = R_p b with a in the plane normal to a.
        sin_sum = 0.0
        cos_sum = 0.0
        for j in range(n):
            if j == primary:
                continue
            cx, cy, cz = kernels.rotated(p0, p1, p2, p3, b[i, j, 0] / sb, b[i, j, 1] / sb, b[i, j, 2] / sb)
            ex, ey, ez = a[i, j, 0] / sa, a[i, j, 1] / sa, a[i, j, 2] / sa
            wj = w[i, j] / sw
            sin_sum += wj * ((cy * ez - cz * ey) * ax + (cz * ex - cx * ez) * ay + (cx * ey - cy * ex) * az)
            cos_sum += wj * (cx * ex + cy * ey + cz * ez - (cx * ax + cy * ay + cz * az) * (ex * ax + ey * ay + ez * az))
        half = 0.5 * math.atan2(sin_sum, cos_sum)
        s = math.sin(half)
        q0, q1, q2, q3 = kernels.quat_product(math.cos(half), s * ax, s * ay, s * az, p0, p1, p2, p3)
        if q0 < 0.0:
            q0, q1, q2, q3 = -q0, -q1, -q2, -q3
    # The rssd straight from the residuals: the textbook Σ w(|a|² + |b|²) - 2 λ_max
    # loses every digit of a good fit to cancellation. Residuals are summed in units of the
    # larger vector scale.
    scale = max(sa, sb)
    ssd = 0.0
    for j in range(n):
        if j == primary and (n > 1 or w[i, j] == np.inf):
            continue
        x, y, z = kernels.rotated(q0, q1, q2, q3, b[i, j, 0] / scale, b[i, j, 1] / scale, b[i, j, 2] / scale)
        dx, dy, dz = a[i, j, 0] / scale - x, a[i, j, 1] / scale - y, a[i, j, 2] / scale - z
        ssd += w[i, j] / sw * (dx * dx + dy * dy + dz * dz)
    out[i, 0], out[i, 1], out[i, 2], out[i, 3] = q0, q1, q2, q3
    out[i, 4] = math.sqrt(ssd) * math.sqrt(sw) * scale
    if primary < 0:
        _sensitivity(_profile(a, b, w, i, sa, sb, sw), w, i, q0, q1, q2, q3, sa, sb, sw, out)


@cached
def _profile(a: NDArray[np.float64], b: NDArray[np.float64], w: NDArray[np.float64], i: int, sa: float, sb: float, sw: float) -> NDArray[np.float64]:
    """The attitude profile matrix ``B = Σ w a bᵀ`` of problem ``i`` divided by ``sa sb sw``."""
    B = np.zeros((3, 3))
    for j in range(a.shape[1]):
        wj = w[i, j] / sw
        a0, a1, a2 = a[i, j, 0] / sa, a[i, j, 1] / sa, a[i, j, 2] / sa
        b0, b1, b2 = b[i, j, 0] / sb, b[i, j, 1] / sb, b[i, j, 2] / sb
        for r, ar in enumerate((a0, a1, a2)):
            B[r, 0] += wj * ar * b0
            B[r, 1] += wj * ar * b1
            B[r, 2] += wj * ar * b2
    return B


@cached
def _sensitivity(B: NDArray[np.float64], w: NDArray[np.float64], i: int, q0: float, q1: float, q2: float, q3: float, sa: float, sb: float,
                 sw: float, out: NDArray[np.float64]) -> None:
    # M = Rᵀ B is symmetric with eigenvalues s₁, s₂, s₃' (the corrected singular
    # values); κ and ζ are its elementary symmetric functions. B is the profile
    # matrix divided by sa sb sw (:func:`_profile`): S does not change when the
    # weights are scaled and is inversely proportional to sa and sb.
    n = w.shape[1]
    wsum = 0.0
    for j in range(n):
        wsum += w[i, j] / sw
    R = kernels.quat_matrix(q0, q1, q2, q3)
    M = np.empty((3, 3))
    for r in range(3):
        for c in range(3):
            M[r, c] = R[r] * B[0, c] + R[3 + r] * B[1, c] + R[6 + r] * B[2, c]
    sigma1 = M[0, 0] + M[1, 1] + M[2, 2]
    kappa = M[0, 0] * M[1, 1] - M[0, 1] * M[1, 0] + M[0, 0] * M[2, 2] - M[0, 2] * M[2, 0] + M[1, 1] * M[2, 2] - M[1, 2] * M[2, 1]
    det = (
        B[0, 0] * (B[1, 1] * B[2, 2] - B[1, 2] * B[2, 1])
        - B[0, 1] * (B[1, 0] * B[2, 2] - B[1, 2] * B[2, 0])
        + B[0, 2] * (B[1, 0] * B[2, 1] - B[1, 1] * B[2, 0])
    )
    zeta = sigma1 * kappa - det
    # ζ = 0: the vectors are all parallel and leave the turn about them undetermined (NaN, refused)
    scale = wsum / n / zeta if zeta != 0.0 else math.nan
    for r in range(3):
        for c in range(3):
            bbt = B[r, 0] * B[c, 0] + B[r, 1] * B[c, 1] + B[r, 2] * B[c, 2]
            out[i, 5 + 3 * r + c] = scale * ((kappa if r == c else 0.0) + bbt) / sa / sb


@cached
def _solve_range(a: NDArray[np.float64], b: NDArray[np.float64], w: NDArray[np.float64], primary: NDArray[np.int64],
                 out: NDArray[np.float64], start: int, stop: int) -> None:
    for i in range(start, stop):
        _solve(a, b, w, i, primary[i], out)


@parallel
def _solve_pieces(a: NDArray[np.float64], b: NDArray[np.float64], w: NDArray[np.float64], primary: NDArray[np.int64],
                  out: NDArray[np.float64], piece: int) -> None:
    # the problems in pieces of about PIECE vectors, on all cores
    m = a.shape[0]
    for c in prange((m + piece - 1) // piece):
        _solve_range(a, b, w, primary, out, c * piece, min(m, (c + 1) * piece))


def _problems(a: ArrayLike, b: ArrayLike,
              weights: ArrayLike | None) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], tuple[int, ...]]:
    """Validated, broadcast ``(m, n, 3)``, ``(m, n, 3)``, ``(m, n)`` arrays and the batch shape."""
    a = as_float_array(a, "a", (3,))
    b = as_float_array(b, "b", (3,))
    if a.shape != b.shape:
        raise ValueError(f"a and b must have the same shape (..., n, 3) or (3,), got {a.shape} and {b.shape}")
    if a.ndim == 1:
        a, b = a[None], b[None]
    if a.shape[-2] == 0:
        raise ValueError(f"a and b must hold at least one vector, got shape {a.shape}")
    if weights is None:
        w = np.ones(a.shape[:-1])
    else:
        w = as_float_array(weights, "weights", finite=False)
        if w.ndim == 0 or np.isnan(w).any() or (w < 0).any():
            raise ValueError("weights must be an array (..., n) of non-negative numbers (at most one inf per problem)")
        try:
            w = np.broadcast_to(w, a.shape[:-1])
        except ValueError:
            raise ValueError(f"weights must have shape (..., n) = {a.shape[:-1]} (one per vector), got {w.shape}") from None
    batch, n = a.shape[:-2], a.shape[-2]
    m = int(np.prod(batch))

    def flat(x: NDArray[np.float64], tail: tuple[int, ...]) -> NDArray[np.float64]:
        return np.ascontiguousarray(x).reshape(m, n, *tail)

    return flat(a, (3,)), flat(b, (3,)), flat(w, ()), batch


def align_vectors(a: ArrayLike, b: ArrayLike, weights: ArrayLike | None = None,
                  return_sensitivity: bool = False) -> tuple[NDArray[np.float64], ...]:
    """Rotations ``R`` with ``a ≈ R b`` (Wahba's problem), for one or many sets of vectors.

    Solves scipy's ``Rotation.align_vectors`` problem (same loss, same special
    cases, same outputs) but for a whole batch of independent problems in
    compiled code: Davenport's q-method for finite weights, the shortest
    arc plus the best turn about it when one weight is infinite or a single
    vector pair is given (see the module notes, which also cover TRIAD).

    Parameters
    ----------
    a : array_like, shape (..., n, 3) or (3,)
        Vectors in frame A (e.g. reference directions in space).
    b : array_like, same shape as ``a``
        The same vectors observed in frame B (e.g. measured in the body).
    weights : array_like, shape (..., n), optional
        Non-negative weights (default 1), broadcast against the batch; at most
        one ``inf`` per problem, whose pair is then matched exactly.
    return_sensitivity : bool
        Also return the sensitivity matrix (refused for problems with an
        infinite weight or a single vector pair, where it has no meaning).

    Returns
    -------
    quat : ndarray, shape (..., 4)
        Unit quaternions of ``R`` (scalar first, q0 >= 0).
    rssd : ndarray, shape (...)
        ``sqrt(Σ w |a - R b|²)`` over the finite-weight pairs.
    sensitivity : ndarray, shape (..., 3, 3)
        Only with ``return_sensitivity=True``.

    Examples
    --------
    Two directions measured in the body (a sun and a magnetic-field direction)
    fix the attitude; 100 such problems are solved at once:

    >>> import numpy as np
    >>> from kreisel import quat_apply, quat_to_matrix
    >>> rng = np.random.default_rng(0)
    >>> q_true = rng.normal(size=(100, 4))
    >>> space = rng.normal(size=(100, 2, 3))
    >>> body = quat_apply(q_true[:, None, :], space, inverse=True)
    >>> q, rssd = align_vectors(space, body)
    >>> q.shape, bool(rssd.max() < 1e-13)
    ((100, 4), True)
    >>> bool(np.allclose(quat_to_matrix(q), quat_to_matrix(q_true)))
    True
    """
    a, b, w, batch = _problems(a, b, weights)
    n = a.shape[1]
    infinite = np.isinf(w)
    count = infinite.sum(axis=-1)
    if (count > 1).any():
        raise ValueError("weights may hold at most one inf per problem (the primary vector)")
    primary = np.where(count == 1, np.argmax(infinite, axis=-1), 0 if n == 1 else -1).astype(np.int64)
    if return_sensitivity and (primary >= 0).any():
        raise ValueError("the sensitivity matrix is undefined with an infinite weight or a single vector pair")
    if (primary >= 0).any():
        rows = np.flatnonzero(primary >= 0)
        pa = np.max(np.abs(a[rows, primary[rows]]), axis=-1)
        pb = np.max(np.abs(b[rows, primary[rows]]), axis=-1)
        if not (pa > 0).all() or not (pb > 0).all():
            raise ValueError("a and b must not have zero-length primary vectors (infinite weight or single pair)")
    out = np.full((a.shape[0], _WIDTH), np.nan)
    if a.shape[0] * n >= PARALLEL_THRESHOLD:
        _solve_pieces(a, b, w, primary, out, max(1, PIECE // n))
    else:
        _solve_range(a, b, w, primary, out, 0, a.shape[0])
    if return_sensitivity and np.isnan(out[:, 5]).any():
        raise ValueError("a and b do not determine the rotation (the vectors of a problem are all parallel): "
                         "its sensitivity matrix is undefined")
    if not np.isfinite(out[:, 4] if not return_sensitivity else out).all():
        raise ValueError("a and b are out of range: the rssd or the sensitivity of vectors this far from "
                         "unit size exceeds the largest float (~1.8e308)")
    out = out.reshape(*batch, _WIDTH)
    quat, rssd = out[..., :4], out[..., 4]
    if return_sensitivity:
        return quat, rssd, out[..., 5:].reshape(*batch, 3, 3)
    return quat, rssd
