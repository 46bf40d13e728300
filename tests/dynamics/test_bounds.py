"""Runs are bounded and interruptible: step budgets, memory, callable outputs, Ctrl-C, progress."""

import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import kreisel as kr
from kreisel._compiled import chunks
from kreisel.dynamics import ConstantTorque, LinearDamping, engine

FIXED = ["splitting", "splitting4", "dmv", "rkmk4", "midpoint", "rk4"]


@pytest.mark.parametrize("dt", [1e-300, 5e-19, 1e-12])
@pytest.mark.parametrize("method", ["rk4", "splitting"])
def test_step_count_over_budget_is_refused_with_its_cost(method, dt):
    # dt = 1e-300 and 5e-19 overflowed the step count into one 10 s step before
    with pytest.raises(ValueError, match=r"needs .* steps.*(years|days|hours).*max_steps") as info:
        kr.simulate([1, 2, 3], [0, 10], [0.1, 1, 0.1], method=method, dt=dt)
    assert f"{method!r}" in str(info.value)


def test_step_count_that_cannot_be_counted_is_refused_even_with_a_huge_budget():
    with pytest.raises(ValueError, match="more than can be counted"):
        kr.simulate([1, 2, 3], [0, 10], [0.1, 1, 0.1], method="rk4", dt=1e-300, max_steps=10**400)


def test_batch_budget_and_6dof_budget():
    with pytest.raises(ValueError, match="per body"):
        kr.simulate_batch([[1, 2, 3], [2, 2, 3]], [0, 1e6], [0.1, 1, 0.1], method="rk4", dt=1e-6)
    with pytest.raises(ValueError, match="max_steps"):
        kr.simulate_6dof([1, 2, 3], [0, 10], [0.1, 1, 0.1], method="rk4", dt=1e-20)


def test_max_steps_is_validated():
    for bad, exc in [(0, ValueError), (-5, ValueError), (1.5, TypeError), (True, TypeError)]:
        with pytest.raises(exc, match="max_steps"):
            kr.simulate([1, 2, 3], [0, 1], [0.1, 1, 0.1], max_steps=bad)


def test_fixed_step_run_just_inside_the_budget_runs():
    tr = kr.simulate([1, 2, 3], [0, 1], [0.1, 1, 0.1], method="rk4", dt=0.01, max_steps=100)
    ref = kr.simulate([1, 2, 3], [0, 1], [0.1, 1, 0.1])
    np.testing.assert_allclose(tr.omega[-1], ref.omega[-1], atol=1e-8)
    with pytest.raises(ValueError, match="max_steps = 99"):
        kr.simulate([1, 2, 3], [0, 1], [0.1, 1, 0.1], method="rk4", dt=0.01, max_steps=99)


# a torque: a free body's run over 1e9 s is refused before it starts (test_a_free_adaptive_run_out_of_reach...)
_NUDGE = ConstantTorque([0.0, 0.0, 1e-3])


@pytest.mark.parametrize("run", [
    lambda steps: kr.simulate([1, 2, 3], [0, 1e9], [0.1, 1, 0.1], torque=_NUDGE, max_steps=steps),
    lambda steps: kr.simulate([1, 2, 3], [0, 1e9], [0.1, 1, 0.1], torque=_NUDGE, method="scipy", max_steps=steps),
    lambda steps: kr.simulate_batch([[1, 2, 3]] * 3, [0, 1e9], [0.1, 1, 0.1], torque=_NUDGE, max_steps=steps),
    lambda steps: kr.frames.simulate_particle([0, 1e9], [1, 0, 0], [0, -1, 0], [0, 0, 1], max_steps=steps),
    lambda steps: kr.earth.foucault_pendulum(1.0, 45.0, 1e9, 0.1, max_steps=steps),
], ids=["simulate", "scipy", "simulate_batch", "simulate_particle", "foucault_pendulum"])
def test_adaptive_run_stops_at_its_step_budget(run):
    with pytest.raises(RuntimeError, match=r"max_steps = 50 steps at t = .* of 1e\+09"):
        run(50)
    with pytest.raises(TypeError, match="max_steps"):
        run(1.5)


