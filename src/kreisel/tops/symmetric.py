"""The symmetric free top I1 = I2: regular precession and the body and space cones (Theory §5.7)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._validation import as_float, as_float_array, check_frame, check_principal_moments
from ..dynamics.trajectory import Trajectory
from ..so3 import euler_to_quat
from .euler_top import _check_moments

__all__ = ["SymmetricTop", "Cones"]


@dataclass(frozen=True)
class Cones:
    """Body and space cones of a symmetric free top (Theory §5.7 (6) and its exercise 1).

    Attributes
    ----------
    nutation_angle : float
        θ0, angle between the angular momentum J and the symmetry axis e3.
    space_half_angle : float
        Half-angle of the space cone: angle between ω and J.
    body_half_angle : float
        Half-angle of the body cone: angle between ω and the symmetry axis,
        tan β = (I3/I1) tan θ0.
    relation : str
        ``"space cone inside body cone"`` (oblate, I3 > I1: J lies between e3
        and ω, the body cone rolls with its inside on the space cone),
        ``"body cone outside space cone"`` (prolate, I3 < I1: ω lies between e3
        and J, the cones touch externally) or ``"degenerate"`` (I3 = I1 or
        θ0 ∈ {0, π/2, π}: ω is fixed).
    same_sense : bool
        Whether ω goes round the body cone (seen in the body, about the half of
        the symmetry axis pointing towards J) in the same sense as it goes round
        the space cone about J: true for oblate, false for prolate bodies.
    space_rate : float
        Angular rate of ω (and of e3) about J in space, J/I1 (Theory §5.7: φ̇).
    body_rate : float
        Angular rate of ω about the symmetry axis in the body,
        Ω = (I3 − I1) J cos θ0 / (I1 I3) (Theory §5.7: −ψ̇).

    Examples
    --------
    An oblate top (I3 = 2 I1) with J at θ0 = 0.3 rad from its axis: the body
    cone's half-angle obeys tan β = (I3/I1) tan θ0, and the space cone's is the
    difference β − θ0 (J lies between the axis and ω):

    >>> import numpy as np
    >>> c = SymmetricTop(1.0, 2.0).cones(J=1.0, theta0=0.3)
    >>> round(float(np.tan(c.body_half_angle)), 12), round(float(2.0 * np.tan(0.3)), 12)
    (0.618672499219, 0.618672499219)
    >>> round(c.space_half_angle, 12) == round(c.body_half_angle - 0.3, 12)
    True
    >>> float(c.space_rate), round(c.body_rate, 12)   # J/I1 and (I3 − I1) J cos θ0/(I1 I3)
    (1.0, 0.477668244563)
    """

    nutation_angle: float
    space_half_angle: float
    body_half_angle: float
    relation: str
    same_sense: bool
    space_rate: float
    body_rate: float


class SymmetricTop:
    """Free symmetric top with transverse moment ``I1`` (= I2) and axial moment ``I3``.

    Closed-form regular precession of Theory §5.7 with the angular momentum J
    along space z: φ = J t/I1 + φ0, θ = θ0, ψ = −(I3 − I1) J cos θ0 t/(I1 I3) + ψ0.

    Parameters
    ----------
    I1 : float
        Moment about any transverse axis, kg m².
    I3 : float
        Moment about the symmetry axis, kg m².

    Examples
    --------
    >>> import numpy as np
    >>> top = SymmetricTop(1.0, 2.0)
    >>> top.euler_angles([0.0, 1.0], J=1.0, theta0=np.pi / 3).round(6).tolist()
    [[0.0, 1.047198, 0.0], [1.0, 1.047198, -0.25]]
    """

    I1: float
    I3: float

    def __init__(self, I1: float, I3: float) -> None:
        self.I1, self.I3 = _check_moments((I1, I3), ("I1", "I3"))
        check_principal_moments([self.I1, self.I1, self.I3], "SymmetricTop moments (I1, I1, I3)")

    def __repr__(self) -> str:
        return f"SymmetricTop(I1={self.I1:g}, I3={self.I3:g})"

    @staticmethod
    def _check_state(J: float, theta0: float) -> tuple[float, float]:
        J = as_float(J, "J")
        if J < 0.0:
            raise ValueError(f"J must be the magnitude |J| >= 0, got {J}")
        theta0 = as_float(theta0, "theta0")
        if not 0.0 <= theta0 <= np.pi:
            raise ValueError(f"theta0 must lie in [0, pi], got {theta0}")
        return J, theta0

    def precession_rate(self, J: float) -> float:
        """φ̇ = J/I1: rate of the symmetry axis (and of ω) about J in space, rad/s.

        Independent of I3 and of the tilt θ0 (Theory §5.7).

        Examples
        --------
        >>> float(SymmetricTop(2.0, 3.0).precession_rate(J=5.0))
        2.5
        """
        return as_float(J, "J") / self.I1

    def body_precession_rate(self, J: float, theta0: float) -> float:
        """Ω = (I3 − I1) J cos θ0/(I1 I3): rate of ω about the symmetry axis in the body (= −ψ̇).

        Examples
        --------
        Euler's free wobble of a rigid Earth: with J cos θ0 = I3 ω3, Ω = ω3 (I3 − I1)/I1,
        so a dynamical flattening (I3 − I1)/I1 = 1/305 gives a period of 305
        sidereal days:

        >>> import numpy as np
        >>> earth = SymmetricTop(1.0, 1.0 + 1.0 / 305.0)
        >>> sidereal_day = 86164.0
        >>> spin = 2 * np.pi / sidereal_day
        >>> wobble = earth.body_precession_rate(J=earth.I3 * spin, theta0=0.0)
        >>> round(float(2 * np.pi / wobble / sidereal_day), 6)
        305.0
        """
        J, theta0 = self._check_state(J, theta0)
        return float((self.I3 - self.I1) * J * np.cos(theta0) / (self.I1 * self.I3))

    def euler_angles(self, t: ArrayLike, J: float, theta0: float, phi0: float = 0.0, psi0: float = 0.0) -> NDArray[np.float64]:
        """ZXZ angles (φ, θ, ψ) at times ``t``, shape (n, 3) (Theory §5.7 (3)).

        Examples
        --------
        A prolate top (I3 < I1): θ stays at θ0, φ grows at J/I1 and ψ grows too
        (ψ̇ = −Ω > 0), here at (I1 − I3) J cos θ0/(I1 I3) = 0.5 rad/s:

        >>> import numpy as np
        >>> SymmetricTop(2.0, 1.0).euler_angles([0.0, 1.0, 2.0], J=2.0, theta0=np.pi / 3).round(6).tolist()
        [[0.0, 1.047198, 0.0], [1.0, 1.047198, 0.5], [2.0, 1.047198, 1.0]]
        """
        t = as_float_array(t, "t")
        J, theta0 = self._check_state(J, theta0)
        phi = J * t / self.I1 + as_float(phi0, "phi0")
        psi = -self.body_precession_rate(J, theta0) * t + as_float(psi0, "psi0")
        return np.stack([phi, np.full_like(t, theta0), psi], axis=-1)

    def angular_velocity(self, t: ArrayLike, J: float, theta0: float, phi0: float = 0.0, psi0: float = 0.0,
                         frame: str = "body") -> NDArray[np.float64]:
        """ω at times ``t`` from the chapter's closed forms (Theory §5.7 (4) body, (5) space).

        Body: ω1 = (J sin θ0/I1) sin ψ, ω2 = (J sin θ0/I1) cos ψ, ω3 = J cos θ0/I3;
        space: ω = J/I1 e_z + (1/I3 − 1/I1) J cos θ0 e3 with e3 the symmetry axis.

        Examples
        --------
        The two closed forms describe one motion: the attitude carries body ω to
        space ω, and the body angular momentum (I1 ω1, I1 ω2, I3 ω3) to the fixed J e_z:

        >>> import numpy as np
        >>> from kreisel.so3 import quat_apply
        >>> top = SymmetricTop(1.0, 2.0)
        >>> t = np.linspace(0.0, 3.0, 4)
        >>> body = top.angular_velocity(t, J=1.0, theta0=0.4)
        >>> space = top.angular_velocity(t, J=1.0, theta0=0.4, frame="space")
        >>> q = top.solve(t, J=1.0, theta0=0.4).q
        >>> bool(np.allclose(quat_apply(q, body), space, rtol=0.0, atol=1e-15))
        True
        >>> bool(np.allclose(quat_apply(q, [1.0, 1.0, 2.0] * body), [0.0, 0.0, 1.0], rtol=0.0, atol=1e-15))
        True
        """
        body = check_frame(frame)
        angles = self.euler_angles(t, J, theta0, phi0, psi0)
        phi, theta, psi = np.moveaxis(angles, -1, 0)
        transverse = J * np.sin(theta) / self.I1
        if body:
            return np.stack([transverse * np.sin(psi), transverse * np.cos(psi), J * np.cos(theta) / self.I3], axis=-1)
        axial = (1.0 / self.I3 - 1.0 / self.I1) * J * np.cos(theta)
        e3 = np.stack([np.sin(theta) * np.sin(phi), -np.sin(theta) * np.cos(phi), np.cos(theta)], axis=-1)
        space: NDArray[np.float64] = axial[..., None] * e3 + np.array([0.0, 0.0, J / self.I1])
        return space

    def solve(self, t: ArrayLike, J: float, theta0: float, phi0: float = 0.0, psi0: float = 0.0) -> Trajectory:
        """Trajectory of the regular precession, J along space z.

        Examples
        --------
        >>> tr = SymmetricTop(1.0, 2.0).solve([0.0, 2.0], J=1.0, theta0=0.5)
        >>> tr.q.shape
        (2, 4)
        """
        angles = self.euler_angles(t, J, theta0, phi0, psi0)
        q = euler_to_quat("ZXZ", angles)
        omega = self.angular_velocity(t, J, theta0, phi0, psi0, frame="body")
        meta = {"method": "closed form", "body": "SymmetricTop", "J": J, "theta0": theta0}
        return Trajectory(t, q, omega, [self.I1, self.I1, self.I3], meta=meta, zxz_angles=angles)

    def cones(self, J: float, theta0: float) -> Cones:
        """Half-angles, relative position and senses of the body and space cones.

        Examples
        --------
        >>> c = SymmetricTop(1.0, 2.0).cones(1.0, 0.3)
        >>> c.relation, c.same_sense
        ('space cone inside body cone', True)
        >>> SymmetricTop(2.0, 1.0).cones(1.0, 0.3).relation
        'body cone outside space cone'
        """
        J, theta0 = self._check_state(J, theta0)
        # measure from the half of the symmetry axis on J's side (θ0 folded to [0, π/2])
        folded = min(theta0, np.pi - theta0)
        body_half = np.arctan2(self.I3 * np.sin(folded), self.I1 * np.cos(folded))
        space_half = abs(body_half - folded)
        if self.I3 == self.I1 or folded == 0.0 or folded == 0.5 * np.pi:
            relation = "degenerate"
        elif self.I3 > self.I1:
            relation = "space cone inside body cone"
        else:
            relation = "body cone outside space cone"
        return Cones(
            nutation_angle=theta0,
            space_half_angle=float(space_half),
            body_half_angle=float(body_half),
            relation=relation,
            same_sense=bool(self.I3 > self.I1),
            space_rate=J / self.I1,
            body_rate=float(self.body_precession_rate(J, theta0)),
        )
