"""Compiled attitude filters: one loop over all samples per call, no Python per sample.

Every filter works on (n, 3) float64 arrays of gyro (rad/s), accelerometer
and magnetometer samples at a fixed step ``dt`` and writes the attitude
frame ← sensor (ENU, z up) into ``q_out``. ``mag`` with ``use_mag`` False is
not read. Parameters come in a float64 vector so that tuning never recompiles.
"""

from __future__ import annotations

import math

import numpy as np

from .._compiled import cached, inlined
from .._compiled.kernels import quat_product, quat_rotvec, rotated, rotvec_quat_in_range

#: Layout of the parameter vector of :func:`kreisel_filter` (names used by the public layer).
KREISEL_PARAMETERS = ("gyro_noise", "bias_walk", "acc_noise", "acc_disturbance", "mag_noise", "mag_norm_tol",
                      "mag_dip_tol", "rest_gyro", "rest_acc", "rest_time", "rest_noise", "rest_tau",
                      "bias_std0", "gravity", "mag_ref_tau", "mag_new_time", "acc_tau", "mag_new_turn")


@inlined
def _normalised(q0, q1, q2, q3):
    s = 1.0 / math.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    return q0 * s, q1 * s, q2 * s, q3 * s


@inlined
def _step(q0, q1, q2, q3, wx, wy, wz, dt):
    """q ⊗ exp(ω dt/2 as a rotation vector ω dt): the exact update for ω constant over the step."""
    d0, d1, d2, d3 = rotvec_quat_in_range(wx * dt, wy * dt, wz * dt)
    p0, p1, p2, p3 = quat_product(q0, q1, q2, q3, d0, d1, d2, d3)
    return _normalised(p0, p1, p2, p3)


@inlined
def _turn_earth(q0, q1, q2, q3, x, y, z):
    """exp(−(x, y, z)) ⊗ q: removes an attitude error (x, y, z) given in the earth frame."""
    d0, d1, d2, d3 = rotvec_quat_in_range(-x, -y, -z)
    p0, p1, p2, p3 = quat_product(d0, d1, d2, d3, q0, q1, q2, q3)
    return _normalised(p0, p1, p2, p3)


@inlined
def _scalar_update(P, dx, k, row, i, r, innovation):
    """Kalman update of the 6-state error with the scalar measurement x_i + noise(r); adds to ``dx``.

    Returns False (and changes nothing) when the innovation is not finite.
    """
    s = P[i, i] + r
    if not (s > 0.0) or not math.isfinite(innovation):
        return False
    for a in range(6):
        k[a] = P[a, i] / s
    nu = innovation - dx[i]
    for a in range(6):
        dx[a] += k[a] * nu
    for b in range(6):
        row[b] = P[i, b]
    for a in range(6):
        for b in range(6):
            P[a, b] -= k[a] * row[b]
    return True


@cached
def triad_start(acc, mag, use_mag):
    """Attitude ENU ← sensor from one accelerometer (up) and magnetometer (north, horizontal part) sample."""
    ax, ay, az = acc[0], acc[1], acc[2]
    na = math.sqrt(ax * ax + ay * ay + az * az)
    ux, uy, uz = ax / na, ay / na, az / na
    if not use_mag:
        # no field, no heading: the shortest turn of the measured up onto z (heading of the sensor kept)
        if uz > -1.0 + 1e-12:
            return _normalised(1.0 + uz, uy, -ux, 0.0)
        return 0.0, 1.0, 0.0, 0.0
    mx, my, mz = mag[0], mag[1], mag[2]
    # east = north × up (sensor components), north = up × east
    ex, ey, ez = my * uz - mz * uy, mz * ux - mx * uz, mx * uy - my * ux
    ne = math.sqrt(ex * ex + ey * ey + ez * ez)
    if not ne > 0.0:
        # no horizontal field: no heading (the callers skip the sample or refuse the start)
        return math.nan, math.nan, math.nan, math.nan
    ex, ey, ez = ex / ne, ey / ne, ez / ne
    nx, ny, nz = uy * ez - uz * ey, uz * ex - ux * ez, ux * ey - uy * ex
    # rows of R (ENU ← sensor) are east, north, up in sensor components
    r00, r01, r02, r10, r11, r12, r20, r21, r22 = ex, ey, ez, nx, ny, nz, ux, uy, uz
    t = r00 + r11 + r22
    if t > 0.0:
        s = 2.0 * math.sqrt(1.0 + t)
        q = (0.25 * s, (r21 - r12) / s, (r02 - r20) / s, (r10 - r01) / s)
    elif r00 > r11 and r00 > r22:
        s = 2.0 * math.sqrt(1.0 + r00 - r11 - r22)
        q = ((r21 - r12) / s, 0.25 * s, (r01 + r10) / s, (r02 + r20) / s)
    elif r11 > r22:
        s = 2.0 * math.sqrt(1.0 + r11 - r00 - r22)
        q = ((r02 - r20) / s, (r01 + r10) / s, 0.25 * s, (r12 + r21) / s)
    else:
        s = 2.0 * math.sqrt(1.0 + r22 - r00 - r11)
        q = ((r10 - r01) / s, (r02 + r20) / s, (r12 + r21) / s, 0.25 * s)
    return _normalised(q[0], q[1], q[2], q[3])