@pytest.mark.parametrize("run", [
    lambda: kr.simulate([1, 2, 3], [0, 1e300], [0.1, 1, 0.1]),
    lambda: kr.simulate([1, 2, 3], [0, 1e300], [0.1, 1, 0.1], method="scipy"),
    lambda: kr.simulate_batch([[1, 2, 3]], [0, 1e300], [[0, 0, 0], [0.1, 1, 0.1]]),
    lambda: kr.simulate_6dof([1, 2, 3], [0, 1e300], [0.1, 1, 0.1], force=kr.dynamics.ConstantForce([0, 0, -9.8])),
], ids=["simulate", "scipy", "simulate_batch", "simulate_6dof"])
def test_a_free_adaptive_run_out_of_reach_is_refused_before_it_starts(monkeypatch, run):
    # it ran for hours until the step budget stopped it
    def no_run(*args, **kwargs):
        raise AssertionError("the integration started")

    monkeypatch.setattr(engine, "_run", no_run)
    monkeypatch.setattr(engine, "_scipy", no_run)
    with pytest.raises(ValueError, match=r"^t = 0 … 1e\+300 is out of reach of the adaptive method .*\|ω\| >= 1\.0\d "
                                         r"rad/s.*needs at least 5\.\d+e\+299 steps, about .* years of computing; "
                                         r"over the budget max_steps = \d(\.\d+)?e\+0[78] \(by default about 10 minutes of computing"):
        run()


def test_the_refusal_of_a_run_out_of_reach_names_what_sets_its_rate():
    # a fast omega0 within a short t: the fuzz test scales omega0 by 1e5 and wants it named
    with pytest.raises(ValueError, match=r"t = 0 … 1 is out of reach.*from omega0 and the moments"):
        kr.simulate_batch([[1, 2, 3]] * 2, [0, 1], [[0.1, 1, 0.1], [1e4, 1e5, 1e4]], max_steps=20_000)


def _steps_taken(run):
    """The steps a run takes: the smallest ``max_steps`` it finishes within (found by bisection)."""
    lo, hi = 1, 1 << 20
    while lo < hi:
        mid = (lo + hi) // 2
        try:
            run(mid)
            hi = mid
        except chunks.StepBudgetExceeded:
            lo = mid + 1
    return lo


