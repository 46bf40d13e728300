"""Elliptic integrals and Jacobi functions that carry the complementary parameter m1 = 1 − m.

Near m = 1 every formula written with m loses the digits of 1 − m, and the
exact tops live there next to their separatrices (Theory §5.3, §6.3). The
compiled kernels below therefore take m1 itself (and its square root
k′ = √m1, which stays representable where m1 underflows), never m:

- Carlson's symmetric integrals R_F, R_D, R_J (duplication with the series of
  Carlson 1995), and from them K(m) = R_F(0, m1, 1),
  F(φ | m) = sin φ R_F(cos²φ, δ², 1) and
  Π(φ, n | m) = F + (n/3) sin³φ R_J(cos²φ, δ², 1, 1 − n sin²φ) with
  δ² = cos²φ + m1 sin²φ (DLMF 19.25), free of cancellation as φ → π/2.
- Jacobi sn, cn, dn on a *split phase* u = nK + r, |r| <= K/2: ascending
  Landen transformations written in k′ (DLMF 22.7.ii) down to the first-order
  expansion about the hyperbolic limit (DLMF 22.10.ii), or the
  arithmetic–geometric mean (A&S 16.4) for m < 1/2, then the quarter-period shift sn(K + r) = cd r,
  cn(K + r) = −k′ sd r, dn(K + r) = k′ nd r (DLMF 22.4.3), so that cn and dn
  keep their relative accuracy next to u = K where they are O(k′).
- Π as a function of the split phase: Π(am(nK + r)) = nΠ(n | m) + P(r) with
  P(r) = Π(am r) for even n and, for odd n, the reflected integral
  ∫₀^r dw / (1 − n cd²w) = r/(1 − n) − n m1 s³ R_J(c², δ², 1, c² + m1 s²/(1 − n)) / (3(1 − n)²),
  s = sn r, c = cn r, so the amplitude is never near π/2 where Π is ill
  conditioned.

The public functions broadcast over their arguments; parameters are given as
``m`` or, for full accuracy near m = 1, as the keyword ``m1``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from .._compiled import cached
from .._validation import as_float_array

__all__ = ["elliptic_pi", "complete_elliptic_pi", "elliptic_f", "elliptic_k", "jacobi_elliptic"]


#: Duplication stops when 4^-n Q < |A_n| (Carlson 1995, relative error below the
#: unit roundoff r = 2^-53): Q = (3r)^(-1/6) max|A0 - x| for R_F, (r/4)^(-1/6) for R_D, R_J.
_RF_FACTOR = (3.0 * 2.0**-53) ** (-1.0 / 6.0)
_RJ_FACTOR = (0.25 * 2.0**-53) ** (-1.0 / 6.0)
#: Below this m1 the hyperbolic expansion of sn, cn, dn is exact to rounding on |r| <= K/2
#: (its O(m1² e^{4r}) remainder is ~16 m1 relative there).
_HYPERBOLIC_M1 = 1e-17
#: Below this m1, K = ln(4/k′) and Π(n | m) = K/(1 − n) − n T(n)/(1 − n) to rounding (DLMF 19.12).
_LOG_M1 = 1e-30


@cached
def _rc1(t):
    """R_C(1, t) for t > 0: atan(√(t − 1))/√(t − 1), atanh(√(1 − t))/√(1 − t) (DLMF 19.2.18–19).

    ``t`` is taken as it is (not 1 + e): for t → 0 the atanh's 1 − √(1 − t) = t/(1 + √(1 − t))
    keeps the digits that forming 1 + e would lose.
    """
    if t > 1.0:
        s = math.sqrt(t - 1.0)
        return math.atan(s) / s
    if t < 1.0:
        s = math.sqrt(1.0 - t)
        return 0.5 * math.log1p(2.0 * s * (1.0 + s) / t) / s
    return 1.0


@cached
def carlson_rf(x, y, z):
    """R_F(x, y, z), x, y, z >= 0, at most one zero."""
    a0 = (x + y + z) / 3.0
    q = _RF_FACTOR * max(abs(a0 - x), abs(a0 - y), abs(a0 - z))
    a, f = a0, 1.0
    xn, yn, zn = x, y, z
    while f * q >= abs(a):
        sx, sy, sz = math.sqrt(xn), math.sqrt(yn), math.sqrt(zn)
        lam = sx * sy + sy * sz + sz * sx
        xn, yn, zn, a = 0.25 * (xn + lam), 0.25 * (yn + lam), 0.25 * (zn + lam), 0.25 * (a + lam)
        f *= 0.25
    X = (a0 - x) * f / a
    Y = (a0 - y) * f / a
    Z = -(X + Y)
    e2 = X * Y - Z * Z
    e3 = X * Y * Z
    return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0) / math.sqrt(a)


@cached
def _series_rd_rj(X, Y, Z, P):
    """The common degree-5 series of R_D and R_J (Carlson 1995, P = Z for R_D)."""
    e2 = X * Y + X * Z + Y * Z - 3.0 * P * P
    e3 = X * Y * Z + 2.0 * e2 * P + 4.0 * P * P * P
    e4 = (2.0 * X * Y * Z + e2 * P + 3.0 * P * P * P) * P
    e5 = X * Y * Z * P * P
    return (
        1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0 - 3.0 * e4 / 22.0 - 9.0 * e2 * e3 / 52.0
        + 3.0 * e5 / 26.0
    )


@cached
def carlson_rd(x: float, y: float, z: float) -> float:
    """R_D(x, y, z) = R_J(x, y, z, z), x, y >= 0 (at most one zero), z > 0."""
    a0 = (x + y + 3.0 * z) / 5.0
    q = _RJ_FACTOR * max(abs(a0 - x), abs(a0 - y), abs(a0 - z))
    a, f, total = a0, 1.0, 0.0
    xn, yn, zn = x, y, z
    while f * q >= abs(a):
        sx, sy, sz = math.sqrt(xn), math.sqrt(yn), math.sqrt(zn)
        lam = sx * sy + sy * sz + sz * sx
        total += f / (sz * (zn + lam))
        xn, yn, zn, a = 0.25 * (xn + lam), 0.25 * (yn + lam), 0.25 * (zn + lam), 0.25 * (a + lam)
        f *= 0.25
    X = (a0 - x) * f / a
    Y = (a0 - y) * f / a
    Z = -(X + Y) / 3.0
    return f * _series_rd_rj(X, Y, Z, Z) / (a * math.sqrt(a)) + 3.0 * total


@cached
def carlson_rj(x: float, y: float, z: float, p: float) -> float:
    """R_J(x, y, z, p), x, y, z >= 0 (at most one zero), p > 0."""
    a0 = (x + y + z + 2.0 * p) / 5.0
    q = _RJ_FACTOR * max(abs(a0 - x), abs(a0 - y), abs(a0 - z), abs(a0 - p))
    a, f, total = a0, 1.0, 0.0
    xn, yn, zn, pn = x, y, z, p
    while f * q >= abs(a):
        sx, sy, sz, sp = math.sqrt(xn), math.sqrt(yn), math.sqrt(zn), math.sqrt(pn)
        lam = sx * sy + sy * sz + sz * sx
        d = (sp + sx) * (sp + sy) * (sp + sz)
        # Carlson's R_C(1, 1 + e_n), e_n = (p_n − x_n)(p_n − y_n)(p_n − z_n)/d_n², whose argument
        # factors as 2√p_n (p_n + λ_n)/d_n: all terms positive, so no cancellation when e_n → −1
        # (widely spread arguments, e.g. Π(ν | m) with both 1 − ν and 1 − m small)
        total += f * _rc1(2.0 * sp * (pn + lam) / d) / d
        xn, yn, zn = 0.25 * (xn + lam), 0.25 * (yn + lam), 0.25 * (zn + lam)
        pn, a = 0.25 * (pn + lam), 0.25 * (a + lam)
        f *= 0.25
    X = (a0 - x) * f / a
    Y = (a0 - y) * f / a
    Z = (a0 - z) * f / a
    P = -0.5 * (X + Y + Z)
    return f * _series_rd_rj(X, Y, Z, P) / (a * math.sqrt(a)) + 6.0 * total


@cached
def _t_function(nu, x):
    """∫₀^x dt/(1 − ν t²): atanh(√ν x)/√ν, atan(√−ν x)/√−ν."""
    if nu > 0.0:
        s = math.sqrt(nu)
        return math.atanh(s * x) / s
    if nu < 0.0:
        s = math.sqrt(-nu)
        return math.atan(s * x) / s
    return x


@cached
def complete_k(m1: float, kc: float) -> float:
    """K(m) from m1 and k′ = √m1 (k′ also when m1 has underflowed)."""
    if m1 < _LOG_M1:
        return math.log(4.0 / kc)
    return carlson_rf(0.0, m1, 1.0)


@cached
def complete_pi(nu: float, one_minus_nu: float, m1: float, kc: float) -> float:
    """Π(ν | m), ν < 1, with 1 − ν given separately (accurate when ν is near 1)."""
    k = complete_k(m1, kc)
    # R_J is exact to a few ulp however far apart m1 and 1 − ν are (down to 1e-300, checked
    # against mpmath), so for ν >= 0 the m1 -> 0 limit serves only m1 = 0 itself (k′ underflowed);
    # for ν < 0 (1 − ν >= 1) the limit is exact to rounding below _LOG_M1, and the R_J term below
    # would overflow once m1 is subnormal (k′ below 1.5e-154), leaving inf · m1 for a finite Π
    if m1 == 0.0 or (nu < 0.0 and m1 < _LOG_M1):
        # Π(ν | m) − K/(1 − ν) → −ν/(1 − ν) ∫₀^1 ds/(1 − ν s²) as m1 → 0; for ν > 0 the integral
        # atanh(√ν)/√ν = (2 ln(1 + √ν) − ln(1 − ν))/(2√ν) keeps the digits of 1 − ν
        if nu > 0.0:
            root = math.sqrt(nu)
            integral = (2.0 * math.log1p(root) - math.log(one_minus_nu)) / (2.0 * root)
        else:
            integral = _t_function(nu, 1.0)
        return (k - nu * integral) / one_minus_nu
    if nu >= 0.0:
        return k + nu / 3.0 * carlson_rj(0.0, m1, 1.0, one_minus_nu)
    # ν < 0: the terms of positive sign only (amplitude_integral at φ = π/2, where R_C drops out)
    return (k - nu * m1 * carlson_rj(0.0, m1, 1.0, m1 / one_minus_nu) / (3.0 * one_minus_nu)) / one_minus_nu


@cached
def _rc(x, y):
    """R_C(x, y) for x > 0, y > 0 (DLMF 19.2.17, homogeneity of degree −1/2)."""
    return _rc1(y / x) / math.sqrt(x)


@cached
def amplitude_integral(s: float, c: float, m1: float, nu: float, one_minus_nu: float) -> float:
    """Π(φ, ν | m) for cos φ = c >= 0, sin φ = s (s² + c² = 1), with δ² = c² + m1 s².

    ν >= 0: F + (ν/3) s³ R_J(c², δ², 1, p), p = c² + (1 − ν) s² (DLMF 19.25.14), all terms
    positive. ν < 0 would subtract nearly equal terms as ν → −∞ (Π → 0 like 1/√(1 − ν), the top
    passing next to the lower vertical), so R_J(p) is traded for R_J(q), q = c² + m1 s²/(1 − ν),
    by (p − x) R_J(p) + (q − x) R_J(q) = 3 R_F − 3 R_C(δ²/c², pq/c²) (DLMF 19.21.12), which leaves
    (s R_F − ν s c R_C(δ², pq) − ν m1 s³ R_J(q)/(3(1 − ν))) / (1 − ν), all terms positive.
    """
    c2 = c * c
    # δ² = 1 − m s² is exact to rounding while m s² <= 1/2 (and 1 − m1 is exact there)
    d2 = c2 + m1 * s * s if m1 < 0.5 else 1.0 - (1.0 - m1) * s * s
    f = s * carlson_rf(c2, d2, 1.0)
    if nu == 0.0 or s == 0.0:
        return f
    s2 = s * s
    if nu > 0.0:
        return f + nu / 3.0 * s2 * s * carlson_rj(c2, d2, 1.0, c2 + one_minus_nu * s2)
    q = c2 + m1 * s2 / one_minus_nu
    total = f - nu * m1 * s2 * s * carlson_rj(c2, d2, 1.0, q) / (3.0 * one_minus_nu)
    if c != 0.0:
        total -= nu * s * c * _rc(d2, (c2 + one_minus_nu * s2) * q)
    return total / one_minus_nu


@cached
def _hyperbolic(r, m1, kc):
    """(sn, cn, dn)(r | m) to first order in m1 about tanh, sech (DLMF 22.10.4–6).

    m1 sinh r cosh r is written with k′e^{|r|} (<= 2√k′ for |r| <= K/2), so
    nothing overflows even where m1 itself has underflowed.
    """
    g = abs(r)
    big = kc * math.exp(g)
    small = kc * math.exp(-g)
    shcosh = math.copysign(0.25 * (big * big - small * small), r)
    mr = m1 * r
    sech = 1.0 / math.cosh(r)
    th = math.tanh(r)
    minus = 0.25 * (shcosh - mr)
    plus = 0.25 * (shcosh + mr)
    return th + minus * sech * sech, sech - minus * th * sech, sech + plus * th * sech


@cached
def _agm(r, m1, kc):
    """(sn, cn, dn)(r | m) by the arithmetic–geometric mean from 1, √m1, √m (A&S 16.4)."""
    aa = np.empty(64)
    cc = np.empty(64)
    a, b = 1.0, kc
    c = math.sqrt(1.0 - m1)
    n = 0
    while abs(c) > 2.0**-53 * a and n < 63:
        n += 1
        a, b, c = 0.5 * (a + b), math.sqrt(a * b), 0.5 * (a - b)
        aa[n] = a
        cc[n] = c
    phi = math.ldexp(a * r, n)
    for k in range(n, 0, -1):
        phi = 0.5 * (phi + math.asin(cc[k] / aa[k] * math.sin(phi)))
    sn = math.sin(phi)
    cn = math.cos(phi)
    return sn, cn, math.sqrt(cn * cn + m1 * sn * sn)


@cached
def jacobi_near(r: float, m1: float, kc: float) -> tuple[float, float, float]:
    """(sn, cn, dn)(r | m) for |r| <= K/2, each to a few ulp relative.

    m >= 1/2 goes up by ascending Landen transformations (DLMF 22.7.ii, written
    in k′: k₂′ = m1/(1 + k)², m1 -> k₂′² ~ m1²/16) until m1 < 1e-17, where the
    hyperbolic expansion is exact to rounding; going back,
    sn = (1 + k₂′) s c/d, cn = (d² − k₂′)/((1 − k₂′) d), dn = (d² + k₂′)/((1 + k₂′) d)
    lose nothing on |r| <= K/2 (there d² >= √k₂′ > k₂′). The AGM serves m < 1/2,
    where cn and dn are bounded away from zero on |r| <= K/2.
    """
    if m1 >= 0.5:
        return _agm(r, m1, kc)
    steps = np.empty(8)
    levels = 0
    w = r
    while m1 >= _HYPERBOLIC_M1:
        k2c = m1 / (1.0 + math.sqrt(1.0 - m1)) ** 2
        steps[levels] = k2c
        levels += 1
        w = w / (1.0 + k2c)
        m1, kc = k2c * k2c, k2c
    s, c, d = _hyperbolic(w, m1, kc)
    for level in range(levels - 1, -1, -1):
        k2c = steps[level]
        s, c, d = (1.0 + k2c) * s * c / d, (d * d - k2c) / ((1.0 - k2c) * d), (d * d + k2c) / ((1.0 + k2c) * d)
    return s, c, d


@cached
def quarter_shift(n: int, sn: float, cn: float, dn: float, kc: float) -> tuple[float, float, float]:
    """(sn, cn, dn) of u = nK + r from those of r (quarter-period shifts, DLMF 22.4.3)."""
    quadrant = n % 4
    if quadrant == 0:
        return sn, cn, dn
    if quadrant == 2:
        return -sn, -cn, dn
    sigma = 1.0 if quadrant == 1 else -1.0
    return sigma * cn / dn, -sigma * kc * sn / dn, kc / dn


@cached
def amplitude_split(n: int, sr: float, cr: float, kc: float) -> float:
    """am u for u = nK + r from sn, cn of r: (n/2)π + am r, or ((n − 1)/2)π + am(K + r)."""
    if n % 2 == 0:
        return 0.5 * n * math.pi + math.atan2(sr, cr)
    return 0.5 * (n - 1) * math.pi + math.atan2(cr, -kc * sr)


@cached
def split_phase(x: float, k: float) -> tuple[int, float]:
    """(n, r) with x = nK + r, |r| <= K/2."""
    n = math.floor(x / k + 0.5)
    return int(n), x - n * k


@cached
def phase_from_sn_cn(sn0: float, cn0: float, m1: float, kc: float) -> tuple[int, float]:
    """Split phase (n, r) of the u with (sn u, cn u) ∝ (sn0, cn0), sn0² + cn0² > 0.

    The amplitude is folded into (−π/2, π/2] around the nearest multiple of K:
    near u = 0 mod 2K directly, near u = ±K through tan(am r) = −cn/(k′ sn),
    so that r = F(am r) never needs an amplitude near π/2.
    """
    if cn0 * cn0 >= kc * sn0 * sn0:
        n = 0
        s, c = sn0, cn0
        if cn0 < 0.0:
            n, s, c = 2, -sn0, -cn0
    else:
        n = 1 if sn0 > 0.0 else -1
        s, c = -n * cn0, kc * abs(sn0)
    h = math.hypot(s, c)
    return n, amplitude_integral(s / h, c / h, m1, 0.0, 1.0)


@cached
def pi_split(n: int, r: float, sn: float, cn: float, m1: float, kc: float, nu: float, one_minus_nu: float,
             pi_complete: float) -> float:
    """Π(am u, ν | m) at u = nK + r, from (sn, cn) of r (not of u).

    Odd n: nΠ(ν | m) plus the reflected integral ∫₀^r dw / (1 − ν cd²w). For ν <= 0 that is
    r/(1 − ν) − ν m1 s³ R_J(c², δ², 1, q)/(3(1 − ν)²), q = c² + m1 s²/(1 − ν), all terms positive;
    for ν > 0 the two terms cancel as ν → 1 (the top passing next to the upper vertical), and
    DLMF 19.21.12 turns it into Π(am r, ν | m) + ν s c R_C(δ², pq)/(1 − ν), p = c² + (1 − ν) s²,
    again all positive.
    """
    if n % 2 == 0:
        if nu == 0.0:
            return n * pi_complete + r
        return n * pi_complete + amplitude_integral(sn, cn, m1, nu, one_minus_nu)
    if nu == 0.0 or sn == 0.0:
        return n * pi_complete + r / one_minus_nu
    c2 = cn * cn
    s2 = sn * sn
    d2 = c2 + m1 * s2
    q = c2 + m1 * s2 / one_minus_nu
    if nu > 0.0:
        reflected = amplitude_integral(sn, cn, m1, nu, one_minus_nu)
        if cn != 0.0:
            reflected += nu * sn * cn * _rc(d2, (c2 + one_minus_nu * s2) * q) / one_minus_nu
        return n * pi_complete + reflected
    # the R_J term is below √k′ relative; beyond k′ = 1e-100 its arguments would underflow
    if kc < 1e-100:
        return n * pi_complete + r / one_minus_nu
    return n * pi_complete + r / one_minus_nu - nu * m1 * s2 * sn * carlson_rj(c2, d2, 1.0, q) / (
        3.0 * one_minus_nu * one_minus_nu)


@cached
def pi_separatrix(r, nu, one_minus_nu):
    """Π(gd r, ν | 1) = r/(1 − ν) − ν T(ν, tanh r)/(1 − ν)."""
    return (r - nu * _t_function(nu, math.tanh(r))) / one_minus_nu


# ---------------------------------------------------------------------------- array wrappers


@cached
def _pi_loop(phi, nu, m1, out):
    for i in range(phi.size):
        kc = math.sqrt(m1[i])
        j = math.floor(phi[i] / math.pi + 0.5)
        p = phi[i] - j * math.pi
        s, c = math.sin(p), abs(math.cos(p))
        value = amplitude_integral(s, c, m1[i], nu[i], 1.0 - nu[i])
        if j != 0.0:
            value += 2.0 * j * complete_pi(nu[i], 1.0 - nu[i], m1[i], kc)
        out[i] = value


@cached
def _complete_pi_loop(nu, m1, out):
    for i in range(nu.size):
        out[i] = complete_pi(nu[i], 1.0 - nu[i], m1[i], math.sqrt(m1[i]))


@cached
def _jacobi_loop(u, m1, sn, cn, dn):
    for i in range(u.size):
        kc = math.sqrt(m1[i])
        if kc == 0.0:
            sn[i], cn[i], dn[i] = math.tanh(u[i]), 1.0 / math.cosh(u[i]), 1.0 / math.cosh(u[i])
            continue
        n, r = split_phase(u[i], complete_k(m1[i], kc))
        s, c, d = jacobi_near(r, m1[i], kc)
        sn[i], cn[i], dn[i] = quarter_shift(n, s, c, d, kc)


def _parameter(m, m1):
    """m1 as an array from exactly one of ``m``, ``m1``; 0 <= m1 (m <= 1)."""
    if (m is None) == (m1 is None):
        raise TypeError("give exactly one of m and m1 (= 1 - m, for full accuracy near m = 1)")
    m1 = 1.0 - as_float_array(m, "m") if m1 is None else as_float_array(m1, "m1")
    if np.any(m1 < 0.0):
        raise ValueError("m must be <= 1 (m1 = 1 - m >= 0; parameter m = k**2)")
    return m1


def _check_characteristic(n):
    n = as_float_array(n, "n")
    if np.any(n >= 1.0):
        raise ValueError("n must be < 1 (the circular case n > 1 has a pole on the path)")
    return n


def _flat(*arrays):
    shape = np.broadcast_shapes(*(a.shape for a in arrays))
    return shape, [np.ascontiguousarray(np.broadcast_to(a, shape), dtype=np.float64).ravel() for a in arrays]


def complete_elliptic_pi(n, m=None, *, m1=None):
    """Complete elliptic integral of the third kind Π(n | m) = Π(π/2, n | m).

    Parameters
    ----------
    n : array_like
        Characteristic, ``n < 1``.
    m : array_like, optional
        Parameter ``m = k**2 < 1`` (Π diverges at ``m = 1``).
    m1 : array_like, optional
        The complementary parameter 1 − m instead of ``m`` (keyword only): give
        it whenever it is known more accurately than ``1 - m``.

    Returns
    -------
    ndarray
        Π(n | m) = R_F(0, m1, 1) + (n/3) R_J(0, m1, 1, 1 − n) (DLMF 19.25.2).

    Examples
    --------
    >>> import numpy as np
    >>> from scipy import special
    >>> bool(np.isclose(complete_elliptic_pi(0.0, 0.5), special.ellipk(0.5)))
    True
    >>> limit = (np.log(4e100) + np.sqrt(0.5) * np.arctan(np.sqrt(0.5))) / 1.5   # m -> 1, DLMF 19.12
    >>> bool(np.isclose(complete_elliptic_pi(-0.5, m1=1e-200), limit, rtol=1e-15, atol=0.0))
    True
    """
    n = _check_characteristic(n)
    m1 = _parameter(m, m1)
    if np.any(m1 <= 0.0):
        raise ValueError("m must be < 1: the complete integral diverges at m = 1")
    shape, (n, m1) = _flat(n, m1)
    out = np.empty(n.size)
    _complete_pi_loop(n, m1, out)
    return out.reshape(shape)


def elliptic_pi(phi, n, m=None, *, m1=None):
    """Incomplete elliptic integral of the third kind Π(φ, n | m), any real φ.

    Π(φ, n | m) = ∫₀^φ dθ / ((1 − n sin²θ) √(1 − m sin²θ)).

    Parameters
    ----------
    phi : array_like
        Amplitude in radians (any real value; quasi-periodic extension
        Π(φ + jπ) = Π(φ) + 2jΠ(n | m) beyond ±π/2, added back exactly).
    n : array_like
        Characteristic, ``n < 1``.
    m : array_like, optional
        Parameter ``m = k**2 <= 1`` (``m = 1`` only for |φ| < π/2).
    m1 : array_like, optional
        1 − m instead of ``m`` (keyword only), for full accuracy near m = 1:
        δ² = cos²φ + m1 sin²φ is then formed without cancellation.

    Returns
    -------
    ndarray
        Π(φ, n | m), broadcast over the inputs. Accuracy: a few ulp of the
        Carlson integrals for |φ| <= π/2; beyond, the absolute error of
        reducing φ modulo π (≈ |φ|·eps) adds.

    Examples
    --------
    >>> import numpy as np
    >>> from scipy import special
    >>> bool(np.isclose(elliptic_pi(1.0, 0.0, 0.3), special.ellipkinc(1.0, 0.3)))
    True
    >>> round(float(elliptic_pi(0.5, 0.0, 0.0)), 15)   # F(φ | 0) = φ
    0.5
    """
    phi = as_float_array(phi, "phi")
    n = _check_characteristic(n)
    m1 = _parameter(m, m1)
    j = np.round(phi / np.pi)
    if np.any((j != 0.0) & (m1 <= 0.0)):
        raise ValueError("phi must satisfy |phi| < pi/2 when m = 1 (the integral diverges)")
    shape, (phi, n, m1) = _flat(phi, n, m1)
    out = np.empty(phi.size)
    _pi_loop(phi, n, m1, out)
    return out.reshape(shape)


def elliptic_f(phi, m=None, *, m1=None):
    """Incomplete elliptic integral of the first kind F(φ | m), any real φ.

    F(φ | m) = sin φ R_F(cos²φ, cos²φ + m1 sin²φ, 1) for |φ| <= π/2 and
    F(φ + jπ) = F(φ) + 2jK beyond (the multiple of K added back exactly).

    Parameters
    ----------
    phi : array_like
        Amplitude, radians.
    m, m1 : array_like
        Parameter m <= 1, or (keyword) its complement m1 = 1 − m >= 0.

    Returns
    -------
    ndarray
        F(φ | m), broadcast over ``phi`` and the parameter.

    Examples
    --------
    >>> from scipy import special
    >>> bool(np.isclose(elliptic_f(2.5, 0.7), special.ellipkinc(2.5, 0.7), rtol=1e-15))
    True
    """
    return elliptic_pi(phi, 0.0, m, m1=m1)


def elliptic_k(m=None, *, m1=None):
    """Complete elliptic integral of the first kind K(m) = R_F(0, m1, 1).

    Parameters
    ----------
    m, m1 : array_like
        Parameter m < 1, or (keyword) its complement m1 = 1 − m > 0.

    Returns
    -------
    ndarray
        K(m); next to m = 1 it grows as ln(4/√m1).

    Examples
    --------
    >>> round(float(elliptic_k(m1=1e-300)), 10) == round(float(np.log(4e150)), 10)
    True
    """
    return complete_elliptic_pi(0.0, m, m1=m1)


def jacobi_elliptic(u, m=None, *, m1=None):
    """Jacobi elliptic functions sn, cn, dn of u | m, accurate next to m = 1 when given ``m1``.

    The argument is split as u = nK + r with |r| <= K/2 (K from m1); sn, cn,
    dn of r come from the arithmetic–geometric mean started at √m1 (or, for
    m1 < 1e-17, the expansion about tanh and sech), and the quarter-period
    shifts keep cn and dn to full relative accuracy where they are O(√m1).
    ``m1 = 0`` gives tanh u, sech u, sech u.

    Parameters
    ----------
    u : array_like
        Argument.
    m, m1 : array_like
        Parameter 0 <= m <= 1, or (keyword) its complement m1 = 1 − m.

    Returns
    -------
    sn, cn, dn : ndarray

    Examples
    --------
    >>> import numpy as np
    >>> from scipy import special
    >>> sn, cn, dn = jacobi_elliptic(0.8, 0.3)
    >>> bool(np.allclose([sn, cn, dn], special.ellipj(0.8, 0.3)[:3], rtol=1e-15))
    True
    >>> _, cn, dn = jacobi_elliptic(elliptic_k(m1=1e-20), m1=1e-20)   # at u = K
    >>> float(abs(cn)) < 1e-25, float(dn)                          # dn(K) = √m1
    (True, 1e-10)
    """
    u = as_float_array(u, "u")
    m1 = _parameter(m, m1)
    if np.any(m1 > 1.0):
        raise ValueError("m must be >= 0 (m1 <= 1)")
    shape, (u, m1) = _flat(u, m1)
    sn, cn, dn = np.empty(u.size), np.empty(u.size), np.empty(u.size)
    _jacobi_loop(u, m1, sn, cn, dn)
    return sn.reshape(shape), cn.reshape(shape), dn.reshape(shape)