@cached
def kreisel_filter(gyr, acc, mag, use_mag, mag_clean, dt, p, start, q_out, bias_out, cov_out, bias_var_out, end):
    """kreisel's estimator: an error-state Kalman filter with the attitude error in the earth frame.

    State error x = (δ, β): q_est = exp(δ) ⊗ q_true (δ in ENU) and
    b_est = b_true + β (sensor frame). In the earth frame the accelerometer
    measures δx, δy (the tilt of the measured up), the magnetometer's
    horizontal part δz (the turn of measured north) and, at rest, the gyro
    measures β: every measurement picks one state, so each update is a
    scalar one. The error propagates as δ' = δ − R β dt.

    ``start`` (43,) holds a start state (q 4, b 3, the 6 × 6 covariance row
    by row), or NaN first for a start from the first samples (TRIAD, zero
    bias); either way no field is trusted yet. ``end`` receives the final
    state in the same layout, ``bias_var_out`` the bias variances.
    ``mag_clean`` (n,) bool, when not empty, decides for every sample
    whether its field is the earth's (a decision taken with hindsight by the
    offline smoother); empty, the filter decides causally from the field's
    norm and dip.
    """
    n = gyr.shape[0]
    (sg, sb, sa, kacc, sm, mtol, diptol, rgyr, racc, rtime, srest, rtau, sb0, grav, mtau, mnew) = (
        p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], p[9], p[10], p[11], p[12], p[13], p[14], p[15])
    alpha_acc = 1.0 - math.exp(-dt / p[16]) if p[16] > 0.0 else 1.0
    P = np.zeros((6, 6))
    dx = np.zeros(6)
    kbuf = np.empty(6)
    rowbuf = np.empty(6)
    if math.isnan(start[0]):
        q0, q1, q2, q3 = triad_start(acc[0], mag[0], use_mag)
        bx = by = bz = 0.0
        for a in range(3):
            P[a, a] = 0.01 ** 2
        P[2, 2] = 0.1 ** 2 if use_mag else 0.0
        for a in range(3, 6):
            P[a, a] = sb0 * sb0
    else:
        q0, q1, q2, q3 = start[0], start[1], start[2], start[3]
        bx, by, bz = start[4], start[5], start[6]
        for a in range(6):
            for b in range(6):
                P[a, b] = start[7 + 6 * a + b]
    # low-passed gyro and accelerometer for rest detection
    lgx, lgy, lgz = gyr[0, 0], gyr[0, 1], gyr[0, 2]
    lax, lay, laz = acc[0, 0], acc[0, 1], acc[0, 2]
    alpha_rest = 1.0 - math.exp(-dt / rtau)
    rest_for = 0.0
    # magnetic reference: norm and dip of the undisturbed field, and a candidate for a new one
    ref_norm = -1.0
    ref_dip = 0.0
    trusted = False
    cand_norm = ref_norm
    cand_dip = ref_dip
    cand_for = 0.0
    cand_turn = 0.0
    alpha_ref = 1.0 - math.exp(-dt / mtau)
    # the accelerometer low-passed in the earth frame, where the body's accelerations average out
    plx = pl_y = 0.0
    plz = -1.0
    qg = sg * sg * dt
    qb = sb * sb * dt
    G = np.empty((3, 3))
    GP = np.empty((3, 3))
    decided = mag_clean.shape[0] > 0
    for j in range(n):
        gx, gy, gz = gyr[j, 0], gyr[j, 1], gyr[j, 2]
        # --- propagation
        # sample 0 is where the start attitude is: the gyro turns it from sample 1 on
        q0, q1, q2, q3 = _step(q0, q1, q2, q3, gx - bx, gy - by, gz - bz, dt if j > 0 else 0.0)
        r00 = 1.0 - 2.0 * (q2 * q2 + q3 * q3)
        r01 = 2.0 * (q1 * q2 - q0 * q3)
        r02 = 2.0 * (q1 * q3 + q0 * q2)
        r10 = 2.0 * (q1 * q2 + q0 * q3)
        r11 = 1.0 - 2.0 * (q1 * q1 + q3 * q3)
        r12 = 2.0 * (q2 * q3 - q0 * q1)
        r20 = 2.0 * (q1 * q3 - q0 * q2)
        r21 = 2.0 * (q2 * q3 + q0 * q1)
        r22 = 1.0 - 2.0 * (q1 * q1 + q2 * q2)
        G[0, 0], G[0, 1], G[0, 2] = -r00 * dt, -r01 * dt, -r02 * dt
        G[1, 0], G[1, 1], G[1, 2] = -r10 * dt, -r11 * dt, -r12 * dt
        G[2, 0], G[2, 1], G[2, 2] = -r20 * dt, -r21 * dt, -r22 * dt
        # P_δδ += G P_βδ + P_δβ Gᵀ + G P_ββ Gᵀ + Q;  P_δβ += G P_ββ
        for a in range(3):
            for b in range(3):
                s = 0.0
                for c in range(3):
                    s += G[a, c] * P[3 + c, 3 + b]
                GP[a, b] = s
        for a in range(3):
            for b in range(3):
                s = 0.0
                for c in range(3):
                    s += G[a, c] * P[3 + c, b] + P[a, 3 + c] * G[b, c] + GP[a, c] * G[b, c]
                P[a, b] += s
        for a in range(3):
            for b in range(3):
                P[a, 3 + b] += GP[a, b]
                P[3 + b, a] = P[a, 3 + b]
        for a in range(3):
            P[a, a] += qg
            P[3 + a, 3 + a] += qb
        ax, ay, az = acc[j, 0], acc[j, 1], acc[j, 2]
        # --- rest detection and the bias measurement it allows
        lgx += alpha_rest * (gx - lgx)
        lgy += alpha_rest * (gy - lgy)
        lgz += alpha_rest * (gz - lgz)
        lax += alpha_rest * (ax - lax)
        lay += alpha_rest * (ay - lay)
        laz += alpha_rest * (az - laz)
        dg = (gx - lgx) ** 2 + (gy - lgy) ** 2 + (gz - lgz) ** 2
        da = (ax - lax) ** 2 + (ay - lay) ** 2 + (az - laz) ** 2
        mean_g = lgx * lgx + lgy * lgy + lgz * lgz
        # a turn at a steady rate is no rest: the low-passed rate itself must be small too
        if dg < rgyr * rgyr and mean_g < rgyr * rgyr and da < racc * racc:
            rest_for += dt
        else:
            rest_for = 0.0
        at_rest = rest_for >= rtime
        for a in range(6):
            dx[a] = 0.0
        if at_rest:
            rr = srest * srest
            _scalar_update(P, dx, kbuf, rowbuf, 3, rr, bx - lgx)
            _scalar_update(P, dx, kbuf, rowbuf, 4, rr, by - lgy)
            _scalar_update(P, dx, kbuf, rowbuf, 5, rr, bz - lgz)
        # --- accelerometer: the tilt of the measured up in the earth frame
        ex, ey, ez = r00 * ax + r01 * ay + r02 * az, r10 * ax + r11 * ay + r12 * az, r20 * ax + r21 * ay + r22 * az
        if plz < 0.0:
            plx, pl_y, plz = ex, ey, ez
        else:
            plx += alpha_acc * (ex - plx)
            pl_y += alpha_acc * (ey - pl_y)
            plz += alpha_acc * (ez - plz)
        ex, ey, ez = plx, pl_y, plz
        na = math.sqrt(ex * ex + ey * ey + ez * ez)
        hn = math.sqrt(ex * ex + ey * ey)
        if na > 0.0:
            ang = math.atan2(hn, ez)
            sc = ang / hn if hn > 1e-12 * na else 1.0 / na
            dev = (na - grav) / grav
            ra = sa * sa + (kacc * dev) ** 2
            if at_rest:
                ra = sa * sa
            _scalar_update(P, dx, kbuf, rowbuf, 0, ra, -ey * sc)
            _scalar_update(P, dx, kbuf, rowbuf, 1, ra, ex * sc)
        # apply the tilt and bias corrections before the heading, which is read from the corrected tilt;
        # the low-passed accelerometer turns with the frame
        q0, q1, q2, q3 = _turn_earth(q0, q1, q2, q3, dx[0], dx[1], dx[2])
        d0, d1, d2, d3 = rotvec_quat_in_range(-dx[0], -dx[1], -dx[2])
        plx, pl_y, plz = rotated(d0, d1, d2, d3, plx, pl_y, plz)
        bx -= dx[3]
        by -= dx[4]
        bz -= dx[5]
        for a in range(6):
            dx[a] = 0.0
        # --- magnetometer: heading from the horizontal part of the field only
        if use_mag:
            mx, my, mz = mag[j, 0], mag[j, 1], mag[j, 2]
            fx, fy, fz = rotated(q0, q1, q2, q3, mx, my, mz)
            fh = math.sqrt(fx * fx + fy * fy)
            fn = math.sqrt(fh * fh + fz * fz)
            if fh > 0.0:
                dip = math.atan2(-fz, fh)
                if ref_norm < 0.0:
                    ref_norm, ref_dip = fn, dip
                    cand_norm, cand_dip = fn, dip
                if decided:
                    if mag_clean[j]:
                        _scalar_update(P, dx, kbuf, rowbuf, 2, sm * sm, math.atan2(-fx, fy))
                elif trusted and abs(fn - ref_norm) < mtol * ref_norm and abs(dip - ref_dip) < diptol:
                    ref_norm += alpha_ref * (fn - ref_norm)
                    ref_dip += alpha_ref * (dip - ref_dip)
                    cand_norm, cand_dip = ref_norm, ref_dip
                    cand_for = 0.0
                    cand_turn = 0.0
                    _scalar_update(P, dx, kbuf, rowbuf, 2, sm * sm, math.atan2(-fx, fy))
                else:
                    # a field that keeps its norm and dip for a while *as the sensor turns* is the
                    # earth's (a magnet on the sensor turns with it and changes both): it becomes the reference
                    if abs(fn - cand_norm) < mtol * cand_norm and abs(dip - cand_dip) < diptol:
                        cand_norm += alpha_ref * (fn - cand_norm)
                        cand_dip += alpha_ref * (dip - cand_dip)
                        cand_for += dt
                        cand_turn += math.sqrt((gx - bx) ** 2 + (gy - by) ** 2 + (gz - bz) ** 2) * dt
                    else:
                        cand_norm, cand_dip = fn, dip
                        cand_for = 0.0
                        cand_turn = 0.0
                    if cand_for >= mnew and cand_turn >= p[17]:
                        ref_norm, ref_dip = cand_norm, cand_dip
                        trusted = True
            q0, q1, q2, q3 = _turn_earth(q0, q1, q2, q3, dx[0], dx[1], dx[2])
            bx -= dx[3]
            by -= dx[4]
            bz -= dx[5]
        q_out[j, 0], q_out[j, 1], q_out[j, 2], q_out[j, 3] = q0, q1, q2, q3
        bias_out[j, 0], bias_out[j, 1], bias_out[j, 2] = bx, by, bz
        for a in range(3):
            for b in range(3):
                cov_out[j, a, b] = P[a, b]
            bias_var_out[j, a] = P[3 + a, 3 + a]
    end[0], end[1], end[2], end[3] = q0, q1, q2, q3
    end[4], end[5], end[6] = bx, by, bz
    for a in range(6):
        for b in range(6):
            end[7 + 6 * a + b] = P[a, b]


