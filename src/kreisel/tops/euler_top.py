"""The free (Euler) top solved exactly: ω by Jacobi elliptic functions, attitude by Π.

Theory §5.1–§5.4 (Euler's equations, first integrals, elliptic solution,
tennis-racket theorem); formulas of Theory §5.3 (Landau–Lifshitz §37
form of ω(t); precession angle by the incomplete elliptic integral of the
third kind). Nothing here steps in time: every sample is evaluated directly,
so errors do not grow with t.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled.chunks import SAMPLES_PER_CALL
from .._html import html_table, number
from .._validation import as_float, as_float_array, check_principal_moments, refuse_long_turn, sample_times
from ..dynamics.trajectory import Trajectory
from ..so3._coercion import as_quaternion
from .._norms import norm
from . import _free_top

__all__ = ["EulerTop", "SteadyRotation", "Regime", "SolutionAccuracy", "solve_free_batch"]

_EPS = float(np.finfo(float).eps)


class Regime(enum.IntEnum):
    """Kind of free motion; ``str(regime)``/``.label`` is the name :meth:`EulerTop.regime` returns.

    Examples
    --------
    >>> Regime.SEPARATRIX.label, str(Regime.ABOUT_LARGEST_AXIS)
    ('separatrix', 'about_largest_axis')
    >>> EulerTop(1.0, 2.0, 3.0).regime([0.1, 1.0, 0.0]) == Regime.ABOUT_SMALLEST_AXIS.label
    True
    """

    STEADY = _free_top.STEADY
    SYMMETRIC = _free_top.SYMMETRIC
    ABOUT_LARGEST_AXIS = _free_top.ABOUT_LARGEST_AXIS
    ABOUT_SMALLEST_AXIS = _free_top.ABOUT_SMALLEST_AXIS
    SEPARATRIX = _free_top.SEPARATRIX

    @property
    def label(self) -> str:
        """``"steady"``, ``"symmetric"``, ``"about_largest_axis"``, ``"about_smallest_axis"``, ``"separatrix"``.

        Examples
        --------
        >>> Regime.STEADY.label
        'steady'
        """
        return self.name.lower()

    def __str__(self) -> str:
        return self.label


@dataclass(frozen=True)
class SolutionAccuracy:
    """How close a motion is to the separatrix, and the error the exact solution guarantees there.

    Attributes
    ----------
    regime : str
        As :meth:`EulerTop.regime`.
    separatrix_distance : float
        (J² − 2T I_mid)/(2T I_mid), formed without cancellation (0 on the
        separatrix, NaN for symmetric and steady motion).
    m1 : float
        Complementary parameter 1 − m of the elliptic functions.
    omega_error : float
        Bound on max |Δω|/|ω0| over |t| <= ``duration``.
    attitude_error : float
        Bound on the attitude error over |t| <= ``duration``, rad.

    Examples
    --------
    Next to the middle axis of a (1, 2, 3) body, 5e-11 from the separatrix, the
    bounds stay near 1e-13 over 20 s:

    >>> acc = EulerTop(1.0, 2.0, 3.0).accuracy([1e-5, 1.0, 1e-5], duration=20.0)
    >>> acc.regime, f"{acc.separatrix_distance:.1e}", acc.omega_error < 1e-12, acc.attitude_error < 1e-12
    ('about_largest_axis', '5.0e-11', True, True)
    """

    regime: str
    separatrix_distance: float
    m1: float
    omega_error: float
    attitude_error: float


def _check_moments(values: tuple[ArrayLike, ...], names: tuple[str, ...]) -> NDArray[np.float64]:
    """Positive finite scalars (moments of inertia, mgl), as a float array, naming the one that is not.

    Whether the moments together form a body is :func:`check_principal_moments`'s
    rule, applied by each top to its three principal moments.
    """
    moments = []
    for given, name in zip(values, names):
        value = as_float_array(given, name)
        if value.ndim != 0 or not value > 0.0:
            raise ValueError(f"{name} must be a single positive number, got {value.tolist()!r}")
        moments.append(float(value))
    return np.array(moments)


def _zxz_quat_from_half_angles(cos_half_theta: NDArray[np.float64], sin_half_theta: NDArray[np.float64], half_sum: NDArray[np.float64],
                               half_difference: NDArray[np.float64]) -> NDArray[np.float64]:
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


class EulerTop:
    """The free rigid body with principal moments ``I1, I2, I3`` (Theory §5, Euler top).

    Moments may be given in any order and may coincide (symmetric and
    spherical bodies); internally they are sorted by a proper rotation of the
    body axes, and results come back in the axes the user gave.

    Parameters
    ----------
    I1, I2, I3 : float
        Principal moments of inertia about the fixed point, kg m².
    allow_unphysical : bool
        Accept positive moments that violate a triangle inequality
        I_i <= I_j + I_k (refused otherwise, by the rule of every entry point:
        user guide, "Which inertia input is accepted"), e.g. the textbook
        body I = (2, 1, 2/3).

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

    def __init__(self, I1: float, I2: float, I3: float, allow_unphysical: bool = False) -> None:
        moments = _check_moments((I1, I2, I3), ("I1", "I2", "I3"))
        self.moments = check_principal_moments(moments, "EulerTop moments", allow_unphysical=allow_unphysical)
        self.allow_unphysical = bool(allow_unphysical)

    def __repr__(self) -> str:
        return "EulerTop({:g}, {:g}, {:g})".format(*self.moments)

    def _repr_html_(self) -> str:
        axis = "xyz"[int(np.argsort(self.moments, kind="stable")[1])]
        rows = [("moments I1, I2, I3", number(self.moments) + " kg m²")]
        if len(set(self.moments.tolist())) == 3:
            rows.append(("unstable axis (intermediate moment)", axis))
        else:
            rows.append(("symmetry", "spherical" if self.moments.min() == self.moments.max() else "symmetric"))
        return html_table("EulerTop (free rigid body)", rows, note="exact solution; quaternions scalar-first, R maps body to space")

    # ---- first integrals -------------------------------------------------------------
    def energy(self, omega: ArrayLike) -> NDArray[np.float64]:
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
        energy: NDArray[np.float64] = 0.5 * np.sum(self.moments * omega**2, axis=-1)
        return energy

    def angular_momentum(self, omega: ArrayLike) -> NDArray[np.float64]:
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
        magnitude: NDArray[np.float64] = np.sqrt(np.sum((self.moments * omega) ** 2, axis=-1))
        return magnitude

    # ---- classification -------------------------------------------------------------
    def _info(self, omega0: ArrayLike) -> dict[str, Any]:
        """:data:`_free_top.INFO_FIELDS` of one initial state, as a dict."""
        omega0 = as_float_array(omega0, "omega0", tail=(3,))
        if omega0.ndim != 1:
            raise ValueError(f"omega0 must have shape (3,), got {omega0.shape}")
        info = np.empty((1, len(_free_top.INFO_FIELDS)))
        _free_top.setup_info(self.moments[None, :], omega0[None, :], info)
        values = dict(zip(_free_top.INFO_FIELDS, info[0].tolist()))
        values["regime"] = Regime(int(values["regime"]))
        return values

    def regime(self, omega0: ArrayLike) -> str:
        """Kind of motion started by body ω0.

        Returns one of ``"steady"`` (rest, rotation about a principal axis, or
        any rotation of a spherical body), ``"symmetric"`` (regular precession),
        ``"about_largest_axis"`` (J² > 2T I_mid: ω circulates about the axis of
        largest moment), ``"about_smallest_axis"`` (J² < 2T I_mid) or
        ``"separatrix"`` (J² = 2T I_mid exactly, decided without rounding:
        J² − 2T I_mid is formed as a difference of two squares). The names
        are the labels of :class:`Regime`.

        Examples
        --------
        >>> EulerTop(3.0, 4.0, 6.0).regime([2.0, 0.3, 1.0])
        'separatrix'
        >>> EulerTop(1.0, 2.0, 3.0).regime([1e-300, 1.0, 0.0])   # next to the middle axis
        'about_smallest_axis'
        """
        regime: Regime = self._info(omega0)["regime"]
        return regime.label

    def omega_period(self, omega0: ArrayLike) -> float:
        """Period of ω(t) in the body, seconds: 4K(m)/λ (asymmetric), 2π/|Ω| (symmetric).

        Infinite for steady rotation and on the separatrix.

        Examples
        --------
        >>> top = EulerTop(2.0, 2.0, 3.0)
        >>> round(float(top.omega_period([1.0, 0.0, 2.0])), 12)  # Ω = (I3 − I1) ω3 / I1 = 1
        6.28318530718
        """
        info = self._info(omega0)
        if info["regime"] == Regime.SEPARATRIX:
            return float("inf")
        return float(info["period"])

    def dzhanibekov_flip_time(self, omega0: ArrayLike) -> float:
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
        info = self._info(omega0)
        if info["regime"] in (Regime.STEADY, Regime.SYMMETRIC):
            raise ValueError("omega0 must start a tumbling motion of an asymmetric body (no flips otherwise)")
        if info["regime"] == Regime.SEPARATRIX:
            return float("inf")
        return float(2.0 * info["quarter_period"] / info["rate"])

    def separatrix_distance(self, omega0: ArrayLike) -> float:
        """(J² − 2T I_mid)/(2T I_mid) of body ω0, without cancellation (Theory §5.3).

        Positive about the largest axis, negative about the smallest, zero on
        the separatrix; NaN for a symmetric or steady motion (no separatrix).

        Examples
        --------
        >>> top = EulerTop(1.0, 2.0, 3.0)
        >>> f"{top.separatrix_distance([1e-8, 1.0, 0.0]):.6e}"    # −I1(I2 − I1)ω1²/(2T I2)
        '-2.500000e-17'
        """
        info = self._info(omega0)
        if info["regime"] in (Regime.STEADY, Regime.SYMMETRIC):
            return float("nan")
        return float(info["separatrix_distance"])

    def accuracy(self, omega0: ArrayLike, duration: float = 20.0) -> SolutionAccuracy:
        """Distance from the separatrix and the error bound of :meth:`solve` over |t| <= ``duration``.

        The solution evaluates ω and the attitude from the elliptic phase
        u = λt + u0 carried as nK + r with |r| <= K/2; rounding enters as a
        phase error of a few ulp of (λ|t| + K) and as the few-ulp errors of the
        Jacobi functions and Carlson integrals, both checked against 30-digit
        references. The bounds below are that first-order analysis:
        |Δω|/|ω0| <= 8 eps (8 + λ|t| + K + |u0|)(1 + κ) with κ >= max |dω/du|/|ω0|, and the
        attitude error <= 8 eps (8 + λ|t| + K + |u0|)(1 + J(I3 − I1)/(I1 I3 λ)) +
        2 eps J|t|/I3. They do not grow as the motion approaches the separatrix
        beyond the logarithmic growth of K.

        Parameters
        ----------
        omega0 : (3,) array_like
            Initial body angular velocity, rad/s.
        duration : float
            Largest |t| of interest, seconds.

        Returns
        -------
        SolutionAccuracy

        Examples
        --------
        >>> acc = EulerTop(1.0, 2.0, 3.0).accuracy([0.0, 1.0, 1e-6], duration=20.0)
        >>> acc.regime, acc.attitude_error < 1e-12
        ('about_largest_axis', True)
        """
        info = self._info(omega0)
        duration = abs(as_float(duration, "duration"))
        omega0 = np.asarray(omega0, dtype=float)
        scale = float(np.max(np.abs(omega0))) or 1.0
        J = float(self.angular_momentum(omega0))
        regime = info["regime"]
        I = np.sort(self.moments)
        if regime in (Regime.STEADY, Regime.SYMMETRIC):
            turns = duration * scale
            return SolutionAccuracy(regime.label, float("nan"), float("nan"), 4.0 * _EPS, 4.0 * _EPS * (4.0 + turns))
        lam, k = info["rate"], info["quarter_period"]
        k = 0.0 if np.isinf(k) else k
        phase = 8.0 * _EPS * (8.0 + lam * duration + k + abs(info["phase0"]))
        # |dω/du| = |ω̇|/λ with |ω̇_i| = |I_j − I_k| |ω_j ω_k|/I_i <= (I3 − I1)|ω|²/(2 I1), |ω|² <= 2T/I1
        two_t = 2.0 * float(self.energy(omega0))
        kappa = np.sqrt(3.0) * (I[2] - I[0]) / (2.0 * I[0]) * two_t / I[0] / (lam * np.linalg.norm(omega0))
        precession = J * (I[2] - I[0]) / (I[0] * I[2] * lam)
        return SolutionAccuracy(
            regime.label,
            info["separatrix_distance"],
            info["m1"],
            float(phase * (1.0 + kappa)),
            float(phase * (1.0 + precession) + 2.0 * _EPS * J * duration / I[2]),
        )

    # ---- stability (tennis-racket theorem) ------------------------------------------
    def steady_rotations(self, spin: float = 1.0) -> tuple[SteadyRotation, ...]:
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
        spin = as_float(spin, "spin")
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
    def omega(self, t: ArrayLike, omega0: ArrayLike) -> NDArray[np.float64]:
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
        out = np.empty((t.size, 3))
        _free_top.body_omega(self.moments, np.ascontiguousarray(omega0), np.ascontiguousarray(t), out)
        return out

    def solve(self, t: ArrayLike, omega0: ArrayLike, q0: ArrayLike | None = None) -> Trajectory:
        """Exact motion of the free top at times ``t`` (no time stepping).

        Body ω(t) by Jacobi elliptic functions (both regimes, the separatrix,
        symmetric and spherical bodies), attitude with J along space z given by
        cos θ = I3 ω3/J, ψ = atan2(I1 ω1, I2 ω2) and φ(t) from the incomplete
        elliptic integral of the third kind (Theory §5.3), then a constant rotation
        carrying z to the actual direction of J and matching ``q0`` at t = 0.
        Everything is written in the complementary parameter m1 = 1 − m, so the
        result stays exact to rounding next to the separatrix (see
        :meth:`accuracy`); a batch of initial states is one compiled, parallel
        call.

        Parameters
        ----------
        t : (n,) array_like
            Times in seconds (any order; t = 0 is the initial state).
        omega0 : (..., 3) array_like
            Initial body angular velocity ω′(0), rad/s; leading axes are a batch.
        q0 : Rotation or array_like, optional
            Initial attitude (body -> space): a ``Rotation``, matrices ``(..., 3, 3)`` or
            scalar-first quaternions ``(..., 4)`` (normalised); identity by default.

        Returns
        -------
        Trajectory
            ``q`` (batch..., n, 4) and ``omega`` (batch..., n, 3), with
            ``meta["regime"]`` naming the kind of motion (a list for a batch).
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
        return _solve(self.moments, t, omega0, q0, meta_body="EulerTop")


def _check_inputs(t: ArrayLike, omega0: ArrayLike,
                  q0: ArrayLike | None) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    t = sample_times(t)
    omega0 = as_float_array(omega0, "omega0", tail=(3,))
    q0 = np.array([1.0, 0.0, 0.0, 0.0]) if q0 is None else as_quaternion(q0, "q0")
    return t, omega0, q0


def _solve(moments: NDArray[np.float64], t: ArrayLike, omega0: ArrayLike, q0: ArrayLike | None, meta_body: str) -> Trajectory:
    """Broadcast (bodies, ω0, q0), run the compiled samples, wrap a Trajectory."""
    t, omega0, q0 = _check_inputs(t, omega0, q0)
    try:
        batch = np.broadcast_shapes(moments.shape[:-1], omega0.shape[:-1], q0.shape[:-1])
    except ValueError:
        raise ValueError(f"the batch shapes of bodies {moments.shape}, omega0 {omega0.shape} and q0 {q0.shape} "
                         "do not broadcast") from None
    # |ω| <= |ω0| I_max/I_min: beyond ~1e15 rad a turn's rounding (1e-16 of it) is more than 0.1 rad
    with np.errstate(over="ignore"):
        turn = np.max(np.abs(t), initial=0.0) * norm(omega0) * (np.max(moments, axis=-1) / np.min(moments, axis=-1))
    refuse_long_turn(float(np.max(turn, initial=0.0)), "t and omega0", "the body turns through up to")
    # the motion depends on the moments' ratios only: a power of two (exact) brings the largest to ~1
    scaled = np.ldexp(moments, -np.frexp(np.max(moments, axis=-1, keepdims=True))[1])
    count = int(np.prod(batch, dtype=np.int64))
    # writable copies: the arrays of EulerTop.regime's call, so that both load one compiled setup_info
    flat = [np.array(np.broadcast_to(a, batch + a.shape[-1:]), order="C").reshape(count, -1)
            for a in (scaled, omega0, q0)]
    info = np.empty((count, len(_free_top.INFO_FIELDS)))
    _free_top.setup_info(flat[0], flat[1], info)
    omega = np.empty((count, t.size, 3))
    quat = np.empty((count, t.size, 4))
    # compiled calls of at most SAMPLES_PER_CALL samples (each sample is computed on its own: the
    # same bits), so that Ctrl-C stops 3e7 samples at once instead of after the whole call
    if count == 1 or t.size * 2 > SAMPLES_PER_CALL:
        for b in range(count):
            # the function of the body's regime: a first run compiles that regime's code only
            samples = _free_top.body_in_regime(int(info[b, 0]))
            for s in range(0, t.size, SAMPLES_PER_CALL):
                e = s + SAMPLES_PER_CALL
                samples(flat[0][b], flat[1][b], flat[2][b], t[s:e], omega[b, s:e], quat[b, s:e])
    else:
        group = SAMPLES_PER_CALL // t.size
        for b in range(0, count, group):
            _free_top.batch_samples(flat[0][b:b + group], flat[1][b:b + group], flat[2][b:b + group], t,
                                    omega[b:b + group], quat[b:b + group])
    labels = [Regime(int(code)).label for code in info[:, 0]]
    meta: dict[str, Any] = {"method": "exact", "body": meta_body}
    if moments.ndim == 1:
        meta["moments"] = tuple(moments.tolist())
    meta["regime"] = labels[0] if batch == () else np.array(labels, dtype=object).reshape(batch).tolist()
    return Trajectory(t, quat.reshape(batch + (t.size, 4)), omega.reshape(batch + (t.size, 3)),
                      np.broadcast_to(moments, batch + (3,)) if moments.ndim > 1 else moments, meta=meta)


def solve_free_batch(bodies: ArrayLike, t: ArrayLike, omega0: ArrayLike, q0: ArrayLike | None = None,
                     allow_unphysical: bool = False) -> Trajectory:
    """Exact free motion of many bodies at once: one compiled, parallel call (batch axes first).

    The exact counterpart of :func:`kreisel.simulate_batch` for torque-free
    bodies: every body is solved as :meth:`EulerTop.solve` would, with no
    Python loop over bodies.

    Parameters
    ----------
    bodies : (..., 3) array_like
        Principal moments of each body (body axes are principal; any order).
    t : (n,) array_like
        Output times shared by all bodies, seconds.
    omega0 : (..., 3) array_like
        Initial body angular velocities, broadcast against ``bodies``.
    q0 : Rotation or array_like, optional
        Initial attitudes (default identity), as in :meth:`EulerTop.solve`, broadcast likewise.
    allow_unphysical : bool
        Accept moments that violate a triangle inequality.

    Returns
    -------
    Trajectory
        Arrays ``(batch..., n, 3 or 4)``; ``meta["regime"]`` per body.

    Examples
    --------
    >>> import numpy as np
    >>> bodies = np.array([[1.0, 2.0, 3.0], [2.0, 2.0, 3.0]])
    >>> tr = solve_free_batch(bodies, np.linspace(0.0, 1.0, 3), [0.1, 1.0, 0.1])
    >>> tr.omega.shape, tr.meta["regime"]
    ((2, 3, 3), ['about_largest_axis', 'symmetric'])
    """
    moments = check_principal_moments(bodies, "bodies", allow_unphysical=allow_unphysical)
    return _solve(moments, t, omega0, q0, meta_body="EulerTop")
