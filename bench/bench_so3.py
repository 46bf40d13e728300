"""kreisel.so3 against scipy.spatial.transform and numpy-quaternion on 10^6 rotations.

For each batch operation: median and best wall time of kreisel, scipy and
(for composition, apply, quat -> matrix and rotvec -> quat) numpy-quaternion,
timed in alternation on the same inputs in one process; the speed-ups; the
ratio to a streaming copy of the operation's input and output (the least
memory traffic any implementation needs); and kreisel's CPU time over wall
time (about 2 when both cores work). Plus one single-rotation
``quat_multiply``. Writes ``bench/results/so3.md`` (notes after the
``_common.NOTES_MARKER`` line are kept).

kreisel runs batches of at least ``PARALLEL_THRESHOLD`` rotations on all
cores (numba ``prange``); scipy and numpy-quaternion are single-threaded.
The peers get their inputs in their own conventions, converted before the
timing (scipy scalar-last ``Rotation`` objects, numpy-quaternion arrays of
``quaternion`` scalars); their outputs are left in their own types.
"""

from __future__ import annotations

import json
import resource
import subprocess
import sys

import numpy as np
import quaternion as npq

from _common import (
    NOTES_MARKER,
    RESULTS,
    atomic_write,
    interleaved,
    load_average,
    median_time,
    streaming_copy,
    table_section,
    write_results,
)
from scipy.spatial.transform import Rotation as S
from scipy.spatial.transform import RotationSpline as ScipySpline

import kreisel as kr

N = 1_000_000
REPEATS = 5

#: Operations whose time is set by memory traffic (the goal: within 2x of the copy bound).
MEMORY_BOUND = {"quat -> matrix", "matrix -> quat", "composition p q", "apply R(q) v", "inverse", "normalisation"}


def _cases(rng):
    q = rng.normal(size=(N, 4))
    q /= np.linalg.norm(q, axis=-1, keepdims=True)
    p = rng.normal(size=(N, 4))
    p /= np.linalg.norm(p, axis=-1, keepdims=True)
    raw = 2.0 * rng.normal(size=(N, 4))  # not unit: for the normalisation
    R = kr.quat_to_matrix(q)
    psi = kr.quat_to_rotvec(q)
    euler = kr.quat_to_euler("ZXZ", q)
    v = rng.normal(size=(N, 3))
    last = lambda x: np.ascontiguousarray(x[:, [1, 2, 3, 0]])  # noqa: E731
    q_last, raw_last = last(q), last(raw)
    sq, sp = S.from_quat(q_last), S.from_quat(last(p))
    Q, P = npq.as_quat_array(q), npq.as_quat_array(p)

    def npq_apply():
        return npq.as_vector_part(Q * npq.from_vector_part(v) * Q.conjugate())

    # The peers agree with kreisel (elementwise apply: numpy-quaternion's
    # rotate_vectors would rotate every vector by every rotation).
    assert np.allclose(npq.as_float_array(P * Q), kr.quat_multiply(p, q), atol=1e-14)
    assert np.allclose(npq_apply(), kr.quat_apply(q, v), atol=1e-14)
    assert np.allclose(npq.as_rotation_matrix(Q), R, atol=1e-14)
    assert np.allclose(npq.as_float_array(npq.from_rotation_vector(psi)), kr.rotvec_to_quat(psi), atol=1e-14)

    # name, kreisel, scipy, numpy-quaternion or None, doubles in, doubles out per rotation
    return [
        ("quat -> matrix", lambda: kr.quat_to_matrix(q), lambda: S.from_quat(q_last).as_matrix(),
         lambda: npq.as_rotation_matrix(Q), 4, 9),
        ("matrix -> quat", lambda: kr.matrix_to_quat(R), lambda: S.from_matrix(R).as_quat(), None, 9, 4),
        ("rotvec -> matrix", lambda: kr.rotvec_to_matrix(psi), lambda: S.from_rotvec(psi).as_matrix(), None, 3, 9),
        ("rotvec -> quat", lambda: kr.rotvec_to_quat(psi), lambda: S.from_rotvec(psi).as_quat(),
         lambda: npq.from_rotation_vector(psi), 3, 4),
        ("matrix -> rotvec", lambda: kr.matrix_to_rotvec(R), lambda: S.from_matrix(R).as_rotvec(), None, 9, 3),
        ("Euler ZXZ -> matrix", lambda: kr.euler_to_matrix("ZXZ", euler), lambda: S.from_euler("ZXZ", euler).as_matrix(),
         None, 3, 9),
        ("matrix -> Euler ZXZ", lambda: kr.matrix_to_euler("ZXZ", R), lambda: S.from_matrix(R).as_euler("ZXZ"), None, 9, 3),
        ("composition p q", lambda: kr.quat_multiply(p, q), lambda: sp * sq, lambda: P * Q, 8, 4),
        ("apply R(q) v", lambda: kr.quat_apply(q, v), lambda: sq.apply(v), npq_apply, 7, 3),
        ("inverse", lambda: kr.quat_inverse(q), lambda: sq.inv(), None, 4, 4),
        ("normalisation", lambda: kr.quat_normalize(raw), lambda: S.from_quat(raw_last), None, 4, 4),
    ]