@cached
def smoother_fusion(qf, pf, qb, pb, k, q_out, cov_out):
    """Two passes fused by their covariances: q = exp(P_f S⁻¹ δ) ⊗ q_f, P = P_f − P_f S⁻¹ P_f, S = P_f + P_b.

    δ is the error q_b ⊗ q_f⁻¹ in the earth frame split into a tilt (δx, δy)
    and a turn about the vertical δz (BROAD's split); only its first ``k``
    components (2: the tilt, 3: all) and the matching blocks of the
    covariances take part, the rest of ``cov_out`` is P_f.
    """
    S = np.zeros((3, 3))
    Si = np.zeros((3, 3))
    step = np.zeros(3)
    for j in range(qf.shape[0]):
        e0, e1, e2, e3 = quat_product(qb[j, 0], qb[j, 1], qb[j, 2], qb[j, 3], qf[j, 0], -qf[j, 1], -qf[j, 2],
                                      -qf[j, 3])
        turn = 2.0 * math.atan2(e3, e0)
        if turn > math.pi:
            turn -= 2.0 * math.pi
        elif turn <= -math.pi:
            turn += 2.0 * math.pi
        t0, t1, t2, t3 = quat_product(e0, e1, e2, e3, math.cos(0.5 * turn), 0.0, 0.0, -math.sin(0.5 * turn))
        tx, ty, _ = quat_rotvec(t0, t1, t2, t3)
        delta = (tx, ty, turn)
        for a in range(3):
            for b in range(3):
                S[a, b] = pf[j, a, b] + pb[j, a, b]
                Si[a, b] = 0.0
        if k == 2:
            det = S[0, 0] * S[1, 1] - S[0, 1] * S[1, 0]
            Si[0, 0], Si[0, 1], Si[1, 0], Si[1, 1] = S[1, 1] / det, -S[0, 1] / det, -S[1, 0] / det, S[0, 0] / det
        else:
            c00 = S[1, 1] * S[2, 2] - S[1, 2] * S[2, 1]
            c01 = S[1, 2] * S[2, 0] - S[1, 0] * S[2, 2]
            c02 = S[1, 0] * S[2, 1] - S[1, 1] * S[2, 0]
            det = S[0, 0] * c00 + S[0, 1] * c01 + S[0, 2] * c02
            Si[0, 0], Si[1, 0], Si[2, 0] = c00 / det, c01 / det, c02 / det
            Si[0, 1] = (S[0, 2] * S[2, 1] - S[0, 1] * S[2, 2]) / det
            Si[1, 1] = (S[0, 0] * S[2, 2] - S[0, 2] * S[2, 0]) / det
            Si[2, 1] = (S[0, 1] * S[2, 0] - S[0, 0] * S[2, 1]) / det
            Si[0, 2] = (S[0, 1] * S[1, 2] - S[0, 2] * S[1, 1]) / det
            Si[1, 2] = (S[0, 2] * S[1, 0] - S[0, 0] * S[1, 2]) / det
            Si[2, 2] = (S[0, 0] * S[1, 1] - S[0, 1] * S[1, 0]) / det
        # u = S⁻¹ δ, step = P_f u; G = S⁻¹ P_f, P = P_f − P_f G (all within the first k components)
        step[:] = 0.0
        for a in range(k):
            u = 0.0
            for b in range(k):
                u += Si[a, b] * delta[b]
            for c in range(k):
                step[c] += pf[j, c, a] * u
        for a in range(3):
            for b in range(3):
                cov_out[j, a, b] = pf[j, a, b]
        for a in range(k):
            for b in range(k):
                s = 0.0
                for c in range(k):
                    g = 0.0
                    for d in range(k):
                        g += Si[c, d] * pf[j, d, b]
                    s += pf[j, a, c] * g
                cov_out[j, a, b] -= s
        d0, d1, d2, d3 = rotvec_quat_in_range(step[0], step[1], step[2])
        p0, p1, p2, p3 = quat_product(d0, d1, d2, d3, qf[j, 0], qf[j, 1], qf[j, 2], qf[j, 3])
        q_out[j, 0], q_out[j, 1], q_out[j, 2], q_out[j, 3] = _normalised(p0, p1, p2, p3)


