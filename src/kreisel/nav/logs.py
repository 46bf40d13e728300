"""Attitude files out, and attitudes between the NED and ENU conventions.

IMU files are read by :func:`kreisel.io.read_imu` (a layer above this one);
its record integrates into attitude with ``.attitude()``, and
:func:`write_attitude` writes quaternions and roll/pitch/yaw (ZYX) in NED or
ENU, atomically.

NED goes with front-right-down (FRD) body axes, ENU with front-left-up (FLU):
the usual aerospace and robotics (ROS REP 103) pairings. Converting an
attitude between them changes both frames,

    q_ENU←FLU = q_ENU←NED ⊗ q_NED←FRD ⊗ q_FRD←FLU,

with q_ENU←NED a half turn about (1, 1, 0)/√2 (x_E = y_N, y_E = x_N, z_U = −z_D)
and q_FRD←FLU a half turn about x.
"""

from __future__ import annotations

import numpy as np

from .._fileio import atomic_output
from .._optional import require
from .._validation import as_float_array

__all__ = ["write_attitude", "convert_attitude_frame"]

_FRAMES = ("NED", "ENU")
_S = np.sqrt(0.5)
# body→nav quaternions of the two pairings relative to each other (module docstring)
_ENU_FROM_NED = np.array([0.0, _S, _S, 0.0])
_FRD_FROM_FLU = np.array([0.0, 1.0, 0.0, 0.0])


def _pandas():
    # pandas is slow to import, and only attitude writing needs it
    return require("pandas", extra="io", feature="writing attitude files")


def convert_attitude_frame(q, from_frame, to_frame):
    """Re-express body → navigation attitudes between NED/FRD and ENU/FLU.

    Parameters
    ----------
    q : (..., 4) array_like
        Unit quaternions, body → ``from_frame``.
    from_frame, to_frame : {"NED", "ENU"}

    Returns
    -------
    (..., 4) ndarray

    Examples
    --------
    >>> q = convert_attitude_frame([1, 0, 0, 0], "NED", "ENU")   # level, facing north
    >>> np.round(q, 12) + 0.0          # ±(cos 45°, 0, 0, sin 45°): yaw 90° from east
    array([-0.70710678,  0.        ,  0.        , -0.70710678])
    """
    for label, f in (("from_frame", from_frame), ("to_frame", to_frame)):
        if f not in _FRAMES:
            raise ValueError(f"{label} must be 'NED' or 'ENU', got {f!r}")
    from ..so3 import quat_multiply  # lower layer, imported when used to keep import light

    q = as_float_array(q, "q", tail=(4,))
    if from_frame == to_frame:
        return q.copy()
    # both factors are half turns, so the same products convert back (−A ⊗ q ⊗ −B = A ⊗ q ⊗ B)
    return quat_multiply(quat_multiply(_ENU_FROM_NED, q), _FRD_FROM_FLU)


def write_attitude(path, t, q, frame="NED", input_frame="NED", degrees=True):
    """Write attitude as quaternions and roll/pitch/yaw (ZYX) to a CSV file, atomically.

    Columns: ``t, q0, q1, q2, q3, roll, pitch, yaw`` (scalar-first quaternion
    body → ``frame``; yaw, pitch, roll are the intrinsic ZYX Euler angles of
    :func:`kreisel.quat_to_euler`, in degrees unless ``degrees=False``). The
    file appears complete or not at all (temporary file + ``os.replace``).

    Parameters
    ----------
    path : str or os.PathLike
        Output CSV file; its directory must exist. An existing file is
        replaced (as by pandas' ``to_csv``).
    t : (n,) array_like
        Times (s).
    q : (n, 4) array_like
        Attitude quaternions, body → ``input_frame``.
    frame : {"NED", "ENU"}
        Navigation frame of the output (body axes FRD for NED, FLU for ENU).
    input_frame : {"NED", "ENU"}
        Navigation frame of ``q``.
    degrees : bool
        Angles in degrees (default) or radians.

    Returns
    -------
    pandas.DataFrame
        The table written.

    Examples
    --------
    A heading of 90° (body x pointing east) written in NED; the yaw column holds
    90° and the file reads back with pandas:

    >>> import os, tempfile
    >>> import pandas as pd
    >>> path = os.path.join(tempfile.mkdtemp(), "attitude.csv")
    >>> q = [[1.0, 0.0, 0.0, 0.0], [np.sqrt(0.5), 0.0, 0.0, np.sqrt(0.5)]]
    >>> table = write_attitude(path, [0.0, 1.0], q)
    >>> list(table.columns)
    ['t', 'q0', 'q1', 'q2', 'q3', 'roll_deg', 'pitch_deg', 'yaw_deg']
    >>> pd.read_csv(path)["yaw_deg"].astype(float).round(9).tolist()
    [0.0, 90.0]
    """
    from ..so3 import quat_to_euler  # same layer below; imported when used to keep import light

    t = as_float_array(t, "t")
    if t.ndim != 1:
        raise ValueError(f"t must be one-dimensional, got shape {t.shape}")
    q = as_float_array(q, "q", tail=(t.size, 4))
    if q.ndim != 2:
        raise ValueError(f"q must have shape ({t.size}, 4), got {q.shape}")
    q = convert_attitude_frame(q, input_frame, frame)
    q = q * np.where(q[:, :1] < 0, -1.0, 1.0)
    yaw_pitch_roll = quat_to_euler("ZYX", q, degrees=degrees)
    unit = "deg" if degrees else "rad"
    table = _pandas().DataFrame({"t": t, "q0": q[:, 0], "q1": q[:, 1], "q2": q[:, 2], "q3": q[:, 3],
                          f"roll_{unit}": yaw_pitch_roll[:, 2], f"pitch_{unit}": yaw_pitch_roll[:, 1],
                          f"yaw_{unit}": yaw_pitch_roll[:, 0]})
    with atomic_output(path) as tmp:
        table.to_csv(tmp, index=False, float_format="%.17g")
    return table
