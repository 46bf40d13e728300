"""Attitude estimation on BROAD's seven trials: kreisel against VQF, ahrs and imufusion, one process.

For every filter: the mean over the seven trials (``bench/data/broad``) of
the total, heading and inclination RMSE in degrees over the ``movement``
samples (BROAD's metric, :func:`kreisel.nav.attitude_error`), one parameter
set for all trials, and the cost per sample of a batch call (median of
``REPEATS`` runs over one trial, kreisel and VQF interleaved). ahrs' Madgwick
works in NWU and its result is turned to ENU; imufusion runs in ENU with
gyro in °/s and specific force in g. ahrs and imufusion run one Python call
per sample, so their cost is that of a user's loop, not of their kernels.
Writes ``bench/results/attitude.md``. Needs the bench extra (vqf, ahrs, imufusion).
"""

from __future__ import annotations

import pathlib

import numpy as np
from _common import header, interleaved, load_average, markdown_table, median_time, write_results

import kreisel as kr

DATA = pathlib.Path(__file__).resolve().parent / "data" / "broad"
REPEATS = 5
ENU_FROM_NWU = np.array([np.sqrt(0.5), 0.0, 0.0, np.sqrt(0.5)])


def trials():
    for path in sorted(DATA.glob("*.npz")):
        with np.load(path) as d:
            # vqf wants C-ordered float64 arrays
            sensors = {key: np.ascontiguousarray(d[key], float) for key in ("gyr", "acc", "mag")}
            yield {"name": path.stem, **sensors, "ref": d["opt_quat"], "movement": d["movement"],
                   "rate": float(d["sampling_rate"])}


def kreisel_filter(method=None, offline=False, mag=True):
    def run(t):
        return kr.nav.estimate_attitude(t["gyr"], t["acc"], t["mag"] if mag else None, rate=t["rate"],
                                        method=method, offline=offline).q
    return run


def vqf_filter(kind):
    import vqf

    def run(t):
        if kind == "offline":
            return vqf.offlineVQF(t["gyr"], t["acc"], t["mag"], 1.0 / t["rate"])["quat9D"]
        out = vqf.VQF(1.0 / t["rate"]).updateBatch(t["gyr"], t["acc"], t["mag"])
        return out["quat9D" if kind == "9D" else "quat6D"]
    return run


def ahrs_filter(kind):
    from ahrs.filters import Madgwick, Mahony

    def run(t):
        if kind == "madgwick":
            q = Madgwick(gyr=t["gyr"], acc=t["acc"], mag=t["mag"], frequency=t["rate"], gain=0.12).Q
            return kr.quat_multiply(ENU_FROM_NWU, q)
        return Mahony(gyr=t["gyr"], acc=t["acc"], mag=t["mag"], frequency=t["rate"], k_P=0.74, k_I=0.0012).Q
    return run


def imufusion_filter(t):
    import imufusion

    settings = imufusion.AhrsSettings()
    settings.convention = imufusion.CONVENTION_ENU
    settings.gain = 0.5
    settings.gyroscope_range = 2000.0
    settings.acceleration_rejection = 10.0
    settings.magnetic_rejection = 10.0
    settings.rejection_timeout = int(5 * t["rate"])
    settings.sample_rate = t["rate"]
    ahrs = imufusion.Ahrs()
    ahrs.set_settings(settings)
    gyr = np.degrees(t["gyr"])
    acc = t["acc"] / 9.81
    q = np.empty((len(gyr), 4))
    for j in range(len(gyr)):
        ahrs.update(gyr[j], acc[j], t["mag"][j])
        q[j] = ahrs.get_quaternion()
    return q


def main():
    load_before = load_average()
    data = list(trials())
    filters = {
        "kreisel (default, causal)": kreisel_filter(),
        "kreisel offline": kreisel_filter(offline=True),
        "kreisel 6D (no magnetometer)": kreisel_filter(mag=False),
        "kreisel Madgwick (β 0.12)": kreisel_filter("madgwick"),
        "kreisel Mahony (kP 0.74, kI 0.0012)": kreisel_filter("mahony"),
        "VQF": vqf_filter("9D"),
        "offline VQF": vqf_filter("offline"),
        "VQF 6D": vqf_filter("6D"),
        "ahrs Madgwick (β 0.12, NWU→ENU)": ahrs_filter("madgwick"),
        "ahrs Mahony (kP 0.74, kI 0.0012)": ahrs_filter("mahony"),
        "imufusion (gain 0.5, rejection 10°/10°, 5 s)": imufusion_filter,
    }
    rows = []
    for name, run in filters.items():
        errors = np.array([kr.nav.attitude_error(run(t), t["ref"], t["movement"]) for t in data])
        cells = [name] + [f"{e:.3f}" for e in errors.mean(axis=0)]
        cells.append(" / ".join(f"{e:.2f}" for e in errors[:, 0]))
        rows.append(cells)
        print(" | ".join(cells), flush=True)
    t = data[0]
    n = len(t["gyr"])
    import vqf

    kreisel_time, vqf_time = interleaved(lambda: kreisel_filter()(t), lambda: vqf_filter("9D")(t), repeats=REPEATS)
    offline_time = median_time(lambda: kreisel_filter(offline=True)(t), REPEATS)
    offline_vqf_time = median_time(lambda: vqf.offlineVQF(t["gyr"], t["acc"], t["mag"], 1.0 / t["rate"]), REPEATS)
    timing = [["kreisel (default, causal)", f"{kreisel_time.median / n * 1e6:.2f}"],
              ["VQF (updateBatch)", f"{vqf_time.median / n * 1e6:.2f}"],
              ["kreisel offline", f"{offline_time / n * 1e6:.2f}"],
              ["offline VQF", f"{offline_vqf_time / n * 1e6:.2f}"]]
    notes = ("Mean over BROAD's seven trials (bench/data/broad) of the RMSE in degrees over the movement samples; "
             "one parameter set per filter for all trials. Per-trial column: total RMSE of trials "
             + ", ".join(d["name"][:2] for d in data) + ".")
    lines = header("Attitude estimation on BROAD", notes, load_before=load_before)
    lines += markdown_table(["filter", "total (°)", "heading (°)", "inclination (°)", "total per trial (°)"],
                            rows, "lrrrl")
    lines += ["", f"Cost per sample of a batch call on trial {t['name'][:2]} ({n} samples), median of {REPEATS}:", ""]
    lines += markdown_table(["filter", "µs per sample"], timing, "lr")
    write_results("attitude", "\n".join(lines))


if __name__ == "__main__":
    main()
