"""Strapdown attitude from gyro data (Theory §3.3, §3.5; Theory §3.5).

Attitude from angle increments with the optimal coning correction, from
sampled rates (q̇ = ½ q ω′ or the Bortz equation), the exact coning motion
that tests them, IMU error models with Allan deviation, and attitude
writing (IMU files are read by :func:`kreisel.io.read_imu`).
"""

from .attitude import KREISEL_DEFAULTS, AttitudeEstimate, compare_attitude, estimate_attitude
from .attitude_error import attitude_error, attitude_error_angles
from .coning import ConingMotion, coning_coefficients, coning_drift, coning_motion
from .imu_errors import (DEG_PER_HOUR, DEG_PER_HOUR_PER_SQRT_HOUR, DEG_PER_SQRT_HOUR, GyroErrorModel,
                         allan_deviation, gauss_markov_allan_deviation)
from .logs import convert_attitude_frame, write_attitude
from .vector_attitude import attitude_from_vectors
from .strapdown import attitude_from_increments, attitude_from_rates

__all__ = [
    "ConingMotion",
    "coning_motion",
    "coning_drift",
    "coning_coefficients",
    "attitude_from_increments",
    "attitude_from_rates",
    "GyroErrorModel",
    "allan_deviation",
    "gauss_markov_allan_deviation",
    "DEG_PER_SQRT_HOUR",
    "DEG_PER_HOUR",
    "DEG_PER_HOUR_PER_SQRT_HOUR",
    "write_attitude",
    "convert_attitude_frame",
    "AttitudeEstimate",
    "estimate_attitude",
    "compare_attitude",
    "KREISEL_DEFAULTS",
    "attitude_error",
    "attitude_error_angles",
    "attitude_from_vectors",
]
