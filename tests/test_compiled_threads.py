"""The thread count of kreisel's multi-core loops (kreisel._compiled.threads): in effect, not in the results."""

import importlib
import os
import pkgutil

import numba
import numpy as np
import pytest
from numba.core.caching import NullCache
from numba.core.registry import CPUDispatcher

import kreisel
import kreisel as kr
from kreisel._compiled import parallel, threads


@numba.njit(parallel=True)
def _threads_seen():
    # the count numba hands the loop (numba.get_num_threads inside compiled code)
    seen = np.zeros(1, dtype=np.int64)
    for i in numba.prange(1):
        seen[i] = numba.get_num_threads()
    return seen[0]


probe = threads.ParallelLoop(_threads_seen)


def _kreisel_modules():
    for info in pkgutil.walk_packages(kreisel.__path__, "kreisel."):
        if not any(part in info.name for part in (".web", ".tour", ".cli", ".__main__", ".plot")):
            yield importlib.import_module(info.name)


def test_every_multi_core_loop_of_kreisel_chooses_its_thread_count():
    loops, bare = [], []
    for module in _kreisel_modules():
        for name, obj in vars(module).items():
            if isinstance(obj, threads.ParallelLoop) and obj.py_func.__module__ == module.__name__:
                loops.append(name)
            elif isinstance(obj, CPUDispatcher) and obj.targetoptions.get("parallel") and \
                    obj.py_func.__module__ == module.__name__:
                bare.append(f"{module.__name__}.{name}")
    assert bare == [] and len(loops) >= 30
    assert isinstance(kr.so3.quaternion._inverse_parallel, threads.ParallelLoop)


def test_the_flavour_compiles_a_cached_parallel_loop():
    def total(a):
        return a.sum()

    loop = parallel(total)
    assert isinstance(loop, threads.ParallelLoop) and loop.py_func is total
    assert loop.dispatcher.targetoptions["parallel"] and not isinstance(loop.dispatcher._cache, NullCache)


@pytest.mark.parametrize(("configured", "runnable", "expected"), [
    (2, None, 2), (2, 1, 2), (2, 2, 2), (2, 3, 1), (2, 9, 1), (1, 5, 1), (8, 9, 7), (8, 1, 8),
])
def test_one_thread_fewer_per_runnable_task_beyond_the_cores(monkeypatch, configured, runnable, expected):
    monkeypatch.setattr(threads, "_CORES", 2 if configured <= 2 else 8)
    assert threads.threads_for(configured, runnable) == expected


def test_the_runnable_tasks_count_the_caller():
    runnable = threads.runnable_tasks()
    assert runnable is None or runnable >= 1


@pytest.mark.skipif(numba.config.NUMBA_NUM_THREADS < 2, reason="needs two numba threads")
@pytest.mark.parametrize(("runnable", "adaptive", "expected"), [(1, True, 2), (3, True, 1), (3, False, 2)])
def test_a_loop_runs_on_the_chosen_count_and_numbas_count_is_restored(monkeypatch, runnable, adaptive, expected):
    monkeypatch.setattr(threads, "_CORES", 2)
    monkeypatch.setattr(threads, "runnable_tasks", lambda: runnable)
    monkeypatch.setattr(threads, "ADAPTIVE", adaptive)
    configured = numba.get_num_threads()
    numba.set_num_threads(2)
    try:
        assert probe() == expected
        assert numba.get_num_threads() == 2
        numba.set_num_threads(1)  # a user's lower count is kept
        assert probe() == 1
    finally:
        numba.set_num_threads(configured)


@pytest.mark.skipif(numba.config.NUMBA_NUM_THREADS < 2, reason="needs two numba threads")
def test_results_do_not_depend_on_the_thread_count():
    rng = np.random.default_rng(5)
    n = 3 * 2**14 + 7  # above the multi-core threshold, pieces of unequal size
    q, p, v = rng.normal(size=(n, 4)), rng.normal(size=(n, 4)), rng.normal(size=(n, 3))
    q[7] *= 1e-200  # a piece the exact loop redoes
    omega0 = [0.1, 1.0, 0.1] + 0.05 * rng.normal(size=(64, 3))

    def results():
        return [kr.quat_inverse(q), kr.quat_normalize(q), kr.quat_multiply(p, q), kr.quat_apply(q, v),
                kr.quat_to_matrix(q), kr.quat_to_rotvec(q), kr.matrix_to_quat(kr.quat_to_matrix(p)),
                kr.simulate_batch([[1.0, 2.0, 2.5]] * 64, [0.0, 1.0], omega0, method="rk4", dt=0.01).q]

    configured = numba.get_num_threads()
    try:
        numba.set_num_threads(2)
        both = results()
        numba.set_num_threads(1)
        one = results()
    finally:
        numba.set_num_threads(configured)
    for a, b in zip(both, one):
        np.testing.assert_array_equal(a, b)


def test_the_chunks_of_a_long_run_share_their_cpu_time_over_the_threads_the_loop_ran_on(monkeypatch):
    monkeypatch.setattr(threads, "_CORES", 2)
    monkeypatch.setattr(threads, "runnable_tasks", lambda: 3)
    probe()
    assert threads.last_threads() == max(1, numba.get_num_threads() - 1)
    monkeypatch.setattr(threads, "runnable_tasks", lambda: 1)
    probe()
    assert threads.last_threads() == numba.get_num_threads()


@pytest.mark.skipif(numba.config.NUMBA_NUM_THREADS < 2, reason="needs two numba threads")
def test_the_chunks_of_a_batch_simulation_keep_numbas_count_on_a_busy_machine(monkeypatch):
    monkeypatch.setattr(threads, "_CORES", 2)
    monkeypatch.setattr(threads, "runnable_tasks", lambda: 6)
    configured = numba.get_num_threads()
    numba.set_num_threads(2)
    try:
        assert probe() == 1
        with threads.numbas_count():
            with threads.numbas_count():
                assert probe() == 2
            assert probe() == 2
        assert probe() == 1
        kr.simulate_batch([[1.0, 2.0, 2.5]] * 64, [0.0, 1.0], [[0.1, 1.0, 0.1]] * 64, method="rk4", dt=0.01)
        assert threads.last_threads() == 2
    finally:
        numba.set_num_threads(configured)


def test_an_unreadable_count_leaves_numbas_count(monkeypatch, tmp_path):
    other = tmp_path / "loadavg"
    other.write_text("no counts here\n")
    fd = os.open(other, os.O_RDONLY)
    try:
        monkeypatch.setattr(threads, "_loadavg", [fd])
        monkeypatch.setattr(threads, "_last", [-1.0, None])
        assert threads.runnable_tasks() is None and threads._loadavg == [None]
    finally:
        os.close(fd)
