"""Attitude at rest from gravity and the magnetic field: TRIAD and the q-method (Wahba's problem).

At rest the accelerometer measures up (the specific force opposes
gravity) and the magnetometer the earth's field, which points to magnetic
north and dips below the horizon by the dip angle I (about 60° in central
Europe). TRIAD takes up as exact and only the field's horizontal direction
for north, so the dip never enters. The q-method (:func:`kreisel.so3.align_vectors`,
Davenport's solution of Wahba's problem) weighs both directions: their
earth-frame references are up = (0, 0, 1) and the field's direction
(0, cos I, −sin I) in ENU, with I given or, by default, the mean measured dip
(the angle between field and horizontal plane, 90° − the angle between field
and up), so that the references are consistent with the measurements.
"""

from __future__ import annotations

import numpy as np

from .._validation import as_float_array
from ..so3 import align_vectors, matrix_to_quat

__all__ = ["attitude_from_vectors"]


def attitude_from_vectors(accel, mag, *, method="triad", dip=None, weights=(1.0, 1.0)):
    """Attitude ENU ← sensor of a sensor at rest from its accelerometer and magnetometer samples.

    Parameters
    ----------
    accel : array_like, shape (..., 3)
        Specific force (any unit; at rest it points up).
    mag : array_like, shape (..., 3)
        Magnetic field (any unit), broadcast against ``accel``.
    method : {"triad", "quest"}
        "triad": up exact, north from the field's horizontal part.
        "quest": the q-method's least-squares fit of both directions.
    dip : float, optional
        Dip angle I in radians (positive: the field points below the
        horizon), "quest" only; default: the mean dip measured.
    weights : tuple of two floats
        Weights (> 0, one may be inf) of up and of the field direction
        ("quest" only).

    Returns
    -------
    ndarray, shape (..., 4)
        Scalar-first unit quaternions ENU ← sensor.

    Raises
    ------
    ValueError
        If an accelerometer sample has zero length or a field sample has no
        horizontal part (zero, or along up): the heading is then undefined;
        if a weight is not > 0; if ``dip`` or ``weights`` are given with
        ``method="triad"``, which would ignore them.

    Examples
    --------
    A level sensor facing east (its x axis east) in a field dipping 60°:

    >>> import numpy as np
    >>> dip = np.radians(60.0)
    >>> q = attitude_from_vectors([0.0, 0.0, 9.81], [0.0, 48 * np.cos(dip), -48 * np.sin(dip)])
    >>> np.round(q, 12).tolist()
    [1.0, 0.0, 0.0, 0.0]
    """
    if method not in ("triad", "quest"):
        raise ValueError(f"method must be 'triad' or 'quest', got {method!r}")
    try:
        weights = np.asarray(weights, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"weights must be two numbers (up, field), got {weights!r}") from None
    if method == "triad":
        # TRIAD takes up exactly and the field's horizontal part only: neither would enter
        if dip is not None:
            raise ValueError(f"dip applies to method='quest' only (TRIAD never uses the dip), got dip={dip!r}")
        if not np.array_equal(weights, (1.0, 1.0)):
            raise ValueError(f"weights apply to method='quest' only (TRIAD takes up exactly), got {weights.tolist()}")
    # a zero weight leaves a direction unmeasured: the heading (or the tilt) would be arbitrary
    elif weights.shape != (2,) or not (weights > 0).all():
        raise ValueError(f"weights must be two numbers > 0 (up, field), got shape {weights.shape}: "
                         f"{weights.tolist()}")
    acc = as_float_array(accel, "accel", tail=(3,))
    field = as_float_array(mag, "mag", tail=(3,))
    # only directions matter: dividing each sample by its largest component keeps the norms finite
    acc, field = (x / np.maximum(np.abs(x).max(axis=-1, keepdims=True), np.finfo(float).tiny)
                  for x in np.broadcast_arrays(acc, field))
    acc_norm = np.linalg.norm(acc, axis=-1, keepdims=True)
    if not (acc_norm > 0).all():
        raise ValueError("accel must not have zero-length samples: up is undefined")
    up = acc / acc_norm
    field_norm = np.linalg.norm(field, axis=-1, keepdims=True)
    east = np.cross(field, up)
    east_norm = np.linalg.norm(east, axis=-1, keepdims=True)
    if not (east_norm > 1e-9 * np.maximum(field_norm, np.finfo(float).tiny)).all():
        raise ValueError("mag must have a horizontal part in every sample (not zero, not along up): "
                         "the heading is undefined")
    if method == "triad":
        east = east / east_norm
        north = np.cross(up, east)
        # rows of R (ENU ← sensor): east, north and up in sensor components
        return matrix_to_quat(np.stack([east, north, up], axis=-2))
    if dip is None:
        dip = float(np.mean(np.arcsin(np.clip(-np.sum(field * up, axis=-1) / field_norm[..., 0], -1.0, 1.0))))
    elif not np.isfinite(dip) or abs(dip) > np.pi / 2:
        raise ValueError(f"dip must be an angle in [-π/2, π/2] (radians), got {dip!r}")
    reference = np.array([[0.0, 0.0, 1.0], [0.0, np.cos(dip), -np.sin(dip)]])
    body = np.stack([up, field / field_norm], axis=-2)
    q, _ = align_vectors(np.broadcast_to(reference, body.shape), body, weights)
    return q
