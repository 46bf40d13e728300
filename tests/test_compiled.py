"""The compiled layer's own rules (one signature per shared kernel, a cache keyed by the sources) and its sincos."""

import json
import os
import pathlib
import platform
import re
import subprocess
import sys

import numba
import numpy as np
import pytest
from numba.core.compiler_lock import global_compiler_lock

import kreisel
from kreisel._compiled import checkout_cache_root, compile_lock, dop853, kernels, signatures, source_state
from kreisel.so3 import quat_normalize, rotvec_to_matrix


def test_a_kernel_compiled_for_two_layouts_is_reported():
    @numba.njit
    def total(a):
        return a.sum()

    total(np.ones(3))
    assert signatures.violations({"total": total}) == {}
    total(np.ones(6)[::2])
    assert list(signatures.violations({"total": total})) == ["total"]


def test_the_shared_kernels_are_the_cached_ones():
    kernels = signatures.shared_kernels()
    assert "kreisel._compiled.kernels.qmul" in kernels and "kreisel._compiled.gufunc._all_finite" in kernels
    # routines taking a compiled right-hand side are compiled for each and never cached
    assert not any(name.endswith(".integrate") for name in kernels)


def test_the_loops_over_pieces_load_from_the_cache_in_a_new_process():
    # in_pieces and piece_results take the per-piece kernel as an argument: each parallel caller
    # inlines them with its own kernel and must still be cached (numba would recompile the ones it cannot)
    psi = np.random.default_rng(3).normal(size=(2**15, 3))
    rotvec_to_matrix(psi)
    quat_normalize(np.ones((2**15, 4)), out=np.empty((2**15, 4)))
    script = """
import numpy as np
from kreisel._compiled import gufunc
from kreisel.so3 import quat_normalize, rotvec, rotvec_to_matrix
psi = np.random.default_rng(3).normal(size=(2**15, 3))
rotvec_to_matrix(psi)
quat_normalize(np.ones((2**15, 4)), out=np.empty((2**15, 4)))
loops = (rotvec._rotvec_to_matrix_parallel, gufunc._rotvecs_in_range_parallel, gufunc._smallest_quat_size_parallel)
print([(sum(f.stats.cache_hits.values()), sum(f.stats.cache_misses.values())) for f in loops])
"""
    source = str(pathlib.Path(kreisel.__file__).parents[1])
    environment = {**os.environ, "NUMBA_CACHE_DIR": numba.config.CACHE_DIR,
                   "PYTHONPATH": os.pathsep.join([source, os.environ.get("PYTHONPATH", "")])}
    found = subprocess.run([sys.executable, "-c", script], env=environment, capture_output=True, text=True, check=True)
    assert found.stdout.strip() == "[(1, 0), (1, 0), (1, 0)]", found.stdout + found.stderr


def test_a_source_checkout_compiles_into_a_cache_of_its_source_state():
    root = checkout_cache_root()
    assert root is not None and (root.parent / "pyproject.toml").is_file()
    expected = os.environ.get("NUMBA_CACHE_DIR") or str(root / source_state())  # a user's choice wins
    assert numba.config.CACHE_DIR.startswith(expected)



# ---------------------------------------------------------------------------- processes sharing a cache

_SHARED = """
from kreisel._compiled import cached
from kreisel._compiled.gufunc import gufunc


@cached
def halved(x):
    return 0.5 * x


@cached
def cubed(x):
    return x * x * x


@gufunc(["void(f8[:], f8[:])"], "(2)->(2)")
def swapped(a, out):
    out[0], out[1] = halved(a[1]), a[0]


@gufunc(["void(f8[:], f8[:])"], "(2)->(2)")
def summed(a, out):
    out[0], out[1] = a[0] + a[1], halved(a[0])


@gufunc(["void(f8[:], f8[:])"], "(3)->(3)")
def cubes(a, out):
    out[0], out[1], out[2] = cubed(a[0]), cubed(a[1]), cubed(a[2])
"""

