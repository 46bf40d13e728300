"""The record every IMU reader returns: time, gyro, and the accelerometer and magnetometer when present."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

__all__ = ["ImuRecording", "SPACING_TOLERANCE"]

#: Largest relative departure of a sample interval from the mean that :meth:`ImuRecording.sampling_rate` accepts:
#: beyond it the recording has a gap or a stall, and filters that step at one rate would misplace the motion.
SPACING_TOLERANCE = 0.25


@dataclass(frozen=True, eq=False, repr=False)
class ImuRecording:
    """Samples of an inertial measurement unit, in the sensor's axes and SI units.

    Attributes
    ----------
    t : (n,) ndarray
        Sample times in seconds, strictly increasing, as in the file (not shifted).
    omega : (n, 3) ndarray
        Body angular velocity ω′ in the sensor's x, y, z axes, rad/s. For a gyro
        that outputs angle increments, the mean rate over the interval ending at
        each ``t`` (the increments are in ``dtheta``).
    accel : (n, 3) ndarray or None
        Specific force from the accelerometer, m/s², when the file has one.
    mag : (n, 3) ndarray or None
        Magnetic field from the magnetometer, µT, when the file has one.
    source : str
        Where the data came from (file, or ``archive.zip:member``).
    notes : tuple of str
        What the reader did that the file did not say: its text encoding when not
        UTF-8, sensors interpolated onto the gyro's clock, samples dropped.
    dtheta : (n, 3) ndarray or None
        Angle increments (rad) of an increment-output gyro, each accumulated since
        the previous sample; None for a rate gyro.
    reference : (n, 4) ndarray or None
        A reference attitude stored with the data (BROAD's motion capture):
        scalar-first quaternions, frame ← sensor, NaN rows where it was lost.
    movement : (n,) bool ndarray or None
        Samples marked as moving (BROAD's evaluation mask).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from kreisel.io import read_imu
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "spin.txt"
    >>> _ = path.write_text("# t wx wy wz\\n0.0 0 0 1\\n0.01 0 0 1\\n")
    >>> rec = read_imu(path)
    >>> rec.t.tolist(), rec.omega.shape, rec.accel, rec.mag
    ([0.0, 0.01], (2, 3), None, None)
    """

    t: np.ndarray
    omega: np.ndarray
    accel: Optional[np.ndarray] = None
    mag: Optional[np.ndarray] = None
    source: str = "<data>"
    notes: tuple = ()
    dtheta: Optional[np.ndarray] = None
    reference: Optional[np.ndarray] = None
    movement: Optional[np.ndarray] = None

    def __len__(self):
        return self.t.size

    def __repr__(self):
        sensors = ", ".join(name for name, value in (("gyro", self.omega), ("accel", self.accel), ("mag", self.mag))
                            if value is not None)
        extra = "".join(f", {name}" for name, value in (("reference", self.reference),
                                                          ("increments", self.dtheta)) if value is not None)
        span = f"t=[{self.t[0]:g}, {self.t[-1]:g}] s" if self.t.size else "t=[]"
        return f"ImuRecording({self.source!r}, n={self.t.size}, {span}, {sensors}{extra})"

    def sampling_rate(self):
        """The sampling rate in Hz of evenly spaced samples: one over the mean interval.

        Raises
        ------
        ValueError
            Fewer than 2 samples, or an interval more than 25 % away from the mean (a gap or a stall),
            naming where.

        Examples
        --------
        >>> ImuRecording(np.array([0.0, 0.01, 0.02]), np.zeros((3, 3))).sampling_rate()
        100.0
        """
        t = self.t
        if t.size < 2:
            raise ValueError(f"{self.source}: {t.size} sample; attitude estimation needs at least 2")
        step = np.diff(t)
        mean = float(t[-1] - t[0]) / (t.size - 1)
        worst = int(np.argmax(np.abs(step - mean)))
        if abs(step[worst] - mean) > SPACING_TOLERANCE * mean:
            # where a rate changes, every interval on one side is as far from the mean: name the first that departs
            # from the mean of those before it too, which is where the spacing changes
            before = np.cumsum(step)[:-1] / np.arange(1, step.size)
            changed = np.flatnonzero(np.abs(step[1:] - before) > SPACING_TOLERANCE * before)
            change = "" if not changed.size else (f"; the interval changes from {before[changed[0]]:.6g} s to "
                                                  f"{step[changed[0] + 1]:.6g} s after t = {t[changed[0] + 1]:.6g} s")
            raise ValueError(f"{self.source}: samples are not evenly spaced (interval {step[worst]:.6g} s after "
                             f"t = {t[worst]:.6g} s, mean {mean:.6g} s{change}); the filters step at one rate: "
                             "resample the recording first")
        return 1.0 / mean

    def attitude(self, q0=(1.0, 0.0, 0.0, 0.0), samples_per_update=None, method=None):
        """Integrate the gyro into attitude (sensor → the frame of ``q0``).

        Rate gyros use :func:`kreisel.nav.attitude_from_rates` (``method``,
        default ``"bortz"``) and return the attitude at every time stamp.
        Increment gyros use :func:`kreisel.nav.attitude_from_increments` with
        ``samples_per_update`` = N (default 1); q0 is the attitude at the start
        of the first increment, taken as t_0 − (t_1 − t_0), and the result holds
        that instant followed by the time stamp closing each update.

        Returns
        -------
        t : (m,) ndarray
            Times of the attitudes.
        q : (m, 4) ndarray
            Attitude quaternions, sensor → navigation frame.

        Examples
        --------
        A rate gyro turning at 0.5 rad/s about z for 2 s:

        >>> rec = ImuRecording(np.linspace(0.0, 2.0, 5), np.tile([0.0, 0.0, 0.5], (5, 1)))
        >>> t, q = rec.attitude()
        >>> round(float(2 * np.arctan2(q[-1, 3], q[-1, 0])), 12)
        1.0
        """
        # nav brings the compiled kernels, which reading a file does not need
        from ..nav import attitude_from_increments, attitude_from_rates, coning_coefficients

        if self.dtheta is None:
            if samples_per_update is not None:
                raise ValueError("samples_per_update applies to increment gyros; this recording holds rates "
                                 "(coning algorithms need increment-output gyros)")
            return self.t, attitude_from_rates(q0, self.t, self.omega, method=method or "bortz")
        if method is not None:
            raise ValueError("method applies to rate gyros; increment gyros use the coning algorithm "
                             "(choose samples_per_update)")
        samples_per_update = 1 if samples_per_update is None else samples_per_update
        coning_coefficients(samples_per_update)  # validates N before the row count is judged
        n = self.t.size
        if n % samples_per_update:
            raise ValueError(f"{self.source}: {n} increment rows are not divisible by samples_per_update="
                             f"{samples_per_update}; trim {n % samples_per_update} row(s) at the end")
        q = attitude_from_increments(q0, self.dtheta, samples_per_update)
        start = self.t[0] - (self.t[1] - self.t[0])
        return np.concatenate([[start], self.t[samples_per_update - 1:: samples_per_update]]), q