def allocating_copy(n_in, n_out):
    """The copy bound for a function that returns a new array: the output buffer is allocated per run.

    In this VM a freshly allocated buffer of many MB often costs far more to
    touch the first time than a reused one (the pages come back from the
    host), and every call of kreisel, scipy or numpy-quaternion pays that too.
    """
    src_in, dst_in, src_out = np.random.rand(n_in), np.empty(n_in), np.random.rand(n_out)

    def run():
        np.copyto(dst_in, src_in)
        return src_out.copy()

    return run


def _ms(t):
    return f"{t * 1e3:.2f}"


def main():
    cases = _cases(np.random.default_rng(0))
    load_before = load_average()
    rows = []
    for name, ours, scipy_run, npq_run, n_in, n_out in cases:
        copies = [streaming_copy(n_in * N, n_out * N), allocating_copy(n_in * N, n_out * N),
                  streaming_copy((n_in + n_out) * N // 2, 0)]
        runs = [ours, scipy_run, *copies] + ([npq_run] if npq_run else [])
        t_ours, t_scipy, t_copy, t_new, t_own, *t_npq = interleaved(*runs, repeats=REPEATS)
        npq_cells = [_ms(t_npq[0].median), f"{t_npq[0].median / t_ours.median:.1f}×"] if t_npq else ["", ""]
        rows.append([
            name + ("" if name in MEMORY_BOUND else " †"),
            _ms(t_ours.median), _ms(t_scipy.median), f"{t_scipy.median / t_ours.median:.1f}×", *npq_cells,
            _ms(t_copy.median), f"{t_ours.median / t_copy.median:.2f}", _ms(t_new.median), f"{t_ours.median / t_new.median:.2f}",
            _ms(t_own.median), f"{t_ours.median / t_own.median:.2f}", f"{t_scipy.median / 3 / t_own.median:.2f}",
            _ms(t_ours.best), f"{t_scipy.best / t_ours.best:.1f}×", f"{t_ours.best / t_copy.best:.2f}",
            f"{t_ours.cpu_median / t_ours.median:.1f}",
        ])
        print(" | ".join(rows[-1]), flush=True)

    a, b = np.array([0.9, 0.1, 0.3, 0.2]), np.array([0.5, -0.5, 0.5, 0.5])
    sa, sb = S.from_quat(a[[1, 2, 3, 0]]), S.from_quat(b[[1, 2, 3, 0]])
    single = median_time(lambda: [kr.quat_multiply(a, b) for _ in range(1000)]) / 1000
    single_scipy = median_time(lambda: [(sa * sb).as_quat() for _ in range(1000)]) / 1000

    lines = table_section(
        "kreisel.so3 vs scipy.spatial.transform and numpy-quaternion",
        [f"10^6 rotations, float64; medians and bests of {REPEATS} runs taken in alternation (kreisel, scipy, copies, "
         f"numpy-quaternion {npq.__version__}) in one process. Copy bound: `np.copyto` of input- and output-sized "
         "preallocated buffers; copy to new output: the same, but the output buffer is allocated per run, as every "
         "function returning a new array must (in this VM first touches of fresh pages are slow and erratic). "
         "kreisel CPU/wall: about 2 when both cores work. "
         "† transcendental-bound (the others are memory-bound: goal within 2× of the copy bound). "
         "Own traffic: one `np.copyto` moving as many bytes as the operation must, (input + output)/2 doubles read "
         "and as many written (half the copy bound's bytes); 3× scipy / own traffic below 1 means that 3× scipy is "
         "faster than this machine moves the operation's bytes."],
        ["operation", "kreisel (ms)", "scipy (ms)", "vs scipy", "numpy-quaternion (ms)", "vs numpy-quaternion",
         "copy bound (ms)", "kreisel / copy", "copy to new output (ms)", "kreisel / copy to new", "own traffic (ms)",
         "kreisel / own traffic", "3× scipy / own traffic", "best kreisel (ms)", "best vs scipy", "best kreisel / best copy",
         "kreisel CPU / wall"],
        rows, "l" + "r" * 16, load_before=load_before,
    )
    lines += [
        "",
        f"Single call `quat_multiply` of two 4-vectors: kreisel {single * 1e6:.2f} µs, "
        f"scipy (`Rotation * Rotation`, then `as_quat`) {single_scipy * 1e6:.2f} µs.",
    ]
    write_results("so3", "\n".join(lines))


#: Heading of the section on the operations scipy users port (kept in so3.md above the notes).
PARITY_HEADING = "## Operations scipy users port: align_vectors, RotationSpline, powers, Davenport angles"
#: Wahba problems in the batch and vectors per problem; scipy solves one per call.
PROBLEMS, VECTORS, SCIPY_LOOP = 100_000, 4, 2_000


def _parity_cases(rng):
    """name, kreisel batch, scipy batch (or per-call loop and its scale), kreisel single, scipy single."""
    q = rng.normal(size=(N, 4))
    q /= np.linalg.norm(q, axis=-1, keepdims=True)
    r, sr = kr.Rotation.from_quat(q), S.from_quat(q, scalar_first=True)
    b = rng.normal(size=(PROBLEMS, VECTORS, 3))
    truth = kr.Rotation.random(PROBLEMS, rng=1)
    a = truth[:, None].apply(b) + 0.01 * rng.normal(size=b.shape)
    w = rng.random((PROBLEMS, VECTORS)) + 0.5
    knots = kr.Rotation.random(100, rng=2)
    times = np.arange(100.0)
    spline, sspline = kr.RotationSpline(times, knots), ScipySpline(times, knots.to_scipy())
    t = rng.uniform(0.0, 99.0, N)
    axes = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [np.cos(0.4), 0.0, np.sin(0.4)]])
    angles = r.as_davenport(axes, "e")
    r1, sr1 = r[0], sr[0]

    # The peers agree before they are timed.
    assert np.allclose(kr.quat_to_matrix(kr.align_vectors(a[:50], b[:50], w[:50])[0]),
                       [S.align_vectors(a[i], b[i], w[i])[0].as_matrix() for i in range(50)], atol=1e-12)
    assert np.allclose(spline(t[:1000], 1, frame="body"), sspline(t[:1000], 1), atol=1e-10)
    assert np.allclose((r[:1000] ** 0.3).as_matrix(), (sr[:1000] ** 0.3).as_matrix(), atol=1e-14)
    assert np.allclose(angles[:1000], sr[:1000].as_davenport(axes, "e"), atol=1e-9)

    def scipy_align_loop():
        for i in range(SCIPY_LOOP):
            S.align_vectors(a[i], b[i], w[i])

    return [
        (f"align_vectors, {PROBLEMS:.0e} problems of {VECTORS} vectors", lambda: kr.align_vectors(a, b, w),
         scipy_align_loop, PROBLEMS / SCIPY_LOOP,
         lambda: kr.Rotation.align_vectors(a[0], b[0], w[0]), lambda: S.align_vectors(a[0], b[0], w[0])),
        ("RotationSpline(t), 10^6 times, 100 knots", lambda: spline(t), lambda: sspline(t), 1.0,
         lambda: spline(t[0]), lambda: sspline(t[0])),
        ("RotationSpline(t, 1), angular velocity", lambda: spline(t, 1, frame="body"), lambda: sspline(t, 1), 1.0,
         lambda: spline(t[0], 1, frame="body"), lambda: sspline(t[0], 1)),
        ("RotationSpline(t, 2), angular acceleration", lambda: spline(t, 2, frame="body"), lambda: sspline(t, 2), 1.0,
         lambda: spline(t[0], 2, frame="body"), lambda: sspline(t[0], 2)),
        ("r ** 0.3", lambda: r**0.3, lambda: sr**0.3, 1.0, lambda: r1**0.3, lambda: sr1**0.3),
        ("from_davenport (tilted axes)", lambda: kr.Rotation.from_davenport(axes, "e", angles),
         lambda: S.from_davenport(axes, "e", angles), 1.0,
         lambda: kr.Rotation.from_davenport(axes, "e", angles[0]), lambda: S.from_davenport(axes, "e", angles[0])),
        ("as_davenport (tilted axes)", lambda: r.as_davenport(axes, "e"), lambda: sr.as_davenport(axes, "e"), 1.0,
         lambda: r1.as_davenport(axes, "e"), lambda: sr1.as_davenport(axes, "e")),
    ]


