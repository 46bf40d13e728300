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

from collections.abc import Callable, Sequence

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


def direction_array(v: ArrayLike, name: str) -> NDArray[np.float64]:
    """Directions ``(..., 3)``: finite nonzero vectors."""
    a = vector_array(v, name)
    if a.size and not np.abs(a).max(axis=-1).min() > 0.0:
        raise ValueError(f"{name} must be nonzero (a zero vector has no direction)")
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


def gibbs_quaternion_array(q: ArrayLike, name: str = "q") -> NDArray[np.float64]:
    """Rotations ``(..., 4)`` with a finite Gibbs vector ``q_v / q0``: no half turn (q0 = 0)."""
    a = quaternion_array(q, name)
    if np.any(a[..., 0] == 0.0):
        raise ValueError(f"{name} must not be a half-turn (ψ = π): its Gibbs vector is infinite")
    return a


#: How far from unitary with unit determinant an SU(2) input may be.
SU2_TOLERANCE = 1e-6


def su2_array(u: ArrayLike, name: str = "u") -> NDArray[np.float64]:
    """SU(2) matrices ``[[a, b], [-b*, a*]]`` as real and imaginary parts ``(..., 2, 2, 2)``, |a|² + |b|² = 1.

    Both copies of ``a`` and ``b`` must agree, and ``|(a, b)|`` be 1, within :data:`SU2_TOLERANCE`.
    """
    parts = finite_array(u, name, (2, 2, 2))
    c = parts[..., 0] + 1j * parts[..., 1]
    mismatch = np.maximum(np.abs(c[..., 0, 0] - c[..., 1, 1].conj()), np.abs(c[..., 0, 1] + c[..., 1, 0].conj()))
    if mismatch.size and np.max(mismatch) > SU2_TOLERANCE:
        raise ValueError(f"{name} must have the SU(2) form [[a, b], [-conj(b), conj(a)]]")
    a = 0.5 * (c[..., 0, 0] + c[..., 1, 1].conj())
    b = 0.5 * (c[..., 0, 1] - c[..., 1, 0].conj())
    length = np.linalg.norm(np.stack([a.real, -b.imag, -b.real, -a.imag], axis=-1), axis=-1)
    if length.size and np.max(np.abs(length - 1.0)) > SU2_TOLERANCE:
        raise ValueError(f"{name} must be special unitary: |a|² + |b|² = 1 (within {SU2_TOLERANCE:g})")
    return parts


def _nonzero_condition(names: Sequence[str]) -> str:
    return f"({finite_condition(names)}) & (({' | '.join(f'({n} != 0.0)' for n in names)}))"


def _rotvec_condition(names: Sequence[str]) -> str:
    return f"({' + '.join(f'{n} * {n}' for n in names)} <= {ROTVEC_RANGE_SQUARED!r})"


def _gibbs_condition(names: Sequence[str]) -> str:
    return f"({finite_condition(names)}) & ({names[0]} != 0.0)"


def _su2_condition(names: Sequence[str]) -> str:
    # the full check's arithmetic: complex moduli as hypot, |q| as the square root of the squares in order
    r00, i00, r01, i01, r10, i10, r11, i11 = names
    a_re, a_im = f"(0.5 * ({r00} + {r11}))", f"(0.5 * ({i00} - {i11}))"
    b_re, b_im = f"(0.5 * ({r01} - {r10}))", f"(0.5 * ({i01} + {i10}))"
    length = f"np.sqrt({a_re} * {a_re} + {b_im} * {b_im} + {b_re} * {b_re} + {a_im} * {a_im})"
    return (f"(np.hypot({r00} - {r11}, {i00} + {i11}) <= {SU2_TOLERANCE!r}) & "
            f"(np.hypot({r01} + {r10}, {i01} - {i10}) <= {SU2_TOLERANCE!r}) & "
            f"(abs({length} - 1.0) <= {SU2_TOLERANCE!r})")


def _matrix_condition(names: Sequence[str], defect: float = ROUNDING_DEFECT) -> str:
    # orthonormal to within defect with det > 0; a NaN fails every comparison
    a, b, c, d, e, f, g, h, i = names
    columns = [(a, d, g), (b, e, h), (c, f, i)]
    terms = []
    for k in range(3):
        for m in range(k, 3):
            dot = " + ".join(f"{x} * {y}" for x, y in zip(columns[k], columns[m]))
            terms.append(f"(abs({dot}{' - 1.0' if k == m else ''}) <= {defect!r})")
    det = f"{a} * ({e} * {i} - {f} * {h}) - {b} * ({d} * {i} - {f} * {g}) + {c} * ({d} * {h} - {e} * {g})"
    return " & ".join(terms) + f" & ({det} > 0.0)"


def _twist_condition(names: Sequence[str]) -> str:
    return f"({finite_condition(names)}) & {_rotvec_condition(names[:3])}"


def twist_array(xi: ArrayLike, name: str) -> NDArray[np.float64]:
    """Twists ``(ω, v)``, ``(..., 6)``: finite, the rotation part ω at most ``ROTVEC_RANGE`` long."""
    a = finite_array(xi, name, (6,))
    refuse_long_angle(float(np.max(norm(a[..., :3]), initial=0.0)), name, "the rotation part |omega|")
    return a


