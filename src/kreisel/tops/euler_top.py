"""The free (Euler) top solved exactly: ω by Jacobi elliptic functions, attitude by Π.

Theory §5.1–§5.4 (Euler's equations, first integrals, elliptic solution,
tennis-racket theorem); formulas of Theory §5.3 (Landau–Lifshitz §37
form of ω(t); precession angle by the incomplete elliptic integral of the
third kind). Nothing here steps in time: every sample is evaluated directly,
so errors do not grow with t.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import special

from .._validation import as_float_array
from ..dynamics.trajectory import Trajectory
from ..so3 import matrix_to_quat, quat_apply, quat_conjugate, quat_multiply, rotvec_to_quat
from ._elliptic import _pi_reduced

__all__ = ["EulerTop", "SteadyRotation"]


def _check_moments(values, names):
    """Positive finite scalar moments of inertia, as a float array."""
    moments = []
    for value, name in zip(values, names):
        value = as_float_array(value, name)
        if value.ndim != 0 or not value > 0.0:
            raise ValueError(f"{name} must be a positive scalar moment of inertia, got {value!r}")
        moments.append(float(value))
    return np.array(moments)


def _zxz_quat_from_half_angles(cos_half_theta, sin_half_theta, half_sum, half_difference):
    """Quaternion of Rz(φ) Rx(θ) Rz(ψ) from cos, sin of θ/2 and (φ ± ψ)/2.

    Taking the half-angles directly lets θ come from atan2 of the angular
    momentum components (well conditioned for every θ) and lets φ, ψ be
    reduced modulo 4π before halving.
    """
    return np.stack(
        [
            cos_half_theta * np.cos(half_sum),
            sin_half_theta * np.cos(half_difference),
            sin_half_theta * np.sin(half_difference),
            cos_half_theta * np.sin(half_sum),
        ],
        axis=-1,
    )


@dataclass(frozen=True)
class SteadyRotation:
    """Linear stability of the steady rotation about one principal axis (Theory §5.4).

    Attributes
    ----------
    axis : int
        Body axis index (0, 1, 2) in the order the moments were given.
    moment : float
        Its principal moment of inertia.
    kind : str
        ``"stable"`` (Lyapunov stable: extreme moment, or the symmetry axis of a
        symmetric top), ``"unstable"`` (middle moment: exponential growth) or
        ``"neutral"`` (a repeated moment: perturbations are not restored and
        drift away linearly, which Theory §5.4 counts as unstable).
    lyapunov_stable : bool
        ``kind == "stable"``.
    growth_rate : float
        Exponential growth rate σ of a perturbation, rad/s (0 unless unstable):
        σ = |Ω| √((I_k − I_i)(I_j − I_k) / (I_i I_j)) for the middle axis k.
    wobble_frequency : float
        Angular frequency of the small oscillation of ω about a stable axis
        (0 unless stable).

    Examples
    --------
    Spinning at Ω = 2 rad/s about each axis of a (1, 2, 3) body: the largest axis
    wobbles at Ω √((I3 − I1)(I3 − I2)/(I1 I2)) = 2, the middle one diverges at
    σ = Ω √((I2 − I1)(I3 − I2)/(I1 I3)) = 2/√3 (tennis-racket theorem):

    >>> smallest, middle, largest = EulerTop(1.0, 2.0, 3.0).steady_rotations(2.0)
    >>> largest.kind, round(largest.wobble_frequency, 12)
    ('stable', 2.0)
    >>> middle.kind, round(middle.growth_rate, 12), middle.lyapunov_stable
    ('unstable', 1.154700538379, False)
    """

    axis: int
    moment: float
    kind: str
    lyapunov_stable: bool
    growth_rate: float
    wobble_frequency: float


class _Steady:
    """Rotation at constant ω in the body: rest, a principal axis, or a sphere."""

    regime = "steady"

    def __init__(self, omega):
        self.omega0 = omega

    def omega_and_quat(self, t, q0):
        omega = np.broadcast_to(self.omega0, t.shape + (3,))
        q = quat_multiply(q0, rotvec_to_quat(t[:, None] * self.omega0))
        return omega, q

    period = np.inf


class _Symmetric:
    """Regular precession of a symmetric body, closed form (Theory §5.7).

    R(t) = exp(t J/I⊥ · X) R0 exp(t c e_k · X), c = ω_k (1 − I_k/I⊥): precession at
    J/I⊥ about the fixed angular momentum, spin at −c relative to it about the
    symmetry axis k (Theory §5.7: ψ̇ = −(I3 − I1) J cos θ0 / (I1 I3)).
    """

    regime = "symmetric"

    def __init__(self, moments, omega, axis, perpendicular_moment):
        self.moments = moments
        self.omega0 = omega
        self.axis = axis
        self.perpendicular = perpendicular_moment
        self.c = omega[axis] * (1.0 - moments[axis] / perpendicular_moment)
        self.period = np.inf if self.c == 0.0 else 2.0 * np.pi / abs(self.c)

    def omega_and_quat(self, t, q0):
        e = np.zeros(3)
        e[self.axis] = 1.0
        momentum_body0 = self.moments * self.omega0
        momentum_space = quat_apply(q0, momentum_body0)
        body_turn = rotvec_to_quat(t[:, None] * (self.c * e))
        space_turn = rotvec_to_quat(t[:, None] * (momentum_space / self.perpendicular))
        q = quat_multiply(quat_multiply(space_turn, q0), body_turn)
        omega = quat_apply(body_turn, momentum_body0, inverse=True) / self.moments
        return omega, q


class _Asymmetric:
    """I1 < I2 < I3 (sorted, right-handed frame), ω not along a principal axis.

    Theory §5.3: case A (J² > 2TI2, about axis 3), case B (J² < 2TI2,
    about axis 1) and the separatrix J² = 2TI2. Differences D1 = J² − 2TI1,
    D2 = J² − 2TI2, D3 = 2TI3 − J² are formed from ω directly so that m and
    1 − m keep full relative accuracy near the separatrix.
    """

    def __init__(self, moments, omega):
        I1, I2, I3 = moments
        w1, w2, w3 = omega
        self.moments = moments
        self.omega0 = omega
        d1 = I2 * (I2 - I1) * w2**2 + I3 * (I3 - I1) * w3**2
        d2 = I3 * (I3 - I2) * w3**2 - I1 * (I2 - I1) * w1**2
        d3 = I1 * (I3 - I1) * w1**2 + I2 * (I3 - I2) * w2**2
        self.momentum = np.sqrt((I1 * w1) ** 2 + (I2 * w2) ** 2 + (I3 * w3) ** 2)
        self.a1 = np.sqrt(d3 / (I1 * (I3 - I1)))
        self.a3 = np.sqrt(d1 / (I3 * (I3 - I1)))
        if d2 > 0.0:
            self.case = "A"
            self.a2 = np.sqrt(d3 / (I2 * (I3 - I2)))
            self.lam = np.sqrt((I3 - I2) * d1 / (I1 * I2 * I3))
            self.m = (I2 - I1) * d3 / ((I3 - I2) * d1)
            self.m1 = (I3 - I1) * d2 / ((I3 - I2) * d1)
            self.sign = np.sign(w3)
            self.ntilde = I3 * (I2 - I1) / (I1 * (I3 - I2))
            amplitude0 = np.arctan2(w2 / self.a2, self.sign * w1 / self.a1)
            self.regime = "about_largest_axis"
        elif d2 < 0.0:
            self.case = "B"
            self.a2 = np.sqrt(d1 / (I2 * (I2 - I1)))
            self.lam = np.sqrt((I2 - I1) * d3 / (I1 * I2 * I3))
            self.m = (I3 - I2) * d1 / ((I2 - I1) * d3)
            self.m1 = (I3 - I1) * (-d2) / ((I2 - I1) * d3)
            self.sign = np.sign(w1)
            self.ntilde = I3 * d1 / (I1 * d3)
            amplitude0 = np.arctan2(w2 / self.a2, self.sign * w3 / self.a3)
            self.regime = "about_smallest_axis"
        else:
            self.case = "S"
            self.m, self.m1 = 1.0, 0.0
        if self.case != "S" and self.m >= 1.0:
            # 1 − m below half an ulp of 1: ellipj cannot tell it from the separatrix
            self.case = "S"
        if self.case == "S":
            self.regime = "separatrix"
            self.a2 = np.sqrt(d3 / (I2 * (I3 - I2)))
            self.lam = np.sqrt((I3 - I2) * d1 / (I1 * I2 * I3))
            self.ntilde = I3 * (I2 - I1) / (I1 * (I3 - I2))
            self.s1, self.s3 = np.sign(w1), np.sign(w3)
            # sech u0 = |ω1|/A1 and tanh u0 = s1 s3 ω2/A2, combined without cancellation
            self.u0 = np.arcsinh(self.s1 * self.s3 * w2 * self.a1 / (self.a2 * abs(w1)))
            self.half_period = np.inf
            self.period = np.inf
        else:
            self.quarter = special.ellipkm1(self.m1)
            self.half_period = 2.0 * self.quarter / self.lam
            self.period = 2.0 * self.half_period
            self.u0 = special.ellipkinc(amplitude0, self.m)
        self._phi_offset = 0.0
        self._phi_offset = self._precession(np.array([0.0]))[0]

    def _elliptic(self, t):
        """sn, cn, dn, am at u = λt + u0, reduced modulo 2K for late times."""
        u = self.lam * t + self.u0
        j = np.round(u / (2.0 * self.quarter))
        sn, cn, dn, ph = special.ellipj(u - 2.0 * self.quarter * j, self.m)
        parity = 1.0 - 2.0 * np.mod(j, 2.0)
        return parity * sn, parity * cn, dn, ph, j

    def omega(self, t):
        if self.case == "S":
            u = self.lam * t + self.u0
            decay = np.exp(-np.abs(u))
            sech = 2.0 * decay / (1.0 + decay * decay)  # 1/cosh u without overflow
            return np.stack(
                [self.s1 * self.a1 * sech, self.s1 * self.s3 * self.a2 * np.tanh(u), self.s3 * self.a3 * sech], axis=-1
            )
        sn, cn, dn, _, _ = self._elliptic(t)
        if self.case == "A":
            return np.stack([self.sign * self.a1 * cn, self.a2 * sn, self.sign * self.a3 * dn], axis=-1)
        return np.stack([self.sign * self.a1 * dn, self.a2 * sn, self.sign * self.a3 * cn], axis=-1)

    def _precession(self, t):
        """φ(t) − φ(0): J t/I3 + J(I3 − I1)/(I1 I3 λ)·ΔΠ(am u, −ñ | m) (Theory §5.3)."""
        I1, _, I3 = self.moments
        scale = self.momentum * (I3 - I1) / (I1 * I3 * self.lam)
        if self.case == "S":
            # Π(gd u, −ñ | 1) = [u + √ñ atan(√ñ tanh u)]/(1 + ñ): linear growth kept exact
            u = self.lam * t + self.u0
            root = np.sqrt(self.ntilde)
            pi = (u + root * np.arctan(root * np.tanh(u))) / (1.0 + self.ntilde)
        else:
            _, _, _, ph, j = self._elliptic(t)
            pi = _pi_reduced(ph, j, -self.ntilde, self.m)
        return self.momentum * t / I3 + scale * pi - self._phi_offset

    def _spin(self, t, omega):
        """ψ = atan2(I1 ω1, I2 ω2) modulo 4π, continuous in case A where it winds.

        The quaternion has period 4π in ψ, so only the parity of the winding
        number is needed; ψ itself stays the exact algebraic value (a large
        unwrapped ψ would carry |ψ|·eps of error into the direction of J).
        """
        I1, I2, _ = self.moments
        psi = np.arctan2(I1 * omega[:, 0], I2 * omega[:, 1])
        if self.case != "A":
            return psi
        sn, cn, _, ph, j = self._elliptic(t)
        a, b = I1 * self.a1, I2 * self.a2
        # continuous atan2(b sin α, a cos α) with α = am u = ph + jπ
        xi = ph + j * np.pi + np.arctan2((b - a) * sn * cn, a * cn * cn + b * sn * sn)
        winding = np.round((self.sign * (0.5 * np.pi - xi) - psi) / (2.0 * np.pi))
        return psi + 2.0 * np.pi * np.mod(winding, 2.0)

    def omega_and_quat(self, t, q0):
        I1, I2, I3 = self.moments
        omega = self.omega(t)
        t_all = np.concatenate([[0.0], t])
        omega_all = np.concatenate([self.omega0[None, :], omega])
        transverse = np.hypot(I1 * omega_all[:, 0], I2 * omega_all[:, 1])
        half_theta = 0.5 * np.arctan2(transverse, I3 * omega_all[:, 2])
        # the quaternion has period 4π in φ; reducing keeps (φ ± ψ)/2 exact to rounding
        phi = np.remainder(self._precession(t_all), 4.0 * np.pi)
        psi = self._spin(t_all, omega_all)
        q_model = _zxz_quat_from_half_angles(
            np.cos(half_theta), np.sin(half_theta), 0.5 * (phi + psi), 0.5 * (phi - psi)
        )
        # constant rotation from the frame with J along z to the actual space frame
        c = quat_multiply(q0, quat_conjugate(q_model[0]))
        return omega, quat_multiply(c, q_model[1:])


class EulerTop:
    """The free rigid body with principal moments ``I1, I2, I3`` (Theory §5, Euler top).

    Moments may be given in any order and may coincide (symmetric and
    spherical bodies); internally they are sorted by a proper rotation of the
    body axes, and results come back in the axes the user gave.

    Parameters
    ----------
    I1, I2, I3 : float
        Principal moments of inertia about the fixed point, kg m².

    Examples
    --------
    >>> import numpy as np
    >>> top = EulerTop(1.0, 2.0, 3.0)
    >>> tr = top.solve(np.linspace(0.0, 10.0, 5), [0.1, 1.0, 0.1])
    >>> bool(np.allclose(tr.energy, tr.energy[0], rtol=1e-13, atol=0.0))
    True
    >>> top.regime([0.1, 1.0, 0.1])
    'about_largest_axis'
    """

    def __init__(self, I1, I2, I3):
        self.moments = _check_moments((I1, I2, I3), ("I1", "I2", "I3"))
        order = np.argsort(self.moments, kind="stable")
        permutation = np.zeros((3, 3))
        permutation[order, np.arange(3)] = 1.0
        if np.linalg.det(permutation) < 0.0:
            # an odd permutation is a reflection: flip the new third axis to keep a rotation
            permutation[:, 2] *= -1.0
        # columns of P are the sorted axes in the user's body axes: ω_user = P ω_sorted
        self._permutation = permutation
        self._q_permutation = matrix_to_quat(permutation)
        self._sorted = self.moments[order]

    def __repr__(self):
        return "EulerTop({:g}, {:g}, {:g})".format(*self.moments)

    # ---- first integrals -------------------------------------------------------------
    def energy(self, omega):
        """Kinetic energy T = ½ Σ I_i ω_i² for body ω (Theory §5.2), broadcast over ``omega``.

        Examples
        --------
        >>> import numpy as np
        >>> top = EulerTop(1.0, 2.0, 3.0)
        >>> float(top.energy([1.0, 1.0, 1.0]))   # ½ (1 + 2 + 3)
        3.0

        T is a first integral: along the exact motion it stays at its initial value.

        >>> tr = top.solve(np.linspace(0.0, 20.0, 9), [0.3, 0.2, 1.0])
        >>> T = top.energy(tr.omega)
        >>> round(float(T[0]), 12), bool(np.allclose(T, T[0], rtol=1e-13, atol=0.0))
        (1.585, True)
        """
        omega = as_float_array(omega, "omega", tail=(3,))
        return 0.5 * np.sum(self.moments * omega**2, axis=-1)

    def angular_momentum(self, omega):
        """|J| = √(Σ I_i² ω_i²) for body ω (Theory §5.2).

        Examples
        --------
        >>> import numpy as np
        >>> top = EulerTop(1.0, 2.0, 3.0)
        >>> round(float(top.angular_momentum([1.0, 1.0, 1.0]) ** 2), 12)   # 1 + 4 + 9
        14.0

        Any motion satisfies 2T I1 <= J² <= 2T I3 (the polhode exists), and J² is
        compared with 2T I2 to tell the two tumbling regimes apart:

        >>> omega = [0.3, 0.2, 1.0]
        >>> J2, T = float(top.angular_momentum(omega)) ** 2, float(top.energy(omega))
        >>> 2 * T * 1.0 <= J2 <= 2 * T * 3.0, J2 > 2 * T * 2.0, top.regime(omega)
        (True, True, 'about_largest_axis')
        """
        omega = as_float_array(omega, "omega", tail=(3,))
        return np.sqrt(np.sum((self.moments * omega) ** 2, axis=-1))

    # ---- classification -------------------------------------------------------------
    def _motion(self, omega):
        omega = np.asarray(omega, dtype=np.float64)
        sorted_moments = self._sorted
        if sorted_moments[0] == sorted_moments[2]:
            return _Steady(omega)
        if sorted_moments[0] == sorted_moments[1] or sorted_moments[1] == sorted_moments[2]:
            repeated = sorted_moments[1]
            axis = int(np.flatnonzero(self.moments != repeated)[0])
            motion = _Symmetric(self.moments, omega, axis, repeated)
            return motion if np.any(omega != 0.0) else _Steady(omega)
        omega_sorted = self._permutation.T @ omega
        if np.count_nonzero(omega_sorted) <= 1:
            return _Steady(omega)
        return _Asymmetric(sorted_moments, omega_sorted)

    def regime(self, omega0):
        """Kind of motion started by body ω0.

        Returns one of ``"steady"`` (rest, rotation about a principal axis, or
        any rotation of a spherical body), ``"symmetric"`` (regular precession),
        ``"about_largest_axis"`` (J² > 2T I_mid: ω circulates about the axis of
        largest moment), ``"about_smallest_axis"`` (J² < 2T I_mid) or
        ``"separatrix"`` (J² = 2T I_mid).

        Examples
        --------
        >>> EulerTop(3.0, 4.0, 6.0).regime([2.0, 0.3, 1.0])
        'separatrix'
        """
        omega0 = as_float_array(omega0, "omega0", tail=(3,))
        if omega0.ndim != 1:
            raise ValueError(f"omega0 must have shape (3,), got {omega0.shape}")
        return self._motion(omega0).regime

    def omega_period(self, omega0):
        """Period of ω(t) in the body, seconds: 4K(m)/λ (asymmetric), 2π/|Ω| (symmetric).

        Infinite for steady rotation and on the separatrix.

        Examples
        --------
        >>> top = EulerTop(1.0, 1.0, 3.0)
        >>> round(float(top.omega_period([1.0, 0.0, 0.5])), 12)  # Ω = (I3 − I1) ω3 / I1 = 1
        6.28318530718
        """
        omega0 = as_float_array(omega0, "omega0", tail=(3,))
        if omega0.ndim != 1:
            raise ValueError(f"omega0 must have shape (3,), got {omega0.shape}")
        return float(self._motion(omega0).period)

    def dzhanibekov_flip_time(self, omega0):
        """Time between two successive flips of a body spun near its middle axis, seconds.

        Half the period of ω: the middle-axis component ω_mid ∝ sn(λt + u0)
        reverses every 2K(m)/λ (Dzhanibekov effect, Theory §5.4). Near the
        separatrix, 1 − m → 0 and 2K/λ ≈ ln(16/(1 − m))/λ grows logarithmically.

        Examples
        --------
        >>> top = EulerTop(1.0, 2.0, 3.0)
        >>> t_flip = top.dzhanibekov_flip_time([1e-3, 1.0, 1e-3])
        >>> round(t_flip, 6)
        27.530841
        """
        omega0 = as_float_array(omega0, "omega0", tail=(3,))
        motion = self._motion(omega0)
        if not isinstance(motion, _Asymmetric):
            raise ValueError("omega0 must start a tumbling motion of an asymmetric body (no flips otherwise)")
        return float(motion.half_period)

    # ---- stability (tennis-racket theorem) ------------------------------------------
    def steady_rotations(self, spin=1.0):
        """Stability of steady rotation at rate ``spin`` about each principal axis (Theory §5.4).

        The linearised Euler equations about ω = Ω e_k give
        ω̈_i = −Ω² (I_k − I_i)(I_k − I_j)/(I_i I_j) ω_i for the two other axes:
        oscillation about the largest and smallest axes, exponential growth about
        the middle one (tennis-racket theorem).

        Parameters
        ----------
        spin : float
            Rotation rate Ω, rad/s.

        Returns
        -------
        tuple of SteadyRotation
            One per axis, in the order the moments were given.

        Examples
        --------
        >>> [s.kind for s in EulerTop(2.0, 1.0, 3.0).steady_rotations()]
        ['unstable', 'stable', 'stable']
        >>> round(EulerTop(1.0, 2.0, 3.0).steady_rotations(1.0)[1].growth_rate, 12)
        0.57735026919
        """
        spin = float(as_float_array(spin, "spin"))
        result = []
        for k in range(3):
            i, j = [a for a in range(3) if a != k]
            Ii, Ij, Ik = self.moments[i], self.moments[j], self.moments[k]
            curvature = (Ik - Ii) * (Ik - Ij) / (Ii * Ij)
            if curvature > 0.0:
                kind, growth, wobble = "stable", 0.0, abs(spin) * np.sqrt(curvature)
            elif curvature < 0.0:
                kind, growth, wobble = "unstable", abs(spin) * np.sqrt(-curvature), 0.0
            else:
                kind, growth, wobble = "neutral", 0.0, 0.0
            result.append(SteadyRotation(k, float(Ik), kind, kind == "stable", float(growth), float(wobble)))
        return tuple(result)

    # ---- exact solution ------------------------------------------------------------
    def omega(self, t, omega0):
        """Body angular velocity ω′(t) alone, without the attitude (Theory §5.3).

        The same exact ω as :meth:`solve` returns, for a fraction of its cost:
        no elliptic integral of the third kind is evaluated. Fitting ω to
        measured gyroscope data calls this many times.

        Parameters
        ----------
        t : (n,) array_like
            Times in seconds (any order; t = 0 is the initial state).
        omega0 : (3,) array_like
            Initial body angular velocity ω′(0), rad/s.

        Returns
        -------
        (n, 3) ndarray
            Body angular velocity at ``t``, rad/s.

        Examples
        --------
        >>> import numpy as np
        >>> top = EulerTop(1.0, 2.0, 3.0)
        >>> t = np.linspace(0.0, 5.0, 4)
        >>> bool(np.allclose(top.omega(t, [0.3, 0.2, 1.0]), top.solve(t, [0.3, 0.2, 1.0]).omega, rtol=0, atol=1e-14))
        True
        """
        t = as_float_array(t, "t")
        if t.ndim != 1:
            raise ValueError(f"t must be one-dimensional, got shape {t.shape}")
        omega0 = as_float_array(omega0, "omega0", tail=(3,))
        if omega0.ndim != 1:
            raise ValueError(f"omega0 must have shape (3,), got {omega0.shape}")
        motion = self._motion(omega0)
        if isinstance(motion, _Asymmetric):
            return motion.omega(t) @ self._permutation.T
        return np.array(motion.omega_and_quat(t, np.array([1.0, 0.0, 0.0, 0.0]))[0])

    def solve(self, t, omega0, q0=None):
        """Exact motion of the free top at times ``t`` (no time stepping).

        Body ω(t) by Jacobi elliptic functions (both regimes, the separatrix,
        symmetric and spherical bodies), attitude with J along space z given by
        cos θ = I3 ω3/J, ψ = atan2(I1 ω1, I2 ω2) and φ(t) from the incomplete
        elliptic integral of the third kind (Theory §5.3), then a constant rotation
        carrying z to the actual direction of J and matching ``q0`` at t = 0.

        Parameters
        ----------
        t : (n,) array_like
            Times in seconds (any order; t = 0 is the initial state).
        omega0 : (..., 3) array_like
            Initial body angular velocity ω′(0), rad/s; leading axes are a batch.
        q0 : (..., 4) array_like, optional
            Initial attitude (body -> space, scalar first); identity by default.

        Returns
        -------
        Trajectory
            ``q`` (batch..., n, 4) and ``omega`` (batch..., n, 3), with
            ``meta["regime"]`` naming the kind of motion (for a single body).
            Energy and space angular momentum are conserved to rounding
            (~1e-15 relative, independent of t); the phase carries the unavoidable
            absolute error |t|·λ·eps of evaluating λt.

        Examples
        --------
        >>> import numpy as np
        >>> top = EulerTop(1.0, 2.0, 3.0)
        >>> tr = top.solve([0.0, 1e5], [0.3, 0.2, 1.0])
        >>> bool(np.allclose(tr.energy, tr.energy[0], rtol=1e-12))
        True
        """
        t = as_float_array(t, "t")
        if t.ndim != 1:
            raise ValueError(f"t must be one-dimensional, got shape {t.shape}")
        omega0 = as_float_array(omega0, "omega0", tail=(3,))
        if q0 is None:
            q0 = np.array([1.0, 0.0, 0.0, 0.0])
        q0 = as_float_array(q0, "q0", tail=(4,))
        norms = np.linalg.norm(q0, axis=-1)
        if np.any(np.abs(norms - 1.0) > 1e-6):
            raise ValueError("q0 must be unit quaternions (|q0| = 1 within 1e-6)")
        q0 = q0 / norms[..., None]
        batch = np.broadcast_shapes(omega0.shape[:-1], q0.shape[:-1])
        omega0 = np.broadcast_to(omega0, batch + (3,))
        q0 = np.broadcast_to(q0, batch + (4,))
        q_out = np.empty(batch + (t.size, 4))
        omega_out = np.empty(batch + (t.size, 3))
        regimes = np.empty(batch, dtype=object)
        for index in np.ndindex(*batch):
            motion = self._motion(omega0[index])
            regimes[index] = motion.regime
            if isinstance(motion, _Asymmetric):
                # work in the sorted right-handed axes: R_sorted = R_user P
                q0_sorted = quat_multiply(q0[index], self._q_permutation)
                omega_sorted, q_sorted = motion.omega_and_quat(t, q0_sorted)
                omega_out[index] = omega_sorted @ self._permutation.T
                q_out[index] = quat_multiply(q_sorted, quat_conjugate(self._q_permutation))
            else:
                omega_out[index], q_out[index] = motion.omega_and_quat(t, q0[index])
        meta = {"method": "exact", "body": "EulerTop", "moments": tuple(self.moments)}
        meta["regime"] = regimes[()] if batch == () else regimes.tolist()
        return Trajectory(t, q_out, omega_out, self.moments, meta=meta)