@inlined
def _unit3(x, y, z):
    n = math.sqrt(x * x + y * y + z * z)
    if n > 0.0:
        return x / n, y / n, z / n, True
    return x, y, z, False


@inlined
def _euler_step(q0, q1, q2, q3, d0, d1, d2, d3, dt):
    """q + q̇ dt renormalised: the first-order update both published filters use."""
    return _normalised(q0 + d0 * dt, q1 + d1 * dt, q2 + d2 * dt, q3 + d3 * dt)


@cached
def madgwick_filter(gyr, acc, mag, use_mag, dt, beta, q_start, q_out):
    """Madgwick's gradient-descent filter (Madgwick 2010 report, eqs. 25-34), in its own frame NWU.

    The earth's field reference is b = (|h_xy|, 0, h_z) with h the measured
    field turned into the earth frame (the report's eq. 46, without the
    factor 2 that its C code has in b). ``q_start`` and ``q_out`` are NWU ← sensor.
    """
    q0, q1, q2, q3 = q_start[0], q_start[1], q_start[2], q_start[3]
    q_out[0, 0], q_out[0, 1], q_out[0, 2], q_out[0, 3] = q0, q1, q2, q3
    for j in range(1, gyr.shape[0]):
        gx, gy, gz = gyr[j, 0], gyr[j, 1], gyr[j, 2]
        d0, d1, d2, d3 = quat_product(q0, q1, q2, q3, 0.0, gx, gy, gz)
        d0, d1, d2, d3 = 0.5 * d0, 0.5 * d1, 0.5 * d2, 0.5 * d3
        ax, ay, az, ok = _unit3(acc[j, 0], acc[j, 1], acc[j, 2])
        if ok:
            f0 = 2.0 * (q1 * q3 - q0 * q2) - ax
            f1 = 2.0 * (q0 * q1 + q2 * q3) - ay
            f2 = 2.0 * (0.5 - q1 * q1 - q2 * q2) - az
            s0 = -2.0 * q2 * f0 + 2.0 * q1 * f1
            s1 = 2.0 * q3 * f0 + 2.0 * q0 * f1 - 4.0 * q1 * f2
            s2 = -2.0 * q0 * f0 + 2.0 * q3 * f1 - 4.0 * q2 * f2
            s3 = 2.0 * q1 * f0 + 2.0 * q2 * f1
            mok = False
            if use_mag:
                mx, my, mz, mok = _unit3(mag[j, 0], mag[j, 1], mag[j, 2])
            if mok:
                hx, hy, hz = rotated(q0, q1, q2, q3, mx, my, mz)
                bx = math.sqrt(hx * hx + hy * hy)
                bz = hz
                f3 = 2.0 * bx * (0.5 - q2 * q2 - q3 * q3) + 2.0 * bz * (q1 * q3 - q0 * q2) - mx
                f4 = 2.0 * bx * (q1 * q2 - q0 * q3) + 2.0 * bz * (q0 * q1 + q2 * q3) - my
                f5 = 2.0 * bx * (q0 * q2 + q1 * q3) + 2.0 * bz * (0.5 - q1 * q1 - q2 * q2) - mz
                s0 += -2.0 * bz * q2 * f3 + (-2.0 * bx * q3 + 2.0 * bz * q1) * f4 + 2.0 * bx * q2 * f5
                s1 += 2.0 * bz * q3 * f3 + (2.0 * bx * q2 + 2.0 * bz * q0) * f4 + (2.0 * bx * q3 - 4.0 * bz * q1) * f5
                s2 += ((-4.0 * bx * q2 - 2.0 * bz * q0) * f3 + (2.0 * bx * q1 + 2.0 * bz * q3) * f4
                       + (2.0 * bx * q0 - 4.0 * bz * q2) * f5)
                s3 += (-4.0 * bx * q3 + 2.0 * bz * q1) * f3 + (-2.0 * bx * q0 + 2.0 * bz * q2) * f4 + 2.0 * bx * q1 * f5
            ns = math.sqrt(s0 * s0 + s1 * s1 + s2 * s2 + s3 * s3)
            if ns > 0.0:
                d0 -= beta * s0 / ns
                d1 -= beta * s1 / ns
                d2 -= beta * s2 / ns
                d3 -= beta * s3 / ns
        q0, q1, q2, q3 = _euler_step(q0, q1, q2, q3, d0, d1, d2, d3, dt)
        q_out[j, 0], q_out[j, 1], q_out[j, 2], q_out[j, 3] = q0, q1, q2, q3