#: Compiles the functions of _SHARED (cubed for the one signature its index picks, everything if it is negative)
#: together with the other processes, after a number of compilations of its own (numba's symbol names carry a
#: per-process counter: they differ from the other processes' ones).
_COMPILER = """
import json, pathlib, sys, time
import numba
import numpy as np
import shared
index, count, ready = int(sys.argv[1]), int(sys.argv[2]), pathlib.Path(sys.argv[3])
for _ in range(index % 3 + 1):
    numba.njit(lambda x: x + 1.0)(1.0)
steps = {"swapped": lambda: shared.swapped(np.array([1.0, 2.0])).tolist(),
         "summed": lambda: shared.summed(np.array([1.0, 2.0])).tolist(),
         "cubes": lambda: shared.cubes(np.array([1.0, 2.0, 3.0])).tolist(),
         "cubed int": lambda: shared.cubed(3), "cubed float": lambda: shared.cubed(0.5)}
names = [name for name in steps if index < 0 or name != ("cubed int", "cubed float")[index % 2]]
(ready / str(index)).touch()
deadline = time.monotonic() + 60
while len(list(ready.iterdir())) < count and time.monotonic() < deadline:
    time.sleep(0.002)
print(json.dumps({name: steps[name]() for name in names}))
"""


def test_processes_compiling_into_one_empty_cache_at_once_build_it_consistently(tmp_path):
    # numba symbol names carry a per-process counter: without the lock of kreisel._compiled.compile_lock a gufunc
    # wrapper saved by one process next to the kernel saved by another segfaulted every process loading them, and two
    # signatures added at once shared one data file
    (tmp_path / "shared.py").write_text(_SHARED)
    source = str(pathlib.Path(kreisel.__file__).parents[1])
    expected = {"swapped": [1.0, 1.0], "summed": [3.0, 0.5], "cubes": [1.0, 8.0, 27.0], "cubed int": 27,
                "cubed float": 0.125}
    writers = 3
    for attempt in range(2):
        cache, ready = tmp_path / f"cache{attempt}", tmp_path / f"ready{attempt}"
        ready.mkdir()
        environment = {**os.environ, "NUMBA_CACHE_DIR": str(cache),
                       "PYTHONPATH": os.pathsep.join([str(tmp_path), source, os.environ.get("PYTHONPATH", "")])}

        def start(index, count):
            return subprocess.Popen([sys.executable, "-c", _COMPILER, str(index), str(count), str(ready)],
                                    env=environment, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)

        runs = [start(writers * attempt + i, writers) for i in range(writers)]
        runs = [(run, *run.communicate()) for run in runs]
        runs.append((loader := start(-1, 0), *loader.communicate()))   # loads everything from the cache
        for run, out, err in runs:
            assert run.returncode == 0, (run.returncode, err[-2000:])
            found = json.loads(out)
            assert found == {name: expected[name] for name in found}, found
        assert list(cache.glob(f"*/{compile_lock.LOCK_NAME}"))



@pytest.mark.skipif(os.name != "posix", reason="fcntl file locks")
def test_numbas_compiler_lock_holds_the_cache_lock_file_from_its_outermost_hold(tmp_path, monkeypatch):
    import fcntl

    # a cache of its own: the test workers' shared cache is locked by whichever worker compiles at the moment
    monkeypatch.setattr(numba.config, "CACHE_DIR", str(tmp_path))
    os.makedirs(os.path.dirname(compile_lock.lock_path()), exist_ok=True)
    with open(compile_lock.lock_path(), "a") as other:   # another open file: another holder to flock
        with global_compiler_lock:
            with global_compiler_lock:
                pass
            with pytest.raises(BlockingIOError):
                fcntl.flock(other, fcntl.LOCK_EX | fcntl.LOCK_NB)
        fcntl.flock(other, fcntl.LOCK_EX | fcntl.LOCK_NB)
        fcntl.flock(other, fcntl.LOCK_UN)


# ---------------------------------------------------------------------------- sincos

