"""The heavy symmetric (Lagrange) top (Theory §6): integrals, V_eff, nutation, apex locus, exact solution.

Gravity along space −z; centre of mass on the body's third axis at distance
l from the pivot; I1 = I2 about the pivot, I3 about the symmetry axis; state
as the chapter's ZXZ angles (φ, θ, ψ) and their rates. With u = cos θ,
a = J3/I1, b = Jz/I1, α = (2E − J3²/I3)/I1, β = 2mgl/I1 (Theory §6.3):

    u̇² = f(u) = (1 − u²)(α − βu) − (b − au)² = β(u − u1)(u − u2)(u − u3),

u1 <= u2 <= 1 < u3, solved by u = u1 + (u2 − u1) sn²(λt + v0 | m) with φ and
ψ from incomplete elliptic integrals of the third kind.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled import cached
from .._compiled.chunks import SAMPLES_PER_CALL
from .._html import html_table, number
from .._validation import (as_float, as_float_array, check_principal_moments, positive_array, refuse_long_turn,
                           sample_times)
from ..dynamics import GravityTorque, simulate
from ..dynamics.trajectory import Trajectory
from ..kinematics import angular_velocity_from_euler_rates
from ..so3 import euler_to_quat, quat_to_euler
from . import _elliptic
from ._free_top import _two_product
from .euler_top import _check_moments, _zxz_quat_from_half_angles

__all__ = ["LagrangeTop", "LagrangeConstants", "FastTop", "larmor_precession_rate"]

ELEMENTARY_CHARGE = 1.602176634e-19  # C (exact, SI 2019)
ELECTRON_MASS = 9.1093837139e-31  # kg (CODATA 2022)


@dataclass(frozen=True)
class LagrangeConstants:
    """Conserved quantities of the Lagrange top (Theory §6.2).

    Attributes
    ----------
    J3 : float
        p_ψ = I3 ω3, angular momentum about the symmetry axis.
    Jz : float
        p_φ = I1 φ̇ sin²θ + J3 cos θ, angular momentum about the vertical.
    E : float
        Energy ½ I1 (θ̇² + φ̇² sin²θ) + J3²/(2 I3) + mgl cos θ.

    Examples
    --------
    φ and ψ are cyclic, so J3 and Jz are conserved along with E; evaluated on
    the exact motion they keep their initial values:

    >>> import numpy as np
    >>> top = LagrangeTop(1.0, 0.5, 1.0)
    >>> tr = top.solve(np.linspace(0.0, 3.0, 5), [0.0, 0.5, 0.0], [0.2, 0.1, 10.0])
    >>> values = np.array([[c.J3, c.Jz, c.E] for c in map(top.constants, tr.zxz_angles, tr.zxz_rates)])
    >>> values[0].round(6).tolist()
    [5.087758, 4.510898, 26.772464]
    >>> bool(np.allclose(values, values[0], rtol=1e-13, atol=0.0))
    True
    """

    J3: float
    Jz: float
    E: float


@dataclass(frozen=True)
class FastTop:
    """Fast top released from rest at θ0 with spin ω3 (Theory §6.7): approximations and exact values.

    Attributes
    ----------
    approx_nutation_amplitude : float
        Peak-to-peak range of u = cos θ, 2 I1 mgl sin²θ0 / J3².
    approx_nutation_frequency : float
        Angular frequency J3/I1 of the nutation.
    approx_precession_rate : float
        Mean precession rate mgl/J3 = mgl/(I3 ω3).
    exact_nutation_amplitude : float
        u2 − u1 from the roots of f(u).
    exact_nutation_frequency : float
        2π / (nutation period 2K(m)/λ).
    exact_precession_rate : float
        Mean φ̇ over one nutation period (complete integrals of the third kind).

    Examples
    --------
    Released from rest at θ0 = 0.8 with J3 = I3 ω3 = 100 (I1 = 1, mgl = 1): the
    nutation is tiny (~2 I1 mgl sin²θ0/J3²) and fast (~J3/I1), the precession slow
    (~mgl/J3); the chapter's estimates agree with the exact values to O(mgl I1/J3²):

    >>> ft = LagrangeTop(1.0, 0.5, 1.0).fast_top(0.8, 200.0)
    >>> round(float(ft.approx_nutation_amplitude), 9), round(ft.exact_nutation_amplitude, 9)
    (0.00010292, 0.000102949)
    >>> round(float(ft.approx_nutation_frequency), 6), round(ft.exact_nutation_frequency, 6)
    (100.0, 99.986066)
    """

    approx_nutation_amplitude: float
    approx_nutation_frequency: float
    approx_precession_rate: float
    exact_nutation_amplitude: float
    exact_nutation_frequency: float
    exact_precession_rate: float


def larmor_precession_rate(magnetic_field: ArrayLike, charge: ArrayLike = ELEMENTARY_CHARGE,
                           mass: ArrayLike = ELECTRON_MASS) -> NDArray[np.float64]:
    """Larmor precession rate eB/(2m) of an orbiting charge (Theory §6.8), rad/s.

    The magnetic energy V = −μ·B = μB cos θ has the form of the top's mgl cos θ,
    so the fast-top mean precession mgl/J3 becomes μB/J with μ = e ω a²/2 and
    J = m ω a², i.e. eB/(2m), independent of the orbit.

    Examples
    --------
    >>> f"{larmor_precession_rate(1.0):.6e}"  # electron in 1 T
    '8.794100e+10'
    """
    b = as_float_array(magnetic_field, "magnetic_field")
    q = as_float_array(charge, "charge")
    m = positive_array(mass, "mass")
    # mantissas and binary exponents apart: |q| b/(2m) of 1e-300 T or 1e300 T rounds once, at the end,
    # instead of passing through a subnormal or an overflowing product
    (mq, eq), (mb, eb), (mm, em) = np.frexp(np.abs(q)), np.frexp(b), np.frexp(m)
    with np.errstate(over="ignore"):
        rate: NDArray[np.float64] = np.ldexp(mq * mb / mm, eq + eb - em - 1)
    if not np.all(np.isfinite(rate)):
        raise ValueError("magnetic_field, charge and mass are out of range: the Larmor rate |charge| magnetic_field"
                         "/(2 mass) exceeds 1.8e308 rad/s, the largest double")
    return rate


# ---- double-double arithmetic for the constants of a state next to the separatrix
# (pairs (hi, lo) with |lo| <= ulp(hi)/2; about 2^-104 relative)
_DD = tuple[float, float]




def _two_sum(a: float, b: float) -> _DD:
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


def _dd_add(x: _DD, y: _DD) -> _DD:
    s, e = _two_sum(x[0], y[0])
    e += x[1] + y[1]
    hi = s + e
    return hi, e - (hi - s)


def _dd_mul(x: _DD, y: _DD) -> _DD:
    p, e = _two_product(x[0], y[0])
    e += x[0] * y[1] + x[1] * y[0]
    hi = p + e
    return hi, e - (hi - p)


def _dd_div(x: _DD, d: float) -> _DD:
    """x / d for a double d."""
    q = x[0] / d
    p, e = _two_product(q, d)
    r = ((x[0] - p) - e + x[1]) / d  # x[0] − p is exact (Sterbenz)
    hi = q + r
    return hi, r - (hi - q)


def _dd(x: Fraction) -> _DD:
    return float(x), float(Fraction(x) - Fraction(float(x)))


#: ±1/n! (sign of the Taylor terms of sin and cos folded in), n = 0 … 29, as double-doubles
_TAYLOR = [_dd(Fraction((-1) ** (n // 2), math.factorial(n))) for n in range(30)]
#: π/2 = _HALF_PI[0] + _HALF_PI[1] + _HALF_PI[2] to about 2^-160
_HALF_PI = (1.5707963267948966, 6.123233995736766e-17, -1.4973849048591698e-33)


def _dd_sin_cos(x: float) -> tuple[_DD, _DD]:
    """(sin x, cos x) as double-doubles for a double 0 <= x <= π/2 (Taylor series about 0 or π/2)."""
    swap = x > 0.5 * _HALF_PI[0]
    z = (x, 0.0)
    if swap:  # π/2 − x: the first difference is exact (Sterbenz)
        z = _dd_add(_dd_add((_HALF_PI[0] - x, 0.0), (_HALF_PI[1], 0.0)), (_HALF_PI[2], 0.0))
    z2 = _dd_mul(z, z)
    sin, cos = _TAYLOR[29], _TAYLOR[28]  # |z| <= π/4: the first term left out is below 2^-110
    for n in range(27, 0, -2):
        sin = _dd_add(_dd_mul(sin, z2), _TAYLOR[n])
        cos = _dd_add(_dd_mul(cos, z2), _TAYLOR[n - 1])
    sin = _dd_mul(sin, z)
    return (cos, sin) if swap else (sin, cos)


class _Quadrature:
    """Roots of f(u) and the elliptic solution for one initial state (Theory §6.3).

    The roots are found as w = 1 − u, the distance from the upright position:
    with δb = b − a and δα = α − β formed from the state in double-double
    (from sin and cos of θ0/2 to about 2^-104: next to the separatrix their O(1)
    terms cancel to O(m1)),

        F(w) = f(1 − w) = −β w³ + (2β − a² − δα) w² + 2(δα − a δb) w − δb²,

    whose small coefficients keep their relative accuracy when the top only just
    reaches (or only just misses) the vertical. There u2 and u3 meet at u = 1,
    m1 = (w2 − w3)/(w1 − w3) → 0, and w2 >= 0 >= w3 makes w2 − w3 a sum: the
    two small roots come, by Vieta's relations, from the quadratic left after
    deflating F by a root found by bracketing, never as differences of numbers
    near 1.
    """

    def __init__(self, top: LagrangeTop, euler0: NDArray[np.float64], rates0: NDArray[np.float64]) -> None:
        # Python floats: an overflow below is then a silent inf, refused by name, not a numpy warning
        I1, I3, mgl = float(top.I1), float(top.I3), float(top.mgl)
        self.I1_over_I3 = top.I1 / top.I3
        phidot, thetadot, psidot = (float(x) for x in rates0)
        # 1 ∓ u0 = 2 sin²(θ0/2), 2 cos²(θ0/2) (relative accuracy at both verticals), u0 = cos θ0
        half_sin, half_cos = _dd_sin_cos(0.5 * float(euler0[1]))
        h2, g2 = _dd_mul(half_sin, half_sin), _dd_mul(half_cos, half_cos)
        h2, g2 = (2.0 * h2[0], 2.0 * h2[1]), (2.0 * g2[0], 2.0 * g2[1])
        u0 = _dd_add(g2, (-h2[0], -h2[1]))
        u0 = (0.5 * u0[0], 0.5 * u0[1])
        # a = J3/I1 = I3 (u0 φ̇ + ψ̇)/I1, β = 2 mgl/I1
        a2 = _dd_div(_dd_mul(_dd_add(_dd_mul(u0, (phidot, 0.0)), (psidot, 0.0)), (I3, 0.0)), I1)
        beta2 = _dd_div((2.0 * mgl, 0.0), I1)
        # δb = φ̇ sin²θ − a(1 − u0) = (1 − u0)(φ̇(1 + u0) − a) = (Jz − J3)/I1,
        # δα = θ̇² + φ̇² sin²θ − β(1 − u0) = θ̇² + (1 − u0)(φ̇²(1 + u0) − β) = α − β
        phig = _dd_mul((phidot, 0.0), g2)
        delta_b2 = _dd_mul(h2, _dd_add(phig, (-a2[0], -a2[1])))
        # likewise b + a = (1 + u0)(φ̇(1 − u0) + a), small for a top that passes near the lower vertical
        sigma_b = _dd_mul(g2, _dd_add(_dd_mul((phidot, 0.0), h2), a2))[0]
        inner = _dd_add(_dd_mul(phig, (phidot, 0.0)), (-beta2[0], -beta2[1]))
        delta_alpha2 = _dd_add(_two_product(thetadot, thetadot), _dd_mul(h2, inner))
        h, g, beta, delta_alpha = h2[0], g2[0], beta2[0], delta_alpha2[0]
        self.a, self.delta_b = a, delta_b = a2[0], delta_b2[0]
        self.b = a + delta_b
        c2 = 2.0 * beta - a * a - delta_alpha
        c1 = 2.0 * (delta_alpha - a * delta_b)
        c0 = -delta_b * delta_b

        def F(w: float) -> float:
            return ((-beta * w + c2) * w + c1) * w + c0

        # F(1 − u0) = u̇0² >= 0 and F(2) = f(−1) = −(b + a)² <= 0 bracket w1 = 1 − u1
        root = h  # released at a turning point (θ̇0 = 0): 1 − u0 itself is a root
        if thetadot != 0.0 and F(h) > 0.0:
            if F(2.0) >= 0.0:
                root = 2.0
            else:
                from scipy.optimize import brentq  # slow to import: only when a root must be searched for

                root = brentq(F, h, 2.0, xtol=1e-300, rtol=1e-15, maxiter=2000)
        # the other two roots: product q = c0/(β root) <= 0, sum from whichever Vieta relation
        # cancels less (c2/β − root when root is the small one, (−c1/β − q)/root when it is w1)
        q = c0 / (beta * root) if root > 0.0 else 0.0
        if root > 0.0 and (abs(c1 / beta) + abs(q)) / root < abs(c2 / beta) + root:
            total = (-c1 / beta - q) / root
        else:
            total = c2 / beta - root
        # q <= 0: no cancellation; hypot, since a weak top (mgl -> 0) has w3 ~ −a²/β beyond 1e154
        spread = math.hypot(total, 2.0 * math.sqrt(-q))
        big = 0.5 * (total + math.copysign(spread, total))
        small = q / big if big != 0.0 else 0.0
        if not math.isfinite(small * big):
            raise ValueError(
                f"mgl is too small for the exact solution of this state: the third root u3 of f(u), about "
                f"(J3/I1)²/(2 mgl/I1), exceeds the largest double (mgl={mgl:g}, J3/I1={a:g})"
            )
        others = (max(big, small), min(big, small))  # >= 0 and <= 0
        # clamped to the physical ranges: exactly, f(±1) <= 0 puts u1, u2 in [−1, 1] and u3 >= 1
        w1, w2 = min(max(root, others[0]), 2.0), max(min(root, others[0]), 0.0)
        w3 = min(others[1], 0.0)
        # 1 + u1 = 2 − w1 would lose its digits next to the lower vertical; F(2) = −(b + a)²
        # = −β(2 − w1)(2 − w2)(2 − w3) gives it as a quotient, as accurate as 2 − w2 >= 2 − w1
        v1 = sigma_b * (sigma_b / (beta * (2.0 - w2) * (2.0 - w3))) if w2 < 2.0 else 0.0
        # passing a vertical at θ ~ √w, φ turns by π within a time ~ √w/θ̇ (Π's 1 − n = w/w1)
        if (delta_b != 0.0 and w2 < 1e-150) or (sigma_b != 0.0 and v1 < 1e-150):
            raise ValueError(
                "the top passes within 1e-75 rad of the vertical without reaching it: its ZXZ angle phi "
                "turns by pi there faster than doubles can follow"
            )
        self.w1, self.w2, self.w3, self.v1, self.sigma_b = w1, w2, w3, v1, sigma_b
        udot0_squared = h * g * thetadot * thetadot
        # A nutation much narrower than 1 ∓ u0 (a fast top: u2 − u1 ~ 2 I1 mgl sin²θ0/J3²) is lost in
        # w1 − w2, and b − a u at the turning points (O(a (u2 − u1)), the precession) in δb + a w. The
        # cubic in x = w − h instead has the roots x1 >= 0 >= x2 and x3 = w3 − h < 0 with, by Vieta,
        # x1 x2 = F(h)/(β x3) <= 0 and x1 + x2 = −F′(h)/(β x3) − x1 x2/x3, F(h) = u̇0² and
        # F′(h) = 2u0(θ̇0² + φ̇0² sin²θ0) + (β − 2aφ̇0) sin²θ0 from the state; b − a u = φ̇0 sin²θ0 + a x.
        sin2 = h * g
        self.g0 = g0 = phidot * sin2
        x3 = w3 - h
        fprime = 2.0 * u0[0] * (thetadot * thetadot + phidot * phidot * sin2) + (beta - 2.0 * a * phidot) * sin2
        product = udot0_squared / (beta * x3)
        total = -fprime / (beta * x3) - product / x3
        spread = math.hypot(total, 2.0 * math.sqrt(-product))
        # narrow in u and in θ: next to a vertical u hardly moves while θ swings (F′(h) cancels there)
        self.local = spread <= 0.25 * min(h, g)
        if self.local:
            big = 0.5 * (total + math.copysign(spread, total))
            small = product / big if big != 0.0 else 0.0
            x1, x2 = max(big, small, 0.0), min(big, small, 0.0)
            self.delta, self.g1, self.g2 = spread, g0 + a * x1, g0 + a * x2
        else:
            self.delta = w1 - w2
            # b − a u = δb + a w = σb − a(2 − w): the form whose O(1) terms do not cancel
            self.g1 = delta_b + a * w1 if w1 <= 1.0 else sigma_b - a * v1
            self.g2 = delta_b + a * w2 if w2 <= 1.0 else sigma_b - a * (v1 + self.delta)
        self.u1, self.u2, self.u3 = (1.0 - w1 if w1 < 1.0 else v1 - 1.0), 1.0 - w2, 1.0 - w3
        self.lam = 0.5 * math.sqrt(beta * (w1 - w3))
        self.m1 = (w2 - w3) / (w1 - w3)
        self.kc = math.sqrt(self.m1)
        self.quarter = _elliptic.complete_k(self.m1, self.kc)
        # phase at t = 0: sn² v0 ∝ u0 − u1 = w1 − h, cn² v0 ∝ u2 − u0 = h − w2, sign from u̇0. The
        # smaller of the two differences (next to a turning point, where the phase moves by
        # √difference/k′) comes from u̇0² = F(h) = β (w1 − h)(h − w2)(h − w3) instead
        # (next to the lower vertical u0 − u1 = (1 + u0) − (1 + u1) keeps its digits)
        d1 = max(g - v1 if w1 > 1.0 and w2 < 2.0 else w1 - h, 0.0)
        d2 = max(h - w2, 0.0)
        if self.local:
            d1, d2 = x1, -x2
        elif d2 <= d1:
            d2 = udot0_squared / (beta * d1 * (h - w3)) if d1 > 0.0 else 0.0
        else:
            d1 = udot0_squared / (beta * d2 * (h - w3))
        if d1 == 0.0 and d2 == 0.0:  # w1 = w2 = 1 − u0: steady precession, any phase
            d2 = 1.0
        sn0 = math.copysign(math.sqrt(d1), -thetadot)  # u̇0 = −sin θ0 θ̇0
        self.n0, self.r0 = _elliptic.phase_from_sn_cn(sn0, math.sqrt(d2), self.m1, self.kc)

    def _partial_fraction_terms(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        """(coefficient, characteristic n, 1 − n) of the 1/(1 − u) and 1/(1 + u) terms of φ̇.

        A vanishing coefficient (b = ±a: the top reaches that vertical, where its
        denominator 1 ∓ u1 may vanish too) drops the term: (0, 0, 1).
        """
        w1, w2, v1, delta = self.w1, self.w2, self.v1, self.delta
        upper = (self.delta_b / w1, delta / w1, w2 / w1) if self.delta_b != 0.0 else (0.0, 0.0, 1.0)
        lower = (self.sigma_b / v1, -delta / v1, (2.0 - w2) / v1) if self.sigma_b != 0.0 else (0.0, 0.0, 1.0)
        return upper, lower

    def motion(self, t: NDArray[np.float64], top: LagrangeTop,
               euler0: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
        """ZXZ angles, their rates, q and body ω at the times t (Theory §6.3).

        φ + ψ takes only the 1/(1 + u) partial fraction and φ − ψ only the 1/(1 − u) one:
        next to the lower vertical (θ -> π) φ and ψ each turn by about π within a time ~ π − θ
        and only φ − ψ is well determined, next to the upper vertical only φ + ψ. The quaternion
        is therefore built from the half sum and difference, weighted by cos(θ/2), sin(θ/2) from
        1 ± u (relative accuracy at both verticals), and ω3 = J3/I3 is the constant itself,
        never the difference φ̇ cos θ + ψ̇ of two rates that grow like 1/sin θ.
        """
        out = np.empty((t.size, 9))
        terms = np.array(self._partial_fraction_terms(), dtype=float)
        for s in range(0, t.size, SAMPLES_PER_CALL):  # Ctrl-C takes effect between the calls; same bits
            e = s + SAMPLES_PER_CALL
            _lagrange_samples(t[s:e], self.lam, self.n0, self.r0, self.m1, self.kc, self.quarter, self.w1, self.w2,
                              self.v1, terms, out[s:e])
        u, one_minus_u, one_plus_u, sn, cn, dn, plus, minus = out[:, :8].T
        udot = 2.0 * self.delta * self.lam * sn * cn * dn
        sin_theta = np.sqrt(one_minus_u * one_plus_u)
        half_sin, half_cos = np.sqrt(0.5 * one_minus_u), np.sqrt(0.5 * one_plus_u)
        theta = 2.0 * np.arctan2(half_sin, half_cos)
        spin_excess = self.a * (top.I1 / top.I3 - 1.0) * t
        total = euler0[0] + euler0[2] + minus / self.lam + spin_excess  # φ + ψ
        difference = euler0[0] - euler0[2] + plus / self.lam - spin_excess  # φ − ψ
        phi, psi = 0.5 * (total + difference), 0.5 * (total - difference)
        # b − a u = δb + a(1 − u) = σb − a(1 + u): the form whose O(1) terms do not cancel; a narrow
        # nutation's g2 + a(u2 − u1) cn², all of whose terms are of the size of b − a u itself
        upper = one_minus_u <= one_plus_u
        if self.local:
            numerator = self.g2 + self.a * self.delta * cn * cn
        else:
            numerator = np.where(upper, self.delta_b + self.a * one_minus_u, self.sigma_b - self.a * one_plus_u)
        phidot = numerator / (one_minus_u * one_plus_u)
        thetadot = -udot / sin_theta
        omega3 = self.a * top.I1 / top.I3
        psidot = omega3 - u * phidot
        q = _zxz_quat_from_half_angles(half_cos, half_sin, 0.5 * total, 0.5 * difference)
        transverse = numerator / sin_theta  # φ̇ sin θ, bounded through the verticals
        cos_psi, sin_psi = np.cos(psi), np.sin(psi)
        omega = np.stack([transverse * sin_psi + thetadot * cos_psi, transverse * cos_psi - thetadot * sin_psi,
                          np.full_like(t, omega3)], axis=-1)
        return (np.stack([phi, theta, psi], axis=-1), np.stack([phidot, thetadot, psidot], axis=-1), q, omega)

    def phase_rate(self) -> float:
        """Largest mean rate (rad/s) of the phases solve() adds up: the elliptic argument λt, the
        nutation 2πλ/(2K), each partial fraction of φ ± ψ (|c| Π(n | m)/K) and the spin excess."""
        fractions = sum(abs(c * _elliptic.complete_pi(n, one_minus_n, self.m1, self.kc))
                        for c, n, one_minus_n in self._partial_fraction_terms() if c != 0.0)
        return float(max(self.lam, math.pi * self.lam / self.quarter, fractions / self.quarter)
                     + abs(self.a * (self.I1_over_I3 - 1.0)))

    def mean_precession_rate(self) -> float:
        """⟨φ̇⟩ over a nutation period: Σ c Π(n | m) / (2K) (complete integrals).

        For a narrow nutation Π(n | m) = K + (n/3) R_J(0, m1, 1, 1 − n) is split: the K terms
        add up to φ̇ at u1, (b − a u1)/(1 − u1²), and the rest is (u2 − u1)-small, so the two
        partial fractions, each O(a), are never subtracted to give the O(mgl/J3) precession of
        a fast top.
        """
        terms = [(c, n, one_minus_n) for c, n, one_minus_n in self._partial_fraction_terms() if c != 0.0]
        if not self.local or self.m1 == 0.0:
            # a wide nutation: no such cancellation, and next to the lower vertical (n -> −∞) the split
            # itself would cancel; K infinite (the top creeps towards a vertical): Π's own limit
            total = sum(c * _elliptic.complete_pi(n, one_minus_n, self.m1, self.kc) for c, n, one_minus_n in terms)
            return float(total / (2.0 * self.quarter))
        # a vertical reached (b = ±a) leaves one term: its own ½ c, no cancellation
        at_u1 = self.g1 / (self.w1 * self.v1) if len(terms) == 2 else 0.5 * sum(c for c, _, _ in terms)
        corrections = sum(c * n * _elliptic.carlson_rj(0.0, self.m1, 1.0, one_minus_n) for c, n, one_minus_n in terms)
        return float(at_u1 + corrections / (6.0 * self.quarter))


@cached
def _lagrange_samples(t: NDArray[np.float64], lam: float, n0: int, r0: float, m1: float, kc: float, quarter: float,
                      w1: float, w2: float, v1: float, terms: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    """Per sample: u, 1 − u, 1 + u, sn, cn, dn and c·ΔΠ of both partial fractions (Theory §6.3)."""
    pic = np.zeros(2)
    pi0 = np.zeros(2)
    s0, c0, _ = _elliptic.jacobi_near(r0, m1, kc)
    for k in range(2):
        # a vanishing coefficient may come with n = 1 (the vertical reached): its Π is not needed
        if terms[k, 0] != 0.0:
            pic[k] = _elliptic.complete_pi(terms[k, 1], terms[k, 2], m1, kc)
            pi0[k] = _elliptic.pi_split(n0, r0, s0, c0, m1, kc, terms[k, 1], terms[k, 2], pic[k])
    for i in range(t.size):
        j, r = _elliptic.split_phase(r0 + lam * t[i], quarter)
        n = n0 + j
        sr, cr, dr = _elliptic.jacobi_near(r, m1, kc)
        sn, cn, dn = _elliptic.quarter_shift(n, sr, cr, dr, kc)
        # 1 − u = w2 + (w1 − w2) cn² keeps its relative accuracy near the vertical
        out[i, 0] = (1.0 - w1) + (w1 - w2) * sn * sn
        out[i, 1] = w2 + (w1 - w2) * cn * cn
        out[i, 2] = v1 + (w1 - w2) * sn * sn
        out[i, 3], out[i, 4], out[i, 5] = sn, cn, dn
        for k in range(2):
            value = 0.0
            if terms[k, 0] != 0.0:
                pi = _elliptic.pi_split(n, r, sr, cr, m1, kc, terms[k, 1], terms[k, 2], pic[k])
                value = terms[k, 0] * (pi - pi0[k])
            out[i, 6 + k] = value


class _PlanarPendulum:
    """J3 = Jz = 0: the top swings in a vertical plane through the vertical (Theory §6.3 with a = b = 0).

    f(u) = (1 − u²)(α − βu) has the roots ±1, so u reaches −1 (or both ±1)
    and the ZXZ angles cannot follow θ through the vertical; the swing angle
    χ = π − θ from the downward vertical is solved instead, as a pendulum:
    sin(χ/2) = k sn(λt + v0 | m) (libration, m = cos²(θ0/2) + g, m1 = sin²(θ0/2) − g,
    g = I1 θ̇0²/(4 mgl), λ = √(mgl/I1)) or χ/2 = ±am(λt + v0 | m) (circulation,
    m = 1/(cos²(θ0/2) + g), λ = √(mgl (cos²(θ0/2) + g)/I1)). θ = π − χ is
    returned continuous (outside [0, π] beyond the vertical), φ and ψ stay
    constant.
    """

    a = b = delta_b = sigma_b = g0 = g1 = g2 = 0.0

    def __init__(self, top: LagrangeTop, theta0: float, thetadot0: float) -> None:
        g = top.I1 * thetadot0**2 / (4.0 * top.mgl)
        s2, c2 = np.sin(0.5 * theta0) ** 2, np.cos(0.5 * theta0) ** 2
        level = c2 + g  # (E + mgl)/(2 mgl)
        self.m1 = abs(s2 - g) / (level if s2 < g else 1.0)
        self.kc = np.sqrt(self.m1)
        self.circulating = bool(s2 <= g)
        self.lam = np.sqrt(top.mgl / top.I1 * (level if self.circulating else 1.0))
        self.k = np.sqrt(1.0 - self.m1)
        half = 0.5 * (np.pi - theta0)  # χ0/2 in (0, π/2)
        if self.circulating:
            self.sign = -np.sign(thetadot0)
            sn0, cn0 = self.sign * np.sin(half), np.cos(half)
            self.w1, self.w2, self.w3 = 2.0, 0.0, 2.0 - 2.0 * level  # u3 = α/β
        else:
            self.sign = 1.0
            # sn v0 = sin(χ0/2)/k, cn v0 = χ̇0/(2kλ) = −θ̇0 √(I1/(4 mgl))/k: both times k, exact
            sn0, cn0 = np.cos(0.5 * theta0), -thetadot0 * np.sqrt(top.I1 / (4.0 * top.mgl))
            self.w1, self.w2, self.w3 = 2.0, 2.0 * max(s2 - g, 0.0), 0.0  # u2 = cos θ0 + 2g
        self.u1, self.u2, self.u3 = 1.0 - self.w1, 1.0 - self.w2, 1.0 - self.w3
        self.v1, self.delta = 0.0, self.w1 - self.w2
        if self.m1 == 0.0:
            self.quarter = np.inf
            self.n0, self.r0 = 0, np.arcsinh(sn0 / cn0)
        else:
            self.quarter = _elliptic.complete_k(self.m1, self.kc)
            self.n0, self.r0 = _elliptic.phase_from_sn_cn(sn0, cn0, self.m1, self.kc)

    def motion(self, t: NDArray[np.float64], top: LagrangeTop,
               euler0: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
        """ZXZ angles, their rates, q and body ω (φ = φ0 and ψ = ψ0 throughout)."""
        out = np.empty((t.size, 4))
        _pendulum_samples(t, self.lam, self.n0, self.r0, self.m1, self.kc, self.quarter, out)
        sn, cn, dn, am = out.T
        if self.circulating:
            chi, chidot = 2.0 * self.sign * am, 2.0 * self.sign * self.lam * dn
        else:
            chi, chidot = 2.0 * np.arctan2(self.k * sn, dn), 2.0 * self.k * self.lam * cn
        zeros = np.zeros_like(t)
        euler = np.stack([np.full_like(t, euler0[0]), np.pi - chi, np.full_like(t, euler0[2])], axis=-1)
        rates = np.stack([zeros, -chidot, zeros], axis=-1)
        q = euler_to_quat("ZXZ", euler)
        return euler, rates, q, angular_velocity_from_euler_rates("ZXZ", euler, rates, frame="body")

    def phase_rate(self) -> float:
        """Largest rate (rad/s) of the phases: the argument λt and, circulating, the swing 2πλ/K."""
        return float(self.lam * max(1.0, 2.0 * math.pi / self.quarter))

    def mean_precession_rate(self) -> float:
        return 0.0


@cached
def _pendulum_samples(t: NDArray[np.float64], lam: float, n0: int, r0: float, m1: float, kc: float, quarter: float,
                      out: NDArray[np.float64]) -> None:
    """sn, cn, dn and am of v = r0 + λt (split phase n0 K + ...; m1 = 0: tanh, sech, gd)."""
    for i in range(t.size):
        v = r0 + lam * t[i]
        if m1 == 0.0:
            sech = 1.0 / math.cosh(v)
            out[i, 0], out[i, 1], out[i, 2], out[i, 3] = math.tanh(v), sech, sech, math.atan(math.sinh(v))
            continue
        j, r = _elliptic.split_phase(v, quarter)
        sr, cr, dr = _elliptic.jacobi_near(r, m1, kc)
        out[i, 0], out[i, 1], out[i, 2] = _elliptic.quarter_shift(n0 + j, sr, cr, dr, kc)
        out[i, 3] = _elliptic.amplitude_split(n0 + j, sr, cr, kc)


class LagrangeTop:
    """Heavy symmetric top on a fixed pivot (Theory §6, Lagrange top).

    Parameters
    ----------
    I1 : float
        Transverse moment about the pivot (I1 = I2), kg m².
    I3 : float
        Moment about the symmetry axis, kg m².
    mgl : float
        Weight times distance from the pivot to the centre of mass (> 0), N m.

    Examples
    --------
    >>> import numpy as np
    >>> top = LagrangeTop(1.0, 0.5, 1.0)
    >>> [round(float(x), 6) for x in top.turning_points([0.0, 0.5, 0.0], [0.0, 0.0, 10.0])]
    [0.5, 0.542863]
    >>> top.apex_locus_kind([0.0, 0.5, 0.0], [0.0, 0.0, 10.0])
    'cusp'
    >>> bool(top.sleeping_top_stable(5.0)), bool(top.sleeping_top_stable(3.0))
    (True, False)
    """

    def __init__(self, I1: float, I3: float, mgl: float) -> None:
        self.I1, self.I3, self.mgl = _check_moments((I1, I3, mgl), ("I1", "I3", "mgl"))
        check_principal_moments([self.I1, self.I1, self.I3], "LagrangeTop moments (I1, I1, I3)")

    def __repr__(self) -> str:
        return f"LagrangeTop(I1={self.I1:g}, I3={self.I3:g}, mgl={self.mgl:g})"

    def _repr_html_(self) -> str:
        rows = [("I1 = I2, I3", f"{number(self.I1)}, {number(self.I3)} kg m²"),
                ("mgl", number(self.mgl) + " N m"),
                ("sleeping top stable for |ω3| >", number(self.sleeping_top_threshold()) + " rad/s")]
        return html_table("LagrangeTop (heavy symmetric top)", rows, note="Euler angles ZXZ (φ, θ, ψ), θ from the vertical")

    # ---- state and constants ---------------------------------------------------------
    @staticmethod
    def _check_state(euler0: ArrayLike, rates0: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        euler0 = as_float_array(euler0, "euler0", tail=(3,))
        rates0 = as_float_array(rates0, "rates0", tail=(3,))
        if euler0.ndim != 1 or rates0.ndim != 1:
            raise ValueError("euler0 and rates0 must each have shape (3,): (phi, theta, psi) and their rates")
        if not 0.0 < euler0[1] < np.pi:
            raise ValueError(
                f"euler0 must have 0 < theta < pi (ZXZ angles are singular on the vertical), got theta={euler0[1]}"
            )
        return euler0, rates0

    def constants(self, euler0: ArrayLike, rates0: ArrayLike) -> LagrangeConstants:
        """J3, Jz and E of the state (Theory §6.2).

        Examples
        --------
        >>> LagrangeTop(1.0, 0.5, 1.0).constants([0.0, np.pi / 2, 0.0], [1.0, 0.0, 2.0])
        LagrangeConstants(J3=1.0, Jz=1.0, E=1.5)
        """
        euler0, rates0 = self._check_state(euler0, rates0)
        return self._constants(euler0, rates0)

    def _constants(self, euler0: NDArray[np.float64], rates0: NDArray[np.float64]) -> LagrangeConstants:
        theta = euler0[1]
        phidot, thetadot, psidot = rates0
        J3 = self.I3 * (np.cos(theta) * phidot + psidot)
        Jz = self.I1 * phidot * np.sin(theta) ** 2 + J3 * np.cos(theta)
        E = 0.5 * self.I1 * (thetadot**2 + (phidot * np.sin(theta)) ** 2) + J3**2 / (2 * self.I3)
        E += self.mgl * np.cos(theta)
        return LagrangeConstants(float(J3), float(Jz), float(E))

    def effective_potential(self, theta: ArrayLike, J3: float, Jz: float) -> NDArray[np.float64]:
        """V_eff(θ) = (Jz − J3 cos θ)²/(2 I1 sin²θ) + mgl cos θ + J3²/(2 I3) (Theory §6.2).

        Examples
        --------
        >>> float(LagrangeTop(1.0, 0.5, 1.0).effective_potential(np.pi / 2, 1.0, 0.0))
        1.0
        """
        theta = as_float_array(theta, "theta")
        J3 = as_float(J3, "J3")
        Jz = as_float(Jz, "Jz")
        if np.any((theta <= 0.0) | (theta >= np.pi)):
            raise ValueError("theta must lie in (0, pi): V_eff is infinite on the vertical")
        c, s = np.cos(theta), np.sin(theta)
        potential: NDArray[np.float64] = ((Jz - J3 * c) ** 2 / (2 * self.I1 * s * s) + self.mgl * c
                                          + J3**2 / (2 * self.I3))
        return potential

    def _quadrature(self, euler0: ArrayLike,
                    rates0: ArrayLike) -> tuple[_Quadrature | _PlanarPendulum, NDArray[np.float64], NDArray[np.float64]]:
        euler0, rates0 = self._check_state(euler0, rates0)
        if euler0[1] < 1e-75:
            raise ValueError(
                f"euler0 must have theta >= 1e-75 for the exact solution (1 - cos theta and the roots of f(u) next to 1 underflow), got theta={euler0[1]}"
            )
        constants = self._constants(euler0, rates0)
        if constants.J3 == 0.0 and constants.Jz == 0.0:
            return _PlanarPendulum(self, euler0[1], rates0[1]), euler0, rates0
        return _Quadrature(self, euler0, rates0), euler0, rates0

    # ---- nutation and the apex ------------------------------------------------------
    def turning_points(self, euler0: ArrayLike, rates0: ArrayLike) -> tuple[float, float]:
        """(θ_min, θ_max), the nutation range: the roots u2, u1 of f(u) in [−1, 1] (Theory §6.4).

        Examples
        --------
        Released with θ̇ = φ̇ = 0 at θ0 = 0.5 the top starts at its highest point, and
        the effective potential equals the energy at both turning points (θ̇ = 0):

        >>> top = LagrangeTop(1.0, 0.5, 1.0)
        >>> euler0, rates0 = [0.0, 0.5, 0.0], [0.0, 0.0, 10.0]
        >>> theta_min, theta_max = top.turning_points(euler0, rates0)
        >>> round(theta_min, 12), round(theta_max, 6)
        (0.5, 0.542863)
        >>> c = top.constants(euler0, rates0)
        >>> [bool(abs(top.effective_potential(th, c.J3, c.Jz) - c.E) < 1e-12) for th in (theta_min, theta_max)]
        [True, True]
        """
        quad, _, _ = self._quadrature(euler0, rates0)
        # θ from 1 − cos θ = w: 2 atan2(√w, √(2 − w)) keeps the relative accuracy of w near θ = 0
        lowest, highest = (float(2.0 * np.arctan2(np.sqrt(w), np.sqrt(2.0 - w))) for w in (quad.w2, quad.w1))
        return lowest, highest

    def cubic_roots(self, euler0: ArrayLike, rates0: ArrayLike) -> tuple[float, float, float]:
        """The three roots u1 <= u2 <= 1 < u3 of f(u) = u̇² (Theory §6.4).

        Examples
        --------
        u = cos θ moves between u1 = cos θ_max and u2 = cos θ_min; the third root
        lies above 1, outside the physical range:

        >>> import numpy as np
        >>> top = LagrangeTop(1.0, 0.5, 1.0)
        >>> u1, u2, u3 = top.cubic_roots([0.0, 0.5, 0.0], [0.0, 0.0, 10.0])
        >>> round(float(u2), 12) == round(float(np.cos(0.5)), 12), round(float(u1), 6), bool(u3 > 1.0)
        (True, 0.856233, True)
        """
        quad, _, _ = self._quadrature(euler0, rates0)
        return quad.u1, quad.u2, quad.u3

    def apex_locus_kind(self, euler0: ArrayLike, rates0: ArrayLike, rtol: float = 1e-9) -> str:
        """Shape of the path of the symmetry axis on the unit sphere (Theory §6.5).

        φ̇ = (b − a u)/(1 − u²) has the sign of b − a u: ``"monotone"`` if it keeps
        one sign on [u1, u2], ``"cusp"`` if it vanishes at a turning point
        (within ``rtol`` of its scale |b − a u0| + |a| (u2 − u1), e.g. released with
        θ̇ = φ̇ = 0), ``"loop"`` if it changes sign inside the nutation range. The scale
        is that of b − a u itself, so a fast top's slow precession (b − a u of order
        mgl/J3 next to a of order J3) and a top next to the vertical are told apart.

        Examples
        --------
        The same tilt and spin (mean precession ≈ 0.2 rad/s) with three initial φ̇:

        >>> top = LagrangeTop(1.0, 0.5, 1.0)
        >>> [top.apex_locus_kind([0.0, 0.5, 0.0], [phidot, 0.0, 10.0]) for phidot in (0.0, 0.3, -0.5)]
        ['cusp', 'monotone', 'loop']
        """
        quad, _, _ = self._quadrature(euler0, rates0)
        g1, g2 = quad.g1, quad.g2  # b − a u at the turning points u1, u2
        # the scale of b − a u over the motion: its value at the start and its change over the nutation
        tol = rtol * (abs(quad.g0) + abs(quad.a) * quad.delta)
        if min(abs(g1), abs(g2)) <= tol:
            return "cusp"
        return "loop" if g1 * g2 < 0.0 else "monotone"

    def nutation_period(self, euler0: ArrayLike, rates0: ArrayLike) -> float:
        """Period of θ(t), 2K(m)/λ, seconds.

        Examples
        --------
        A fast top (J3 = 100, I1 = 1) nods with nearly the period 2π I1/J3 (Theory §6.7):

        >>> import numpy as np
        >>> top = LagrangeTop(1.0, 0.5, 1.0)
        >>> round(top.nutation_period([0.0, 0.8, 0.0], [0.0, 0.0, 200.0]), 6), round(2 * np.pi / 100.0, 6)
        (0.062841, 0.062832)
        """
        quad, _, _ = self._quadrature(euler0, rates0)
        return float(2.0 * quad.quarter / quad.lam)

    def mean_precession_rate(self, euler0: ArrayLike, rates0: ArrayLike) -> float:
        """Exact mean φ̇ over a nutation period, rad/s (complete integrals of the third kind).

        Accurate to a few units of rounding of the largest |φ̇| over the nutation: relative
        accuracy for a fast top (J3 -> ∞, mean ≈ mgl/J3) and wherever the mean is of the size
        of φ̇ itself, absolute only for a weak top (mgl -> 0) whose apex circles J away from
        the vertical, where the mean, O(mgl), is what is left of φ̇ swinging both ways.

        Examples
        --------
        Started at the slow steady-precession rate there is no nutation and the mean
        is that rate; released from rest, a fast top precesses at about mgl/J3:

        >>> top = LagrangeTop(1.0, 0.5, 1.0)
        >>> slow, _ = top.steady_precession_rates(0.5, 10.0)
        >>> import numpy as np
        >>> rates0 = [slow, 0.0, 10.0 - slow * np.cos(0.5)]   # ω3 = φ̇ cos θ + ψ̇ = 10
        >>> round(top.mean_precession_rate([0.0, 0.5, 0.0], rates0), 9), round(slow, 9)
        (0.207561568, 0.207561568)
        >>> round(top.mean_precession_rate([0.0, 0.8, 0.0], [0.0, 0.0, 200.0]), 6)   # mgl/J3 = 0.01
        0.010001
        """
        quad, _, _ = self._quadrature(euler0, rates0)
        return quad.mean_precession_rate()

    def steady_precession_rates(self, theta: float, omega3: float) -> tuple[float, float]:
        """(slow, fast) rates φ̇ of steady precession at fixed θ with spin ω3.

        From the θ equation with θ̈ = θ̇ = 0: I1 cos θ φ̇² − J3 φ̇ + mgl = 0,
        φ̇ = (J3 ∓ √(J3² − 4 I1 mgl cos θ)) / (2 I1 cos θ); at θ = π/2 only the
        slow rate mgl/J3 exists (fast = ±inf). NaN when J3² < 4 I1 mgl cos θ
        (no steady precession at that tilt).

        Examples
        --------
        >>> slow, fast = LagrangeTop(1.0, 0.5, 1.0).steady_precession_rates(0.5, 20.0)
        >>> round(slow, 6), round(fast, 6)
        (0.100893, 11.294046)
        """
        theta = as_float(theta, "theta")
        J3 = self.I3 * as_float(omega3, "omega3")
        c = np.cos(theta)
        discriminant = J3 * J3 - 4.0 * self.I1 * self.mgl * c
        if discriminant < 0.0:
            return float("nan"), float("nan")
        root = np.sqrt(discriminant)
        # slow root without cancellation: 2 mgl / (J3 ± root), sign chosen with J3
        big = J3 + np.copysign(root, J3)
        slow = 2.0 * self.mgl / big
        fast = big / (2.0 * self.I1 * c) if c != 0.0 else np.copysign(np.inf, J3)
        return float(slow), float(fast)

    def sleeping_top_threshold(self) -> float:
        """Smallest spin ω3 = 2√(I1 mgl)/I3 for which the upright top is stable, rad/s.

        Examples
        --------
        >>> LagrangeTop(1.0, 0.5, 1.0).sleeping_top_threshold()   # 2 √(1 · 1)/0.5
        4.0
        """
        return float(2.0 * np.sqrt(self.I1 * self.mgl) / self.I3)

    def sleeping_top_stable(self, omega3: ArrayLike) -> np.bool_ | NDArray[np.bool_]:
        """Whether the upright (sleeping) top spinning at ω3 is stable: J3² > 4 I1 mgl (Theory §6.6).

        Examples
        --------
        Friction slows the spin below :meth:`sleeping_top_threshold` (4 rad/s here)
        and the top starts to wobble; broadcasts over ``omega3``:

        >>> LagrangeTop(1.0, 0.5, 1.0).sleeping_top_stable([6.0, 4.1, 3.9, -5.0]).tolist()
        [True, True, False, True]
        """
        J3 = self.I3 * as_float_array(omega3, "omega3")
        stable: np.bool_ | NDArray[np.bool_] = J3 * J3 > 4.0 * self.I1 * self.mgl
        return stable

    def fast_top(self, theta0: float, omega3: float) -> FastTop:
        """Fast top released from rest at θ0 with spin ω3: Theory §6.7 estimates against the exact motion.

        Examples
        --------
        >>> ft = LagrangeTop(1.0, 0.5, 1.0).fast_top(0.8, 200.0)
        >>> round(float(ft.approx_precession_rate), 6), round(ft.exact_precession_rate, 6)
        (0.01, 0.010001)
        """
        theta0 = as_float(theta0, "theta0")
        omega3 = as_float(omega3, "omega3")
        euler0 = np.array([0.0, theta0, 0.0])
        rates0 = np.array([0.0, 0.0, omega3])
        quad, _, _ = self._quadrature(euler0, rates0)
        J3 = self.I3 * omega3
        return FastTop(
            approx_nutation_amplitude=2.0 * self.I1 * self.mgl * np.sin(theta0) ** 2 / J3**2,
            approx_nutation_frequency=abs(J3) / self.I1,
            approx_precession_rate=self.mgl / J3,
            exact_nutation_amplitude=float(quad.delta),
            exact_nutation_frequency=float(np.pi * quad.lam / quad.quarter),
            exact_precession_rate=quad.mean_precession_rate(),
        )

    # ---- motion -------------------------------------------------------------------
    def solve(self, t: ArrayLike, euler0: ArrayLike, rates0: ArrayLike) -> Trajectory:
        """Exact motion by quadrature (Theory §6.3): u(t) by sn², φ and ψ by Π.

        Parameters
        ----------
        t : (n,) array_like
            Times in seconds, t = 0 being the initial state.
        euler0, rates0 : (3,) array_like
            ZXZ angles (φ, θ, ψ) with 0 < θ < π, and their rates.

        Returns
        -------
        Trajectory
            With ``q``, body ``omega`` and the extra arrays ``zxz_angles`` (n, 3),
            continuous (φ and ψ not wrapped), and ``zxz_rates`` (n, 3).

        Examples
        --------
        >>> tr = LagrangeTop(1.0, 0.5, 1.0).solve([0.0, 1.0], [0.0, 0.5, 0.0], [0.0, 0.0, 10.0])
        >>> round(float(tr.zxz_angles[1, 1]), 6)
        0.523312
        """
        t = sample_times(t)
        quad, euler0, rates0 = self._quadrature(euler0, rates0)
        with np.errstate(over="ignore"):
            turn = float(np.max(np.abs(t), initial=0.0)) * quad.phase_rate()
        refuse_long_turn(turn, "t, euler0 and rates0", "the top's angles and phases turn through up to")
        euler, rates, q, omega = quad.motion(t, self, euler0)
        meta = {"method": "exact", "body": repr(self), "roots": (quad.u1, quad.u2, quad.u3)}
        return Trajectory(t, q, omega, [self.I1, self.I1, self.I3], meta=meta, zxz_angles=euler, zxz_rates=rates)

    def simulate(self, t: ArrayLike, euler0: ArrayLike, rates0: ArrayLike, method: str | None = None,
                 **options: Any) -> Trajectory:
        """Numerical motion: :func:`kreisel.simulate` with :class:`kreisel.dynamics.GravityTorque`.

        The body is (I1, I1, I3) about the pivot, weight ``mgl`` at lever (0, 0, 1)
        (only the product m g l enters). ``options`` go to :func:`kreisel.simulate`
        (``dt``, ``rtol``, ``atol``). The returned trajectory also carries the
        ZXZ angles ``zxz_angles`` recovered from ``q`` (φ and ψ unwrapped).

        Examples
        --------
        >>> tr = LagrangeTop(1.0, 0.5, 1.0).simulate([0.0, 1.0], [0.0, 0.5, 0.0], [0.0, 0.0, 10.0])
        >>> round(float(tr.zxz_angles[1, 1]), 6)
        0.523312
        """
        euler0, rates0 = self._check_state(euler0, rates0)
        omega0 = angular_velocity_from_euler_rates("ZXZ", euler0, rates0, frame="body")
        q0 = euler_to_quat("ZXZ", euler0)
        torque = GravityTorque(self.mgl, [0.0, 0.0, 1.0])
        tr = simulate([self.I1, self.I1, self.I3], t, omega0, q0, torque=torque, method=method, **options)
        euler = quat_to_euler("ZXZ", tr.q)
        euler[:, 0] = np.unwrap(euler[:, 0])
        euler[:, 2] = np.unwrap(euler[:, 2])
        euler[:, 0] += euler0[0] - euler[0, 0]
        euler[:, 2] += euler0[2] - euler[0, 2]
        return Trajectory(tr.t, tr.q, tr.omega, tr.inertia, meta=tr.meta, zxz_angles=euler)
