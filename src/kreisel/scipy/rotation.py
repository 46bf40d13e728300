"""scipy's ``Rotation`` over kreisel's: scalar-last quaternions and scipy's defaults.

The rotations are held by a :class:`kreisel.so3.Rotation` (scalar-first unit
quaternions) and every operation runs on kreisel's compiled kernels; this
module only translates at the boundary: quaternion order, scipy's default
arguments (the gimbal-lock warning of ``as_euler``), its projection of
non-orthogonal matrices, and the return types scipy gives.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Iterable, Iterator
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._norms import nearest_rotation
from .._validation import as_float_array, batch_shape, check_flag
from ..so3 import davenport as _davenport
from ..so3 import euler as _euler
from ..so3 import matrix as _matrix
from ..so3 import quaternion as _quat
from ..so3.rotation import Rotation as _Rotation

__all__ = ["Rotation"]

#: Distance of the middle angle from its singular value below which ``as_euler`` warns, radians.
_GIMBAL_TOLERANCE = 1e-7
#: Largest deviation of ``M Mᵀ`` from the identity for which a matrix is used as it is.
_ORTHOGONALITY_TOLERANCE = 1e-12


def _last_to_first(q: NDArray[np.float64]) -> NDArray[np.float64]:
    # C order: indexing the last axis with a list gives a Fortran-ordered array, which the kernels read ~20x slower
    return np.ascontiguousarray(q[..., [3, 0, 1, 2]])


def _warn_gimbal_lock(mask: NDArray[np.bool_]) -> None:
    if np.any(mask):
        warnings.warn(
            "Gimbal lock: the first and third angles are not unique; the third angle is set to zero "
            f"({int(np.sum(mask))} of {np.size(mask)} rotations)",
            _euler.GimbalLockWarning,  # a UserWarning, as scipy's
            stacklevel=3,
        )


def _third_angle_zero(q: NDArray[np.float64], angles: NDArray[np.float64], lock: NDArray[np.bool_],
                      axes: NDArray[np.float64], intrinsic: bool, degrees: bool) -> NDArray[np.float64]:
    """``angles`` with, where ``lock``, the third angle 0 and the first one turning the rest (scipy's choice).

    At gimbal lock only the sum or difference of the outer angles is defined.
    With the third angle 0 the rotation is ``R₁(a₁) R₂(a₂)`` (intrinsic) or
    ``R₂(a₂) R₁(a₁)`` (extrinsic), so ``R₁(a₁)`` is what is left of ``R``
    once the middle turn is taken off, and ``a₁`` its angle about the first
    axis (exact at lock, the nearest such angle within the 1e-7 rad of the
    warning).
    """
    if not np.any(lock):
        return angles
    n1, n2 = (axes[:2] / np.linalg.norm(axes[:2], axis=-1, keepdims=True))
    a = np.array(angles)
    half = 0.5 * (np.deg2rad(a[..., 1]) if degrees else a[..., 1])
    undo_middle = np.concatenate([np.cos(half)[..., None], -np.sin(half)[..., None] * n2], axis=-1)
    rest = _quat.quat_multiply(q, undo_middle) if intrinsic else _quat.quat_multiply(undo_middle, q)
    first = np.remainder(2.0 * np.arctan2(rest[..., 1:] @ n1, rest[..., 0]) + np.pi, 2.0 * np.pi) - np.pi
    a[..., 0] = np.where(lock, np.rad2deg(first) if degrees else first, a[..., 0])
    a[..., 2] = np.where(lock, 0.0, a[..., 2])
    return a


def _scipy_flip(q: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Where scalar-first ``q`` has the other sign than scipy's matrix conversion gives (largest component > 0).

    Ties go to the first of x, y, z, w, the order in which scipy compares them.
    """
    q = np.asarray(q)
    largest = np.argmax(np.abs(q[..., [1, 2, 3, 0]]), axis=-1)[..., None]
    return np.take_along_axis(q, (largest + 1) % 4, axis=-1)[..., 0] < 0.0


def _scipy_sign(q: NDArray[np.float64]) -> NDArray[np.float64]:
    """``q`` with the sign scipy's matrix conversion gives it."""
    return np.where(_scipy_flip(q)[..., None], -q, q)


def _by_axes(axes: NDArray[np.float64], other: NDArray[np.float64], width: int,
             convert: Callable[[NDArray[np.float64], NDArray[np.float64]], NDArray[np.float64]]) -> NDArray[np.float64]:
    """``convert(axes_set, rows)`` for batched Davenport axes ``(..., k, 3)`` against ``other`` ``(..., m)``.

    The batch shapes broadcast; kreisel's kernels take one axes set per
    call, so the rows are grouped by distinct axes set (one call each).
    """
    batch = np.broadcast_shapes(axes.shape[:-2], other.shape[:-1])
    sets = np.broadcast_to(axes, batch + axes.shape[-2:]).reshape(-1, *axes.shape[-2:])
    rows = np.broadcast_to(other, batch + other.shape[-1:]).reshape(-1, other.shape[-1])
    result = np.empty((len(rows), width))
    if len(rows):
        distinct, group = np.unique(sets.reshape(len(sets), -1), axis=0, return_inverse=True)
        for i, key in enumerate(distinct):
            chosen = group.ravel() == i
            result[chosen] = convert(key.reshape(axes.shape[-2:]), rows[chosen])
    return result.reshape(batch + (width,))


def _shape_argument(num: int | None, shape: int | tuple[int, ...] | None) -> tuple[int, ...]:
    if num is not None and shape is not None:
        raise ValueError("give either num or shape, not both")
    return batch_shape(shape if num is None else num)


class Rotation:
    """Rotations with scipy's interface: ``from kreisel.scipy import Rotation``.

    A drop-in for ``scipy.spatial.transform.Rotation``: quaternions are scalar
    last (``[x, y, z, w]``) unless ``scalar_first=True``, ``as_euler`` warns at
    gimbal lock, ``from_matrix`` projects a non-orthogonal matrix onto the
    nearest rotation. kreisel's own :class:`kreisel.so3.Rotation` (scalar
    first) is :meth:`to_kreisel`.

    Parameters
    ----------
    quat : array_like, shape (..., 4)
        Quaternions, scalar last unless ``scalar_first``.
    normalize : bool
        Scale to unit norm (``False``: used as given, the caller vouches for unit norm).
    copy : bool
        Copy the array (only read when ``normalize=False``).
    scalar_first : bool

    Examples
    --------
    >>> import numpy as np
    >>> from kreisel.scipy import Rotation
    >>> r = Rotation.from_quat([0, 0, np.sqrt(0.5), np.sqrt(0.5)])      # [x, y, z, w]
    >>> round(float(np.degrees(r.magnitude())), 9)
    90.0
    >>> r.to_kreisel().as_quat().round(6).tolist()                      # kreisel: [w, x, y, z]
    [0.707107, 0.0, 0.0, 0.707107]
    """

    __slots__ = ("_r",)
    _r: _Rotation

    def __init__(self, quat: ArrayLike, normalize: bool = True, copy: bool = True, *,
                 scalar_first: bool = False) -> None:
        q = as_float_array(quat, "quat", (4,), finite=False)
        if not check_flag(scalar_first, "scalar_first"):
            q = _last_to_first(q)
        if check_flag(normalize, "normalize"):
            self._r = _Rotation(q)
        else:
            self._r = _Rotation(np.array(q) if copy else q, _validated=True)

    @classmethod
    def _of(cls, rotation: _Rotation) -> Rotation:
        obj = cls.__new__(cls)
        obj._r = rotation
        return obj

    @classmethod
    def from_kreisel(cls, rotation: _Rotation) -> Rotation:
        """The same rotations as a :class:`kreisel.so3.Rotation` (no copy).

        Examples
        --------
        >>> import kreisel as kr
        >>> from kreisel.scipy import Rotation
        >>> Rotation.from_kreisel(kr.Rotation.identity()).as_quat().tolist()
        [0.0, 0.0, 0.0, 1.0]
        """
        if not isinstance(rotation, _Rotation):
            raise TypeError(f"rotation must be a kreisel.so3.Rotation, got {type(rotation).__name__}")
        return cls._of(rotation)

    def to_kreisel(self) -> _Rotation:
        """The same rotations as a :class:`kreisel.so3.Rotation`, scalar-first.

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> Rotation.identity().to_kreisel().as_quat().tolist()
        [1.0, 0.0, 0.0, 0.0]
        """
        return self._r

    # -- construction ------------------------------------------------------------------------
    @classmethod
    def from_quat(cls, quat: ArrayLike, *, scalar_first: bool = False) -> Rotation:
        """From quaternions, scalar last (``[x, y, z, w]``) unless ``scalar_first``; normalised.

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> Rotation.from_quat([0, 0, 1, 1]).as_rotvec().round(6).tolist()
        [0.0, 0.0, 1.570796]
        """
        return cls(quat, scalar_first=scalar_first)

    @classmethod
    def from_matrix(cls, matrix: ArrayLike, *, assume_valid: bool = False) -> Rotation:
        """From rotation matrices; a non-orthogonal one is replaced by the nearest rotation.

        The nearest rotation in the Frobenius norm (``U Vᵀ`` of the SVD
        ``M = U S Vᵀ``) is used for matrices whose ``M Mᵀ`` is more than 1e-12
        from the identity. Matrices with ``det M <= 0`` are refused.
        ``assume_valid=True`` skips the checks for matrices known orthogonal.

        Examples
        --------
        >>> import numpy as np
        >>> from kreisel.scipy import Rotation
        >>> r = Rotation.from_matrix(np.diag([1.0, 1.0, 2.0]))     # projected onto SO(3)
        >>> r.as_matrix().round(12).tolist() == np.eye(3).tolist()
        True
        """
        m = as_float_array(matrix, "matrix", (3, 3), finite=False)
        try:
            # kreisel's compiled conversion projects matrices up to 1e-6 from orthogonal itself
            q = _matrix.matrix_to_quat(m)
        except ValueError:
            if check_flag(assume_valid, "assume_valid"):
                raise
            q = _matrix.matrix_to_quat(_orthogonal(m))
        return cls._of(_Rotation._wrap(_scipy_sign(q)))

    @classmethod
    def from_rotvec(cls, rotvec: ArrayLike, degrees: bool = False) -> Rotation:
        """From rotation vectors (axis times angle).

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> Rotation.from_rotvec([0, 0, 90], degrees=True).as_quat().round(6).tolist()
        [0.0, 0.0, 0.707107, 0.707107]
        """
        return cls._of(_Rotation.from_rotvec(rotvec, degrees=degrees))

    @classmethod
    def from_mrp(cls, mrp: ArrayLike) -> Rotation:
        """From modified Rodrigues parameters ``n tan(ψ/4)``.

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> round(float(Rotation.from_mrp([0, 0, 1]).magnitude()), 12)
        3.14159265359
        """
        return cls._of(_Rotation.from_mrp(mrp))

    @classmethod
    def from_euler(cls, seq: str, angles: ArrayLike, degrees: bool = False) -> Rotation:
        """From Euler angles: uppercase intrinsic, lowercase extrinsic axes (1 to 3).

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> Rotation.from_euler("z", 90, degrees=True).as_quat().round(6).tolist()
        [0.0, 0.0, 0.707107, 0.707107]
        """
        return cls._of(_Rotation.from_euler(seq, angles, degrees=degrees))

    @classmethod
    def from_davenport(cls, axes: ArrayLike, order: str, angles: ArrayLike, degrees: bool = False) -> Rotation:
        """From Davenport angles about ``axes`` (``"e"``/``"extrinsic"`` or ``"i"``/``"intrinsic"``).

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> r = Rotation.from_davenport([[0, 0, 1], [1, 0, 0], [0, 0, 1]], "extrinsic", [10, 20, 30], degrees=True)
        >>> bool(r.approx_equal(Rotation.from_euler("zxz", [10, 20, 30], degrees=True)))
        True
        """
        a = as_float_array(axes, "axes", (3,))
        if a.ndim <= 2:
            return cls._of(_Rotation.from_davenport(a, order, angles, degrees=degrees))
        rows = as_float_array(angles, "angles", (a.shape[-2],), finite=False)
        return cls._of(_Rotation._wrap(_by_axes(
            a, rows, 4, lambda key, part: _davenport.davenport_to_quat(key, order, part, degrees=degrees))))

    @classmethod
    def identity(cls, num: int | None = None, *, shape: int | tuple[int, ...] | None = None) -> Rotation:
        """Identity rotations: one, ``num`` or of batch ``shape``.

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> Rotation.identity(2).as_quat().tolist()
        [[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, 1.0]]
        """
        return cls._of(_Rotation.identity(_shape_argument(num, shape)))

    @classmethod
    def random(cls, num: int | None = None, rng: Any = None, *,
               shape: int | tuple[int, ...] | None = None, random_state: Any = None) -> Rotation:
        """Uniform random rotations (scipy's draws for the same seed; ``random_state`` is ``rng``'s old name).

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> Rotation.random(3, rng=0).shape
        (3,)
        """
        if random_state is not None:
            if rng is not None:
                raise ValueError("give either rng or random_state (its old name), not both")
            rng = random_state
        return cls._of(_Rotation.random(_shape_argument(num, shape), rng=rng))

    @classmethod
    def concatenate(cls, rotations: Rotation | Iterable[Rotation]) -> Rotation:
        """One batch of the given rotations (single ones count as one each).

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> len(Rotation.concatenate([Rotation.identity(), Rotation.random(2, rng=0)]))
        3
        """
        if isinstance(rotations, Rotation):
            return cls._of(_Rotation.concatenate(rotations._r))
        parts = list(rotations)
        if not all(isinstance(r, Rotation) for r in parts):
            raise TypeError("rotations must be a sequence of kreisel.scipy Rotation objects")
        return cls._of(_Rotation.concatenate([r._r for r in parts]))

    @classmethod
    def align_vectors(cls, a: ArrayLike, b: ArrayLike, weights: ArrayLike | None = None,
                      return_sensitivity: bool = False) -> tuple[Any, ...]:
        """The rotation ``R`` with ``a ≈ R b`` (Wahba's problem), its rssd and optionally the sensitivity.

        Examples
        --------
        >>> import numpy as np
        >>> from kreisel.scipy import Rotation
        >>> r, rssd = Rotation.align_vectors([[0, 1, 0]], [[1, 0, 0]])
        >>> r.as_rotvec().round(6).tolist(), rssd < 1e-12
        ([0.0, 0.0, 1.570796], True)
        """
        for name, vectors in (("a", a), ("b", b)):
            if np.ndim(vectors) > 2:
                raise ValueError(f"{name} must have shape (N, 3) or (3,), got {np.shape(vectors)} "
                                 "(kreisel.so3.Rotation.align_vectors solves batches)")
        rotation, *rest = _Rotation.align_vectors(a, b, weights, return_sensitivity)
        return (cls._of(_Rotation._wrap(_scipy_sign(rotation.as_quat()))), *rest)

    @classmethod
    def create_group(cls, group: str, axis: str = "Z") -> Rotation:
        """A finite rotation group: ``"I"``, ``"O"``, ``"T"``, ``"Dn"`` or ``"Cn"``.

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> len(Rotation.create_group("O"))
        24
        """
        return cls._of(_Rotation.create_group(group, axis))

    # -- representations ---------------------------------------------------------------------
    def as_quat(self, canonical: bool = False, *, scalar_first: bool = False) -> NDArray[np.float64]:
        """Unit quaternions, scalar last unless ``scalar_first``; ``canonical`` picks ``w >= 0``.

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> Rotation.from_quat([0, 0, -1, -1]).as_quat(canonical=True).round(6).tolist()
        [0.0, 0.0, 0.707107, 0.707107]
        """
        return np.ascontiguousarray(self._r.as_quat(canonical, scalar_first))

    def as_matrix(self) -> NDArray[np.float64]:
        """Rotation matrices, shape ``(..., 3, 3)``.

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> Rotation.identity().as_matrix().tolist()
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
        """
        return self._r.as_matrix()

    def as_rotvec(self, degrees: bool = False) -> NDArray[np.float64]:
        """Rotation vectors with angle in [0, π].

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> Rotation.from_quat([0, 0, 1, 1]).as_rotvec(degrees=True).round(9).tolist()
        [0.0, 0.0, 90.0]
        """
        return self._r.as_rotvec(degrees)

    def as_mrp(self) -> NDArray[np.float64]:
        """Modified Rodrigues parameters with ``|p| <= 1``.

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> Rotation.from_rotvec([0, 0, 3.141592653589793]).as_mrp().round(12).tolist()
        [0.0, 0.0, 1.0]
        """
        return self._r.as_mrp()

    def as_euler(self, seq: str, degrees: bool = False, *, suppress_warnings: bool = False) -> NDArray[np.float64]:
        """Euler angles; warns (:class:`~kreisel.kinematics.GimbalLockWarning`) at gimbal lock, where the third angle is set to zero.

        Examples
        --------
        >>> import warnings
        >>> from kreisel.scipy import Rotation
        >>> with warnings.catch_warnings(record=True) as caught:
        ...     warnings.simplefilter("always")
        ...     angles = Rotation.identity().as_euler("zxz", degrees=True)
        >>> caught[0].category.__name__, (angles + 0.0).tolist()
        ('GimbalLockWarning', [0.0, 0.0, 0.0])
        """
        angles = self._r.as_euler(seq, degrees)
        if len(seq) != 3:
            return angles
        lock = _euler.gimbal_lock(seq, angles, degrees=degrees, tolerance=_GIMBAL_TOLERANCE)
        if not check_flag(suppress_warnings, "suppress_warnings"):
            _warn_gimbal_lock(lock)
        axes = np.eye(3)[["xyz".index(c) for c in seq.lower()]]
        return _third_angle_zero(self._r.as_quat(), angles, lock, axes, seq.isupper(), degrees)

    def as_davenport(self, axes: ArrayLike, order: str, degrees: bool = False, *,
                     suppress_warnings: bool = False) -> NDArray[np.float64]:
        """Davenport angles about ``axes``; warns at gimbal lock as :meth:`as_euler`.

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> axes = [[0, 0, 1], [1, 0, 0], [0, 0, 1]]
        >>> r = Rotation.from_davenport(axes, "e", [10, 20, 30], degrees=True)
        >>> r.as_davenport(axes, "e", degrees=True).round(9).tolist()
        [10.0, 20.0, 30.0]
        """
        a = as_float_array(axes, "axes", (3,))
        warn = not check_flag(suppress_warnings, "suppress_warnings") and a.shape[-2:] == (3, 3)
        count = a.shape[-2] if a.ndim > 1 else 1

        def angles_and_lock(key: NDArray[np.float64], q: NDArray[np.float64]) -> NDArray[np.float64]:
            # the angles and, in a last column, whether they are at gimbal lock
            angles = _davenport.quat_to_davenport(key, order, q, degrees=degrees)
            lock = np.zeros(angles.shape[:-1], dtype=bool)
            if count == 3:
                lock = _davenport.davenport_gimbal_lock(key, order, angles, degrees, _GIMBAL_TOLERANCE)
                angles = _third_angle_zero(q, angles, lock, key, order in ("i", "intrinsic"), degrees)
            return np.concatenate([angles, lock[..., None]], axis=-1)

        if a.ndim <= 2:
            both = angles_and_lock(a, self._r.as_quat())
        else:
            both = _by_axes(a, self._r.as_quat(), count + 1, angles_and_lock)
        if warn:
            _warn_gimbal_lock(both[..., -1] > 0.0)
        return np.ascontiguousarray(both[..., :-1])

    # -- operations --------------------------------------------------------------------------
    def apply(self, vectors: ArrayLike, inverse: bool = False) -> NDArray[np.float64]:
        """Rotate vectors ``(..., 3)`` (``inverse=True``: by the inverse rotations), broadcasting.

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> Rotation.from_rotvec([0, 0, 90], degrees=True).apply([1, 0, 0]).round(12).tolist()
        [0.0, 1.0, 0.0]
        """
        return self._r.apply(vectors, inverse)

    def inv(self) -> Rotation:
        """Inverse rotations.

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> r = Rotation.random(rng=0)
        >>> bool((r * r.inv()).approx_equal(Rotation.identity()))
        True
        """
        return Rotation._of(self._r.inv())

    def magnitude(self) -> Any:
        """Rotation angles in [0, π] (a float for a single rotation).

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> round(Rotation.from_rotvec([0, 0, 1]).magnitude(), 12)
        1.0
        """
        angle = self._r.magnitude()
        return float(angle) if self.single else angle

    def approx_equal(self, other: Rotation, atol: float | None = None, degrees: bool = False) -> Any:
        """Whether the rotations agree in angle to ``atol`` (1e-8 rad when not given).

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> Rotation.from_quat([0, 0, 1, 1]).approx_equal(Rotation.from_quat([0, 0, -1, -1]))
        True
        """
        other = _rotation(other, "other")
        if atol is None:
            if degrees:
                warnings.warn("atol must be set to use the degrees flag; the default 1e-8 rad is used",
                              UserWarning, stacklevel=2)
            atol, degrees = 1e-8, False
        equal = self._r.approx_equal(other._r, atol, degrees)
        return bool(equal) if equal.ndim == 0 else equal

    def mean(self, weights: ArrayLike | None = None, axis: int | tuple[int, ...] | None = None) -> Rotation:
        """Chordal L2 mean over the batch ``axis`` (all axes when None); a single rotation is its own mean.

        Examples
        --------
        >>> from kreisel.scipy import Rotation
        >>> (Rotation.from_rotvec([[0, 0, 0.2], [0, 0, 0.6]]).mean().as_rotvec().round(9) + 0.0).tolist()
        [0.0, 0.0, 0.4]
        """
        return Rotation._of(self._r.mean(weights, axis))

    def reduce(self, left: Rotation | None = None, right: Rotation | None = None,
               return_indices: bool = False) -> Any:
        """The equivalent rotation ``l * self * r`` of smallest angle, with ``l``, ``r`` from the groups given.

        Examples
        --------
        >>> import numpy as np
        >>> from kreisel.scipy import Rotation
        >>> r = Rotation.from_rotvec([0, 0, np.radians(100)]).reduce(right=Rotation.create_group("O"))
        >>> round(float(np.degrees(r.magnitude())), 9)
        10.0
        """
        reduced, li, ri = self._r.reduce(None if left is None else _rotation(left, "left")._r,
                                         None if right is None else _rotation(right, "right")._r, True)
        out = Rotation._of(reduced)
        return (out, li, ri) if check_flag(return_indices, "return_indices") else out

    def __mul__(self, other: Rotation) -> Rotation:
        if not isinstance(other, Rotation):
            return NotImplemented
        return Rotation._of(self._r * other._r)

    def __pow__(self, n: ArrayLike, modulus: None = None) -> Rotation:
        """``r ** n``: the rotation about the same axis by ``n`` times its angle (in [0, π])."""
        if modulus is not None:
            raise NotImplementedError("pow() with a modulus is not defined for rotations")
        return Rotation._of(self._r ** _scalar_exponent(n))

    # -- container protocol ------------------------------------------------------------------
    @property
    def shape(self) -> tuple[int, ...]:
        """Batch shape (``()`` for a single rotation)."""
        return self._r.shape

    @property
    def single(self) -> bool:
        """True for a single rotation."""
        return self._r.single

    def __len__(self) -> int:
        return len(self._r)

    def __bool__(self) -> bool:
        return True

    def __iter__(self) -> Iterator[Rotation]:
        for r in self._r:
            yield Rotation._of(r)

    def __getitem__(self, index: Any) -> Rotation:
        return Rotation._of(self._r[index])

    def __setitem__(self, index: Any, value: Rotation) -> None:
        self._r[index] = _rotation(value, "value")._r

    def __getstate__(self) -> NDArray[np.float64]:
        return self.as_quat(scalar_first=True)

    def __setstate__(self, state: NDArray[np.float64]) -> None:
        self._r = _Rotation(state, _validated=True)

    @property
    def _quat(self) -> NDArray[np.float64]:
        # scipy's private name for the scalar-last quaternions, read by code written against scipy's internals
        return self.as_quat()

    def __repr__(self) -> str:
        return _repr("Rotation.from_matrix(", self.as_matrix())


def _repr(prefix: str, array: NDArray[np.float64]) -> str:
    """``prefix`` and the array's repr, continuation lines aligned under its first row (scipy's layout)."""
    return prefix + repr(array).replace("\n", "\n" + " " * len(prefix)) + ")"


def _scalar_exponent(n: ArrayLike) -> float:
    exponent = np.asarray(n, dtype=np.float64)
    if exponent.size != 1:
        raise ValueError(f"the exponent must be a scalar (one element), got shape {exponent.shape}")
    return float(exponent.reshape(()))


def _rotation(value: Any, name: str) -> Rotation:
    if not isinstance(value, Rotation):
        raise TypeError(f"{name} must be a kreisel.scipy Rotation, got {type(value).__name__}")
    return value


def _orthogonal(m: NDArray[np.float64]) -> NDArray[np.float64]:
    """``m`` with every matrix that is not orthogonal to 1e-12 replaced by its nearest rotation; det <= 0 refused."""
    det = np.linalg.det(m)
    if np.any(det <= 0.0):
        index = tuple(int(i) for i in np.argwhere(det <= 0.0)[0])
        raise ValueError(f"matrix must have a positive determinant (a right-handed frame); matrix {index} has "
                         f"det = {float(det[index]):.3g}")
    gram = m @ np.swapaxes(m, -1, -2)
    orthogonal = np.all(np.abs(gram - np.eye(3)) <= _ORTHOGONALITY_TOLERANCE, axis=(-2, -1))
    if np.all(orthogonal):
        return m
    m = np.array(m)
    m[~orthogonal] = nearest_rotation(m[~orthogonal])
    return m