@cached
def mahony_filter(gyr, acc, mag, use_mag, dt, kp, ki, q_start, q_out, bias_out):
    """Mahony's explicit complementary filter with bias (Mahony, Hamel, Pflimlin 2008, eq. 48), ENU.

    ω_mes = a × v̂_a + m × v̂_m with v̂ the estimated up and field directions in
    the sensor frame (field reference (0, |h_xy|, h_z) in ENU);
    b' = −k_I ω_mes, Ω = ω_y − b + k_P ω_mes.
    """
    q0, q1, q2, q3 = q_start[0], q_start[1], q_start[2], q_start[3]
    bx = by = bz = 0.0
    q_out[0, 0], q_out[0, 1], q_out[0, 2], q_out[0, 3] = q0, q1, q2, q3
    bias_out[0, 0], bias_out[0, 1], bias_out[0, 2] = 0.0, 0.0, 0.0
    for j in range(1, gyr.shape[0]):
        wx, wy, wz = gyr[j, 0], gyr[j, 1], gyr[j, 2]
        ax, ay, az, ok = _unit3(acc[j, 0], acc[j, 1], acc[j, 2])
        if ok:
            vx, vy, vz = rotated(q0, -q1, -q2, -q3, 0.0, 0.0, 1.0)
            ex, ey, ez = ay * vz - az * vy, az * vx - ax * vz, ax * vy - ay * vx
            mok = False
            if use_mag:
                mx, my, mz, mok = _unit3(mag[j, 0], mag[j, 1], mag[j, 2])
            if mok:
                hx, hy, hz = rotated(q0, q1, q2, q3, mx, my, mz)
                rx, ry, rz = rotated(q0, -q1, -q2, -q3, 0.0, math.sqrt(hx * hx + hy * hy), hz)
                ux, uy, uz, _ = _unit3(rx, ry, rz)
                ex += my * uz - mz * uy
                ey += mz * ux - mx * uz
                ez += mx * uy - my * ux
            bx -= ki * ex * dt
            by -= ki * ey * dt
            bz -= ki * ez * dt
            wx += kp * ex - bx
            wy += kp * ey - by
            wz += kp * ez - bz
        d0, d1, d2, d3 = quat_product(q0, q1, q2, q3, 0.0, wx, wy, wz)
        q0, q1, q2, q3 = _euler_step(q0, q1, q2, q3, 0.5 * d0, 0.5 * d1, 0.5 * d2, 0.5 * d3, dt)
        q_out[j, 0], q_out[j, 1], q_out[j, 2], q_out[j, 3] = q0, q1, q2, q3
        bias_out[j, 0], bias_out[j, 1], bias_out[j, 2] = bx, by, bz


