"""The input checks of kreisel's array functions: one per kind of input, with its message.

Each check converts an argument to float64 with the expected trailing shape
(:func:`~kreisel._validation.as_float_array`), verifies what it must hold
and raises a ``ValueError`` naming the argument otherwise. The kinds
(:data:`VECTOR`, :data:`QUATERNION`, ...) pair each check with the condition
that the loops of :mod:`.elementwise` evaluate per element, so that a batch
is checked in the pass that computes it and the checks below run only on the
slow path of a refusal (or before writing into ``out=``).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._norms import ORTHOGONALITY_TOLERANCE, ROUNDING_DEFECT, checked_rotation_matrices, norm
from .._validation import ROTVEC_RANGE, as_float_array, refuse_long_angle
from .elementwise import Kind, finite_condition

#: ``ROTVEC_RANGE²``: a rotation vector whose squared length is at most this is finite and in range.
ROTVEC_RANGE_SQUARED = ROTVEC_RANGE * ROTVEC_RANGE


def refuse_nonfinite(finite: bool, name: str) -> None:
    """ValueError naming ``name`` if a batch is not all finite."""
    if not finite:
        raise ValueError(f"{name} must be finite (no NaN or inf)")


def finite_array(x: ArrayLike, name: str, tail: tuple[int, ...] | None = (3,)) -> NDArray[np.float64]:
    """Float64 array with trailing shape ``tail`` and only finite entries."""
    a = as_float_array(x, name, tail, finite=False)
    refuse_nonfinite(bool(np.isfinite(a).all()), name)
    return a


def vector_array(v: ArrayLike, name: str, length: int = 3) -> NDArray[np.float64]:
    """Finite vectors ``(..., length)``."""
    return finite_array(v, name, (length,))


def quaternion_array(q: ArrayLike, name: str = "q", nonzero: bool = True) -> NDArray[np.float64]:
    """Quaternions ``(..., 4)``: finite, and nonzero unless told otherwise (the norm need not be 1)."""
    a = as_float_array(q, name, (4,), finite=False)
    if not np.isfinite(a).all():
        raise ValueError(f"{name} must be finite quaternions (no NaN or inf)")
    if nonzero and a.size and not np.abs(a).max(axis=-1).min() > 0.0:
        raise ValueError(f"{name} must be nonzero quaternions (a zero quaternion is not a rotation)")
    return a


def rotvec_array(psi: ArrayLike, name: str, what: str = "|psi|") -> NDArray[np.float64]:
    """Rotation vectors ``(..., 3)``: finite and at most ``ROTVEC_RANGE`` long.

    A rotation depends on its vector's length modulo 2π, which rounding no
    longer determines beyond :data:`~kreisel._validation.ROTVEC_RANGE`.
    """
    a = as_float_array(psi, name, (3,), finite=False)
    refuse_nonfinite(bool(np.isfinite(a).all()), name)
    refuse_long_angle(float(np.max(norm(a), initial=0.0)), name, what)
    return a


def matrix_array(R: ArrayLike, name: str = "R", tolerance: float = ORTHOGONALITY_TOLERANCE) -> NDArray[np.float64]:
    """Rotation matrices ``(..., 3, 3)``; nearly orthogonal ones are projected.

    Matrices with det <= 0, non-finite entries or an orthogonality defect
    ``max |RᵀR - 1|`` above ``tolerance`` raise ``ValueError``. If the defect
    is above rounding level but within ``tolerance``, the batch is replaced by
    its nearest rotations.
    """
    a = as_float_array(R, name, (3, 3), finite=False)
    if a.size == 0:
        return a
    with np.errstate(all="ignore"):
        gram = np.einsum("...ki,...kj->...ij", a, a) - np.eye(3)
        worst = float(np.max(np.abs(gram)))
        smallest_det = float(np.min(np.linalg.det(a)))
    return checked_rotation_matrices(a, name, worst, smallest_det, tolerance)


def _nonzero_condition(names: Sequence[str]) -> str:
    return f"({finite_condition(names)}) & (({' | '.join(f'({n} != 0.0)' for n in names)}))"


def _rotvec_condition(names: Sequence[str]) -> str:
    return f"({' + '.join(f'{n} * {n}' for n in names)} <= {ROTVEC_RANGE_SQUARED!r})"


def _matrix_condition(names: Sequence[str]) -> str:
    # orthonormal to rounding with det > 0; a NaN fails every comparison
    a, b, c, d, e, f, g, h, i = names
    columns = [(a, d, g), (b, e, h), (c, f, i)]
    terms = []
    for k in range(3):
        for m in range(k, 3):
            dot = " + ".join(f"{x} * {y}" for x, y in zip(columns[k], columns[m]))
            terms.append(f"(abs({dot}{' - 1.0' if k == m else ''}) <= {ROUNDING_DEFECT!r})")
    det = f"{a} * ({e} * {i} - {f} * {h}) - {b} * ({d} * {i} - {f} * {g}) + {c} * ({d} * {h} - {e} * {g})"
    return " & ".join(terms) + f" & ({det} > 0.0)"


#: Finite numbers of any shape.
VECTOR = Kind(finite_condition, lambda a, name: finite_array(a, name, None))
#: Finite quaternions, zero allowed (products, conjugates).
ANY_QUATERNION = Kind(finite_condition, lambda a, name: quaternion_array(a, name, nonzero=False))
#: Finite nonzero quaternions: rotations, normalised where the formula needs it.
QUATERNION = Kind(_nonzero_condition, quaternion_array)
#: Rotation matrices: orthonormal to rounding in the loop; projected within the tolerance, else refused.
MATRIX = Kind(_matrix_condition, matrix_array)


def rotation_vector(what: str = "|psi|") -> Kind:
    """Rotation vectors finite and at most 1e8 rad long; ``what`` names the length in the refusal."""
    return Kind(_rotvec_condition, lambda a, name: rotvec_array(a, name, what))


#: Rotation vectors, refused as ``|psi|``.
ROTVEC = rotation_vector()

__all__ = ["ANY_QUATERNION", "MATRIX", "QUATERNION", "ROTVEC", "VECTOR", "finite_array", "matrix_array",
           "quaternion_array", "refuse_nonfinite", "rotation_vector", "rotvec_array", "vector_array"]
