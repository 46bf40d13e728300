"""kreisel.nav strapdown updates against plain-Python and scipy loops.

10^6 coning increments (α = 1°, 1 Hz, 100 Hz sampling) through
:func:`kreisel.nav.attitude_from_increments` for N = 1, 2, 4 and 10^6 rate
samples through :func:`kreisel.nav.attitude_from_rates`. The peers are the
same algorithm written as a per-update Python loop over numpy scalars, and a
scipy loop (update rotation vectors vectorised, then ``Rotation`` products
one update at a time); they are timed on ``PEER_N`` increments and scaled to
10^6 (the loops are linear in n). Median of several runs, same process.
Writes ``bench/results/nav.md``.
"""

from __future__ import annotations

import numpy as np
from _common import header, load_average, markdown_table, median_time, write_results
from scipy.spatial.transform import Rotation

import kreisel as kr

N = 1_000_000
PEER_N = 10_000
REPEATS = 5
K = {1: (), 2: (2 / 3,), 4: (54 / 105, 92 / 105, 214 / 105)}


def update_vectors(dtheta, n):
    """φ of every update, vectorised: Σ Δθ_i + (Σ_{i<N} k_i Δθ_i) × Δθ_N."""
    d = dtheta.reshape(-1, n, 3)
    phi = d.sum(axis=1)
    if n > 1:
        phi += np.cross(np.tensordot(K[n], d[:, :-1], axes=(0, 1)), d[:, -1])
    return phi


def python_loop(q0, dtheta, n):
    out = [np.asarray(q0, float)]
    q = out[0]
    k = np.array(K[n])
    for j in range(dtheta.shape[0] // n):
        d = dtheta[j * n:(j + 1) * n]
        phi = d.sum(axis=0)
        if n > 1:
            phi = phi + np.cross(k @ d[:-1], d[-1])
        a = np.linalg.norm(phi)
        dq = np.concatenate([[np.cos(a / 2)], np.sin(a / 2) / a * phi]) if a > 0 else np.array([1.0, 0, 0, 0])
        w0, v0 = q[0], q[1:]
        w1, v1 = dq[0], dq[1:]
        q = np.concatenate([[w0 * w1 - v0 @ v1], w0 * v1 + w1 * v0 + np.cross(v0, v1)])
        q = q / np.linalg.norm(q)
        out.append(q)
    return np.array(out)


def scipy_loop(q0, dtheta, n):
    steps = Rotation.from_rotvec(update_vectors(dtheta, n))
    r = Rotation.from_quat(q0, scalar_first=True)
    out = [r]
    for i in range(len(steps)):
        r = r * steps[i]
        out.append(r)
    return Rotation.concatenate(out).as_quat(scalar_first=True)


# (α in degrees, N, samples per cone period, cone periods): the cases of tests/nav/test_coning.py
DRIFT_CASES = [(1.0, 1, 60, 20), (1.0, 2, 60, 20), (1.0, 3, 24, 40), (0.1, 4, 16, 100)]


def drift_table():
    """Measured drift rate (body frame, whole cone periods) against the classical coefficient."""
    rows = []
    for alpha_deg, n, per_period, periods in DRIFT_CASES:
        alpha, ts = np.radians(alpha_deg), 1.0 / per_period
        m = kr.nav.coning_motion(alpha, 2 * np.pi, ts, per_period * periods)
        q = kr.nav.attitude_from_increments(m.q[0], m.dtheta, n)
        error = kr.quat_to_rotvec(kr.quat_multiply(kr.quat_conjugate(m.q[-1]), q[-1]))
        drift = error / m.t[-1]
        formula = kr.nav.coning_drift(alpha, 2 * np.pi, ts, n)
        angle = np.arccos(-drift[0] / np.linalg.norm(drift))
        rows.append((f"{alpha_deg}°", n, f"{2 * np.pi * ts:.4f}", f"{formula:.4e}", f"{-drift[0]:.4e}",
                     f"{-drift[0] / formula:.4f}", f"{angle / alpha:.3f}"))
    lines = ["", ("## Coning drift (1 Hz cone): measured rate of the body-frame error vs "
                  "α²Ωλ^(2N) N!/(2^(N+1)(2N+1)!!)"), ""]
    lines += markdown_table(["α", "N", "λ = ΩT_s", "formula (rad/s)", "measured −x (rad/s)", "ratio", "angle to −x / α"],
                            rows, align="rrrrrrr")
    return lines


def main():
    m = kr.nav.coning_motion(np.radians(1.0), 2 * np.pi, 0.01, N)
    q0, d = m.q[0], m.dtheta
    dp = d[:PEER_N]
    load_before = load_average()
    rows = []
    for n in (1, 2, 4):
        ours = median_time(lambda n=n: kr.nav.attitude_from_increments(q0, d, n), REPEATS)
        ref = kr.nav.attitude_from_increments(q0, dp, n)
        for name, fn in (("python loop", python_loop), ("scipy Rotation loop", scipy_loop)):
            got = fn(q0, dp, n)
            agree = np.abs(np.abs(np.sum(got * ref, axis=-1)) - 1).max()
            assert agree < 1e-12, (name, n, agree)
            peer = median_time(lambda fn=fn, n=n: fn(q0, dp, n), repeats=3) * N / PEER_N
            rows.append((f"increments, N = {n}", name, ours, peer))
    t = m.t
    for method in ("quaternion", "bortz"):
        ours = median_time(lambda method=method: kr.nav.attitude_from_rates(q0, t, m.omega, method=method), REPEATS)
        rows.append((f"rates, {method} RK4", "—", ours, float("nan")))

    lines = header("kreisel.nav benchmark",
                   f"10^6 samples (coning, α = 1°, 1 Hz, T_s = 10 ms); peers timed on {PEER_N} and scaled to 10^6.",
                   f"Medians of {REPEATS} runs (peers 3); contract: 10^6 increments in < 0.5 s.",
                   load_before=load_before)
    table = []
    for case, peer_name, ours, peer in rows:
        ratio = "—" if np.isnan(peer) else f"{peer / ours:.0f}×"
        peer_s = "—" if np.isnan(peer) else f"{peer:.2f}"
        table.append((case, peer_name, f"{ours:.4f}", peer_s, ratio))
    lines += markdown_table(["case", "peer", "kreisel (s)", "peer (s, scaled)", "speed-up"], table, align="--rrr")
    write_results("nav", "\n".join(lines + drift_table()))


if __name__ == "__main__":
    main()
