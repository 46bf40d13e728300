"""kreisel.sweep on a real LocalCluster: worker death, retries, failures, resumption."""

import os
import pathlib
import signal
import sys
import time

import cloudpickle
import numpy as np
import pytest

from kreisel.sweep import SweepError, sweep

distributed = pytest.importorskip("distributed")

# the test module is not importable on the workers (importlib import mode): ship its functions by value
cloudpickle.register_pickle_by_value(sys.modules[__name__])

GRID = {"x": np.arange(6.0), "y": np.array([0.5, 1.5])}


def polynomial(x, y, delay=0.0):
    time.sleep(delay)
    return {"p": x**2 + 3.0 * y, "pair": np.stack([x * y, x - y], axis=-1)}


class Flaky:
    """Fails on points with x == fail_x (always, or only the first time) until a file "fixed" appears in the
    log directory, and logs every call to it."""

    def __init__(self, log, fail_x=None, first_time_only=False):
        self.log, self.fail_x, self.first_time_only = pathlib.Path(log), fail_x, first_time_only

    def __call__(self, x, y):
        (self.log / f"call-{x[0]:g}-{y[0]:g}-{time.monotonic_ns()}").touch()
        # "fixed" in the log directory repairs the failure without changing the function or its state
        if self.fail_x is not None and np.any(x == self.fail_x) and not (self.log / "fixed").exists():
            marker = self.log / "failed-once"
            if not (self.first_time_only and marker.exists()):
                marker.touch()
                raise ArithmeticError(f"planned failure at x = {self.fail_x}")
        return polynomial(x, y)


@pytest.fixture(scope="module")
def cluster():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as c:
        with distributed.Client(c) as client:
            yield c, client


@pytest.fixture(scope="module")
def reference():
    return sweep(polynomial, GRID, chunk_size=2, scheduler="serial")


def calls(log):
    return sorted(p.name for p in pathlib.Path(log).glob("call-*"))


def test_default_local_cluster_matches_serial(reference):
    events = []
    ds = sweep(polynomial, GRID, chunk_size=5, n_workers=2, progress=events.append)
    chunked = sweep(polynomial, GRID, chunk_size=5, scheduler="serial")
    assert ds.identical(chunked)
    assert ds.drop_attrs().identical(reference.drop_attrs())   # the chunking changes nothing but the metadata
    assert [e.done for e in events] == [1, 2, 3] and {e.event for e in events} == {"done"}


def test_worker_killed_mid_sweep(cluster, reference):
    _, client = cluster
    pids_before = set(client.run(os.getpid).values())
    killed = []

    def kill_one_worker(event):
        if not killed:  # the other worker is still busy: its task dies with it and must be rerun
            victim = min(pids_before)
            os.kill(victim, signal.SIGKILL)
            killed.append(victim)

    ds = sweep(polynomial, GRID, constants={"delay": 0.3}, chunk_size=2, scheduler=client,
               progress=kill_one_worker)
    assert killed
    np.testing.assert_array_equal(ds.p.values, reference.p.values)
    np.testing.assert_array_equal(ds.pair.values, reference.pair.values)
    client.wait_for_workers(2, timeout=60)   # the nanny replaced the dead worker
    assert killed[0] not in set(client.run(os.getpid).values())


def test_failed_chunk_is_retried_and_reported(cluster, reference, tmp_path):
    _, client = cluster
    events = []
    ds = sweep(Flaky(tmp_path, fail_x=3.0, first_time_only=True), GRID, chunk_size=2,
               scheduler=client.scheduler.address, retries=1, progress=events.append)
    np.testing.assert_array_equal(ds.p.values, reference.p.values)
    retries = [e for e in events if e.event == "retry"]
    assert len(retries) == 1 and retries[0].chunk == 3
    assert "ArithmeticError: planned failure at x = 3" in retries[0].message and "x 3..3" in retries[0].message


def test_chunk_failing_for_good_then_resumed(cluster, reference, tmp_path):
    _, client = cluster
    log, checkpoint = tmp_path / "log", tmp_path / "chunks"
    log.mkdir()
    events = []
    with pytest.raises(SweepError, match=r"1 of 6 chunks failed after 1 retries .*chunk 4.*ArithmeticError") as info:
        sweep(Flaky(log, fail_x=4.0), GRID, chunk_size=2, scheduler=client, retries=1,
              checkpoint=checkpoint, progress=events.append)
    assert list(info.value.failures) == [4]
    assert [e.event for e in events if e.chunk == 4] == ["retry", "failed"]
    assert len(list(checkpoint.glob("chunk-*.npz"))) == 5

    # the interrupted sweep starts again: only the missing chunk is computed
    (log / "fixed").touch()
    for p in log.glob("call-*"):
        p.unlink()
    events.clear()
    ds = sweep(Flaky(log, fail_x=4.0), GRID, chunk_size=2, scheduler=client, checkpoint=checkpoint, progress=events.append)
    assert [c.split("-")[1] for c in calls(log)] == ["4"]
    assert sorted(e.chunk for e in events if e.event == "resumed") == [0, 1, 2, 3, 5]
    np.testing.assert_array_equal(ds.p.values, reference.p.values)
    assert not checkpoint.exists()   # removed after success
