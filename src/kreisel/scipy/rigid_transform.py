"""scipy's ``RigidTransform`` over kreisel's: scalar-last dual quaternions, scipy's normalisation.

The poses are held by a :class:`kreisel.se3.RigidTransform` and every
operation runs on its compiled kernels. At the boundary this module
translates scipy's conventions: the rotation part of a homogeneous matrix is
replaced by the nearest rotation, a dual quaternion is normalised (unit real
part, dual part made orthogonal to it), dual quaternions are scalar last
unless ``scalar_first``, and rotations are :class:`kreisel.scipy.Rotation`.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._validation import as_float_array, check_flag
from ..se3.transform import RigidTransform as _RigidTransform
from .rotation import Rotation, _repr, _scalar_exponent, _scipy_flip, _scipy_sign, _shape_argument

__all__ = ["RigidTransform"]


def _from_matrix(matrix: ArrayLike) -> _RigidTransform:
    m = as_float_array(matrix, "matrix", (4, 4), finite=False)
    bottom = m[..., 3, :] == np.array([0.0, 0.0, 0.0, 1.0])
    if not np.all(bottom):
        index = tuple(int(i) for i in np.argwhere(~np.all(bottom, axis=-1))[0]) if m.ndim > 2 else ()
        raise ValueError(f"matrix must have the last row exactly [0, 0, 0, 1]; matrix {index} has "
                         f"{m[index + (3,)].tolist()}")
    rotation = Rotation.from_matrix(m[..., :3, :3])
    return _RigidTransform(rotation.to_kreisel(), m[..., :3, 3])


def _dual_parts(dual_quat: ArrayLike, scalar_first: bool) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Scalar-first real and dual parts of ``dual_quat`` normalised to a unit dual quaternion.

    The real part is scaled to unit norm (a zero real part is read as the
    identity) and the dual part by the same factor, then its component along
    the real part is removed: the unit condition ``|q_r| = 1``, ``q_r·q_d = 0``.
    """
    dq = as_float_array(dual_quat, "dual_quat", (8,), finite=False)
    order = [0, 1, 2, 3] if check_flag(scalar_first, "scalar_first") else [3, 0, 1, 2]
    real, dual = np.ascontiguousarray(dq[..., :4][..., order]), np.ascontiguousarray(dq[..., 4:][..., order])
    norm = np.linalg.norm(real, axis=-1, keepdims=True)
    zero = norm == 0.0
    real = np.where(zero, [1.0, 0.0, 0.0, 0.0], real) / np.where(zero, 1.0, norm)
    dual = dual / np.where(zero, 1.0, norm)
    dual = dual - np.sum(real * dual, axis=-1, keepdims=True) * real
    return real, dual


