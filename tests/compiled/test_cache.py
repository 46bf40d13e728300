"""kreisel's on-disk cache: one directory per source state, shared safely by processes, no side effects."""

import json
import os
import pathlib
import subprocess
import sys

import pytest

import kreisel
from kreisel._compiled.cache import cache_root, checkout_cache_root, source_state

_SOURCE = str(pathlib.Path(kreisel.__file__).parents[1])


def _environment(**extra):
    return {**os.environ, "PYTHONPATH": os.pathsep.join([_SOURCE, os.environ.get("PYTHONPATH", "")]), **extra}


def test_a_source_checkout_compiles_into_a_cache_of_its_source_state():
    root = checkout_cache_root()
    assert root is not None and (root.parent / "pyproject.toml").is_file()
    user = os.environ.get("NUMBA_CACHE_DIR")
    expected = pathlib.Path(user) / "kreisel" if user else root   # a user's choice wins
    assert cache_root() == expected / source_state()


#: Records what kreisel must leave as it was, runs batch operations (multi-core) and simulations, compares.
_UNTOUCHED = """
import json, signal, sys
import numba
import numpy as np
from numba.core.compiler_lock import global_compiler_lock

def state():
    config = {k: repr(v) for k, v in vars(numba.config).items() if k.isupper()}
    return {"config": config, "lock": repr(type(global_compiler_lock._lock)), "lock id": id(global_compiler_lock._lock),
            "threads": numba.get_num_threads(), "threading layer set": numba.config.THREADING_LAYER,
            "signals": {s: repr(signal.getsignal(s)) for s in (signal.SIGINT, signal.SIGTERM)},
            "switch interval": sys.getswitchinterval()}

before = state()
import kreisel as kr
rng = np.random.default_rng(0)
q, v = rng.normal(size=(40_000, 4)), rng.normal(size=(40_000, 3))
results = [kr.quat_inverse(q), kr.quat_apply(q, v), kr.quat_multiply(q, q), kr.quat_normalize(q[:3]),
           kr.quat_norm(q)]
body = kr.RigidBody([1.0, 2.0, 3.0])
t = np.linspace(0.0, 1.0, 11)
results += [kr.simulate(body, t, [0.1, 1.0, 0.1]).q, kr.simulate(body, t, [0.1, 1.0, 0.1], method="splitting", dt=1e-2).q]
results += [kr.simulate_batch(np.ones((3, 3)) + np.arange(3.0), t, [0.1, 1.0, 0.1], method="rk4", dt=1e-2).q]
owned = [bool(r.flags.owndata or (type(r.base) is np.ndarray and r.base.flags.owndata)) for r in results]
print(json.dumps({"before": before, "after": state(), "owned": owned}))
"""


def test_kreisel_leaves_numba_and_the_process_as_they_were():
    found = json.loads(subprocess.run([sys.executable, "-c", _UNTOUCHED], env=_environment(), capture_output=True,
                                      text=True, check=True).stdout)
    assert found["after"] == found["before"]
    assert all(found["owned"]), found["owned"]


#: Compiles into an empty cache together with the other processes of its round (released at once by a
#: directory of ready marks), then prints what it computed.
_CALLER = """
import json, pathlib, sys, time
import numpy as np
import cubes
index, count, ready = int(sys.argv[1]), int(sys.argv[2]), pathlib.Path(sys.argv[3])
(ready / str(index)).touch()
deadline = time.monotonic() + 60
while len(list(ready.iterdir())) < count and time.monotonic() < deadline:
    time.sleep(0.002)
import kreisel as kr
q = np.array([[1.0, 2.0, 3.0, 4.0], [0.5, -0.5, 0.5, 0.5]])
steps = {"inverse": lambda: kr.quat_inverse(q).tolist(),
         "apply": lambda: kr.quat_apply(q, [1.0, 0.0, 0.0]).tolist(),
         "product": lambda: kr.quat_multiply(q, q[::-1]).tolist(),
         "cubed int": lambda: cubes.cubed(3), "cubed float": lambda: cubes.cubed(0.5)}
order = list(steps) if index % 2 else list(steps)[::-1]
print(json.dumps({name: steps[name]() for name in order}))
"""

#: A kreisel-flavoured cached function compiled for two signatures: their saves must not share a data file.
_CUBES = """
from kreisel._compiled import cached


@cached
def cubed(x):
    return x * x * x
"""


def _expected():
    import numpy as np

    q = np.array([[1.0, 2.0, 3.0, 4.0], [0.5, -0.5, 0.5, 0.5]])
    return {"inverse": kreisel.quat_inverse(q).tolist(), "apply": kreisel.quat_apply(q, [1.0, 0.0, 0.0]).tolist(),
            "product": kreisel.quat_multiply(q, q[::-1]).tolist(), "cubed int": 27, "cubed float": 0.125}


def test_processes_on_an_empty_cache_at_once_never_crash_nor_load_a_wrong_kernel(tmp_path):
    (tmp_path / "cubes.py").write_text(_CUBES)
    expected = _expected()
    convert = ["-m", "kreisel", "convert", "--from", "euler:ZXZ", "--to", "quat", "-30", "45", "60", "--degrees"]
    reference = subprocess.run([sys.executable, *convert], env=_environment(), capture_output=True, text=True)
    assert reference.returncode == 0, reference.stderr
    callers = 2
    for round_ in range(20):
        cache, ready = tmp_path / f"cache{round_}", tmp_path / f"ready{round_}"
        ready.mkdir()
        environment = _environment(NUMBA_CACHE_DIR=str(cache),
                                   PYTHONPATH=os.pathsep.join([str(tmp_path), _SOURCE, os.environ.get("PYTHONPATH", "")]))
        runs = [subprocess.Popen([sys.executable, "-c", _CALLER, str(i), str(callers + 1), str(ready)],
                                 env=environment, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
                for i in range(callers)]
        (ready / "cli").touch()
        runs.append(subprocess.Popen([sys.executable, *convert], env=environment, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True))
        finished = [(run, *run.communicate(timeout=300)) for run in runs]
        # and a process that loads what the others saved
        loader = subprocess.run([sys.executable, "-c", _CALLER, "0", "0", str(ready)], env=environment,
                                capture_output=True, text=True, timeout=300)
        for run, out, err in [*finished[:-1], (loader, loader.stdout, loader.stderr)]:
            assert run.returncode == 0, (round_, run.returncode, err[-2000:])
            assert json.loads(out) == expected, (round_, out)
        cli, out, err = finished[-1]
        assert cli.returncode == 0 and out == reference.stdout, (round_, cli.returncode, out, err[-2000:])
        assert list((cache / "kreisel").glob("*/save.lock"))


@pytest.mark.skipif(os.name != "posix", reason="fcntl file locks")
def test_a_save_holds_the_cache_lock_and_nothing_else_does(tmp_path, monkeypatch):
    import fcntl

    from kreisel._compiled import cache

    monkeypatch.setattr(cache, "cache_root", lambda: tmp_path)
    held = []

    def save(self, sig, data):
        with open(tmp_path / cache.LOCK_NAME, "a") as other:
            try:
                fcntl.flock(other, fcntl.LOCK_EX | fcntl.LOCK_NB)
                held.append(False)
            except BlockingIOError:
                held.append(True)

    monkeypatch.setattr(cache.FunctionCache, "save_overload", save)
    cache.KreiselCache.save_overload(object.__new__(cache.KreiselCache), None, None)
    assert held == [True]
    with open(tmp_path / cache.LOCK_NAME, "a") as other:   # free again once the save is over
        fcntl.flock(other, fcntl.LOCK_EX | fcntl.LOCK_NB)
