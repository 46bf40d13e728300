"""Compiled exact solution of the free top, one body per call, batches in one parallel loop.

Theory §5.3 in the form that keeps every digit next to the separatrix:

- the body is taken to its sorted right-handed principal frame I1 < I2 < I3
  (a permutation, with the third axis flipped for an odd one);
- ω is scaled by its largest component and J² − 2TI1, 2TI3 − J² are formed
  as sums of squares from ω directly, J² − 2TI2 as a difference of squares in
  double-double, so that the parameter m, its complement m1 and k′ = √m1 are
  those of the given ω0 to full relative accuracy (k′ even where m1
  underflows), and the separatrix is recognised exactly;
- the elliptic phase is carried as u = nK + r with |r| <= K/2, the initial
  one from the signs and sizes of ω0 (never through sign(0)), so ω(0) = ω0 to
  rounding and sn, cn, dn keep their relative accuracy next to u = ±K;
- the precession angle is Π(am u, −ñ | m) on the same split phase.

Case codes are plain integers so that the kernels can return them; the
Python layer names them (:class:`kreisel.tops.euler_top.Regime`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray
from numba import prange

from .._compiled import cached
from .._compiled import parallel
from .._compiled.kernels import matrix_entries_quat, quat_product, rotated, rotvec_quat
from ._elliptic import (
    amplitude_split,
    complete_k,
    complete_pi,
    jacobi_near,
    phase_from_sn_cn,
    pi_separatrix,
    pi_split,
    quarter_shift,
    split_phase,
)


STEADY, SYMMETRIC, ABOUT_LARGEST_AXIS, ABOUT_SMALLEST_AXIS, SEPARATRIX = 0, 1, 2, 3, 4
#: Entries of the per-body ``info`` row written by :func:`setup_info`.
INFO_FIELDS = ("regime", "m1", "k_prime", "quarter_period", "rate", "separatrix_distance", "period", "phase0")
_EPS = 2.0**-53


@cached
def _sort_axes(a, b, c):
    """Indices of the moments in ascending (stable) order and the sign of the third sorted axis."""
    i0, i1, i2 = 0, 1, 2
    v = (a, b, c)
    if v[i1] < v[i0]:
        i0, i1 = i1, i0
    if v[i2] < v[i1]:
        i1, i2 = i2, i1
        if v[i1] < v[i0]:
            i0, i1 = i1, i0
    # the permutation is even exactly when it is cyclic
    return i0, i1, i2, 1.0 if i1 == (i0 + 1) % 3 else -1.0


@cached
def _permutation_quat(i0, i1, i2, flip):
    """Unit quaternion of P with P[i_k, k] = 1 (column 2 times ``flip``): ω_user = P ω_sorted."""
    p = np.zeros((3, 3))
    p[i0, 0] = 1.0
    p[i1, 1] = 1.0
    p[i2, 2] = flip
    return matrix_entries_quat(p[0, 0], p[0, 1], p[0, 2], p[1, 0], p[1, 1], p[1, 2], p[2, 0], p[2, 1], p[2, 2])


@cached
def _binary_scale(x):
    """The power of two nearest above |x| (x != 0): dividing by it is exact."""
    return math.ldexp(1.0, math.frexp(x)[1])


@cached
def _two_product(a: float, b: float) -> tuple[float, float]:
    """a·b = p + e exactly (Dekker, Veltkamp splitting; no fused multiply–add needed)."""
    p = a * b
    c = 134217729.0 * a
    ah = c - (c - a)
    al = a - ah
    c = 134217729.0 * b
    bh = c - (c - b)
    bl = b - bh
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


@cached
def _dd_times(hi, lo, b):
    """(hi + lo)·b as an unevaluated sum, to about 2^-104 relative."""
    p, e = _two_product(hi, b)
    e += lo * b
    s = p + e
    return s, e - (s - p)


@cached
def _dd_axis_term(Ia, Ib, Ic, v):
    """Ia (Ib − Ic) v² in double-double (Ib − Ic by an exact two-difference)."""
    d = Ib - Ic
    bb = d - Ib
    err = (Ib - (d - bb)) + (-Ic - bb)
    hi, lo = _dd_times(d, err, Ia)
    hi, lo = _dd_times(hi, lo, v)
    return _dd_times(hi, lo, v)


@cached
def _middle_difference(I1, I2, I3, v1, v3):
    """J² − 2T I2 = I3(I3 − I2)v3² − I1(I2 − I1)v1² to full relative accuracy, as (s², D) with value s² D.

    The two squares cancel next to the separatrix, so each is carried in
    double-double; the pair (v1, v3) is scaled by a power of two near its largest entry so that
    neither the sign nor √|value| = s √|D| is lost to underflow when ω1, ω3
    are tiny. D = 0 only for a state exactly on the separatrix.
    """
    s = _binary_scale(max(abs(v1), abs(v3)))
    a3, e3 = _dd_axis_term(I3, I3, I2, v3 / s)
    a1, e1 = _dd_axis_term(I1, I2, I1, v1 / s)
    return s, (a3 - a1) + (e3 - e1)


@cached
def _asymmetric(I1, I2, I3, w1, w2, w3):
    """Constants of the elliptic solution in the sorted frame (ω not along an axis).

    Returns (regime, Ac, A2, Ad, lam, m1, kc, K, sc, s2, sd, n0, r0, nu, pic, momentum, swap, distance):
    ω_c = sc·Ac·cn, ω2 = s2·A2·sn, ω_d = sd·Ad·dn with (c, d) = (1, 3) about the
    largest axis and on the separatrix, (3, 1) about the smallest (``swap``).
    """
    # a power of two, so that the scaled components are exactly those of ω0
    scale = _binary_scale(max(abs(w1), abs(w2), abs(w3)))
    v1, v2, v3 = w1 / scale, w2 / scale, w3 / scale
    # √(J² − 2TI1), √(2TI3 − J²) as hypotenuses; J² − 2TI2 = p3² − p1² factored
    h1 = math.hypot(math.sqrt(I2 * (I2 - I1)) * v2, math.sqrt(I3 * (I3 - I1)) * v3)
    h3 = math.hypot(math.sqrt(I1 * (I3 - I1)) * v1, math.sqrt(I2 * (I3 - I2)) * v2)
    pair, d2 = _middle_difference(I1, I2, I3, v1, v3)
    root_d2 = pair * math.sqrt(abs(d2))
    momentum = scale * math.sqrt((I1 * v1) ** 2 + (I2 * v2) ** 2 + (I3 * v3) ** 2)
    two_t_i2 = I2 * (I1 * v1 * v1 + I2 * v2 * v2 + I3 * v3 * v3)
    distance = pair * pair * d2 / two_t_i2
    a1 = scale * h3 / math.sqrt(I1 * (I3 - I1))
    a3 = scale * h1 / math.sqrt(I3 * (I3 - I1))
    if d2 >= 0.0:
        # about the largest axis (and the separatrix, d2 == 0): c = 1, d = 3
        regime = ABOUT_LARGEST_AXIS if d2 > 0.0 else SEPARATRIX
        a2 = scale * h3 / math.sqrt(I2 * (I3 - I2))
        lam = scale * h1 * math.sqrt((I3 - I2) / (I1 * I2 * I3))
        kc = math.sqrt((I3 - I1) / (I3 - I2)) * root_d2 / h1
        ntilde = I3 * (I2 - I1) / (I1 * (I3 - I2))
        ac, ad, wc, wd, swap = a1, a3, w1, w3, False
    else:
        regime = ABOUT_SMALLEST_AXIS
        a2 = scale * h1 / math.sqrt(I2 * (I2 - I1))
        lam = scale * h3 * math.sqrt((I2 - I1) / (I1 * I2 * I3))
        kc = math.sqrt((I3 - I1) / (I2 - I1)) * root_d2 / h3
        ntilde = I3 / I1 * (h1 / h3) ** 2
        ac, ad, wc, wd, swap = a3, a1, w3, w1, True
    m1 = kc * kc
    nu = -ntilde
    sn0 = w2 / a2
    if regime == SEPARATRIX:
        # both ω1, ω3 are nonzero here (equal nonzero squares): their signs choose the branch
        sc, sd = math.copysign(1.0, wc), math.copysign(1.0, wd)
        s2 = sc * sd
        r0 = math.asinh(s2 * sn0 / (abs(wc) / ac))
        return (regime, ac, a2, ad, lam, 0.0, 0.0, math.inf, sc, s2, sd, 0, r0, nu, math.inf, momentum, swap,
                distance)
    # the d component is nonzero off the separatrix (dn > 0): its sign is the branch
    s = math.copysign(1.0, wd)
    k = complete_k(m1, kc)
    n0, r0 = phase_from_sn_cn(sn0, s * wc / ac, m1, kc)
    pic = complete_pi(nu, 1.0 + ntilde, m1, kc)
    return regime, ac, a2, ad, lam, m1, kc, k, s, 1.0, s, n0, r0, nu, pic, momentum, swap, distance


@cached
def _phase_functions(x, regime, m1, kc, k, n0):
    """Split phase (n, r), sn, cn, dn of u = n0 K + x and of r at the phase x = r0 + λt."""
    if regime == SEPARATRIX:
        sech = 1.0 / math.cosh(x)
        th = math.tanh(x)
        return 0, x, th, sech, sech, th, sech, sech
    j, r = split_phase(x, k)
    sr, cr, dr = jacobi_near(r, m1, kc)
    sn, cn, dn = quarter_shift(n0 + j, sr, cr, dr, kc)
    return n0 + j, r, sn, cn, dn, sr, cr, dr


@cached
def _model_quat(I1, I2, I3, o1, o2, o3, phi, psi_parity):
    """Rz(φ) Rx(θ) Rz(ψ) with cos θ = I3ω3/J, ψ = atan2(I1ω1, I2ω2) (+2π for odd parity)."""
    half_theta = 0.5 * math.atan2(math.hypot(I1 * o1, I2 * o2), I3 * o3)
    psi = math.atan2(I1 * o1, I2 * o2) + 2.0 * math.pi * psi_parity
    ch, sh = math.cos(half_theta), math.sin(half_theta)
    hs, hd = 0.5 * (phi + psi), 0.5 * (phi - psi)
    return ch * math.cos(hs), sh * math.cos(hd), sh * math.sin(hd), ch * math.sin(hs)


@cached
def _psi_parity(regime, I1, I2, ac, a2, sc, o1, o2, alpha, sn, cn):
    """Parity of the winding of ψ about the largest axis (the quaternion has period 4π in ψ)."""
    if regime != ABOUT_LARGEST_AXIS:
        return 0.0
    a, b = I1 * ac, I2 * a2
    # continuous atan2(b sin α, a cos α): α plus a bounded correction
    xi = alpha + math.atan2((b - a) * sn * cn, a * cn * cn + b * sn * sn)
    psi = math.atan2(I1 * o1, I2 * o2)
    winding = math.floor((sc * (0.5 * math.pi - xi) - psi) / (2.0 * math.pi) + 0.5)
    return winding % 2.0


@cached
def _asymmetric_samples(I1, I2, I3, w1, w2, w3, q0, q1, q2, q3, t, omega, quat, permute):
    """Samples in the sorted frame; ``permute`` = (i0, i1, i2, flip, qp0..qp3) maps them back."""
    (regime, ac, a2, ad, lam, m1, kc, k, sc, s2, sd, n0, r0, nu, pic, momentum, swap,
     _) = _asymmetric(I1, I2, I3, w1, w2, w3)
    one_minus_nu = 1.0 - nu
    precession_scale = momentum * (I3 - I1) / (I1 * I3 * lam)
    i0, i1, i2, flip = int(permute[0]), int(permute[1]), int(permute[2]), permute[3]
    qp0, qp1, qp2, qp3 = permute[4], permute[5], permute[6], permute[7]
    # sorted-frame attitude at t = 0: R_sorted = R_user P
    c0, c1, c2, c3 = quat_product(q0, q1, q2, q3, qp0, qp1, qp2, qp3)
    pi0 = 0.0
    for i in range(-1, t.size):
        x = r0 if i < 0 else r0 + lam * t[i]
        n, r, sn, cn, dn, sr, cr, _ = _phase_functions(x, regime, m1, kc, k, n0)
        if regime == SEPARATRIX:
            pi = pi_separatrix(r, nu, one_minus_nu)
            alpha = 0.0
        else:
            pi = pi_split(n, r, sr, cr, m1, kc, nu, one_minus_nu, pic)
            alpha = amplitude_split(n, sr, cr, kc)
        if i < 0:
            # the initial state itself (not its rounded elliptic image) fixes the constant rotation
            o1, o2, o3 = w1, w2, w3
            pi0 = pi
            phi = 0.0
        else:
            oc, o2, od = sc * ac * cn, s2 * a2 * sn, sd * ad * dn
            o1, o3 = (od, oc) if swap else (oc, od)
            # the quaternion has period 4π in φ: reducing keeps (φ ± ψ)/2 exact to rounding
            phi = momentum * t[i] / I3 + precession_scale * (pi - pi0)
            phi -= 4.0 * math.pi * math.floor(phi / (4.0 * math.pi) + 0.5)
        parity = _psi_parity(regime, I1, I2, ac, a2, sc, o1, o2, alpha, sn, cn)
        m0, m1_, m2, m3 = _model_quat(I1, I2, I3, o1, o2, o3, phi, parity)
        if i < 0:
            # C = q0_sorted ⊗ conj(q_model(0))
            c0, c1, c2, c3 = quat_product(c0, c1, c2, c3, m0, -m1_, -m2, -m3)
            continue
        s0, s1, s2_, s3 = quat_product(c0, c1, c2, c3, m0, m1_, m2, m3)
        # back to the user's axes: q_user = q_sorted ⊗ conj(qP), ω_user[i_k] = ±ω_sorted[k]
        quat[i, 0], quat[i, 1], quat[i, 2], quat[i, 3] = quat_product(s0, s1, s2_, s3, qp0, -qp1, -qp2, -qp3)
        omega[i, i0] = o1
        omega[i, i1] = o2
        omega[i, i2] = flip * o3


@cached
def _asymmetric_omega(I1, I2, I3, w1, w2, w3, t, omega, permute):
    """ω alone (no integral of the third kind) in the sorted frame, mapped back by ``permute``."""
    (regime, ac, a2, ad, lam, m1, kc, k, sc, s2, sd, n0, r0, _, _, _, swap,
     _) = _asymmetric(I1, I2, I3, w1, w2, w3)
    i0, i1, i2, flip = int(permute[0]), int(permute[1]), int(permute[2]), permute[3]
    for i in range(t.size):
        sn, cn, dn = _phase_functions(r0 + lam * t[i], regime, m1, kc, k, n0)[2:5]
        oc, o2, od = sc * ac * cn, s2 * a2 * sn, sd * ad * dn
        o1, o3 = (od, oc) if swap else (oc, od)
        omega[i, i0] = o1
        omega[i, i1] = o2
        omega[i, i2] = flip * o3


@cached
def _symmetric_samples(moments, axis, perpendicular, w, q0, t, omega, quat):
    """Regular precession R(t) = exp(t J/I⊥·X) R0 exp(t c e_k·X), c = ω_k(1 − I_k/I⊥) (Theory §5.7)."""
    c = w[axis] * (1.0 - moments[axis] / perpendicular)
    j0, j1, j2 = moments[0] * w[0], moments[1] * w[1], moments[2] * w[2]
    js0, js1, js2 = rotated(q0[0], q0[1], q0[2], q0[3], j0, j1, j2)
    e = np.zeros(3)
    for i in range(t.size):
        e[:] = 0.0
        e[axis] = t[i] * c
        b0, b1, b2, b3 = rotvec_quat(e[0], e[1], e[2])
        s0, s1, s2, s3 = rotvec_quat(t[i] * js0 / perpendicular, t[i] * js1 / perpendicular, t[i] * js2 / perpendicular)
        p0, p1, p2, p3 = quat_product(s0, s1, s2, s3, q0[0], q0[1], q0[2], q0[3])
        quat[i, 0], quat[i, 1], quat[i, 2], quat[i, 3] = quat_product(p0, p1, p2, p3, b0, b1, b2, b3)
        o0, o1, o2 = rotated(b0, -b1, -b2, -b3, j0, j1, j2)
        omega[i, 0], omega[i, 1], omega[i, 2] = o0 / moments[0], o1 / moments[1], o2 / moments[2]


@cached
def _steady_samples(w, q0, t, omega, quat):
    """Rotation at constant body ω: q(t) = q0 ⊗ exp(t ω)."""
    for i in range(t.size):
        e0, e1, e2, e3 = rotvec_quat(t[i] * w[0], t[i] * w[1], t[i] * w[2])
        quat[i, 0], quat[i, 1], quat[i, 2], quat[i, 3] = quat_product(q0[0], q0[1], q0[2], q0[3], e0, e1, e2, e3)
        omega[i, 0], omega[i, 1], omega[i, 2] = w[0], w[1], w[2]


@cached
def _classify(moments, w):
    """(regime, symmetric axis, perpendicular moment, i0, i1, i2, flip, sorted ω) of one body."""
    i0, i1, i2, flip = _sort_axes(moments[0], moments[1], moments[2])
    lo, mid, hi = moments[i0], moments[i1], moments[i2]
    v1, v2, v3 = w[i0], w[i1], flip * w[i2]
    nonzero = int(w[0] != 0.0) + int(w[1] != 0.0) + int(w[2] != 0.0)
    if lo == hi or nonzero == 0:
        return STEADY, -1, 0.0, i0, i1, i2, flip, v1, v2, v3
    if lo == mid or mid == hi:
        axis = i2 if lo == mid else i0
        return SYMMETRIC, axis, mid, i0, i1, i2, flip, v1, v2, v3
    if nonzero == 1:
        return STEADY, -1, 0.0, i0, i1, i2, flip, v1, v2, v3
    regime = _asymmetric(lo, mid, hi, v1, v2, v3)[0]
    return regime, -1, 0.0, i0, i1, i2, flip, v1, v2, v3


@cached
def steady_body(moments: NDArray[np.float64], w: NDArray[np.float64], q: NDArray[np.float64], t: NDArray[np.float64],
                omega: NDArray[np.float64], quat: NDArray[np.float64]) -> None:
    """:func:`body_samples` of a body in the regime :data:`STEADY`."""
    _steady_samples(w, q, t, omega, quat)


@cached
def symmetric_body(moments: NDArray[np.float64], w: NDArray[np.float64], q: NDArray[np.float64], t: NDArray[np.float64],
                   omega: NDArray[np.float64], quat: NDArray[np.float64]) -> None:
    """:func:`body_samples` of a body in the regime :data:`SYMMETRIC`."""
    _, axis, perpendicular = _classify(moments, w)[:3]
    _symmetric_samples(moments, axis, perpendicular, w, q, t, omega, quat)


@cached
def asymmetric_body(moments: NDArray[np.float64], w: NDArray[np.float64], q: NDArray[np.float64], t: NDArray[np.float64],
                    omega: NDArray[np.float64], quat: NDArray[np.float64]) -> None:
    """:func:`body_samples` of a body in one of the elliptic regimes (about an axis, the separatrix)."""
    _, _, _, i0, i1, i2, flip, v1, v2, v3 = _classify(moments, w)
    qp0, qp1, qp2, qp3 = _permutation_quat(i0, i1, i2, flip)
    permute = np.array([i0, i1, i2, flip, qp0, qp1, qp2, qp3], dtype=np.float64)
    _asymmetric_samples(moments[i0], moments[i1], moments[i2], v1, v2, v3, q[0], q[1], q[2], q[3], t, omega,
                        quat, permute)


@cached
def body_samples(moments: NDArray[np.float64], w: NDArray[np.float64], q: NDArray[np.float64], t: NDArray[np.float64], omega: NDArray[np.float64],
                 quat: NDArray[np.float64]) -> None:
    """Exact ω (n, 3) and q (n, 4) of one body at times t, written into ``omega``, ``quat``.

    It holds the code of every regime; a caller that knows the regime (from
    :func:`setup_info`) calls that regime's function (:func:`body_in_regime`)
    and compiles that one only.
    """
    regime = _classify(moments, w)[0]
    if regime == STEADY:
        steady_body(moments, w, q, t, omega, quat)
    elif regime == SYMMETRIC:
        symmetric_body(moments, w, q, t, omega, quat)
    else:
        asymmetric_body(moments, w, q, t, omega, quat)


def body_in_regime(regime: int) -> Any:
    """The compiled :func:`body_samples` of a body in ``regime`` (a case code), with its arguments.

    Examples
    --------
    >>> body_in_regime(STEADY) is steady_body, body_in_regime(SEPARATRIX) is asymmetric_body
    (True, True)
    """
    return steady_body if regime == STEADY else symmetric_body if regime == SYMMETRIC else asymmetric_body


@cached
def body_omega(moments: NDArray[np.float64], w: NDArray[np.float64], t: NDArray[np.float64], omega: NDArray[np.float64]) -> None:
    """Exact ω (n, 3) of one body at times t (the attitude is not computed)."""
    regime, axis, perpendicular, i0, i1, i2, flip, v1, v2, v3 = _classify(moments, w)
    if regime == STEADY or regime == SYMMETRIC:
        quat = np.empty((t.size, 4))
        identity = np.array([1.0, 0.0, 0.0, 0.0])
        if regime == STEADY:
            _steady_samples(w, identity, t, omega, quat)
        else:
            _symmetric_samples(moments, axis, perpendicular, w, identity, t, omega, quat)
        return
    permute = np.array([i0, i1, i2, flip], dtype=np.float64)
    _asymmetric_omega(moments[i0], moments[i1], moments[i2], v1, v2, v3, t, omega, permute)


@parallel
def batch_samples(moments: NDArray[np.float64], w: NDArray[np.float64], q: NDArray[np.float64], t: NDArray[np.float64], omega: NDArray[np.float64],
                  quat: NDArray[np.float64]) -> None:
    """:func:`body_samples` for bodies (B, 3), ω0 (B, 3), q0 (B, 4) -> (B, n, 3), (B, n, 4)."""
    for b in prange(moments.shape[0]):
        body_samples(moments[b], w[b], q[b], t, omega[b], quat[b])


@cached
def setup_info(moments: NDArray[np.float64], w: NDArray[np.float64], info: NDArray[np.float64]) -> None:
    """Per body (B rows): the :data:`INFO_FIELDS` of its motion."""
    for b in range(moments.shape[0]):
        regime, axis, perpendicular, i0, i1, i2, flip, v1, v2, v3 = _classify(moments[b], w[b])
        row = info[b]
        row[:] = 0.0
        row[0] = regime
        row[6] = math.inf
        if regime == SYMMETRIC:
            c = w[b, axis] * (1.0 - moments[b, axis] / perpendicular)
            if c != 0.0:
                row[6] = 2.0 * math.pi / abs(c)
        elif regime != STEADY:
            out = _asymmetric(moments[b, i0], moments[b, i1], moments[b, i2], v1, v2, v3)
            lam, m1, kc, k = out[4], out[5], out[6], out[7]
            row[1], row[2], row[3], row[4], row[5] = m1, kc, k, lam, out[17]
            row[6] = 4.0 * k / lam
            row[7] = out[11] * k + out[12] if regime != SEPARATRIX else out[12]