def parity(repeats=3):
    """The parity section's lines: batch and single-call times against scipy."""
    load_before = load_average()
    rows = []
    for name, ours, theirs, scale, ours_one, theirs_one in _parity_cases(np.random.default_rng(0)):
        t_ours, t_theirs = interleaved(ours, theirs, repeats=repeats)
        scipy_batch = t_theirs.median * scale
        one = median_time(lambda: [ours_one() for _ in range(200)]) / 200
        one_scipy = median_time(lambda: [theirs_one() for _ in range(200)]) / 200
        rows.append([name, _ms(t_ours.median), _ms(scipy_batch) + (" (loop, scaled)" if scale != 1.0 else ""),
                     f"{scipy_batch / t_ours.median:.1f}×", f"{t_ours.cpu_median / t_ours.median:.1f}",
                     f"{one * 1e6:.1f}", f"{one_scipy * 1e6:.1f}", f"{one_scipy / one:.1f}×"])
        print(" | ".join(rows[-1]), flush=True)
    return [PARITY_HEADING, ""] + table_section(
        None,
        [f"Batches of 10^6 rotations or times (align_vectors: {PROBLEMS} problems; scipy has no batched "
         f"align_vectors, so its time is a loop of {SCIPY_LOOP} calls scaled to {PROBLEMS}); medians of {repeats} "
         "runs in alternation, one process. Single call: median of 200 calls on one rotation, time, or problem."],
        ["operation", "kreisel (ms)", "scipy (ms)", "vs scipy", "kreisel CPU / wall", "single kreisel (µs)",
         "single scipy (µs)", "single vs scipy"],
        rows, "l" + "r" * 7, load_before=load_before,
    )


