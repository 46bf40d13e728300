"""The ``Rotation`` object: a batch of rotations with every representation (Theory §1, §2, appendix).

A ``Rotation`` holds unit quaternions (scalar first) of any batch shape and
converts to and from all representations of :mod:`kreisel.so3`. ``a * b``
composes (``b`` first, then ``a``): ``(a * b).as_matrix() == a.as_matrix() @ b.as_matrix()``.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled.outputs import deliver, takes_out
from .._html import html_table, number
from .._validation import as_float_array, batch_shape, check_flag
from . import alignment as _alignment
from . import davenport as _davenport
from . import euler as _euler
from . import groups as _groups
from . import interpolation as _interp
from . import matrix as _matrix
from . import quaternion as _quat
from . import rodrigues as _rodrigues
from . import rotvec as _rotvec
from . import su2 as _su2
from ._batch import QuaternionBatch

if TYPE_CHECKING:
    from scipy.spatial.transform import Rotation as ScipyRotation

__all__ = ["Rotation"]


def _scalar_first(q: ArrayLike, scalar_first: bool, name: str = "quat") -> NDArray[np.float64]:
    # The width is checked before any reordering: q[..., [3, 0, 1, 2]] of a
    # (..., 5) array would silently become a rotation.
    scalar_first = check_flag(scalar_first, "scalar_first")
    array = as_float_array(q, name, (4,), finite=False)
    return array if scalar_first else array[..., [3, 0, 1, 2]]


#: Distance of the middle angle from gimbal lock below which
#: ``suppress_warnings=False`` warns, radians (scipy's threshold).
_GIMBAL_TOLERANCE = 1e-7


def _warn_gimbal_lock(mask: NDArray[np.bool_]) -> None:
    if np.any(mask):
        warnings.warn(
            f"gimbal lock in {int(np.sum(mask))} of {np.size(mask)} rotations: the first and third angles are "
            "not unique (the third intrinsic angle is set to 0; the rotation is reproduced exactly)",
            _euler.GimbalLockWarning,
            stacklevel=3,
        )


def canonical_quat(q: ArrayLike) -> NDArray[np.float64]:
    """The sign of ``q`` with ``q0 > 0``, or, for half turns (``q0 = 0``), the first nonzero component > 0.

    ``q`` and ``-q`` give the same result, so the canonical quaternion is unique.
    """
    q = np.asarray(q)
    first = np.take_along_axis(q, np.argmax(q != 0.0, axis=-1)[..., None], axis=-1)
    return np.where(first < 0.0, -q, q) + 0.0  # + 0.0 turns -0.0 into 0.0: bitwise unique


class Rotation(QuaternionBatch):
    """Rotations of batch shape ``shape`` (``()`` for a single rotation).

    Build with a ``from_*`` class method, read with the matching ``as_*``.
    Active convention: ``apply`` maps body components to space components.

    Examples
    --------
    >>> import numpy as np
    >>> r = Rotation.from_euler("ZXZ", [90, 0, 0], degrees=True)
    >>> r
    Rotation.from_quat([0.707107, 0, 0, 0.707107])
    >>> np.round(r.apply([1.0, 0.0, 0.0]), 12) + 0.0
    array([0., 1., 0.])
    >>> round(float(np.degrees((r * r).magnitude())), 9)
    180.0
    """

    __slots__ = ()

    def __init__(self, quat: ArrayLike, *, _validated: bool = False) -> None:
        # Internal constructors pass quaternions that are already unit.
        self._q = cast("NDArray[np.float64]", quat) if _validated else _quat.quat_normalize(quat)

    @classmethod
    def _wrap(cls, q: ArrayLike) -> Rotation:
        return cls(q, _validated=True)

    # -- construction -------------------------------------------------------
    @classmethod
    def from_quat(cls, quat: ArrayLike, scalar_first: bool = True) -> Rotation:
        """From quaternions (normalised); ``scalar_first=False`` for ``[x, y, z, w]`` input.

        Examples
        --------
        A quarter turn about z; the quaternion is normalised on the way in:

        >>> import numpy as np
        >>> r = Rotation.from_quat([2.0, 0.0, 0.0, 2.0])
        >>> r.as_quat().round(6).tolist()
        [0.707107, 0.0, 0.0, 0.707107]
        >>> bool(Rotation.from_quat([0.0, 0.0, 1.0, 1.0], scalar_first=False).approx_equal(r))
        True
        """
        return cls(_scalar_first(quat, scalar_first))

    @classmethod
    def from_matrix(cls, matrix: ArrayLike) -> Rotation:
        """From rotation matrices (nearly orthogonal ones are projected).

        Examples
        --------
        >>> import numpy as np
        >>> rz = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
        >>> r = Rotation.from_matrix(rz)
        >>> round(float(np.degrees(r.magnitude())), 9)
        90.0
        >>> bool(np.allclose(r.as_matrix(), rz, atol=1e-15))
        True
        """
        return cls._wrap(_matrix.matrix_to_quat(matrix))

    @classmethod
    def from_rotvec(cls, rotvec: ArrayLike, degrees: bool = False) -> Rotation:
        """From rotation vectors ψ = ψ n (exponential map).

        Vectors longer than 1e8 rad are refused (:func:`~kreisel.so3.rotvec_to_quat`
        says why): reduce them modulo 2π first.

        Examples
        --------
        The rotation vector's length is the angle, its direction the axis:

        >>> import numpy as np
        >>> r = Rotation.from_rotvec([0.0, 0.0, 90.0], degrees=True)
        >>> np.round(r.apply([1.0, 0.0, 0.0]), 12).tolist()
        [0.0, 1.0, 0.0]
        >>> np.round(r.as_rotvec(degrees=True), 9).tolist()
        [0.0, 0.0, 90.0]
        """
        psi = as_float_array(rotvec, "rotvec", (3,), finite=False)
        return cls._wrap(_rotvec.exp_quat(np.deg2rad(psi) if check_flag(degrees, "degrees") else psi, "rotvec"))

    @classmethod
    def from_axis_angle(cls, axis: ArrayLike, angle: ArrayLike, degrees: bool = False) -> Rotation:
        """From an axis (any nonzero length) and an angle, at most 1e8 rad (as :meth:`from_rotvec`).

        Examples
        --------
        The axis need not be unit length:

        >>> import numpy as np
        >>> r = Rotation.from_axis_angle([0.0, 0.0, 5.0], np.pi / 2)
        >>> bool(r.approx_equal(Rotation.from_rotvec([0.0, 0.0, np.pi / 2])))
        True
        """
        return cls._wrap(_rotvec.exp_quat(_rotvec.axis_angle_to_rotvec(axis, angle, degrees=degrees), "angle",
                                          what="|angle|"))

    @classmethod
    def from_euler(cls, seq: str, angles: ArrayLike, degrees: bool = False) -> Rotation:
        """From Euler angles in any of the 24 conventions (see :mod:`kreisel.so3.euler`).

        Examples
        --------
        The chapter's mechanics angles (φ, θ, ψ) are the intrinsic sequence ``"ZXZ"``,
        R = Rz(φ) Rx(θ) Rz(ψ):

        >>> import numpy as np
        >>> r = Rotation.from_euler("ZXZ", [30, 40, 50], degrees=True)
        >>> rz = lambda deg: Rotation.from_rotvec([0.0, 0.0, deg], degrees=True)
        >>> rx = Rotation.from_rotvec([40.0, 0.0, 0.0], degrees=True)
        >>> bool(r.approx_equal(rz(30) * rx * rz(50)))
        True
        >>> np.round(r.as_euler("ZXZ", degrees=True), 9).tolist()
        [30.0, 40.0, 50.0]
        """
        return cls._wrap(_euler.euler_to_quat(seq, angles, degrees=degrees))

    @classmethod
    def from_davenport(cls, axes: ArrayLike, order: str, angles: ArrayLike, degrees: bool = False) -> Rotation:
        """From Davenport angles about any axes, the middle one orthogonal to the others.

        scipy's ``from_davenport`` (see :mod:`kreisel.so3.davenport`):
        ``order`` is ``"i"``/``"intrinsic"`` or ``"e"``/``"extrinsic"``; Euler
        angles are the special case of coordinate axes.

        Examples
        --------
        >>> import numpy as np
        >>> axes = [[0, 0, 1], [1, 0, 0], [0, 0, 1]]
        >>> r = Rotation.from_davenport(axes, "intrinsic", [30, 40, 50], degrees=True)
        >>> bool(r.approx_equal(Rotation.from_euler("ZXZ", [30, 40, 50], degrees=True)))
        True
        """
        return cls._wrap(_davenport.davenport_to_quat(axes, order, angles, degrees=degrees))

    @takes_out
    def as_davenport(self, axes: ArrayLike, order: str, degrees: bool = False, *,
                     suppress_warnings: bool = True, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Davenport angles about ``axes`` (scipy's ``as_davenport``), exact through gimbal lock.

        As :meth:`as_euler`, no warning by default; ``suppress_warnings=False``
        warns (:class:`~kreisel.kinematics.GimbalLockWarning`) for rotations
        within 1e-7 rad of gimbal lock. One and two axes are accepted too.

        Parameters
        ----------
        axes : array_like, shape (n, 3)
        order : {"e", "extrinsic", "i", "intrinsic"}
        degrees : bool
        suppress_warnings : bool

        Examples
        --------
        >>> import numpy as np
        >>> axes = [[1, 0, 0], [0, 1, 0], [np.sqrt(0.5), 0, np.sqrt(0.5)]]
        >>> r = Rotation.from_davenport(axes, "e", [0.1, 0.2, 0.3])
        >>> r.as_davenport(axes, "e").round(12).tolist()
        [0.1, 0.2, 0.3]
        """
        angles = _davenport.quat_to_davenport(axes, order, self._q, degrees=degrees, out=out)
        if not suppress_warnings and np.shape(axes) == (3, 3):
            _warn_gimbal_lock(_davenport.davenport_gimbal_lock(axes, order, angles, degrees, _GIMBAL_TOLERANCE))
        return angles

    @classmethod
    def from_su2(cls, u: ArrayLike) -> Rotation:
        """From SU(2) matrices ``exp(-i σ·ψ/2)``.

        Examples
        --------
        A half turn about x is ``-i σx`` in SU(2):

        >>> import numpy as np
        >>> u = np.array([[0.0, -1.0j], [-1.0j, 0.0]])
        >>> bool(Rotation.from_su2(u).approx_equal(Rotation.from_rotvec([np.pi, 0.0, 0.0])))
        True
        """
        return cls._wrap(_su2.su2_to_quat(u))

    @classmethod
    def from_cayley_klein(cls, ck: ArrayLike) -> Rotation:
        """From Cayley–Klein parameters ``(α, β, γ, δ)``.

        Examples
        --------
        Round trip through the Cayley–Klein parameters:

        >>> r = Rotation.from_euler("ZXZ", [0.3, 0.4, 0.5])
        >>> bool(Rotation.from_cayley_klein(r.as_cayley_klein()).approx_equal(r))
        True
        """
        return cls._wrap(_su2.cayley_klein_to_quat(ck))

    @classmethod
    def from_euler_parameters(cls, e: ArrayLike) -> Rotation:
        """From the chapter's (Goldstein's) Euler parameters, ``e = q*`` (see :func:`quat_to_euler_parameters`).

        Examples
        --------
        The chapter's Euler parameters are the conjugate quaternion (passive sign of the vector part):

        >>> import numpy as np
        >>> r = Rotation.from_euler_parameters([np.sqrt(0.5), 0.0, 0.0, -np.sqrt(0.5)])
        >>> (r.as_quat().round(6) + 0.0).tolist()
        [0.707107, 0.0, 0.0, 0.707107]
        """
        return cls._wrap(_su2.euler_parameters_to_quat(e))

    @classmethod
    def from_gibbs(cls, g: ArrayLike) -> Rotation:
        """From Gibbs (classical Rodrigues) vectors ``n tan(ψ/2)``.

        Examples
        --------
        The Gibbs vector of a quarter turn about z is ``tan(45°) z``:

        >>> import numpy as np
        >>> r = Rotation.from_gibbs([0.0, 0.0, 1.0])
        >>> round(float(np.degrees(r.magnitude())), 9)
        90.0
        """
        return cls._wrap(_rodrigues.gibbs_to_quat(g))

    @classmethod
    def from_mrp(cls, p: ArrayLike) -> Rotation:
        """From modified Rodrigues parameters ``n tan(ψ/4)``.

        Examples
        --------
        The modified Rodrigues parameters of a rotation are its Gibbs vector ``g``
        divided by ``1 + sqrt(1 + |g|²)``; unit length is a half turn (tan(π/4) = 1):

        >>> import numpy as np
        >>> g = np.array([0.0, 0.0, 1.0])                                    # a quarter turn about z
        >>> bool(Rotation.from_mrp(g / (1.0 + np.sqrt(2.0))).approx_equal(Rotation.from_gibbs(g)))
        True
        >>> bool(np.isclose(Rotation.from_mrp([1.0, 0.0, 0.0]).magnitude(), np.pi))
        True
        """
        return cls._wrap(_rodrigues.mrp_to_quat(p))

    @classmethod
    def from_scipy(cls, rotation: ScipyRotation) -> Rotation:
        """From a ``scipy.spatial.transform.Rotation`` (scalar-last internally).

        Examples
        --------
        >>> from scipy.spatial.transform import Rotation as ScipyRotation
        >>> s = ScipyRotation.from_rotvec([0.1, 0.2, 0.3])
        >>> bool(Rotation.from_scipy(s).approx_equal(Rotation.from_rotvec([0.1, 0.2, 0.3])))
        True
        """
        return cls.from_quat(rotation.as_quat(), scalar_first=False)

    @classmethod
    def align_vectors(cls, a: ArrayLike, b: ArrayLike, weights: ArrayLike | None = None,
                      return_sensitivity: bool = False) -> tuple[Any, ...]:
        """The rotation ``R`` with ``a ≈ R b`` in the weighted least-squares sense (Wahba's problem).

        scipy's ``Rotation.align_vectors``: same loss ``½ Σ w |a - R b|²``,
        the shortest-arc rotation for a single vector pair, exact alignment
        of the one pair with ``weights = inf`` (TRIAD for two vectors), the
        root sum squared distance and Markley's sensitivity matrix. Solved by
        Davenport's q-method in compiled code (see :mod:`kreisel.so3.alignment`
        for the background). As a kreisel extension, ``a`` and ``b`` may carry
        batch axes, ``(..., n, 3)``: every problem is solved at once.

        Parameters
        ----------
        a, b : array_like, shape (n, 3), (3,) or (..., n, 3)
            Vectors in frame A and the same vectors observed in frame B.
        weights : array_like, shape (n,) or (..., n), optional
            Non-negative; at most one ``inf`` per problem.
        return_sensitivity : bool
            Also return the sensitivity matrix (not for an infinite weight or
            a single pair).

        Returns
        -------
        rotation : Rotation
            Batch shape ``a.shape[:-2]`` (a single rotation for ``(n, 3)``).
        rssd : float or ndarray
            ``sqrt(Σ w |a - R b|²)`` over the finite-weight pairs.
        sensitivity : ndarray, shape (..., 3, 3)
            With ``return_sensitivity=True``.

        Examples
        --------
        Star-tracker style: three catalogue directions and the same stars seen
        from the body fix the attitude:

        >>> import numpy as np
        >>> truth = Rotation.from_euler("ZYX", [30, 20, 10], degrees=True)
        >>> catalogue = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.6, 0.8]])
        >>> seen = truth.apply(catalogue, inverse=True)
        >>> r, rssd = Rotation.align_vectors(catalogue, seen)
        >>> bool(r.approx_equal(truth)), rssd < 1e-15
        (True, True)
        """
        a_shape = np.shape(a)
        out = _alignment.align_vectors(a, b, weights, return_sensitivity)
        rotation = cls._wrap(out[0])
        rssd = float(out[1]) if len(a_shape) <= 2 else out[1]
        return (rotation, rssd, *out[2:])

    @classmethod
    def create_group(cls, group: str, axis: str = "Z") -> Rotation:
        """A finite rotation group: ``"I"`` (60), ``"O"`` (24), ``"T"`` (12), ``"Dn"`` (2n) or ``"Cn"`` (n).

        scipy's ``create_group`` (same orientation; see :mod:`kreisel.so3.groups`),
        identity first. ``axis`` is the main axis of ``Cn`` and ``Dn``.

        Examples
        --------
        The square's symmetries about x, and closure under composition:

        >>> import numpy as np
        >>> g = Rotation.create_group("C4", axis="X")
        >>> np.degrees(g.as_rotvec()[:, 0]).round(9).tolist()
        [0.0, 90.0, 180.0, -90.0]
        >>> len(Rotation.create_group("O"))
        24
        """
        return cls._wrap(_groups.create_group(group, axis))

    def reduce(self, left: Rotation | None = None, right: Rotation | None = None,
               return_indices: bool = False) -> Rotation | tuple[Rotation, Any, Any]:
        """The equivalent rotation ``l * self * r`` with the smallest angle (scipy's ``reduce``).

        Parameters
        ----------
        left, right : Rotation, optional
            Symmetry groups applied on the left and on the right (None: none).
        return_indices : bool
            Also return the indices of the chosen ``l`` and ``r`` (None for a
            side not given), shaped like the batch.

        Examples
        --------
        Two cube orientations 100° apart about z differ by only 10° up to the cube's symmetry:

        >>> import numpy as np
        >>> cube = Rotation.create_group("O")
        >>> r = Rotation.from_rotvec([0.0, 0.0, np.radians(100)])
        >>> round(float(np.degrees(r.reduce(right=cube).magnitude())), 9)
        10.0
        """
        if left is None and right is None:
            reduced, li, ri = self._q.copy(), None, None
        else:
            reduced, li, ri = _groups.reduce_quat(
                self._q, None if left is None else left._q, None if right is None else right._q
            )
        out = Rotation._wrap(reduced)
        return (out, li, ri) if return_indices else out

    @classmethod
    def concatenate(cls, rotations: Rotation | Iterable[Rotation]) -> Rotation:
        """One batch from a sequence of rotations (single ones count as one element each).

        Examples
        --------
        >>> r = Rotation.concatenate([Rotation.identity(), Rotation.random(3, rng=0)])
        >>> r.shape
        (4,)
        """
        if isinstance(rotations, Rotation):
            return cls._wrap(rotations._q.copy())
        parts = list(rotations)
        if not all(isinstance(r, Rotation) for r in parts):
            raise TypeError("rotations must be a sequence of kreisel Rotation objects")
        if not parts:
            raise ValueError("rotations must hold at least one Rotation")
        return cls._wrap(np.concatenate([np.atleast_2d(r._q) for r in parts]))

    @classmethod
    def identity(cls, shape: int | tuple[int, ...] | None = ()) -> Rotation:
        """Identity rotations of batch shape ``shape``.

        Examples
        --------
        >>> r = Rotation.identity((2, 3))
        >>> r.shape
        (2, 3)
        >>> r.as_quat()[0, 0].tolist()
        [1.0, 0.0, 0.0, 0.0]
        """
        return cls._wrap(_quat.quat_identity(shape))

    @classmethod
    def random(cls, shape: int | tuple[int, ...] | None = (), rng: Any = None) -> Rotation:
        """Rotations uniform on SO(3) (Haar measure): normalised 4-D Gaussians.

        The same seed gives the same rotations as scipy's ``Rotation.random``:
        the Gaussian draws are read in scipy's scalar-last order, and
        :meth:`as_quat` returns them scalar first.

        Parameters
        ----------
        shape : None, int or tuple of int
            Batch shape (``()`` or ``None``: a single rotation).
        rng : None, int or numpy.random.Generator
            Seed or generator, as for ``numpy.random.default_rng``.

        Examples
        --------
        >>> Rotation.random(5, rng=1).shape
        (5,)
        >>> from scipy.spatial.transform import Rotation as ScipyRotation
        >>> bool(Rotation.random(5, rng=1).approx_equal(Rotation.from_scipy(ScipyRotation.random(5, rng=1))).all())
        True
        """
        shape = batch_shape(shape)
        rng = np.random.default_rng(rng)
        # scipy reads the same Gaussian draws as scalar-last quaternions.
        q = rng.standard_normal((*shape, 4))[..., [3, 0, 1, 2]]
        # C order: the index along the last axis leaves the components as the slow axis
        return cls._wrap(np.ascontiguousarray(q / np.linalg.norm(q, axis=-1, keepdims=True)))

    # -- representations ----------------------------------------------------
    @takes_out
    def as_quat(self, canonical: bool = False, scalar_first: bool = True, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Unit quaternions; ``canonical=True`` picks the unique sign (q0 > 0, else first nonzero > 0).

        Parameters
        ----------
        canonical : bool
        scalar_first : bool
            ``False`` gives scipy's default order ``(x, y, z, w)``.

        Examples
        --------
        ``q`` and ``-q`` are the same rotation; ``canonical=True`` picks ``q0 >= 0``:

        >>> r = Rotation.from_quat([-0.6, 0.0, 0.8, 0.0])
        >>> r.as_quat(canonical=True).tolist()
        [0.6, 0.0, -0.8, 0.0]

        A half turn (q0 = 0) is made unique by its first nonzero component:

        >>> Rotation.from_quat([0.0, 0.0, -0.6, 0.8]).as_quat(canonical=True).tolist()
        [0.0, 0.0, 0.6, -0.8]
        >>> r.as_quat(scalar_first=False).tolist()
        [0.0, 0.8, 0.0, -0.6]
        """
        scalar_first = check_flag(scalar_first, "scalar_first")
        q = canonical_quat(self._q) if check_flag(canonical, "canonical") else self._q
        q = q if scalar_first else q[..., [1, 2, 3, 0]]
        return np.array(q) if out is None else deliver(q, out)

    @takes_out
    def as_matrix(self, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Rotation matrices ``R`` (body → space), shape ``(..., 3, 3)``.

        Examples
        --------
        The matrix is orthogonal with determinant +1:

        >>> import numpy as np
        >>> m = Rotation.from_rotvec([0.3, -0.2, 0.9]).as_matrix()
        >>> bool(np.allclose(m @ m.T, np.eye(3), atol=1e-15)), round(float(np.linalg.det(m)), 12)
        (True, 1.0)
        """
        return _matrix.quat_to_matrix(self._q, out=out)

    @takes_out
    def as_rotvec(self, degrees: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Rotation vectors with |ψ| <= π.

        Parameters
        ----------
        degrees : bool

        Examples
        --------
        Logs are returned with ``|ψ| <= π``: a 270° turn about z comes back as -90°:

        >>> import numpy as np
        >>> r = Rotation.from_rotvec([0.0, 0.0, 270.0], degrees=True)
        >>> (np.round(r.as_rotvec(degrees=True), 9) + 0.0).tolist()
        [0.0, 0.0, -90.0]
        """
        degrees = check_flag(degrees, "degrees")
        psi = _rotvec.quat_to_rotvec(self._q, out=out)
        return np.rad2deg(psi, out=psi) if degrees else psi

    def as_axis_angle(self, degrees: bool = False) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``(axis, angle)`` with angle in [0, π] (axis ``[0, 0, 1]`` for the identity).

        Examples
        --------
        >>> import numpy as np
        >>> axis, angle = Rotation.from_rotvec([0.0, 0.6, 0.8]).as_axis_angle(degrees=True)
        >>> axis.round(12).tolist(), round(float(angle), 6)
        ([0.0, 0.6, 0.8], 57.29578)
        """
        degrees = check_flag(degrees, "degrees")
        axis, angle = _rotvec.rotvec_to_axis_angle(_rotvec.quat_to_rotvec(self._q))
        return axis, (np.rad2deg(angle) if degrees else angle)

    @takes_out
    def as_euler(self, seq: str, degrees: bool = False, *, suppress_warnings: bool = True,
                 out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Euler angles, exact through gimbal lock (any 1-, 2- or 3-axis sequence).

        Unlike scipy, no warning is issued by default at gimbal lock: the
        angles returned there are exact (the rotation rebuilt from them
        matches to rounding), with the third intrinsic (first extrinsic) angle
        set to 0 where only a sum or difference is defined. Pass
        ``suppress_warnings=False`` (scipy's default) to get a
        :class:`~kreisel.kinematics.GimbalLockWarning` for rotations within
        1e-7 rad of gimbal lock, where the outer angles are not unique.

        Parameters
        ----------
        seq : str
            Uppercase intrinsic, lowercase extrinsic axes, e.g. ``"ZXZ"``.
        degrees : bool
        suppress_warnings : bool

        Examples
        --------
        At gimbal lock (θ = 0 in ``"ZXZ"``) only φ + ψ is defined; the sum is kept exactly:

        >>> import numpy as np
        >>> r = Rotation.from_euler("ZXZ", [20, 0, 30], degrees=True)
        >>> phi, theta, psi = r.as_euler("ZXZ", degrees=True)
        >>> round(float(phi + psi), 9), round(float(theta), 9)
        (50.0, 0.0)
        >>> import warnings
        >>> with warnings.catch_warnings(record=True) as caught:
        ...     warnings.simplefilter("always")
        ...     _ = r.as_euler("ZXZ", suppress_warnings=False)
        >>> caught[0].category.__name__
        'GimbalLockWarning'
        """
        suppress_warnings = check_flag(suppress_warnings, "suppress_warnings")
        angles = _euler.quat_to_euler(seq, self._q, degrees=degrees, out=out)
        if not suppress_warnings and len(seq) == 3:
            _warn_gimbal_lock(_euler.gimbal_lock(seq, angles, degrees=degrees, tolerance=_GIMBAL_TOLERANCE))
        return angles

    @takes_out
    def as_su2(self, *, out: NDArray[np.complex128] | None = None) -> NDArray[np.complex128]:
        """SU(2) matrices ``exp(-i σ·ψ/2)`` (keeps the quaternion's sign).

        Examples
        --------
        SU(2) matrices are unitary with determinant 1 and compose like the rotations:

        >>> import numpy as np
        >>> a, b = Rotation.from_rotvec([0.1, 0.2, 0.3]), Rotation.from_rotvec([-0.4, 0.0, 0.5])
        >>> u = a.as_su2()
        >>> bool(np.allclose(u @ u.conj().T, np.eye(2))), round(float(np.linalg.det(u).real), 12)
        (True, 1.0)
        >>> bool(np.allclose((a * b).as_su2(), a.as_su2() @ b.as_su2()))
        True
        """
        return _su2.quat_to_su2(self._q, out=out)

    @takes_out
    def as_cayley_klein(self, *, out: NDArray[np.complex128] | None = None) -> NDArray[np.complex128]:
        """Cayley–Klein parameters ``(α, β, γ, δ)``.

        Examples
        --------
        The parameters satisfy αδ − βγ = 1:

        >>> import numpy as np
        >>> alpha, beta, gamma, delta = Rotation.from_euler("ZXZ", [0.3, 0.4, 0.5]).as_cayley_klein()
        >>> bool(np.isclose(alpha * delta - beta * gamma, 1.0))
        True
        """
        return _su2.quat_to_cayley_klein(self._q, out=out)

    @takes_out
    def as_euler_parameters(self, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Euler parameters of the Theory §A (2), ``e = q*``.

        Examples
        --------
        The Euler parameters are the conjugate quaternion, and have unit norm:

        >>> import numpy as np
        >>> r = Rotation.from_rotvec([0.0, 0.0, np.pi / 2])
        >>> r.as_euler_parameters().round(6).tolist()
        [0.707107, -0.0, -0.0, -0.707107]
        """
        return _su2.quat_to_euler_parameters(self._q, out=out)

    @takes_out
    def as_gibbs(self, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Gibbs vectors ``n tan(ψ/2)`` (refused for half-turns).

        Examples
        --------
        >>> import numpy as np
        >>> g = Rotation.from_rotvec([0.0, 0.0, np.pi / 2]).as_gibbs()
        >>> g.round(12).tolist()
        [0.0, 0.0, 1.0]
        """
        return _rodrigues.quat_to_gibbs(self._q, out=out)

    @takes_out
    def as_mrp(self, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Modified Rodrigues parameters with |p| <= 1.

        Examples
        --------
        MRPs are chosen on the short side, |p| <= 1 (p = n tan(ψ/4)):

        >>> import numpy as np
        >>> p = Rotation.from_rotvec([0.0, 0.0, np.pi / 2]).as_mrp()
        >>> round(float(p[2]), 12) == round(float(np.tan(np.pi / 8)), 12)
        True
        """
        return _rodrigues.quat_to_mrp(self._q, out=out)

    def to_scipy(self) -> ScipyRotation:
        """The same rotations as a ``scipy.spatial.transform.Rotation``.

        Examples
        --------
        >>> import numpy as np
        >>> r = Rotation.from_euler("ZXZ", [0.3, 0.4, 0.5])
        >>> bool(np.allclose(r.to_scipy().as_matrix(), r.as_matrix(), atol=1e-15))
        True
        """
        from scipy.spatial.transform import Rotation as ScipyRotation

        return ScipyRotation.from_quat(self._q[..., [1, 2, 3, 0]])

    # -- group operations ---------------------------------------------------
    def __mul__(self, other: Rotation) -> Rotation:
        if not isinstance(other, Rotation):
            return NotImplemented
        return Rotation._wrap(_quat.compose_unit(self._q, other._q))

    def inv(self) -> Rotation:
        """Inverse rotations.

        Examples
        --------
        A rotation composed with its inverse is the identity:

        >>> r = Rotation.from_rotvec([0.3, -0.2, 0.9])
        >>> bool((r * r.inv()).approx_equal(Rotation.identity()))
        True
        """
        return Rotation._wrap(_quat.quat_conjugate(self._q))

    @takes_out
    def apply(self, vectors: ArrayLike, inverse: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Rotate vectors ``(..., 3)``: ``R v`` (``Rᵀ v`` with ``inverse=True``), broadcasting.

        Parameters
        ----------
        vectors : array_like, shape (..., 3)
            Body components (space components with ``inverse=True``).
        inverse : bool

        Examples
        --------
        Rotating preserves length, and ``inverse=True`` undoes it:

        >>> import numpy as np
        >>> r = Rotation.from_rotvec([0.3, -0.2, 0.9])
        >>> v = np.array([1.0, 2.0, 3.0])
        >>> w = r.apply(v)
        >>> bool(np.isclose(np.linalg.norm(w), np.linalg.norm(v))), bool(np.allclose(r.apply(w, inverse=True), v))
        (True, True)
        """
        return _quat.quat_apply(self._q, vectors, inverse=inverse, out=out)

    @takes_out
    def magnitude(self, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Rotation angles in [0, π].

        Examples
        --------
        >>> import numpy as np
        >>> r = Rotation.from_rotvec([[0.0, 0.0, 0.5], [0.0, 3.0, 4.0]])
        >>> r.magnitude().round(6).tolist()
        [0.5, 1.283185]
        """
        return deliver(np.linalg.norm(self.as_rotvec(), axis=-1), out)

    def mean(self, weights: ArrayLike | None = None, axis: int | tuple[int, ...] | None = None) -> Rotation:
        """Chordal L2 mean (see :func:`quat_mean`) over the batch ``axis``, as scipy's ``mean``.

        Parameters
        ----------
        weights : array_like, optional
            Non-negative, of the batch shape (``(1,)`` for a single rotation).
        axis : None, int or tuple of int
            Batch axes to average over; ``None`` (scipy's default) means all. A single
            rotation is averaged as a batch of one: its mean is itself.

        Examples
        --------
        The mean of two rotations about the same axis lies halfway between them:

        >>> import numpy as np
        >>> r = Rotation.from_rotvec([[0.0, 0.0, 0.2], [0.0, 0.0, 0.6]])
        >>> (r.mean().as_rotvec().round(9) + 0.0).tolist()
        [0.0, 0.0, 0.4]
        >>> Rotation.random((5, 3), rng=0).mean(axis=0).shape
        (3,)
        """
        # as scipy: a single rotation is a batch of one, so its mean is itself
        q = self._q[np.newaxis] if self.single else self._q
        return Rotation._wrap(_interp.mean_over(q, weights, axis)[0])

    def __pow__(self, p: ArrayLike, modulus: None = None) -> Rotation:
        """``r ** p``: the rotation about the same axis by ``p`` times the angle, ``exp(p log r)``.

        As in scipy: ``log`` takes the angle in [0, π], so ``p`` scales the
        shortest rotation; ``r ** -1`` is the inverse and ``r ** 0`` the
        identity (both exact); ``p`` may also be an array broadcast against
        the batch. ``r ** 2`` of a 270° turn is a 180° turn the other way.

        Examples
        --------
        >>> import numpy as np
        >>> r = Rotation.from_rotvec([0.0, 0.0, 0.6])
        >>> (r ** 0.5).as_rotvec().round(12).tolist(), ((r ** -2).as_rotvec().round(12) + 0.0).tolist()
        ([0.0, 0.0, 0.3], [0.0, 0.0, -1.2])
        """
        if modulus is not None:
            raise TypeError("pow() with a modulus is not defined for rotations")
        return Rotation._wrap(_quat.quat_power(self._q, p))

    def slerp(self, other: Rotation, t: ArrayLike) -> Rotation:
        """Spherical linear interpolation from ``self`` (t = 0) to ``other`` (t = 1).

        Examples
        --------
        Slerp moves at constant angular rate along the shortest arc:

        >>> import numpy as np
        >>> a = Rotation.identity()
        >>> b = Rotation.from_rotvec([0.0, 0.0, 1.2])
        >>> a.slerp(b, [0.25, 0.5]).as_rotvec().round(9).tolist()
        [[0.0, 0.0, 0.3], [0.0, 0.0, 0.6]]
        """
        return Rotation._wrap(_interp.quat_slerp(self._q, other._q, t))

    @takes_out
    def approx_equal(self, other: Rotation, atol: float = 1e-12, degrees: bool = False, *,
                     out: NDArray[np.bool_] | None = None) -> NDArray[np.bool_]:
        """Whether the rotations agree to ``atol`` in angle (sign of q ignored).

        Parameters
        ----------
        other : Rotation
            Broadcast against ``self``.
        atol : float
            Largest angle between equal rotations, radians (degrees when ``degrees``).
        degrees : bool
            ``atol`` is in degrees, as scipy's ``approx_equal(other, atol, degrees=True)``.

        Examples
        --------
        ``q`` and ``-q`` are equal rotations:

        >>> import numpy as np
        >>> q = np.array([0.6, 0.8, 0.0, 0.0])
        >>> bool(Rotation.from_quat(q).approx_equal(Rotation.from_quat(-q)))
        True
        """
        tolerance = np.deg2rad(atol) if check_flag(degrees, "degrees") else atol
        return deliver((self.inv() * other).magnitude() <= tolerance, out)

    # -- container protocol (shape, single and len: QuaternionBatch) --------
    def __iter__(self) -> Iterator[Rotation]:
        if self.single:
            raise self._single_error("is not iterable")
        for i in range(len(self)):
            yield self[i]

    def __bool__(self) -> bool:
        # As scipy: a Rotation is true even when its batch is empty.
        return True

    def __setitem__(self, index: Any, value: Rotation) -> None:
        if self.single:
            raise self._single_error("does not support item assignment")
        if not isinstance(value, Rotation):
            raise TypeError(f"value must be a kreisel Rotation, got {type(value).__name__}")
        if isinstance(index, tuple):
            index = (*index, slice(None))
        # Copy first: the array may be shared with the Rotation it was sliced from.
        q = np.array(self._q)
        q[index] = value._q
        self._q = q

    def __getitem__(self, index: Any) -> Rotation:
        if self.single:
            raise self._single_error("is not subscriptable")
        if isinstance(index, tuple):
            index = (*index, slice(None))
        return Rotation._wrap(self._q[index])

    def __repr__(self) -> str:
        def fmt(x: float) -> str:
            return np.format_float_positional(x, precision=6, trim="-")

        if self.single:
            return "Rotation.from_quat([" + ", ".join(fmt(x) for x in self._q) + "])"
        body = np.array2string(self._q, precision=6, suppress_small=True, separator=", ", threshold=20)
        return f"Rotation.from_quat({body})  # shape {self.shape}"

    def _repr_html_(self) -> str:
        note = "quaternion scalar-first [q0, q1, q2, q3], active, R maps body to space; ZXZ intrinsic"
        rows: list[tuple[str, object]]
        if self.single:
            rows = [
                ("quaternion", number(self._q)),
                ("rotation vector ψ", number(self.as_rotvec()) + " rad"),
                ("angle", number(np.degrees(self.magnitude())) + "°"),
                ("Euler ZXZ (φ, θ, ψ)", number(self.as_euler("ZXZ", degrees=True)) + "°"),
            ]
        else:
            angles = np.degrees(self.magnitude())
            rows = [("shape", self.shape), ("count", angles.size)]
            if angles.size:
                first = self._q.reshape(-1, 4)[0]
                rows += [("first quaternion", number(first)),
                         ("angles", f"{number(angles.min())}° … {number(angles.max())}°")]
        return html_table("Rotation", rows, note=note)
