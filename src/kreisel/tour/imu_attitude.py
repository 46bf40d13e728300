"""Tour section for Theory §3.3, §3.5: attitude from a real IMU against motion capture."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from .. import nav, so3
from ..io.gyro import read_imu, recording_path
from ..plot.attitude import attitude_estimate
from .report import Check, Section

__all__ = ["imu_attitude", "rotation_angle", "angle_between", "TOTAL_BOUND", "SECTIONS"]

#: Bound on kreisel's total RMSE on the bundled trial, degrees: measured 2.10° causal and 2.21° offline
#: (with a field), against 3.8° for Madgwick's and Mahony's filters.
TOTAL_BOUND = 2.5


def rotation_angle(R):
    """Angle (rad) of rotation matrices ``R`` (..., 3, 3) from their trace and skew part, accurate near 0.

    Examples
    --------
    >>> from kreisel import rotvec_to_matrix
    >>> float(rotation_angle(rotvec_to_matrix([0.0, 1e-9, 0.0])))
    1e-09
    """
    skew = np.stack([R[..., 2, 1] - R[..., 1, 2], R[..., 0, 2] - R[..., 2, 0], R[..., 1, 0] - R[..., 0, 1]], axis=-1)
    return np.arctan2(0.5 * np.linalg.norm(skew, axis=-1), 0.5 * (np.trace(R, axis1=-2, axis2=-1) - 1.0))


def angle_between(u, v):
    """Angle (rad) between the rows of ``u`` and ``v``, accurate near 0 and π.

    Examples
    --------
    >>> float(angle_between(np.array([1.0, 0.0, 0.0]), np.array([0.0, 2.0, 0.0])) / np.pi)
    0.5
    """
    return np.arctan2(np.linalg.norm(np.cross(u, v), axis=-1), np.sum(u * v, axis=-1))


def imu_attitude(quick):
    """Attitude from a real IMU against motion capture"""
    rec = read_imu(recording_path("broad_07"))
    rate = (rec.t.size - 1) / (rec.t[-1] - rec.t[0])
    runs = {"kreisel": nav.estimate_attitude(rec.omega, rec.accel, rec.mag, rate=rate),
            "kreisel offline": nav.estimate_attitude(rec.omega, rec.accel, rec.mag, rate=rate, offline=True),
            "Madgwick": nav.estimate_attitude(rec.omega, rec.accel, rec.mag, rate=rate, method="madgwick"),
            "Mahony": nav.estimate_attitude(rec.omega, rec.accel, rec.mag, rate=rate, method="mahony"),
            "kreisel without magnetometer": nav.estimate_attitude(rec.omega, rec.accel, None, rate=rate)}
    rmse = {name: nav.attitude_error(run.q, rec.reference, rec.movement) for name, run in runs.items()}
    total, heading, inclination = rmse["kreisel"]
    # the BROAD metric recomputed another way: the angle of R R_refᵀ, and the angle between the up
    # directions the estimate and the motion capture see in the sensor (a tilt error moves up, a heading error not)
    kept = np.isfinite(rec.reference).all(axis=1) & rec.movement
    R, R_ref = so3.quat_to_matrix(runs["kreisel"].q[kept]), so3.quat_to_matrix(rec.reference[kept])
    direct_total = np.degrees(np.sqrt(np.mean(rotation_angle(R @ np.swapaxes(R_ref, -1, -2)) ** 2)))
    direct_inclination = np.degrees(np.sqrt(np.mean(angle_between(R[:, 2, :], R_ref[:, 2, :]) ** 2)))
    # the gyro alone (q̇ = ½ q ω′) from the reference's first attitude: at rest its error grows as |b| t
    first = int(np.flatnonzero(np.isfinite(rec.reference).all(axis=1))[0])
    still = slice(first, int(np.flatnonzero(rec.movement)[0]))
    gyro_alone = nav.attitude_from_rates(rec.reference[first], rec.t[first:], rec.omega[first:])
    drift = np.degrees(nav.attitude_error_angles(gyro_alone, rec.reference[first:])[0])
    bias = rec.omega[still].mean(axis=0)
    rest_time = rec.t[still][-1] - rec.t[first]
    at_rest = rec.reference[still]
    wander = np.degrees(np.max(nav.attitude_error_angles(at_rest, np.broadcast_to(at_rest[0], at_rest.shape))[0]))
    learned = np.linalg.norm(runs["kreisel"].bias[still.stop - 1] - bias) / np.linalg.norm(bias)
    best_published = min(rmse["Madgwick"][0], rmse["Mahony"][0])

    fig = Figure(figsize=(8, 5.6), layout="constrained")
    top, bottom = fig.subplots(2, 1, sharex=True)
    gyro_rmse = nav.attitude_error(gyro_alone, rec.reference[first:], rec.movement[first:])[0]
    top.semilogy(rec.t[first:], drift, color="0.6", lw=1.0, label=f"gyro alone ({gyro_rmse:.1f}°)")
    for name, color in (("Mahony", "tab:green"), ("Madgwick", "tab:orange"), ("kreisel offline", "tab:purple"),
                        ("kreisel", "tab:blue")):
        errors = np.degrees(nav.attitude_error_angles(runs[name].q, rec.reference)[0])
        top.semilogy(rec.t, errors, color=color, lw=0.9, label=f"{name} ({rmse[name][0]:.2f}°)")
    for ax in (top, bottom):
        ax.axvline(rec.t[still][-1], color="0.5", lw=0.8, ls=":")
    top.set(ylabel="total error (°)", ylim=(0.05, 100), title="BROAD trial 07: error against motion capture (RMSE)")
    top.legend(loc="upper left", ncols=3, fontsize="small")
    for name, style in (("kreisel", "-"), ("kreisel without magnetometer", "--")):
        _, head, incl = np.degrees(nav.attitude_error_angles(runs[name].q, rec.reference))
        bottom.plot(rec.t, head, style, color="tab:purple", lw=0.9, label=f"heading, {name}")
        bottom.plot(rec.t, incl, style, color="tab:red", lw=0.9, label=f"inclination, {name}")
    bottom.set(xlabel="t (s)", ylabel="error (°)", ylim=(0, 9),
               title="kreisel's heading and inclination errors, with and without the field")
    bottom.legend(loc="upper right", ncols=2, fontsize="small")
    angles = attitude_estimate(rec.t, runs["kreisel"].q, rec.reference, rec.movement,
                               title="kreisel's estimate (solid) and the motion capture (dashed), ENU ← sensor")

    return Section(
        "Attitude from a real IMU against motion capture", "§3.3, §3.5",
        "Integrating the gyro's ω′ (q̇ = ½ q ω′) turns its bias into an attitude error that grows without bound. "
        "The accelerometer sees up and corrects the inclination; the magnetometer's horizontal part points north "
        "and corrects the heading. The bundled recording is the first minute of trial 07 of BROAD (Laidig et al., "
        f"2021): gyro, accelerometer and magnetometer at {rate:.1f} Hz, 26.5 s at rest and then fast rotation, "
        "with the attitude measured by optical motion capture. Over the movement kreisel's estimator "
        f"(kreisel.nav.estimate_attitude) is off by {total:.2f}° in total RMS ({heading:.2f}° heading, "
        f"{inclination:.2f}° inclination), the published filters of Madgwick and Mahony by "
        f"{rmse['Madgwick'][0]:.2f}° and {rmse['Mahony'][0]:.2f}°. The offline variant, which fuses a backward "
        f"pass into the inclination, does not gain on this trial ({rmse['kreisel offline'][0]:.2f}°). The gyro "
        f"alone, started on the motion capture's attitude, is {drift[still.stop - first - 1]:.1f}° off at the end "
        f"of the rest: its bias of {np.degrees(np.linalg.norm(bias)) * 3600:.0f}°/h, which kreisel's estimator "
        "learns at rest. The field at the start points "
        f"{np.degrees(nav.attitude_error_angles(runs['kreisel'].q[[first]], rec.reference[[first]])[1][0]):.1f}° "
        "away from the motion capture's north; kreisel trusts a field only once it has kept its strength and "
        "dip while the sensor turned, and then the heading error falls to about a degree. Without the "
        "magnetometer the inclination is unchanged, and the heading comes from the gyro alone: it starts at the "
        "sensor's own and nothing corrects its drift.",
        [Check.below("kreisel, causal: total RMSE over the movement (°)", total, TOTAL_BOUND),
         Check.below("kreisel, offline: total RMSE over the movement (°)", rmse["kreisel offline"][0], TOTAL_BOUND),
         Check.below("kreisel's total RMSE / the better of Madgwick and Mahony", total / best_published, 0.7),
         Check.close("attitude_error: total RMSE (°)", total, direct_total, rtol=1e-12,
                     source="angle of R R_refᵀ"),
         Check.close("attitude_error: inclination RMSE (°)", inclination, direct_inclination, rtol=1e-12,
                     source="angle between the up directions seen from the sensor"),
         Check.close("inclination RMSE without the magnetometer (°)", rmse["kreisel without magnetometer"][2],
                     inclination, atol=0.01, source="with it: the field corrects the heading only"),
         Check.close("gyro alone: error at the end of the rest (°)", drift[still.stop - first - 1],
                     np.degrees(np.linalg.norm(bias)) * rest_time, atol=wander,
                     source="|mean gyro at rest| × time, within the motion capture's wander at rest"),
         Check.below("kreisel's bias at the end of the rest − mean gyro at rest (relative)", learned, 0.05)],
        [(fig, "Error angle against the motion capture over time (log scale; the RMSE in brackets counts the "
               "movement only, after the dotted line), and kreisel's heading and inclination errors with and "
               "without the magnetometer."),
         (angles, "Yaw, pitch and roll of kreisel's estimate and of the motion capture; below, the errors.")],
    )


SECTIONS = (imu_attitude,)