#: Heading of the section on large fresh outputs in a script-like order of calls (kept above the notes).
FRESH_HEADING = "## Large fresh outputs in a script's order of calls"


def _fresh_output_cases(rng):
    """name, kreisel, scipy, kreisel into a caller-owned out=, doubles per result (72 or 128 MB each)."""
    q = rng.normal(size=(N, 4))
    q /= np.linalg.norm(q, axis=-1, keepdims=True)
    psi = kr.quat_to_rotvec(q)
    euler = kr.quat_to_euler("ZXZ", q)
    poses = kr.RigidTransform.from_rotation_translation(q, rng.normal(size=(N, 3)))
    q_last, spose = np.ascontiguousarray(q[:, [1, 2, 3, 0]]), poses.to_scipy()
    R, M = np.empty((N, 3, 3)), np.empty((N, 4, 4))
    return [
        ("quat -> matrix", lambda: kr.quat_to_matrix(q), lambda: S.from_quat(q_last).as_matrix(),
         lambda: kr.quat_to_matrix(q, out=R), 9),
        ("Euler ZXZ -> matrix", lambda: kr.euler_to_matrix("ZXZ", euler), lambda: S.from_euler("ZXZ", euler).as_matrix(),
         lambda: kr.euler_to_matrix("ZXZ", euler, out=R), 9),
        ("rotvec -> matrix", lambda: kr.rotvec_to_matrix(psi), lambda: S.from_rotvec(psi).as_matrix(),
         lambda: kr.rotvec_to_matrix(psi, out=R), 9),
        ("se3 as 4x4 matrix", lambda: poses.as_matrix(), lambda: spose.as_matrix(), lambda: poses.as_matrix(out=M), 16),
    ]