class RigidTransform:
    """Rigid transforms with scipy's interface: ``from kreisel.scipy import RigidTransform``.

    A drop-in for ``scipy.spatial.transform.RigidTransform`` built on
    :class:`kreisel.se3.RigidTransform` (:meth:`to_kreisel`).

    Parameters
    ----------
    matrix : array_like, shape (..., 4, 4)
        Homogeneous matrices ``[[R, t], [0, 0, 0, 1]]``; ``R`` is replaced by
        the nearest rotation when it is not orthogonal.
    normalize, copy : bool
        Accepted for scipy's signature; the rotation part is always made
        orthogonal (kreisel stores unit quaternions), and always copied.

    Examples
    --------
    >>> import numpy as np
    >>> from kreisel.scipy import RigidTransform
    >>> tf = RigidTransform.from_translation([1.0, 2.0, 3.0])
    >>> tf.apply([0.0, 0.0, 0.0]).tolist()
    [1.0, 2.0, 3.0]
    """

    __slots__ = ("_t",)
    _t: _RigidTransform

    def __init__(self, matrix: ArrayLike, normalize: bool = True, copy: bool = True) -> None:
        check_flag(normalize, "normalize")
        check_flag(copy, "copy")
        self._t = _from_matrix(matrix)

    @classmethod
    def _of(cls, transform: _RigidTransform) -> RigidTransform:
        obj = cls.__new__(cls)
        obj._t = transform
        return obj

    def to_kreisel(self) -> _RigidTransform:
        """The same poses as a :class:`kreisel.se3.RigidTransform`.

        Examples
        --------
        >>> from kreisel.scipy import RigidTransform
        >>> RigidTransform.from_translation([1.0, 0.0, 0.0]).to_kreisel().translation.tolist()
        [1.0, 0.0, 0.0]
        """
        return self._t

    # -- construction ------------------------------------------------------------------------
    @classmethod
    def from_matrix(cls, matrix: ArrayLike) -> RigidTransform:
        """From homogeneous matrices; a non-orthogonal rotation block is replaced by the nearest rotation.

        The last row must be exactly ``[0, 0, 0, 1]``.

        Examples
        --------
        >>> import numpy as np
        >>> from kreisel.scipy import RigidTransform
        >>> m = np.diag([1.0, 1.0, 2.0, 1.0])                         # not rigid: projected
        >>> RigidTransform.from_matrix(m).as_matrix().round(12).tolist() == np.eye(4).tolist()
        True
        """
        return cls(matrix)

    @classmethod
    def from_rotation(cls, rotation: Rotation) -> RigidTransform:
        """Pure rotations.

        Examples
        --------
        >>> from kreisel.scipy import RigidTransform, Rotation
        >>> RigidTransform.from_rotation(Rotation.from_rotvec([0, 0, 1])).translation.tolist()
        [0.0, 0.0, 0.0]
        """
        r = _checked_rotation(rotation)
        return cls._of(_RigidTransform(r.to_kreisel(), np.zeros(r.shape + (3,))))

    @classmethod
    def from_translation(cls, translation: ArrayLike) -> RigidTransform:
        """Pure translations, ``(..., 3)``.

        Examples
        --------
        >>> from kreisel.scipy import RigidTransform
        >>> RigidTransform.from_translation([[1, 2, 3]]).shape
        (1,)
        """
        return cls._of(_RigidTransform.from_translation(translation))

    @classmethod
    def from_components(cls, translation: ArrayLike, rotation: Rotation) -> RigidTransform:
        """Rotate by ``rotation``, then translate by ``translation`` (batch shapes broadcast).

        Examples
        --------
        >>> from kreisel.scipy import RigidTransform, Rotation
        >>> tf = RigidTransform.from_components([1, 0, 0], Rotation.from_rotvec([0, 0, 1.5707963267948966]))
        >>> tf.apply([1, 0, 0]).round(12).tolist()
        [1.0, 1.0, 0.0]
        """
        return cls._of(_RigidTransform(_checked_rotation(rotation).to_kreisel(), translation))

    @classmethod
    def from_exp_coords(cls, exp_coords: ArrayLike) -> RigidTransform:
        """Exponential map of twists ``(ω, v)``, ``(..., 6)``.

        Examples
        --------
        >>> import numpy as np
        >>> from kreisel.scipy import RigidTransform
        >>> RigidTransform.from_exp_coords([0, 0, 0, 1, 2, 3]).translation.tolist()
        [1.0, 2.0, 3.0]
        """
        return cls._of(_RigidTransform.from_exp_coords(exp_coords))

    @classmethod
    def from_dual_quat(cls, dual_quat: ArrayLike, *, scalar_first: bool = False) -> RigidTransform:
        """From dual quaternions ``[real, dual]``, each part scalar last unless ``scalar_first``; normalised.

        Examples
        --------
        >>> from kreisel.scipy import RigidTransform
        >>> RigidTransform.from_dual_quat([0, 0, 0, 2, 1, 2, 3, 0]).translation.tolist()
        [1.0, 2.0, 3.0]
        """
        real, dual = _dual_parts(dual_quat, scalar_first)
        return cls._of(_RigidTransform.from_dual_quat(np.concatenate([real, dual], axis=-1)))

    @classmethod
    def identity(cls, num: int | None = None, *, shape: int | tuple[int, ...] | None = None) -> RigidTransform:
        """Identity transforms: one, ``num`` or of batch ``shape``.

        Examples
        --------
        >>> from kreisel.scipy import RigidTransform
        >>> RigidTransform.identity(2).shape
        (2,)
        """
        return cls._of(_RigidTransform.identity(_shape_argument(num, shape)))

    @classmethod
    def concatenate(cls, transforms: RigidTransform | Iterable[RigidTransform]) -> RigidTransform:
        """One batch of the given transforms (single ones count as one each).

        Examples
        --------
        >>> from kreisel.scipy import RigidTransform
        >>> len(RigidTransform.concatenate([RigidTransform.identity(), RigidTransform.identity(2)]))
        3
        """
        if isinstance(transforms, RigidTransform):
            return cls._of(_RigidTransform.concatenate(transforms._t))
        parts = list(transforms)
        if not all(isinstance(t, RigidTransform) for t in parts):
            raise TypeError("transforms must be a sequence of kreisel.scipy RigidTransform objects")
        return cls._of(_RigidTransform.concatenate([t._t for t in parts]))

    # -- representations ---------------------------------------------------------------------
    def as_matrix(self) -> NDArray[np.float64]:
        """Homogeneous matrices, ``(..., 4, 4)``.

        Examples
        --------
        >>> from kreisel.scipy import RigidTransform
        >>> RigidTransform.from_translation([1, 2, 3]).as_matrix()[:3, 3].tolist()
        [1.0, 2.0, 3.0]
        """
        return self._t.as_matrix()

    def as_components(self) -> tuple[NDArray[np.float64], Rotation]:
        """``(translation, rotation)``, scipy's order.

        Examples
        --------
        >>> from kreisel.scipy import RigidTransform
        >>> t, r = RigidTransform.from_translation([1, 2, 3]).as_components()
        >>> t.tolist(), r.as_quat().tolist()
        ([1.0, 2.0, 3.0], [0.0, 0.0, 0.0, 1.0])
        """
        return self.translation, self.rotation

    def as_exp_coords(self) -> NDArray[np.float64]:
        """Twists ``(ω, v)`` of the transforms, ``|ω| <= π``.

        Examples
        --------
        >>> from kreisel.scipy import RigidTransform
        >>> RigidTransform.from_translation([1, 2, 3]).as_exp_coords().tolist()
        [0.0, 0.0, 0.0, 1.0, 2.0, 3.0]
        """
        return self._t.as_exp_coords()

    def as_dual_quat(self, *, scalar_first: bool = False) -> NDArray[np.float64]:
        """Unit dual quaternions ``[real, dual]``, each part scalar last unless ``scalar_first``.

        Examples
        --------
        >>> from kreisel.scipy import RigidTransform
        >>> RigidTransform.from_translation([2, 4, 6]).as_dual_quat().tolist()
        [0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 3.0, 0.0]
        """
        dq = self._t.as_dual_quat()
        # scipy holds matrices: the quaternion's sign is that of its matrix conversion
        dq = np.where(_scipy_flip(dq[..., :4])[..., None], -dq, dq)
        if check_flag(scalar_first, "scalar_first"):
            return dq
        return np.ascontiguousarray(dq[..., [1, 2, 3, 0, 5, 6, 7, 4]])

    @property
    def rotation(self) -> Rotation:
        """The rotation part."""
        # scipy holds matrices: the quaternion's sign is that of its matrix conversion
        return Rotation.from_kreisel(type(self._t.rotation)._wrap(_scipy_sign(self._t.as_quat())))

    @property
    def translation(self) -> NDArray[np.float64]:
        """The translation part, ``(..., 3)``."""
        return self._t.translation

    # -- operations --------------------------------------------------------------------------
    def apply(self, vector: ArrayLike, inverse: bool = False) -> NDArray[np.float64]:
        """Transform points: ``R v + t`` (``inverse=True``: ``Rᵀ (v - t)``), broadcasting.

        Examples
        --------
        >>> from kreisel.scipy import RigidTransform
        >>> RigidTransform.from_translation([1, 2, 3]).apply([1, 1, 1], inverse=True).tolist()
        [0.0, -1.0, -2.0]
        """
        return self._t.apply(vector, inverse)

    def inv(self) -> RigidTransform:
        """Inverse transforms.

        Examples
        --------
        >>> from kreisel.scipy import RigidTransform
        >>> RigidTransform.from_translation([1, 2, 3]).inv().translation.tolist()
        [-1.0, -2.0, -3.0]
        """
        return RigidTransform._of(self._t.inv())

    def mean(self, weights: ArrayLike | None = None, axis: int | tuple[int, ...] | None = None) -> RigidTransform:
        """Chordal mean of the rotations and mean of the translations over the batch ``axis``.

        Examples
        --------
        >>> from kreisel.scipy import RigidTransform
        >>> RigidTransform.from_translation([[0, 0, 0], [2, 0, 0]]).mean().translation.tolist()
        [1.0, 0.0, 0.0]
        """
        return RigidTransform._of(self._t.mean(weights, axis))

    def __mul__(self, other: RigidTransform) -> RigidTransform:
        if not isinstance(other, RigidTransform):
            return NotImplemented
        return RigidTransform._of(self._t * other._t)

    def __pow__(self, n: ArrayLike, modulus: None = None) -> RigidTransform:
        """``tf ** n``: the screw motion scaled by ``n`` (rotation angle of the log in [0, π])."""
        if modulus is not None:
            raise NotImplementedError("pow() with a modulus is not defined for rigid transforms")
        return RigidTransform._of(self._t ** _scalar_exponent(n))

    # -- container protocol ------------------------------------------------------------------
    @property
    def shape(self) -> tuple[int, ...]:
        """Batch shape (``()`` for a single transform)."""
        return self._t.shape

    @property
    def single(self) -> bool:
        """True for a single transform."""
        return self._t.single

    def __len__(self) -> int:
        return len(self._t)

    def __iter__(self) -> Iterator[RigidTransform]:
        for t in self._t:
            yield RigidTransform._of(t)

    def __getitem__(self, index: Any) -> RigidTransform:
        return RigidTransform._of(self._t[index])

    def __setitem__(self, index: Any, value: RigidTransform) -> None:
        if not isinstance(value, RigidTransform):
            raise TypeError(f"value must be a kreisel.scipy RigidTransform, got {type(value).__name__}")
        self._t[index] = value._t

    def __getstate__(self) -> NDArray[np.float64]:
        return self.as_matrix()

    def __setstate__(self, state: NDArray[np.float64]) -> None:
        self._t = _from_matrix(state)

    @property
    def _matrix(self) -> NDArray[np.float64]:
        # scipy's private name for the homogeneous matrices, read by code written against scipy's internals
        return self.as_matrix()

    def __repr__(self) -> str:
        return _repr("RigidTransform.from_matrix(", self.as_matrix())


def _checked_rotation(rotation: Any) -> Rotation:
    if not isinstance(rotation, Rotation):
        raise TypeError(f"rotation must be a kreisel.scipy Rotation, got {type(rotation).__name__}")
    return rotation
