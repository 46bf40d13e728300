"""The one place where kreisel turns "a rotation" given by a user into arrays.

Every layer that accepts a rotation argument (inertia tensors rotated into
new axes, rigid transforms, initial attitudes of the integrators) calls
:func:`as_quaternion` or :func:`as_rotation_matrix`, so they all accept the
same inputs with the same tolerance:

- a kreisel :class:`~kreisel.Rotation`, a ``scipy.spatial.transform.Rotation`` or a
  ``kreisel.scipy.Rotation``;
- arrays ``(..., 3, 3)``: rotation matrices. A matrix whose orthogonality
  defect ``max |RᵀR − 1|`` is at most :data:`ORTHOGONALITY_TOLERANCE` (1e-6)
  is projected onto the nearest rotation; a larger defect, ``det R <= 0`` or
  a non-finite entry is refused;
- arrays ``(..., 4)``: scalar-first quaternions of any nonzero finite norm,
  standing for ``q/|q|``.
"""

from __future__ import annotations

from typing import TypeAlias, Union

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled.checks import matrix_array
from .._norms import ORTHOGONALITY_TOLERANCE
from .._validation import as_float_array
from .matrix import matrix_to_quat, quat_to_matrix
from .quaternion import quat_normalize
from .rotation import Rotation

__all__ = ["ORTHOGONALITY_TOLERANCE", "RotationLike", "as_quaternion", "as_rotation_matrix"]

#: What a rotation argument accepts: a :class:`~kreisel.Rotation`, matrices ``(..., 3, 3)`` or quaternions ``(..., 4)``
#: (a scipy rotation too; scipy's own annotations are not read).
RotationLike: TypeAlias = Union[Rotation, ArrayLike]


def _is_scipy_rotation(obj: object) -> bool:
    # scipy's Rotation or kreisel.scipy's (the same interface), checked by module name so that neither is
    # imported here: scipy only when it is used, kreisel.scipy being a layer above this one.
    return type(obj).__name__ == "Rotation" and type(obj).__module__.startswith(("scipy.spatial.transform",
                                                                                  "kreisel.scipy"))


def _array(rotation: RotationLike, name: str) -> NDArray[np.float64]:
    """Quaternions or matrices ``(..., 3, 3)`` of ``rotation``, by shape; checked by their conversions."""
    if isinstance(rotation, Rotation):
        return rotation.as_quat()
    if _is_scipy_rotation(rotation):
        return rotation.as_quat(scalar_first=True)
    a = as_float_array(rotation, name, finite=False)
    if a.shape[-2:] == (3, 3) or a.shape[-1:] == (4,):
        return a
    raise ValueError(
        f"{name} must be a Rotation, rotation matrices (..., 3, 3) or quaternions (..., 4), got shape {a.shape}"
    )


def as_quaternion(rotation: RotationLike, name: str = "rotation") -> NDArray[np.float64]:
    """Unit quaternions ``(..., 4)`` of any rotation input (see the module note for what is accepted).

    Examples
    --------
    >>> import numpy as np
    >>> as_quaternion([2.0, 0.0, 0.0, 0.0])
    array([1., 0., 0., 0.])
    >>> as_quaternion(np.eye(3))
    array([1., 0., 0., 0.])
    """
    a = _array(rotation, name)
    if a.shape[-2:] == (3, 3):
        return matrix_to_quat.__operation__.renamed(R=name)(a)
    return quat_normalize.__operation__.renamed(q=name)(a)


def as_rotation_matrix(rotation: RotationLike, name: str = "rotation") -> NDArray[np.float64]:
    """Rotation matrices ``(..., 3, 3)`` of any rotation input (see the module note for what is accepted).

    Examples
    --------
    >>> import numpy as np
    >>> np.round(as_rotation_matrix([np.cos(np.pi / 4), 0, 0, np.sin(np.pi / 4)]), 12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    a = _array(rotation, name)
    if a.shape[-2:] == (3, 3):
        return matrix_array(a, name)
    return quat_to_matrix.__operation__.renamed(q=name)(a)
