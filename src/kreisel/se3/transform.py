"""Rigid displacements (R, r_C) as batched objects: :class:`RigidTransform`.

Theory §1.3 (Chasles' theorem): every body point P moves as
``r_P = R r′_CP + r_C``: a rotation ``R`` about the base point C followed by
the translation ``r_C`` of C. A :class:`RigidTransform` stores that pair as a
unit quaternion (scalar first, ``R = R(q)`` of Theory §2.4) and a translation.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled.checks import finite_array
from .._compiled.elementwise import uses
from .._compiled.outputs import deliver, takes_out
from .._html import html_table, number
from .._validation import batch_shape, check_flag
from ..so3 import Rotation, quat_to_rotvec
from ..so3.interpolation import gather_samples, mean_over
from ..so3.quaternion import check_angle_multiple
from ..so3._batch import QuaternionBatch
from ..so3._coercion import ORTHOGONALITY_TOLERANCE, as_quaternion
from . import _kernels
from .screw import Screw, screw_parameters, screw_pose

if TYPE_CHECKING:
    from scipy.spatial.transform import RigidTransform as ScipyRigidTransform

__all__ = ["RigidTransform", "change_base_point"]

#: Largest accepted departure from rigidity: |bottom row - (0, 0, 0, 1)| of a
#: homogeneous matrix, ||q_r| - 1| and the relative q_r·q_d of a dual
#: quaternion. Inputs within it are projected onto SE(3); others are refused
#: (the kinds POSE_MATRIX and UNIT_DUAL_QUATERNION of :mod:`kreisel._compiled.checks`).
RIGIDITY_TOLERANCE = ORTHOGONALITY_TOLERANCE


class RigidTransform(QuaternionBatch):
    """Rigid displacements ``r -> R r + r_C`` (Theory §1.3), batched like numpy arrays.

    The rotation ``R`` maps body components to space components and ``r_C``
    is the space position of the base point C, so a body point with body
    components ``r′_CP`` sits at ``r_P = R r′_CP + r_C`` (Chasles' theorem).
    ``a * b`` applies ``b`` first, then ``a`` (as for matrices).

    Construct with the ``from_*`` class methods; ``RigidTransform(rotation,
    translation)`` is :meth:`from_rotation_translation`.

    Parameters
    ----------
    rotation : Rotation or array_like
        A kreisel (or scipy) ``Rotation``, rotation matrices ``(..., 3, 3)``
        or scalar-first quaternions ``(..., 4)``.
    translation : array_like, shape (..., 3)
        Space position of the base point, ``r_C``.

    Examples
    --------
    >>> import numpy as np
    >>> T = RigidTransform([[0, -1, 0], [1, 0, 0], [0, 0, 1]], [1.0, 0.0, 0.0])
    >>> T.apply([1.0, 0.0, 0.0])                  # rotate 90° about z, then shift
    array([1., 1., 0.])
    >>> (T * T.inv()).as_matrix().round(12) + 0.0
    array([[1., 0., 0., 0.],
           [0., 1., 0., 0.],
           [0., 0., 1., 0.],
           [0., 0., 0., 1.]])
    """

    __slots__ = ("_pose", "_translation")
    __array_ufunc__ = None  # ndarray * RigidTransform raises instead of looping elementwise

    #: The poses packed, [q, r_C] (..., 7), C-ordered: what the operations of :mod:`._kernels` read.
    _pose: NDArray[np.float64]
    _translation: NDArray[np.float64]

    def __init__(self, rotation: Rotation | ArrayLike, translation: ArrayLike) -> None:
        quat = as_quaternion(rotation, "rotation")
        self._set(_packed(quat, finite_array(translation, "translation")))

    # -- construction ------------------------------------------------------------------------

    def _set(self, pose: NDArray[np.float64]) -> None:
        self._pose, self._q, self._translation = pose, pose[..., :4], pose[..., 4:]

    @classmethod
    def _from_pose(cls, pose: NDArray[np.float64]) -> RigidTransform:
        # A trusted, C-ordered array (unit quaternions, finite translations) of its own: no checks, no copy.
        obj = cls.__new__(cls)
        obj._set(pose)
        return obj

    @classmethod
    def _from_arrays(cls, quat: NDArray[np.float64], translation: NDArray[np.float64]) -> RigidTransform:
        # Trusted arrays (unit quaternions, finite translations), broadcast against each other: no checks.
        return cls._from_pose(_packed(quat, translation))

    @classmethod
    def from_rotation_translation(cls, rotation: Rotation | ArrayLike, translation: ArrayLike) -> RigidTransform:
        """Pose with rotation ``R`` about the base point and its translation ``r_C``.

        Parameters
        ----------
        rotation : Rotation or array_like
            kreisel/scipy ``Rotation``, matrices ``(..., 3, 3)`` or quaternions ``(..., 4)``.
        translation : array_like, shape (..., 3)
            ``r_C``; broadcast against the rotation's batch shape.

        Examples
        --------
        >>> RigidTransform.from_rotation_translation([1, 0, 0, 0], [1, 2, 3])
        RigidTransform(quat=[1.0, 0.0, 0.0, 0.0], translation=[1.0, 2.0, 3.0])
        """
        return cls(rotation, translation)

    @classmethod
    def from_components(cls, translation: ArrayLike, rotation: Rotation | ArrayLike) -> RigidTransform:
        """scipy's argument order, translation first: the same as ``RigidTransform(rotation, translation)``.

        Examples
        --------
        >>> RigidTransform.from_components([1.0, 2.0, 3.0], [1.0, 0.0, 0.0, 0.0]).translation
        array([1., 2., 3.])
        """
        return cls(rotation, translation)

    @classmethod
    def concatenate(cls, transforms: RigidTransform | Iterable[RigidTransform]) -> RigidTransform:
        """One batch from a sequence of transforms (single ones count as one element each).

        Examples
        --------
        >>> RigidTransform.concatenate([RigidTransform.identity(), RigidTransform.identity(2)]).shape
        (3,)
        """
        if isinstance(transforms, RigidTransform):
            return cls._from_pose(np.array(transforms._pose))
        parts = list(transforms)
        if not parts or not all(isinstance(t, RigidTransform) for t in parts):
            raise TypeError("transforms must be a non-empty sequence of kreisel RigidTransform objects")
        return cls._from_pose(np.concatenate([np.atleast_2d(t._pose) for t in parts]))

    @classmethod
    def from_rotation(cls, rotation: Rotation | ArrayLike) -> RigidTransform:
        """Pure rotation about the origin (zero translation).

        Examples
        --------
        >>> RigidTransform.from_rotation([0.0, 0.0, 0.0, 1.0]).apply([1.0, 0.0, 0.0]) + 0.0
        array([-1.,  0.,  0.])
        """
        return cls._from_arrays(as_quaternion(rotation, "rotation"), np.zeros(3))

    @classmethod
    def from_translation(cls, translation: ArrayLike) -> RigidTransform:
        """Pure translation (identity rotation).

        Examples
        --------
        >>> RigidTransform.from_translation([1.0, 2.0, 3.0]).apply([1.0, 1.0, 1.0])
        array([2., 3., 4.])
        """
        return cls._from_arrays(np.array([1.0, 0.0, 0.0, 0.0]), finite_array(translation, "translation"))

    @classmethod
    def identity(cls, shape: int | tuple[int, ...] | None = None) -> RigidTransform:
        """Identity transforms of batch shape ``shape`` (``None`` or ``()``: a single one).

        Examples
        --------
        >>> RigidTransform.identity(3).shape
        (3,)
        """
        shape = batch_shape(shape)
        quat = np.zeros(shape + (4,))
        quat[..., 0] = 1.0
        return cls._from_arrays(quat, np.zeros(shape + (3,)))

    @classmethod
    def random(cls, shape: int | tuple[int, ...] | None = None, rng: Any = None,
               translation_scale: float = 1.0) -> RigidTransform:
        """Random poses: uniform (Haar) rotations and Gaussian translations.

        Parameters
        ----------
        shape : None, int or tuple of int
            Batch shape (``None``: a single transform).
        rng : None, int or numpy.random.Generator
            Seed or generator, for reproducible draws.
        translation_scale : float
            Standard deviation of each translation component, metres.

        Examples
        --------
        >>> len(RigidTransform.random(5, rng=0))
        5
        """
        shape = batch_shape(shape)
        rng = np.random.default_rng(rng)
        rotation = Rotation.random(shape, rng=rng)
        translation = translation_scale * rng.standard_normal(shape + (3,))
        return cls._from_arrays(rotation.as_quat(), translation)

    @classmethod
    def from_matrix(cls, matrix: ArrayLike) -> RigidTransform:
        """Poses from homogeneous matrices ``[[R, r_C], [0, 0, 0, 1]]`` of shape ``(..., 4, 4)``.

        Raises ``ValueError`` when the bottom row is not (0, 0, 0, 1) or the
        upper-left block is not a rotation (tolerance ``RIGIDITY_TOLERANCE``);
        matrices within it are projected onto the nearest pose.

        Examples
        --------
        >>> m = [[0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]
        >>> RigidTransform.from_matrix(m).translation
        array([1., 2., 3.])
        """
        return cls._from_pose(_kernels.from_matrix(matrix))

    @classmethod
    def from_dual_quat(cls, dual_quat: ArrayLike) -> RigidTransform:
        """Poses from unit dual quaternions ``σ = q_r + ε q_d`` stored as ``(..., 8)``.

        Layout ``[q_r, q_d]`` with both parts scalar first (Hamilton);
        ``q_d = ½ (0, r_C) q_r``, hence ``r_C = 2 vec(q_d q_r*)``. Unit means
        ``|q_r| = 1`` and ``q_r·q_d = 0``; inputs off by more than
        ``RIGIDITY_TOLERANCE`` raise ``ValueError``, closer ones are projected.

        Examples
        --------
        >>> RigidTransform.from_dual_quat([1, 0, 0, 0, 0, 0.5, 1.0, 1.5]).translation
        array([1., 2., 3.])
        """
        return cls._from_pose(_kernels.from_dual_quat(dual_quat))

    @classmethod
    def from_exp_coords(cls, exp_coords: ArrayLike) -> RigidTransform:
        """Exponential map of twists ``ξ = (ω, v)`` (rotation part first), ``(..., 6)``.

        ``T = exp([[hat ω, v], [0, 0]])``: ``R = exp(hat ω)`` and
        ``r_C = J_l(ω) v`` with the SO(3) left Jacobian (see :mod:`kreisel.se3.lie`).
        Agrees with scipy's ``RigidTransform.from_exp_coords``. Rotation parts
        longer than 1e8 rad are refused (see :func:`~kreisel.so3.rotvec_to_quat`).

        Examples
        --------
        >>> import numpy as np
        >>> T = RigidTransform.from_exp_coords([0, 0, np.pi / 2, 1.0, 0, 0])   # quarter screw turn
        >>> T.translation.round(6) + 0.0                   # (2/π)(1, 1, 0)
        array([0.63662, 0.63662, 0.     ])
        """
        return cls._from_pose(_kernels.exp(exp_coords))

    @classmethod
    def from_screw(cls, axis: ArrayLike, point: ArrayLike, angle: ArrayLike, translation: ArrayLike = 0.0) -> RigidTransform:
        """Screw displacements (Chasles/Mozzi): turn by ``angle`` about the line
        ``point + λ axis`` and slide ``translation`` along ``axis``.

        Parameters
        ----------
        axis : array_like, shape (..., 3)
            Nonzero direction (normalised here).
        point : array_like, shape (..., 3)
            Any point of the axis.
        angle : array_like, shape (...)
            Rotation angle, right-handed about ``axis``, radians.
        translation : array_like, shape (...)
            Slide along ``axis``, metres.

        Examples
        --------
        >>> T = RigidTransform.from_screw([0, 0, 1], [1.0, 0.0, 0.0], 3.141592653589793, 2.0)
        >>> T.apply([1.0, 0.0, 0.0]).round(12) + 0.0          # a point of the axis only slides
        array([1., 0., 2.])
        """
        return cls._from_arrays(*screw_pose(axis, point, angle, translation))

    @classmethod
    def from_scipy(cls, transform: ScipyRigidTransform) -> RigidTransform:
        """Convert a ``scipy.spatial.transform.RigidTransform`` (scipy >= 1.16).

        Examples
        --------
        >>> from scipy.spatial.transform import RigidTransform as ScipyRigidTransform
        >>> RigidTransform.from_scipy(ScipyRigidTransform.from_translation([1.0, 0.0, 0.0]))
        RigidTransform(quat=[1.0, 0.0, 0.0, 0.0], translation=[1.0, 0.0, 0.0])
        """
        if not hasattr(transform, "as_components"):
            raise TypeError(f"transform must be a scipy RigidTransform, got {type(transform).__name__}")
        translation, rotation = transform.as_components()
        return cls._from_arrays(rotation.as_quat(scalar_first=True), np.asarray(translation, dtype=np.float64))

    # -- conversion ----------------------------------------------------------------------------

    @property
    def rotation(self) -> Rotation:
        """The rotation part as a kreisel :class:`~kreisel.so3.Rotation`."""
        return Rotation.from_quat(self._q)

    @property
    def translation(self) -> NDArray[np.float64]:
        """The translation ``r_C``, ``(..., 3)``."""
        return np.array(self._translation)

    @takes_out
    def as_quat(self, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Unit quaternions of the rotation part, scalar first, ``(..., 4)``.

        Examples
        --------
        >>> import numpy as np
        >>> T = RigidTransform.from_rotation_translation([np.sqrt(0.5), 0, 0, np.sqrt(0.5)], [1.0, 0, 0])
        >>> T.as_quat().round(6).tolist()
        [0.707107, 0.0, 0.0, 0.707107]
        """
        return np.array(self._q) if out is None else deliver(self._q, out)

    def as_components(self) -> tuple[Rotation, NDArray[np.float64]]:
        """``(rotation, translation)``: a kreisel ``Rotation`` and ``r_C``.

        Examples
        --------
        The pair is a round trip: it rebuilds the same displacement:

        >>> import numpy as np
        >>> T = RigidTransform.from_rotation_translation([np.sqrt(0.5), 0, 0, np.sqrt(0.5)], [1.0, 2.0, 3.0])
        >>> rotation, translation = T.as_components()
        >>> round(float(np.degrees(rotation.magnitude())), 9), translation.tolist()
        (90.0, [1.0, 2.0, 3.0])
        >>> bool(np.allclose(RigidTransform.from_rotation_translation(rotation, translation).as_matrix(), T.as_matrix()))
        True
        """
        return self.rotation, self.translation

    @uses(_kernels.as_matrix)
    @takes_out
    def as_matrix(self, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Homogeneous matrices ``[[R, r_C], [0, 0, 0, 1]]``, ``(..., 4, 4)``.

        Examples
        --------
        The homogeneous matrix acting on ``(r, 1)`` moves points like :meth:`apply`,
        and matrix products compose like ``*``:

        >>> import numpy as np
        >>> T = RigidTransform.from_rotation_translation([np.sqrt(0.5), 0, 0, np.sqrt(0.5)], [1.0, 0, 0])
        >>> M = T.as_matrix()
        >>> (M @ [1.0, 0.0, 0.0, 1.0]).round(12).tolist(), T.apply([1.0, 0.0, 0.0]).round(12).tolist()
        ([1.0, 1.0, 0.0, 1.0], [1.0, 1.0, 0.0])
        >>> bool(np.allclose((T * T).as_matrix(), M @ M))
        True
        """
        return _kernels.as_matrix(self._pose, out=out)

    @uses(_kernels.as_dual_quat)
    @takes_out
    def as_dual_quat(self, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Unit dual quaternions ``[q_r, q_d]``, ``(..., 8)``, with ``q_d = ½ (0, r_C) q_r``.

        Both parts scalar first; ``q_r`` is the stored rotation quaternion
        (either sign of the double cover may appear).

        Examples
        --------
        >>> RigidTransform.from_translation([1.0, 2.0, 3.0]).as_dual_quat()
        array([1. , 0. , 0. , 0. , 0. , 0.5, 1. , 1.5])
        """
        return _kernels.as_dual_quat(self._pose, out=out)

    @uses(_kernels.log)
    @takes_out
    def as_exp_coords(self, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Logarithm as twists ``ξ = (ω, v)``, ``(..., 6)``, with ``|ω| <= π``.

        Accurate to a few ulp at all angles, including tiny ones and near π.

        Examples
        --------
        >>> RigidTransform.from_translation([1.0, 2.0, 3.0]).as_exp_coords()
        array([0., 0., 0., 1., 2., 3.])
        """
        return _kernels.log(self._pose, out=out)

    def as_screw(self) -> Screw:
        """Chasles/Mozzi screw of each displacement, as a :class:`~kreisel.se3.Screw`.

        Axis direction, the axis point closest to the origin, the angle in
        [0, π], the slide along the axis and the pitch. Pure rotations have
        zero slide; pure translations have angle 0, the direction of travel as
        axis, point 0 and pitch ``inf``. Accurate near π (no division by
        sin θ) and at small angles.

        Examples
        --------
        >>> T = RigidTransform.from_translation([0.0, 3.0, 0.0])
        >>> T.as_screw().axis, float(T.as_screw().translation)
        (array([0., 1., 0.]), 3.0)
        """
        return screw_parameters(self._q, self._translation)

    @uses(_kernels.adjoint)
    @takes_out
    def adjoint(self, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Adjoint matrices ``Ad_T = [[R, 0], [hat(r_C) R, R]]`` acting on twists ``(ω, v)``, ``(..., 6, 6)``.

        Examples
        --------
        The adjoint carries twists between frames, ``exp(Ad_T ξ) = T exp(ξ) T⁻¹``, and
        is a homomorphism, ``Ad_(T1 T2) = Ad_T1 Ad_T2``:

        >>> import numpy as np
        >>> T1 = RigidTransform.from_exp_coords([0.3, -0.2, 0.5, 1.0, 2.0, 0.0])
        >>> T2 = RigidTransform.from_exp_coords([0.0, 0.4, 0.1, 0.0, -1.0, 0.5])
        >>> xi = np.array([0.1, 0.2, 0.3, 0.4, 0.5, 0.6])
        >>> lhs = RigidTransform.from_exp_coords(T1.adjoint() @ xi).as_matrix()
        >>> bool(np.allclose(lhs, (T1 * RigidTransform.from_exp_coords(xi) * T1.inv()).as_matrix()))
        True
        >>> bool(np.allclose((T1 * T2).adjoint(), T1.adjoint() @ T2.adjoint()))
        True
        """
        return _kernels.adjoint(self._pose, out=out)

    def to_scipy(self) -> ScipyRigidTransform:
        """Equivalent ``scipy.spatial.transform.RigidTransform``.

        Examples
        --------
        >>> import numpy as np
        >>> T = RigidTransform.from_exp_coords([0.3, -0.2, 0.5, 1.0, 2.0, 0.0])
        >>> bool(np.allclose(T.to_scipy().apply([1.0, 2.0, 3.0]), T.apply([1.0, 2.0, 3.0])))
        True
        """
        from scipy.spatial.transform import RigidTransform as ScipyRigidTransform
        from scipy.spatial.transform import Rotation as ScipyRotation

        rotation = ScipyRotation.from_quat(self._q, scalar_first=True)
        return ScipyRigidTransform.from_components(self._translation, rotation)

    # -- group operations ------------------------------------------------------------------------

    def __mul__(self, other: RigidTransform) -> RigidTransform:
        if not isinstance(other, RigidTransform):
            return NotImplemented
        return RigidTransform._from_pose(_kernels.compose(self._pose, other._pose))

    def __pow__(self, p: ArrayLike, modulus: None = None) -> RigidTransform:
        """``T ** p = exp(p log T)``: the screw motion scaled by ``p`` (scipy's ``RigidTransform.__pow__``).

        The logarithm has rotation angle in [0, π]; ``p = -1`` is the
        inverse and ``p = 0`` the identity, exactly. ``p`` may be an array
        broadcast against the batch (scipy takes a scalar only); ``|p|`` times
        the rotation angle must be at most 1e8 rad (see :func:`~kreisel.so3.rotvec_to_quat`).

        Examples
        --------
        Half of a screw motion turns half as far and slides half as far along the axis:

        >>> import numpy as np
        >>> T = RigidTransform.from_screw([0, 0, 1], [1.0, 0.0, 0.0], np.pi / 2, 2.0)
        >>> half = T ** 0.5
        >>> round(float(np.degrees(half.rotation.magnitude())), 9), float(half.as_screw().translation.round(12))
        (45.0, 1.0)
        >>> bool(np.allclose((half * half).as_matrix(), T.as_matrix()))
        True
        """
        if modulus is not None:
            raise TypeError("pow() with a modulus is not defined for rigid transforms")
        exponent = finite_array(p, "p", ())
        if exponent.ndim == 0 and exponent in (0.0, 1.0, -1.0):
            if exponent == 1.0:
                return self
            if exponent == -1.0:
                return self.inv()
            return RigidTransform.identity(self.shape)
        check_angle_multiple(exponent, lambda: self._q, "p", "|p| times the rotation angle")
        return RigidTransform._from_pose(_kernels.power(self._pose, exponent))

    def mean(self, weights: ArrayLike | None = None, axis: int | tuple[int, ...] | None = None) -> RigidTransform:
        """Mean pose: chordal L2 mean of the rotations and weighted mean of the translations.

        scipy's ``RigidTransform.mean``: the rotation part is
        :meth:`Rotation.mean <kreisel.so3.Rotation.mean>`, the translation the
        (weighted) arithmetic mean, both over the batch ``axis`` (``None``:
        all axes).

        Parameters
        ----------
        weights : array_like, optional
            Non-negative, of the batch shape (``(1,)`` for a single pose).
        axis : None, int or tuple of int
            As for :meth:`Rotation.mean <kreisel.so3.Rotation.mean>`.

        Examples
        --------
        >>> import numpy as np
        >>> T = RigidTransform.from_rotation_translation(
        ...     [[1.0, 0, 0, 0], [np.cos(0.2), 0, 0, np.sin(0.2)]], [[0.0, 0, 0], [2.0, 0, 0]]
        ... )
        >>> m = T.mean()
        >>> m.translation.tolist(), round(float(m.rotation.magnitude()), 12)
        ([1.0, 0.0, 0.0], 0.2)
        """
        q, translation = self._q, np.asarray(self._translation)
        if self.single:  # as scipy: a single pose is a batch of one, so its mean is itself
            q, translation = q[np.newaxis], translation[np.newaxis]
        quat, axes = mean_over(q, weights, axis)
        nd = q.ndim - 1
        t = gather_samples(translation, nd, axes)
        if weights is None:
            translation = t.mean(axis=-2)
        else:
            w = gather_samples(np.asarray(weights, dtype=np.float64), nd, axes)[..., None]
            translation = (w * t).sum(axis=-2) / w.sum(axis=-2)
        return RigidTransform._from_arrays(quat, translation)

    def inv(self) -> RigidTransform:
        """Inverse displacements ``(Rᵀ, -Rᵀ r_C)``.

        Examples
        --------
        >>> RigidTransform.from_translation([1.0, 2.0, 3.0]).inv().translation
        array([-1., -2., -3.])
        """
        return RigidTransform._from_pose(_kernels.invert(self._pose))

    @uses(_kernels.move)
    @takes_out
    def apply(self, points: ArrayLike, inverse: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Move points: ``R r + r_C`` (Theory §1.3), or ``Rᵀ (r - r_C)`` with ``inverse=True``.

        Parameters
        ----------
        points : array_like, shape (..., 3)
            Broadcast against the batch shape.
        inverse : bool
            Apply the inverse displacement.

        Returns
        -------
        ndarray, shape (..., 3)
            Moved points, with the broadcast batch shape.

        Examples
        --------
        >>> T = RigidTransform.from_translation([0.0, 0.0, 1.0])
        >>> T.apply([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
        array([[1., 0., 1.],
               [0., 1., 1.]])
        """
        return _kernels.move(self._pose, points, check_flag(inverse, "inverse"), out=out)

    @uses(_kernels.turn)
    @takes_out
    def apply_vector(self, vectors: ArrayLike, inverse: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """Rotate free vectors (no translation): ``R v``, or ``Rᵀ v`` with ``inverse=True``.

        Parameters
        ----------
        vectors : array_like, shape (..., 3)
            Free vectors (directions, velocities, forces): turned, never shifted.
        inverse : bool
            Turn by ``Rᵀ`` instead.

        Examples
        --------
        >>> RigidTransform.from_translation([5.0, 5.0, 5.0]).apply_vector([1.0, 0.0, 0.0])
        array([1., 0., 0.])
        """
        return _kernels.turn(self._pose, vectors, check_flag(inverse, "inverse"), out=out)

    def change_base_point(self, offset: ArrayLike) -> RigidTransform:
        """Same displacement about another base point; see :func:`kreisel.se3.change_base_point`.

        Examples
        --------
        A door turned 90° about its hinge at the origin; describing the same motion
        about the door's far corner A (1 m along body x) keeps R and moves the base
        point to where A went:

        >>> import numpy as np
        >>> T = RigidTransform.from_rotation([np.sqrt(0.5), 0, 0, np.sqrt(0.5)])
        >>> TA = T.change_base_point([1.0, 0.0, 0.0])
        >>> (TA.translation.round(12) + 0.0).tolist(), bool(np.allclose(TA.as_quat(), T.as_quat()))
        ([0.0, 1.0, 0.0], True)
        >>> bool(np.allclose(TA.apply([0.5, 0.0, 0.0]), T.apply([1.5, 0.0, 0.0])))
        True
        """
        return change_base_point(self, offset)

    # -- container protocol (shape, single and len: QuaternionBatch) -----------------------------

    def __getitem__(self, key: Any) -> RigidTransform:
        if self.single:
            raise self._single_error("is not subscriptable")
        # Index an array of batch positions so that any numpy index (slices,
        # masks, Ellipsis, fancy) acts on the batch axes only.
        index = np.arange(int(np.prod(self.shape))).reshape(self.shape)[key]
        return RigidTransform._from_pose(self._pose.reshape(-1, 7)[index])

    def __iter__(self) -> Iterator[RigidTransform]:
        if self.single:
            raise self._single_error("is not iterable")
        for i in range(len(self)):
            yield self[i]

    def __setitem__(self, key: Any, value: RigidTransform) -> None:
        if self.single:
            raise self._single_error("does not support item assignment")
        if not isinstance(value, RigidTransform):
            raise TypeError(f"value must be a kreisel RigidTransform, got {type(value).__name__}")
        # A fresh array: the stored one may be shared with other transforms.
        pose = np.array(self._pose)
        index = np.arange(int(np.prod(self.shape))).reshape(self.shape)[key]
        pose.reshape(-1, 7)[index] = value._pose
        self._set(pose)

    def __repr__(self) -> str:
        def fmt(a: NDArray[np.float64]) -> str:
            return np.array2string(a, separator=", ", precision=6, threshold=24, floatmode="maxprec_equal")

        if self.single:
            q = "[" + ", ".join(repr(float(x)) for x in self._q) + "]"
            t = "[" + ", ".join(repr(float(x)) for x in self._translation) + "]"
            return f"RigidTransform(quat={q}, translation={t})"
        return f"RigidTransform(shape={self.shape}, quat={fmt(self._q)}, translation={fmt(self._translation)})"

    def _repr_html_(self) -> str:
        note = "r_P = R r′_P + r_C; quaternion scalar-first, R maps body to space"
        rows: list[tuple[str, object]]
        if self.single:
            rows = [
                ("quaternion", number(self._q)),
                ("angle", number(np.degrees(np.linalg.norm(quat_to_rotvec(self._q)))) + "°"),
                ("translation r_C", number(self._translation)),
            ]
        else:
            rows = [("shape", self.shape), ("count", int(np.prod(self.shape)))]
            if np.prod(self.shape):
                rows += [("first quaternion", number(self._q.reshape(-1, 4)[0])),
                         ("first translation", number(self._translation.reshape(-1, 3)[0]))]
        return html_table("RigidTransform", rows, note=note)


def change_base_point(transform: RigidTransform, offset: ArrayLike) -> RigidTransform:
    """The same displacement described about another body point (Theory §1.3, corollary).

    With base point C, ``r_P = R r′_CP + r_C``. Taking instead the body
    point A with body components ``r′_CA = offset`` (relative to C) as the
    base point gives ``r_P = R r′_AP + r_A`` with the **same** R and
    ``r_A = R r′_CA + r_C``. The result maps body components relative to A
    to space positions; it equals ``transform * RigidTransform.from_translation(offset)``.

    Parameters
    ----------
    transform : RigidTransform
        Displacement described with base point C.
    offset : array_like, shape (..., 3)
        ``r′_CA``: body components of the new base point A, relative to C.

    Returns
    -------
    RigidTransform

    Examples
    --------
    >>> import numpy as np
    >>> from kreisel.se3 import RigidTransform
    >>> T = RigidTransform.from_rotation_translation([0, 0, 0, 1], [1.0, 0.0, 0.0])  # 180° about z
    >>> TA = change_base_point(T, [1.0, 0.0, 0.0])
    >>> TA.translation                                   # where A went
    array([0., 0., 0.])
    >>> np.allclose(TA.as_quat(), T.as_quat())           # R unchanged
    True
    """
    if not isinstance(transform, RigidTransform):
        raise TypeError(f"transform must be a RigidTransform, got {type(transform).__name__}")
    return RigidTransform._from_pose(_kernels.based_at(transform._pose, offset))


def _packed(quat: NDArray[np.float64], translation: NDArray[np.float64]) -> NDArray[np.float64]:
    """Poses ``[q, t]`` ``(..., 7)`` of quaternions and translations broadcast against each other."""
    pose = np.empty(np.broadcast_shapes(quat.shape[:-1], translation.shape[:-1]) + (7,))
    pose[..., :4], pose[..., 4:] = quat, translation
    return pose