def _pose_matrix_condition(names: Sequence[str]) -> str:
    # the bottom row (0, 0, 0, 1) and a rotation block, each to within the tolerance
    bottom = [f"(abs({n}{' - 1.0' if k == 3 else ''}) <= {ORTHOGONALITY_TOLERANCE!r})" for k, n in enumerate(names[12:])]
    block = [names[4 * row + column] for row in range(3) for column in range(3)]
    return " & ".join(bottom) + " & " + _matrix_condition(block, ORTHOGONALITY_TOLERANCE)


def _unit_dual_condition(names: Sequence[str]) -> str:
    # |q_r| = 1 and q_r·q_d = 0 relative to 1 + |q_d|, to within the tolerance
    real, dual = names[:4], names[4:]
    length = f"np.sqrt({' + '.join(f'{n} * {n}' for n in real)})"
    along = " + ".join(f"{r} * {d}" for r, d in zip(real, dual))
    scale = f"(1.0 + np.sqrt({' + '.join(f'{n} * {n}' for n in dual)}))"
    return (f"(abs({length} - 1.0) <= {ORTHOGONALITY_TOLERANCE!r}) & "
            f"(abs({along}) / {scale} <= {ORTHOGONALITY_TOLERANCE!r})")


def _within(condition: Callable[[Sequence[str]], str], width: int, refusal: str) -> Kind:
    """Finite numbers of ``width`` components for which ``condition`` holds, refused as ``"{name} must be {refusal}"``.

    The full check evaluates the loop's own expression on whole columns, so that both draw the
    line at the same numbers.
    """
    names = [f"x{k}" for k in range(width)]
    expression = compile(condition(names), f"<condition of {refusal}>", "eval")

    def check(a: NDArray[np.float64], name: str) -> NDArray[np.float64]:
        a = finite_array(a, name, None)
        with np.errstate(all="ignore"):
            holds = eval(expression, {"np": np}, dict(zip(names, a.reshape(-1, width).T)))  # noqa: S307
        if not np.all(holds):
            raise ValueError(f"{name} must be {refusal}")
        return a

    return Kind(lambda names: f"({finite_condition(names)}) & ({condition(names)})", check)


#: Finite numbers of any shape.
VECTOR = Kind(finite_condition, lambda a, name: finite_array(a, name, None))
#: Finite quaternions, zero allowed (products, conjugates).
ANY_QUATERNION = Kind(finite_condition, lambda a, name: quaternion_array(a, name, nonzero=False))
#: Finite nonzero quaternions: rotations, normalised where the formula needs it.
QUATERNION = Kind(_nonzero_condition, quaternion_array)
#: Directions: finite nonzero vectors, of any length.
DIRECTION = Kind(_nonzero_condition, direction_array)
#: Rotations other than half turns (finite nonzero quaternions with q0 != 0), whose Gibbs vector is finite.
GIBBS_QUATERNION = Kind(_gibbs_condition, gibbs_quaternion_array)
#: Rotation matrices: orthonormal to rounding in the loop; projected within the tolerance, else refused.
MATRIX = Kind(_matrix_condition, matrix_array)
#: SU(2) matrices as real and imaginary parts, unitary with unit determinant within :data:`SU2_TOLERANCE`.
SU2 = Kind(_su2_condition, su2_array)


def rotation_vector(what: str = "|psi|") -> Kind:
    """Rotation vectors finite and at most 1e8 rad long; ``what`` names the length in the refusal."""
    return Kind(_rotvec_condition, lambda a, name: rotvec_array(a, name, what))


#: Rotation vectors, refused as ``|psi|``.
ROTVEC = rotation_vector()
#: Packed poses ``[q, t]`` ``(7,)`` held by a ``RigidTransform``, which checked them when it made them: no
#: condition in the loop (a pose costs its 7 tests there otherwise), finite in the full check.
POSE = Kind(lambda names: "True", lambda a, name: finite_array(a, name, None))
#: Twists ``(ω, v)``: finite, with rotation parts at most 1e8 rad long.
TWIST = Kind(_twist_condition, twist_array)
#: Homogeneous matrices ``(4, 4)`` of poses, to within ``ORTHOGONALITY_TOLERANCE`` (Shepperd's
#: quaternion of the block is the nearest rotation's).
POSE_MATRIX = _within(_pose_matrix_condition, 16, "rigid: bottom row (0, 0, 0, 1) and a rotation block (max |R^T R - 1| "
                      f"or bottom-row error <= {ORTHOGONALITY_TOLERANCE:g}, det R > 0)")
#: Unit dual quaternions ``(8,)``, to within ``ORTHOGONALITY_TOLERANCE``.
UNIT_DUAL_QUATERNION = _within(_unit_dual_condition, 8, "unit dual quaternions: |q_r| = 1 and q_r·q_d = 0")

__all__ = ["ANY_QUATERNION", "DIRECTION", "GIBBS_QUATERNION", "MATRIX", "POSE", "POSE_MATRIX", "QUATERNION", "ROTVEC",
           "SU2", "SU2_TOLERANCE", "TWIST", "UNIT_DUAL_QUATERNION", "VECTOR", "direction_array", "finite_array",
           "gibbs_quaternion_array", "matrix_array", "quaternion_array", "refuse_nonfinite", "rotation_vector",
           "rotvec_array", "su2_array", "twist_array", "vector_array"]