@pytest.mark.parametrize("moments, omega0, options", [
    ([1, 2, 3], [0, 0, 1.0], {}),  # uniform spin: the longest steps
    ([1, 2, 3], [0, 0, 1.0], dict(rtol=0.999)),
    ([1, 2, 3], [0, 0, 1.0], dict(atol=1.0)),
    ([1, 2, 3], [0.6, 0.1, 0.6], {}),  # tumbling
    ([1, 1, 1e-3], [0, 0, 1.0], dict(rtol=1e-6)),  # about the smallest axis: 2T/|J| = |ω|
])
def test_the_reach_check_never_refuses_a_free_run_that_can_finish(moments, omega0, options):
    # the run is tried with max_steps = the steps it takes: the up-front bound, a lower bound on them, lets it
    # through (bisection runs every budget without ValueError); for uniform spin it is within 10x of them
    span = 2000.0
    steps = _steps_taken(lambda budget: kr.simulate(moments, [0.0, span], omega0, max_steps=budget, **options))
    if not np.count_nonzero(omega0) - 1:
        with pytest.raises(ValueError, match="out of reach"):
            kr.simulate(moments, [0.0, span], omega0, max_steps=steps // 10, **options)


def test_long_runs_of_slow_or_resting_bodies_are_not_refused():
    slow = kr.simulate([1, 2, 3], [0.0, 1e6], [1e-3, 1e-2, 1e-3])  # 1e4 rad in 1e6 s
    assert slow.t[-1] == 1e6 and abs(slow.energy[-1] / slow.energy[0] - 1.0) < 1e-9
    rest = kr.simulate([1, 2, 3], [0.0, 1e300], [0.0, 0.0, 0.0])
    np.testing.assert_array_equal(rest.q[-1], [1.0, 0.0, 0.0, 0.0])
    kr.simulate([1, 2, 3], [0.0, 1e300], [1e-300, 0.0, 0.0], max_steps=10**4)


def test_output_too_large_for_memory_is_refused_with_its_size():
    bodies = np.broadcast_to([1.0, 2.0, 3.0], (10**6, 3))
    t = np.linspace(0.0, 1.0, 10**6)
    with pytest.raises(ValueError, match=r"10\^?.*samples.*would need 5.6 ?\d* ?TB|would need 56 TB"):
        kr.simulate_batch(bodies, t, [0.1, 1, 0.1])


def test_tiny_atol_is_refused_with_the_reason_not_a_zero_division():
    with pytest.raises(ValueError, match="atol = 1e-300 is below 1e-150"):
        kr.simulate([1, 2, 3], [0, 10], [0.1, 1, 0.1], atol=1e-300)
    # still fine where the error norm does not overflow
    tr = kr.simulate([1, 2, 3], [0, 1], [0.1, 1, 0.1], atol=1e-100)
    assert np.isfinite(tr.omega).all()


def late(bad, t_switch=1.0):
    """A torque that is fine until ``t_switch``, then returns ``bad``."""

    def torque(t, q, w):
        return bad if t > t_switch else np.zeros(3)

    return torque


@pytest.mark.parametrize("method,dt", [("rk4", 0.01), ("dop853", None), ("splitting", 0.01)])
@pytest.mark.parametrize("bad,match", [(np.zeros(2), r"\(2,\)"), (1.0, r"\(\)"), (np.zeros((3, 1)), r"\(3, 1\)"),
                                       (np.zeros(5), r"\(5,\)")])
def test_torque_callable_shape_is_checked_at_every_call(method, dt, bad, match):
    with pytest.raises(ValueError, match=r"torque callable must return shape \(3,\), got " + match):
        kr.simulate([1, 2, 3], [0, 10], [0.1, 1, 0.1], torque=late(bad), method=method, dt=dt)


def test_torque_callable_non_real_and_non_finite_outputs_stop_the_run_at_once():
    with pytest.raises(TypeError, match="real array.*complex128"):
        kr.simulate([1, 2, 3], [0, 10], [0.1, 1, 0.1], torque=late(np.ones(3) * 1j), method="rk4", dt=0.01)
    with pytest.raises(TypeError, match="real array.*datetime64"):
        kr.simulate([1, 2, 3], [0, 10], [0.1, 1, 0.1], torque=late(np.zeros(3, "datetime64[s]")))
    # a NaN late in a long run is reported where it happens, not as a step-size collapse later
    with pytest.raises(ValueError, match=r"torque callable returned a non-finite value \[ 0\.  0\. nan\] at t = 5\.\d+"):
        kr.simulate([1, 2, 3], [0, 1e6], [0.1, 1, 0.1], torque=late(np.array([0, 0, np.nan]), 5.0))


def test_force_callable_output_is_checked_at_every_call():
    def force(t, q, w, r, v):
        return np.zeros(3) if t < 0.5 else np.zeros(4)

    with pytest.raises(ValueError, match=r"force callable must return shape \(3,\), got \(4,\)"):
        kr.simulate_6dof([1, 2, 3], [0, 1], [0.1, 1, 0.1], force=force)


@pytest.mark.parametrize("method", ["dop853"] + FIXED)
def test_results_do_not_depend_on_where_the_run_pauses(monkeypatch, method):
    dt = None if method == "dop853" else 0.01
    t = np.linspace(0.0, 30.0, 7)
    torque = ConstantTorque([0.1, 0.0, 0.2]) + LinearDamping(0.01)
    runs = []
    for chunk_seconds, first in ((chunks.CHUNK_SECONDS, engine._FIRST_CHUNK_STEPS), (0.0, 1)):
        # (0, 1): every call takes one step, then pauses
        monkeypatch.setattr(chunks, "CHUNK_SECONDS", chunk_seconds)
        monkeypatch.setattr(engine, "_FIRST_CHUNK_STEPS", first)
        free = kr.simulate([1, 2, 3], t, [0.1, 1, 0.1], method=method, dt=dt)
        forced = kr.simulate([1, 2, 3], t, [0.1, 1, 0.1], method=method, dt=dt, torque=torque)
        six = kr.simulate_6dof([1, 2, 3], t, [0.1, 1, 0.1], velocity0=[1, 0, 0], method=method, dt=dt,
                               torque=lambda tt, q, w: [0.1 * np.sin(tt), 0.0, 0.0])
        batch = kr.simulate_batch([[1, 2, 3], [2, 2, 3]], t, [0.1, 1, 0.1], method=method, dt=dt)
        sparse = kr.simulate_batch([[1, 2, 3], [2, 2, 3]], t, [0.1, 1, 0.1], method=method, dt=dt, every=3)
        runs.append([free.omega, free.q, forced.omega, forced.q, six.position, six.q, batch.omega, batch.q,
                     sparse.omega, sparse.q])
    for a, b in zip(*runs):
        np.testing.assert_array_equal(a, b)


def test_progress_reports_increasing_times_up_to_the_end(monkeypatch):
    monkeypatch.setattr(chunks, "CHUNK_SECONDS", 0.0)
    monkeypatch.setattr(engine, "_FIRST_CHUNK_STEPS", 1)
    for method, dt, end in [("rk4", 1e-2, 10.0), ("dop853", None, 100.0)]:
        seen = []
        kr.simulate([1, 2, 3], [0, end / 2, end], [0.1, 1, 0.1], method=method, dt=dt, progress=seen.append)
        assert len(seen) > 10
        assert np.all(np.diff(seen) >= 0) and 0 <= seen[0] and seen[-1] < end
        assert any(end / 2 < s < end for s in seen)
    with pytest.raises(TypeError, match="progress must be callable"):
        kr.simulate([1, 2, 3], [0, 1], [0.1, 1, 0.1], progress=3)


def test_angular_velocity_whose_squares_overflow_is_refused_as_out_of_range():
    for w in ([1e200, 0, 0], [1e151, 1e151, 0]):
        with pytest.raises(ValueError, match="out of range"):
            kr.simulate([1, 2, 3], [0, 1], w)
        with pytest.raises(ValueError, match="out of range"):
            kr.simulate_batch([[1, 2, 3], [1, 2, 3]], [0, 1], [[0.1, 1, 0.1], w])
    # Euler's equations are homogeneous: ω0 scaled by s runs s times faster (in range, fast bodies are fine)
    fast = kr.simulate([1, 2, 3], [0, 1e-140], [1e140, 1e140, 1e140])
    slow = kr.simulate([1, 2, 3], [0, 1], [1.0, 1.0, 1.0])
    np.testing.assert_allclose(fast.omega[-1], 1e140 * slow.omega[-1], rtol=1e-9)
    np.testing.assert_allclose(fast.q[-1], slow.q[-1], atol=1e-9)


CHILD = textwrap.dedent("""
    import sys, time, numpy as np, kreisel as kr
    from kreisel.dynamics import ConstantTorque
    simulate = [
        dict(omega0=[0.1, 1, 0.1], method="rk4", dt=1e-3, max_steps=10**13),
        # budgets that let the free runs over 1e9 s start (they need at least 5e8 and 8e13 steps)
        dict(omega0=[0.1, 1, 0.1], max_steps=10**15),
        dict(omega0=[1e5, 1e5, 1e5], max_steps=10**15),
        dict(omega0=[0.1, 1, 0.1], torque=ConstantTorque([1e12, 0, 1e12])),
        dict(omega0=[0.1, 1, 0.1], torque=lambda t, q, w: np.sin(t) * np.ones(3)),
        dict(omega0=[0.1, 1, 0.1], method="scipy", max_steps=10**15),
        dict(omega0=[0.1, 1, 0.1], method="scipy", torque=lambda t, q, w: np.sin(t) * np.ones(3)),
    ]
    def simulate_case(case):
        def run(t):
            return kr.simulate([1, 2, 3], t, **case)
        run.warm_up = 1e-6 if "torque" in case and isinstance(case["torque"], ConstantTorque) else 1e-1
        return run
    runs = {
        "simulate": [simulate_case(case) for case in simulate],
        "simulate_batch": [lambda t: kr.simulate_batch([[1, 2, 3]] * 4, t, [0.1, 1, 0.1], max_steps=10**15)],
        "simulate_particle": [lambda t: kr.frames.simulate_particle(t, [1, 0, 0], [0, -1, 0], [0, 0, 1])],
        "simulate_particle_callable_force": [
            lambda t: kr.frames.simulate_particle(t, [1, 0, 0], [0, -1, 0], [0, 0, 1], force=lambda tt, r, v: -r),
        ],
        # at least 2 s: a run shorter than half a swing (1 s) measures no swing plane and is refused
        "foucault_pendulum": [lambda t: kr.earth.foucault_pendulum(1.0, 45.0, max(1e-2 * t[-1], 2.0), 0.1)],
    }[sys.argv[1]]
    for run in runs:
        # compile (or load) first, over a span that compiles every kernel the long run uses; the 1e12
        # torque turns the body 5e9 rad in 0.1 s, so it warms up over 1e-6 s
        run(np.array([0, getattr(run, 'warm_up', 1e-1)]))
        print("ready", flush=True)
        try:
            run(np.array([0, 1e9]))
        except KeyboardInterrupt:
            print(time.perf_counter(), flush=True)
""")


@pytest.mark.parametrize("runs, count", [
    ("simulate", 7), ("simulate_batch", 1), ("simulate_particle", 1), ("foucault_pendulum", 1),
    ("simulate_particle_callable_force", 1),
])
def test_ctrl_c_stops_a_long_run_promptly(runs, count):
    # a chunk of work lasts ~50 ms: generous for a loaded machine, each run would take hours
    child = subprocess.Popen([sys.executable, "-c", CHILD, runs], stdout=subprocess.PIPE, text=True)
    # a child that never answers is killed, so readline() returns "" and the test fails instead of hanging
    watchdog = threading.Timer(240.0, child.kill)
    watchdog.start()
    try:
        for _ in range(count):
            assert child.stdout.readline().strip() == "ready"
            time.sleep(0.2)
            sent = time.perf_counter()
            child.send_signal(signal.SIGINT)
            assert float(child.stdout.readline()) - sent < 2.0
        assert child.wait(timeout=30) == 0
    finally:
        watchdog.cancel()
        if child.poll() is None:
            child.kill()
            child.wait()


def test_a_run_estimated_far_beyond_ten_minutes_is_refused_unless_forced(monkeypatch):
    # issue 34: kr.simulate(body, [0, 1e9], ω) ran over 8 minutes (only 1e11 s was refused)
    def no_run(*args, **kwargs):
        raise AssertionError("the integration started")

    monkeypatch.setattr(engine, "_run", no_run)
    with pytest.raises(ValueError, match=r"^t = 0 … 1e\+09 is out of reach .* at least 5\.0\de\+08 steps, about 12\.\d "
                                         r"minutes of computing; over the budget max_steps = 4e\+08 \(by default about "
                                         r"10 minutes .* pass a larger max_steps to run it anyway$"):
        kr.simulate([1, 2, 3], [0, 1e9], [0.1, 1, 0.1])
    # an explicit budget is the documented way to run it anyway: the run starts
    with pytest.raises(AssertionError, match="the integration started"):
        kr.simulate([1, 2, 3], [0, 1e9], [0.1, 1, 0.1], max_steps=10**9)


def test_a_heavy_top_out_of_reach_is_refused_before_it_starts(monkeypatch):
    # issue 33: LagrangeTop(1, .5, 1).simulate([0, 1e17], ...) ran 3.5 h before the step budget stopped it;
    # gravity keeps the spin ω3 about the symmetry axis, a lower bound on |ω| like a free body's 2T/|J|
    monkeypatch.setattr(engine, "_run", lambda *args, **kwargs: (_ for _ in ()).throw(AssertionError("ran")))
    with pytest.raises(ValueError, match=r"t = 0 … 1e\+17 is out of reach .* \|ω\| >= 10\.2 rad/s \(the spin about the "
                                         r"symmetry axis, conserved under gravity\)"):
        kr.LagrangeTop(1.0, 0.5, 1.0).simulate([0, 1e17], [0.0, 1.0, 0.0], [0.3, 0.2, 10.0])


def test_an_output_that_does_not_fit_names_its_size_and_the_remedy(monkeypatch):
    from kreisel import _validation

    monkeypatch.setattr(_validation, "memory_budget", lambda: 1e6)
    with pytest.raises(ValueError, match=r"the output \(1 × 100001 samples × 7 states\) would need 5\.6 MB, more than "
                                         r"the 1 MB allowed .*: ask for fewer times in t, or keep every N-th sample"):
        kr.simulate([1, 2, 3], np.linspace(0.0, 1.0, 100001), [0.1, 1, 0.1])


def test_kernels_are_compiled_before_the_loop_that_holds_back_ctrl_c(monkeypatch):
    # issue 33: with an empty cache SIGINT during a first simulate(..., torque=python_function) took effect
    # 17–25 s later: numba compiled inside the loop that defers Ctrl-C. Nothing is compiled in there now.
    from kreisel.dynamics import _integrators

    kernels = [_integrators.run_dop853, _integrators.run_dop853_batch]
    kernels += [runner for method in engine.METHODS.values() if method not in (None, _integrators.DOP853)
                for free in (False, True) for runner in _integrators.runners(method, free)]
    loop = engine.run_chunked

    def checked(*args, **kwargs):
        before = [len(k.signatures) for k in kernels]
        loop(*args, **kwargs)
        assert [len(k.signatures) for k in kernels] == before, "a kernel was compiled inside the chunked loop"

    monkeypatch.setattr(engine, "run_chunked", checked)
    kr.simulate([1, 2, 3], [0, 1], [0.1, 1, 0.1], torque=lambda t, q, w: np.zeros(3))
    kr.simulate([1, 2, 3], [0, 1], [0.1, 1, 0.1], method="rk4", dt=0.01)
    kr.simulate_batch([[1, 2, 3]] * 2, [0, 1], [0.1, 1, 0.1])
    kr.simulate_batch([[1, 2, 3]] * 2, [0, 1], [0.1, 1, 0.1], method="splitting", dt=0.01)
    kr.LagrangeTop(1.0, 0.5, 1.0).simulate([0, 1], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0])