def _ulps(got, want):
    """|got - want| in units of the last place of ``want`` rounded to a double (want: long double or mpmath)."""
    w = np.asarray(want, dtype=np.float64)
    ulp = np.where(w == 0.0, 5e-324, np.spacing(np.abs(w)))
    return np.abs(np.asarray(got, dtype=np.longdouble) - np.asarray(want, dtype=np.longdouble)) / ulp


def test_sincos_is_within_a_quarter_ulp_of_libm_and_below_0_8_ulp():
    """The vectorisable sine and cosine against references, at random arguments over the whole range
    (long double: 11 more bits than a double) and where they are hardest (mpmath): the doubles nearest
    to multiples of π/2 (|r| down to 2^-60.5 at 45.553093477052), tiny arguments, the range's end.
    Measured on 2·10^6 random arguments: at most 0.78 ulp (sin) and 0.75 ulp (cos); libm 0.52."""
    mpmath = pytest.importorskip("mpmath")
    if np.finfo(np.longdouble).nmant < 63:
        pytest.skip("long double is not the x87 extended format here")
    rng = np.random.default_rng(23)
    n = 50_000
    x = np.concatenate([
        np.exp(rng.uniform(np.log(1e-300), np.log(kernels.SINCOS_RANGE), n)) * rng.choice([-1.0, 1.0], n),
        rng.uniform(-8.0, 8.0, n),
        rng.integers(-2**26, 2**26, n) * (np.pi / 2) * (1 + rng.uniform(-1e-15, 1e-15, n)),
    ])
    got = np.array([kernels.sincos(v) for v in x])
    libm = np.stack([np.sin(x), np.cos(x)], axis=-1)
    want = np.stack([np.sin(x.astype(np.longdouble)), np.cos(x.astype(np.longdouble))], axis=-1)
    error, libm_error = _ulps(got, want).max(axis=0), _ulps(libm, want).max(axis=0)
    assert np.all(error <= 0.8) and np.all(error <= libm_error + 0.3), (error, libm_error)
    # hard cases in mpmath: nearest doubles to k π/2 (k = 29 is the closest approach below 1e8), tiny, the end
    with mpmath.workdps(60):
        hard = [float(k * mpmath.pi / 2) for k in [1, 2, 3, 29, 355, 2**20 + 7, 41_000_000, *rng.integers(1, 2**26, 40)]]
        hard += [1e-300, 5e-324, 1e-8, 0.785398163397448, -0.785398163397449, kernels.SINCOS_RANGE, 0.0]
        for v in hard:
            s, c = kernels.sincos(v)
            for got_value, exact in ((s, mpmath.sin(v)), (c, mpmath.cos(v))):
                ulp = np.spacing(abs(float(exact))) if float(exact) else 5e-324
                assert float(abs(mpmath.mpf(got_value) - exact)) / ulp <= 0.8, (v, got_value, exact)


@pytest.mark.skipif(platform.machine().lower() not in ("x86_64", "amd64"), reason="x86 packed instructions")
def test_the_half_angle_loop_vectorises():
    # the reason sincos exists: LLVM's one libm sincos call per element kept the exp loops scalar
    # an uncached copy: numba does not show the machine code of cached functions
    half_angles = numba.njit(nogil=True)(kernels._half_angles.py_func)
    scratch = np.empty(kernels.EXP_BLOCK)
    half_angles(np.ones((8, 3)), 0, 8, scratch, scratch.copy(), scratch.copy())
    assembly = "".join(half_angles.inspect_asm().values())
    assert "mulpd" in assembly and not re.findall(r"\$\w*sin\w*", assembly)   # packed, no libm sin/sincos


# ---------------------------------------------------------------------------- DOP853 dense output

