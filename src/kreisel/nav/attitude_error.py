"""Attitude errors against a reference, split into heading and inclination (BROAD's metric).

An estimate q and a reference q_ref (both frame ← sensor, z of the frame up)
differ by the error quaternion e = q ⊗ q_ref⁻¹, a rotation *in the earth
frame*. It factors uniquely (up to sign) as e = e_tilt ⊗ e_heading with
e_heading a rotation about the vertical z and e_tilt a rotation about a
horizontal axis: with e = (w, x, y, z), e_heading = (w, 0, 0, z)/√(w² + z²)
and e_tilt = (√(w² + z²), (wx − yz)/√(w² + z²), (wy + xz)/√(w² + z²), 0).
The heading error is the angle of e_heading, 2 atan(|z|/|w|); the
inclination error the angle of e_tilt, 2 acos √(w² + z²); the total error
the angle of e, 2 acos |w|. The inclination error is what the accelerometer
can correct (the direction of up seen from the sensor), the heading error
what only the magnetometer can.
"""

from __future__ import annotations

import numpy as np

from .._validation import as_float_array

__all__ = ["attitude_error", "attitude_error_angles"]


def quaternion_rows(q, name):
    """``q`` as float rows (n, 4), each divided by its largest component (NaN rows kept as NaN).

    Every error angle is a ratio of products of the two quaternions, so the
    scale drops out; dividing first keeps the products of huge or tiny
    quaternions finite and exact to rounding.
    """
    q = as_float_array(q, name, finite=False)
    if q.ndim != 2 or q.shape[1] != 4:
        raise ValueError(f"{name} must have shape (n, 4) (scalar-first quaternions), got {q.shape}")
    if q.size and np.isnan(q).all():
        raise ValueError(f"{name} is NaN in every row: there is nothing to compare")
    if np.isinf(q).any():
        raise ValueError(f"{name} must not hold infinite values")
    size = np.abs(q).max(axis=1, keepdims=True)
    if (size == 0.0).any():
        raise ValueError(f"{name} must not hold a zero quaternion (row {int(np.flatnonzero(size == 0.0)[0])})")
    return q / size


def attitude_error_angles(q, q_ref):
    """Per-sample total, heading and inclination errors (radians) of ``q`` against ``q_ref``.

    Parameters
    ----------
    q, q_ref : array_like, shape (n, 4)
        Scalar-first quaternions frame ← sensor (z of the frame up, e.g. ENU);
        neither needs unit norm. Rows of ``q_ref`` that are NaN give NaN errors;
        ``q`` must not hold NaN.

    Returns
    -------
    total, heading, inclination : ndarray, shape (n,)
        Angles in [0, π] of the error rotation q ⊗ q_ref⁻¹ (in the earth
        frame), of its part about the vertical and of its horizontal-axis part.

    Examples
    --------
    A pure yaw error of 3° is all heading:

    >>> import numpy as np
    >>> yaw = np.radians(3.0)
    >>> q = np.array([[np.cos(yaw / 2), 0.0, 0.0, np.sin(yaw / 2)]])
    >>> total, heading, incl = attitude_error_angles(q, [[1.0, 0.0, 0.0, 0.0]])
    >>> np.degrees([total[0], heading[0], incl[0]]).round(12).tolist()
    [3.0, 3.0, 0.0]
    """
    q = quaternion_rows(q, "q")
    q_ref = quaternion_rows(q_ref, "q_ref")
    if q.shape != q_ref.shape:
        raise ValueError(f"q and q_ref must have the same shape, got {q.shape} and {q_ref.shape}")
    if np.isnan(q).any():
        raise ValueError("q must not hold NaN (only q_ref may, where the reference lost track)")
    # the unit check is done through the norms below: scale drops out of every ratio
    a0, a1, a2, a3 = q.T
    b0, b1, b2, b3 = q_ref.T
    w = a0 * b0 + a1 * b1 + a2 * b2 + a3 * b3
    z = -a0 * b3 + a3 * b0 - a1 * b2 + a2 * b1
    x = -a0 * b1 + a1 * b0 - a2 * b3 + a3 * b2
    y = -a0 * b2 + a2 * b0 - a3 * b1 + a1 * b3
    vertical = np.hypot(w, z)
    horizontal = np.hypot(x, y)
    total = 2.0 * np.arctan2(np.sqrt(x * x + y * y + z * z), np.abs(w))
    heading = 2.0 * np.arctan2(np.abs(z), np.abs(w))
    inclination = 2.0 * np.arctan2(horizontal, vertical)
    # atan2 keeps all three accurate near zero and π, where acos would lose half the digits
    return total, heading, inclination


def attitude_error(q, q_ref, mask=None):
    """Total, heading and inclination RMSE in degrees of ``q`` against a reference (BROAD's metric).

    The error quaternion q ⊗ q_ref⁻¹ is taken in the earth frame (z up, as in
    ENU or NWU) and split into a rotation about the vertical (heading) and one
    about a horizontal axis (inclination); see the module notes. Rows where
    ``q_ref`` is NaN (a reference that lost track) are left out.

    Parameters
    ----------
    q : array_like, shape (n, 4)
        Estimated attitude, scalar-first, frame ← sensor. Must be finite.
    q_ref : array_like, shape (n, 4)
        Reference attitude in the same frame; NaN rows are left out.
    mask : array_like of bool, shape (n,), optional
        Samples to evaluate (BROAD uses its ``movement`` flags); default all.

    Returns
    -------
    total, heading, inclination : float
        Root-mean-square errors in degrees over the selected, tracked samples.

    Raises
    ------
    ValueError
        If shapes disagree, ``q`` holds non-finite values in the evaluated
        rows, or no sample is left to evaluate.

    Examples
    --------
    >>> import numpy as np
    >>> ref = np.tile([1.0, 0.0, 0.0, 0.0], (4, 1))
    >>> tilt = np.radians(2.0)
    >>> est = np.tile([np.cos(tilt / 2), np.sin(tilt / 2), 0.0, 0.0], (4, 1))
    >>> [round(e, 12) for e in attitude_error(est, ref)]
    [2.0, 0.0, 2.0]
    """
    q = quaternion_rows(q, "q")
    q_ref = quaternion_rows(q_ref, "q_ref")
    if q.shape != q_ref.shape:
        raise ValueError(f"q and q_ref must have the same shape, got {q.shape} and {q_ref.shape}")
    keep = ~np.isnan(q_ref).any(axis=1)
    if mask is not None:
        mask = np.asarray(mask)
        if mask.dtype != bool or mask.shape != (q.shape[0],):
            raise ValueError(f"mask must be a boolean array of shape ({q.shape[0]},), got {mask.dtype} {mask.shape}")
        keep &= mask
    if not keep.any():
        raise ValueError("no sample to evaluate: mask selects none, or q_ref is NaN in all selected rows")
    if not np.isfinite(q[keep]).all():
        raise ValueError("q must be finite in the evaluated rows")
    if not np.isfinite(q_ref[keep]).all():
        raise ValueError("q_ref rows must be finite or wholly NaN")
    angles = attitude_error_angles(q[keep], q_ref[keep])
    total, heading, inclination = (float(np.degrees(np.sqrt(np.mean(a * a)))) for a in angles)
    return total, heading, inclination