@cached
def complementary_filter(gyr, acc, mag, use_mag, dt, gain, q_start, q_out):
    """The quaternion complementary filter: q ← nlerp(q_gyro, q_am, gain) with q_am from TRIAD, ENU.

    q_gyro is the exact gyro update of the previous attitude; q_am the
    attitude of the current accelerometer and magnetometer samples (without
    a magnetometer: the shortest turn of q_gyro that makes the measured up
    vertical, so that the heading stays the gyro's).
    """
    q0, q1, q2, q3 = q_start[0], q_start[1], q_start[2], q_start[3]
    q_out[0, 0], q_out[0, 1], q_out[0, 2], q_out[0, 3] = q0, q1, q2, q3
    for j in range(1, gyr.shape[0]):
        q0, q1, q2, q3 = _step(q0, q1, q2, q3, gyr[j, 0], gyr[j, 1], gyr[j, 2], dt)
        ax, ay, az, ok = _unit3(acc[j, 0], acc[j, 1], acc[j, 2])
        if ok:
            if use_mag:
                m0, m1, m2, m3 = triad_start(acc[j], mag[j], True)
            else:
                ux, uy, uz = rotated(q0, q1, q2, q3, ax, ay, az)
                # the turn of the measured up onto z, applied in the earth frame
                c0, c1, c2, c3 = _normalised(1.0 + uz, uy, -ux, 0.0) if uz > -1.0 + 1e-12 else (0.0, 1.0, 0.0, 0.0)
                m0, m1, m2, m3 = quat_product(c0, c1, c2, c3, q0, q1, q2, q3)
            if m0 * q0 + m1 * q1 + m2 * q2 + m3 * q3 < 0.0:
                m0, m1, m2, m3 = -m0, -m1, -m2, -m3
            if math.isfinite(m0):
                q0, q1, q2, q3 = _normalised(q0 + gain * (m0 - q0), q1 + gain * (m1 - q1), q2 + gain * (m2 - q2),
                                             q3 + gain * (m3 - q3))
        q_out[j, 0], q_out[j, 1], q_out[j, 2], q_out[j, 3] = q0, q1, q2, q3