@pytest.mark.parametrize("count", [1, 7, dop853.LANES, 13, 20, dop853.BLOCK])
@pytest.mark.parametrize("scale", [1.0, 1e-200, 1e200])
@pytest.mark.parametrize("unit", [3, -1])
def test_samples_interpolated_together_are_those_of_the_one_sample_interpolant(scale, unit, count):
    # bit for bit the per-sample interpolant and quat_unit, including quat_unit's rescaling of quaternions
    # whose squares would underflow or overflow (scale), and y_new itself at the step's end; counts that
    # are not a whole number of SIMD registers are padded, and the padding never reaches the samples
    rng = np.random.default_rng(7)
    ny, block = 7, np.full((9, dop853.BLOCK), np.nan)
    y, y_new, dense = rng.normal(size=ny), rng.normal(size=ny), 1e-2 * rng.normal(size=(7, ny))
    for a in (y, y_new, dense.T):
        a[3:7] *= scale
    t, h = 2.0, 0.3
    t_new = t + h
    times = np.concatenate([np.sort(rng.uniform(t, t_new, count - 1)), [t_new]])
    block[ny, :count] = times
    dop853.interpolate_samples(dense, y, y_new, t, t_new, h, count, unit, block)
    expected = np.empty((count, ny))
    for s in range(count):
        if times[s] == t_new:
            expected[s] = y_new
        else:
            dop853.interpolate(dense, y, (times[s] - t) / h, expected[s])
        if unit >= 0:
            expected[s, 3:7] = kernels.quat_unit(*expected[s, 3:7])
    np.testing.assert_array_equal(block[:ny, :count].T, expected)
    if unit >= 0:
        np.testing.assert_allclose(np.linalg.norm(block[3:7, :count], axis=0), 1.0, rtol=1e-15)


@pytest.mark.skipif(platform.machine().lower() not in ("x86_64", "amd64"), reason="x86 packed instructions")
def test_the_sample_normalisation_vectorises():
    # the reason interpolate_samples works on components of many samples: packed square roots and divisions
    normalise = numba.njit(nogil=True, error_model="numpy")(dop853._normalise.py_func)
    q = np.ones((5, 8))
    normalise(q, 0, 4, 8)
    np.testing.assert_array_equal(q[:4], 0.5)
    assembly = "".join(normalise.inspect_asm().values())
    assert "sqrtpd" in assembly and "divpd" in assembly


@numba.njit
def _faulty_oscillator(t, y, args, dy, offset):
    # y'' = -y, whose slope turns non-finite (args[2]) in stage args[0] of every step past t = args[1] only
    dy[offset] = y[1]
    dy[offset + 1] = -y[0]
    if offset == args[0] * y.size and t > args[1]:
        dy[offset] = args[2]


@pytest.mark.parametrize("bad", [np.inf, np.nan])
@pytest.mark.parametrize("stage", [1, 2, 3, 4, 13, 14, 15])
@pytest.mark.parametrize("dense_output", [True, False])
def test_a_non_finite_middle_stage_is_refused_not_interpolated_around(stage, bad, dense_output):
    # the dense output leaves stages 1-4 out of its sums (zero weights), so a non-finite one no longer spreads
    # into the samples as 0·inf; the step's own sums still weigh it and reject the step, so the run stops
    # (no finite wrong sample); a non-finite extra stage (13-15) would reach the samples only: refused too
    t_out = np.linspace(0.0, 2.0, 41) if dense_output else np.array([0.0, 2.0])
    atol = np.full(2, 1e-12)
    out = np.full((t_out.size, 2), 7.0)
    status = dop853.integrate(_faulty_oscillator, np.array([float(stage), 1.0, bad]), t_out, np.array([1.0, 0.0]),
                              1e-12, atol, np.inf, dop853.tableau(), out, False)
    clean = np.full((t_out.size, 2), 7.0)
    assert dop853.integrate(_faulty_oscillator, np.array([float(stage), 1e300, bad]), t_out, np.array([1.0, 0.0]),
                            1e-12, atol, np.inf, dop853.tableau(), clean, False) == dop853.OK
    np.testing.assert_allclose(clean[:, 0], np.cos(t_out), atol=1e-11)
    if stage > 12 and not dense_output:
        # end state only: the extra stages shape no sample, the run is right
        assert status == dop853.OK and np.array_equal(out, clean)
    else:
        assert status in (dop853.STEP_TOO_SMALL, dop853.NOT_FINITE)
