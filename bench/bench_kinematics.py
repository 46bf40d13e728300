"""Batch rate maps: kreisel's compiled kernels against vectorised numpy on 10^6 samples.

The numpy references are the natural whole-array expressions of the same
formulas (Theory §3.5 Bortz equation with the same small-angle series; the
chapter's explicit ZXZ body inverse of §3.6 and the aerospace ZYX body inverse),
with the same NaN at gimbal lock. Each reference is checked against kreisel
before timing. kreisel's times include its input validation. "one core"
forces the serial loop; the default uses both cores for large batches.

Run: python bench/bench_kinematics.py  (writes bench/results/kinematics.md)
"""

import warnings

import numpy as np
from _common import header, load_average, markdown_table, median_time, write_results

import kreisel as kr
from kreisel._compiled.series import BORTZ_SERIES, BORTZ_SERIES_BELOW
from kreisel._compiled import elementwise

N = 1_000_000
TOL = 1e-8
REPEATS = 7


def bortz_numpy(psi, w):
    angle = np.sqrt(np.einsum("ij,ij->i", psi, psi))
    h = 0.5 * angle
    with np.errstate(divide="ignore", invalid="ignore"):
        f = (1.0 - h * np.cos(h) / np.sin(h)) / (angle * angle)
    f = np.where(angle < BORTZ_SERIES_BELOW, np.polyval(BORTZ_SERIES, angle * angle), f)
    f = np.where((angle > np.pi) & (np.abs(np.sin(h)) <= TOL), np.nan, f)
    c = np.cross(psi, w)
    return w + 0.5 * c + f[:, None] * np.cross(psi, c)


def zxz_body_numpy(angles, w):
    """Theory §3.6: φ̇ = (ω₁ sin ψ + ω₂ cos ψ)/sin θ, θ̇ = ω₁ cos ψ − ω₂ sin ψ, ψ̇ = ω₃ − cos θ φ̇."""
    theta, psi = angles[:, 1], angles[:, 2]
    s, c = np.sin(psi), np.cos(psi)
    st = np.sin(theta)
    st = np.where(np.abs(st) <= TOL, np.nan, st)
    phidot = (w[:, 0] * s + w[:, 1] * c) / st
    return np.stack([phidot, w[:, 0] * c - w[:, 1] * s, w[:, 2] - np.cos(theta) * phidot], axis=-1)


def zyx_body_numpy(angles, w):
    """Yaw, pitch, roll (intrinsic ZYX): ψ̇ = (sin φ ω₂ + cos φ ω₃)/cos θ, θ̇ = cos φ ω₂ − sin φ ω₃, φ̇ = ω₁ + sin θ ψ̇."""
    theta, phi = angles[:, 1], angles[:, 2]
    s, c = np.sin(phi), np.cos(phi)
    ct = np.cos(theta)
    ct = np.where(np.abs(ct) <= TOL, np.nan, ct)
    yawdot = (s * w[:, 1] + c * w[:, 2]) / ct
    return np.stack([yawdot, c * w[:, 1] - s * w[:, 2], w[:, 0] + np.sin(theta) * yawdot], axis=-1)


def single_core(fn):
    def run():
        saved = elementwise.PARALLEL_THRESHOLD
        elementwise.PARALLEL_THRESHOLD = 1 << 62
        try:
            return fn()
        finally:
            elementwise.PARALLEL_THRESHOLD = saved

    return run


def main():
    rng = np.random.default_rng(0)
    axis = rng.normal(size=(N, 3))
    psi = axis / np.linalg.norm(axis, axis=1, keepdims=True) * rng.uniform(0.0, 3.0, size=(N, 1))
    w = rng.normal(size=(N, 3))
    angles = rng.uniform(-3.0, 3.0, size=(N, 3))
    angles[:, 1] = rng.uniform(0.05, 1.5, size=N)

    cases = [
        ("rotvec_rate (Bortz, body)", lambda: kr.rotvec_rate(psi, w, frame="body"), lambda: bortz_numpy(psi, w)),
        ("euler_rates ZXZ body", lambda: kr.euler_rates("ZXZ", angles, w, frame="body"), lambda: zxz_body_numpy(angles, w)),
        ("euler_rates ZYX body", lambda: kr.euler_rates("ZYX", angles, w, frame="body"), lambda: zyx_body_numpy(angles, w)),
    ]
    load_before = load_average()
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for name, ours, numpy_ref in cases:
            got, want = ours(), numpy_ref()
            err = np.max(np.abs(got - want) / (1.0 + np.abs(want)))
            assert err < 1e-12, (name, err)
            t_np = median_time(numpy_ref, REPEATS)
            t_1 = median_time(single_core(ours), REPEATS)
            t_2 = median_time(ours, REPEATS)
            rows.append((name, f"{t_np * 1e3:.1f}", f"{t_1 * 1e3:.1f}", f"{t_2 * 1e3:.1f}", f"{t_np / t_1:.1f}",
                         f"{t_np / t_2:.1f}", f"{err:.1e}"))
    lines = header(
        None,
        f"Rate maps on {N:,} samples, medians of {REPEATS} runs (ms); ratio = numpy time / kreisel time.",
        "Shared machine: the 2-core column needs a free second core.",
        load_before=load_before,
    )
    lines += markdown_table(
        ["operation", "numpy", "kreisel, one core", "kreisel, default (2 cores)", "ratio, one core", "ratio, default",
         "max rel. difference"],
        rows,
    )
    write_results("kinematics", "\n".join(lines))


if __name__ == "__main__":
    main()
