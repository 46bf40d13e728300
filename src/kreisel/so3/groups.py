"""Finite rotation groups (crystal and molecular symmetry) and reduction by symmetry.

The point groups of proper rotations: cyclic ``Cn`` (turns by 2πk/n about one
axis), dihedral ``Dn`` (``Cn`` plus n half turns about axes normal to it),
tetrahedral ``T`` (12), octahedral ``O`` (24) and icosahedral ``I`` (60), in
scipy's orientation: ``T`` ⊂ ``O`` with their 2-fold axes along x, y, z, and
``T`` ⊂ ``I`` with the 5-fold axes along (0, ±1, ±φ) and its cyclic
permutations. ``T``, ``O`` and ``I`` are built here by closing a set of
generators under composition.

Reducing a rotation ``p`` by symmetry groups ``L`` and ``R`` picks, among the
equivalent rotations ``l p r``, the one with the smallest angle (largest
``|q0|``): e.g. the misorientation of two crystal grains.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled.checks import quaternion_array
from .._compiled.outputs import deliver, takes_out
from .quaternion import quat_multiply, quat_normalize
from .rotvec import rotvec_to_quat

__all__ = ["create_group", "reduce_quat"]

_GOLDEN = (1.0 + np.sqrt(5.0)) / 2.0


def _closure(generators: list[NDArray[np.float64]]) -> NDArray[np.float64]:
    """All products of the generators: the finite group they generate, identity first."""
    elements = [np.array([1.0, 0.0, 0.0, 0.0])]
    keys = {_key(elements[0])}
    frontier = list(elements)
    while frontier:
        grown = []
        for g in frontier:
            for h in generators:
                p = quat_multiply(g, h)
                key = _key(p)
                if key not in keys:
                    keys.add(key)
                    elements.append(p)
                    grown.append(p)
        frontier = grown
    return np.array(elements)


def _key(q: NDArray[np.float64]) -> tuple[float, ...]:
    # q and -q are one rotation: round the canonical sign.
    first = q[np.flatnonzero(np.abs(q) > 1e-9)[0]]
    return tuple(np.round(q * np.sign(first), 9) + 0.0)


def _turn(axis: ArrayLike, angle: float) -> NDArray[np.float64]:
    axis = np.asarray(axis, dtype=np.float64)
    return rotvec_to_quat(angle * axis / np.linalg.norm(axis))


@takes_out(result="Result array of shape (order, 4)")
def create_group(group: str, axis: str = "Z", *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Quaternions of a rotation group: ``"I"``, ``"O"``, ``"T"``, ``"Dn"`` or ``"Cn"`` (n >= 1).

    Parameters
    ----------
    group : str
    axis : {"X", "Y", "Z"} (either case)
        Main axis of ``Cn`` and ``Dn`` (ignored for the others).

    Returns
    -------
    ndarray, shape (order, 4)
        Unit quaternions, scalar first, the identity first.

    Examples
    --------
    >>> create_group("O").shape, create_group("D3", axis="x").shape
    ((24, 4), (6, 4))
    """
    return deliver(_group(group, axis), out)


def _group(group: str, axis: str) -> NDArray[np.float64]:
    if not isinstance(group, str):
        raise ValueError(f"group must be a string 'I', 'O', 'T', 'Dn' or 'Cn', got {group!r}")
    if not isinstance(axis, str) or axis.lower() not in ("x", "y", "z"):
        raise ValueError(f"axis must be one of 'X', 'Y', 'Z' (or lowercase), got {axis!r}")
    e = np.eye(3)
    main = e["xyz".index(axis.lower())]
    if group == "T":
        return _closure([_turn([1, 1, 1], 2 * np.pi / 3), _turn([0, 0, 1], np.pi)])
    if group == "O":
        return _closure([_turn([1, 1, 1], 2 * np.pi / 3), _turn([0, 0, 1], np.pi / 2)])
    if group == "I":
        return _closure([_turn([1, 1, 1], 2 * np.pi / 3), _turn([0, 0, 1], np.pi), _turn([0, 1, _GOLDEN], 2 * np.pi / 5)])
    if group[:1] in ("C", "D") and group[1:].isdigit() and int(group[1:]) >= 1:
        n = int(group[1:])
        angles = 2 * np.pi * np.arange(n) / n
        cyclic = rotvec_to_quat(angles[:, None] * main)
        if group[0] == "C":
            return cyclic
        # Half turns about axes normal to the main one, at angles πk/n from the next coordinate axis.
        u, v = e[("xyz".index(axis.lower()) + 1) % 3], e[("xyz".index(axis.lower()) + 2) % 3]
        theta = np.pi * np.arange(n) / n
        flips = rotvec_to_quat(np.pi * (np.cos(theta)[:, None] * u + np.sin(theta)[:, None] * v))
        return np.concatenate([cyclic, flips])
    raise ValueError(f"group must be 'I', 'O', 'T', 'Dn' or 'Cn' with n >= 1, got {group!r}")


def reduce_quat(q: ArrayLike, left: ArrayLike | None = None,
                right: ArrayLike | None = None) -> tuple[NDArray[np.float64], NDArray[np.intp] | None, NDArray[np.intp] | None]:
    """The smallest of the equivalent rotations ``l q r`` over ``l`` in ``left``, ``r`` in ``right``.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Unit quaternions to reduce.
    left, right : array_like, shape (L, 4) and (R, 4), optional
        Symmetry groups (or any sets of rotations); None means the identity.

    Returns
    -------
    reduced : ndarray, shape (..., 4)
    left_index, right_index : ndarray of int, shape (...)
        The chosen elements (None for a side not given).

    Examples
    --------
    A 100° turn about z is 10° away from a quarter turn of the square's symmetry C4:

    >>> import numpy as np
    >>> q = rotvec_to_quat([0.0, 0.0, np.radians(100)])
    >>> reduced, _, right = reduce_quat(q, right=create_group("C4"))
    >>> round(float(np.degrees(2 * np.arccos(abs(reduced[0])))), 9), int(right)
    (10.0, 3)
    """
    q = quat_normalize(quaternion_array(q, "q"))
    identity = np.array([[1.0, 0.0, 0.0, 0.0]])
    ls = identity if left is None else quat_normalize(quaternion_array(left, "left")).reshape(-1, 4)
    rs = identity if right is None else quat_normalize(quaternion_array(right, "right")).reshape(-1, 4)
    batch = q.shape[:-1]
    if q.size == 0:
        chosen = np.zeros(batch, dtype=np.intp)
        return q, None if left is None else chosen, None if right is None else chosen.copy()
    flat = q.reshape(-1, 4)
    lp = quat_multiply(ls[:, None, :], flat[None, :, :])  # (L, N, 4)
    # Scalar part of (l p) r for every pair: (lp)₀ r₀ - (lp)_v · r_v.
    scalar = np.einsum("lni,ri->nlr", lp * np.array([1.0, -1.0, -1.0, -1.0]), rs)
    best = np.argmax(np.abs(scalar).reshape(len(flat), -1), axis=-1)
    li, ri = np.divmod(best, len(rs))
    reduced = quat_multiply(lp[li, np.arange(len(flat))], rs[ri]).reshape(*batch, 4)
    return (
        reduced,
        None if left is None else li.reshape(batch),
        None if right is None else ri.reshape(batch),
    )