def _faults():
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt


def fresh_outputs_child():
    """Run in a new process: the order of calls of a script, timed; prints one JSON row per operation.

    Other 10^6-sized arrays are allocated first (the inputs and their
    conversions), then each operation is called once (compilation, cache
    load) and timed in alternation with scipy and an allocating copy of the
    same output size.
    """
    for name, ours, scipy_run, into, n_out in _fresh_output_cases(np.random.default_rng(0)):
        new_copy = allocating_copy(0, n_out * N)
        faults = []

        def counted():
            before = _faults()
            result = ours()
            faults.append(_faults() - before)
            return result

        ours()
        t_ours, t_scipy, t_new, t_into = interleaved(counted, scipy_run, new_copy, into, repeats=REPEATS,
                                                     warmup=(False, True, True, True))
        print(json.dumps({"name": name, "ours": t_ours.times, "scipy": t_scipy.times, "new": t_new.times,
                          "into": t_into.times, "faults": faults}), flush=True)


def fresh_outputs():
    """The section's lines: large fresh outputs, in a new process."""
    load_before = load_average()
    rows = []
    child = subprocess.run([sys.executable, __file__, "--fresh-outputs-child"], capture_output=True, text=True,
                           check=True)
    for line in child.stdout.splitlines():
        r = json.loads(line)
        med = {key: float(np.median(r[key])) for key in ("ours", "scipy", "new", "into")}
        rows.append([
            r["name"], " ".join(_ms(t) for t in r["ours"]), _ms(med["ours"]), _ms(med["scipy"]),
            f"{med['scipy'] / med['ours']:.1f}×", _ms(med["new"]), f"{med['ours'] / med['new']:.2f}",
            _ms(med["into"]), str(int(np.median(r["faults"]))),
        ])
        print(" | ".join(rows[-1]), flush=True)
    return [FRESH_HEADING, ""] + table_section(
        None,
        [f"A new process allocates other 10^6-sized arrays first, then times each operation in alternation with "
         f"scipy and a copy into a newly allocated output of the same size ({REPEATS} runs after one untimed call; "
         "every run returns a new 72 MB or 128 MB array on freshly mapped pages, as numpy allocates it). Page "
         "faults: minor faults of one kreisel call (median)."],
        ["operation", "kreisel runs (ms)", "kreisel (ms)", "scipy (ms)", "vs scipy", "copy to new output (ms)",
         "kreisel / copy to new", "kreisel into out= (ms)", "page faults"],
        rows, "l" + "r" * 8, load_before=load_before,
    )


def write_section(heading, lines):
    """Put a section into results/so3.md (replacing an earlier one of that heading), above the kept notes."""
    path = RESULTS / "so3.md"
    old = path.read_text(encoding="utf-8")
    notes = old.find(NOTES_MARKER)
    body, tail = (old[:notes], old[notes:]) if notes >= 0 else (old, "")
    if heading in body:
        start = body.index(heading)
        following = body.find("\n## ", start + len(heading))
        body = body[:start] + (body[following + 1:] if following >= 0 else "")
    atomic_write(path, body.rstrip("\n") + "\n\n" + "\n".join(lines) + "\n\n" + tail)


if __name__ == "__main__":
    if sys.argv[1:2] == ["--fresh-outputs-child"]:
        fresh_outputs_child()
    elif sys.argv[1:] == ["--parity"]:
        write_section(PARITY_HEADING, parity())
    elif sys.argv[1:] == ["--fresh-outputs"]:
        write_section(FRESH_HEADING, fresh_outputs())
    else:
        main()
        write_section(FRESH_HEADING, fresh_outputs())
        write_section(PARITY_HEADING, parity())
