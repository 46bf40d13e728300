"""kreisel.sweep in process: assembly, outputs, checkpoints, sweep files, bundled sweeps and their plots."""

import io

import numpy as np
import pytest
import xarray as xr
from matplotlib.figure import Figure
from rich.console import Console

import kreisel.sweep as ks
from kreisel.sweep import SweepFileError, parse_sweep_file, sweep


def affine(a, b, offset=0.0):
    return {"s": a + 10 * b + offset, "ab": np.stack([a, b], axis=-1)}


GRID = {"a": [1.0, 2.0, 3.0], "b": np.array([0, 1, 2, 3])}


def test_assembly_and_chunking():
    one = sweep(affine, GRID, chunk_size=12, scheduler="serial", constants={"offset": 0.5})
    many = sweep(affine, GRID, chunk_size=5, scheduler="serial", constants={"offset": 0.5})
    expected = np.array([1.0, 2.0, 3.0])[:, None] + 10 * np.arange(4) + 0.5
    np.testing.assert_array_equal(one.s.values, expected)
    assert one.s.dims == ("a", "b") and one.ab.dims == ("a", "b", "ab_dim_0")
    np.testing.assert_array_equal(one.ab.values[2, 3], [3.0, 3.0])
    assert one.drop_attrs().identical(many.drop_attrs())
    assert many.attrs["sweep_chunks"] == 3 and many.attrs["sweep_function"].endswith("affine")


@pytest.mark.parametrize("suffix", [".nc", ".zarr"])
def test_output_round_trip_and_replacement(tmp_path, suffix):
    target = tmp_path / f"out{suffix}"
    first = sweep(affine, GRID, chunk_size=5, scheduler="serial", output=target)
    opened = xr.open_dataset(target, engine="zarr" if suffix == ".zarr" else None).load()
    xr.testing.assert_identical(opened, first)
    second = sweep(affine, GRID, chunk_size=5, scheduler="serial", output=target, constants={"offset": 1.0})
    np.testing.assert_array_equal(xr.open_dataset(target, engine="zarr" if suffix == ".zarr" else None).s, second.s)
    assert sorted(p.name for p in tmp_path.iterdir()) == [target.name]   # no temporaries or checkpoints left


def test_checkpoint_of_another_sweep_is_refused(tmp_path):
    sweep(affine, GRID, chunk_size=5, scheduler="serial", checkpoint=tmp_path / "c", keep_checkpoint=True)
    assert len(list((tmp_path / "c").glob("chunk-*.npz"))) == 3
    with pytest.raises(ValueError, match="different sweep"):
        sweep(affine, GRID, chunk_size=4, scheduler="serial", checkpoint=tmp_path / "c")


def _defined(source):
    """``scale`` defined from ``source`` text with no file behind it (as in a notebook): bytecode only."""
    namespace = {"__name__": "user_model"}
    exec(compile(source, "<notebook cell>", "exec"), namespace)
    return namespace["scale"]


BUGGY = "def scale(a, b):\n    if a[0] >= 3.0:\n        raise ArithmeticError('bug')\n    return {'s': a + b}\n"
FIXED = "def scale(a, b):\n    return {'s': 2.0 * a + b}\n"


def test_chunks_of_changed_code_are_discarded_and_said_so(tmp_path):
    from kreisel.sweep import SweepError

    checkpoint = tmp_path / "c"
    with pytest.raises(SweepError):
        sweep(_defined(BUGGY), GRID, chunk_size=4, scheduler="serial", retries=0, checkpoint=checkpoint)
    assert len(list(checkpoint.glob("chunk-*.npz"))) == 2
    # the fixed function has the same module and name: its sweep must not reuse the buggy chunks
    with pytest.warns(UserWarning, match=r"discarded 2 of the chunks .* computed by other code"):
        events = []
        ds = sweep(_defined(FIXED), GRID, chunk_size=4, scheduler="serial", checkpoint=checkpoint,
                   progress=events.append)
    assert [e.chunk for e in events if e.event == "discarded"] == [0, 1]
    assert not any(e.event == "resumed" for e in events)
    np.testing.assert_array_equal(ds.s.values, 2.0 * ds.a.values[:, None] + ds.b.values[None, :])


def test_same_code_resumes_and_a_new_kreisel_version_discards(tmp_path, monkeypatch):
    import kreisel._version

    checkpoint = tmp_path / "c"
    sweep(_defined(FIXED), GRID, chunk_size=4, scheduler="serial", checkpoint=checkpoint, keep_checkpoint=True)
    events = []
    sweep(_defined(FIXED), GRID, chunk_size=4, scheduler="serial", checkpoint=checkpoint, keep_checkpoint=True,
          progress=events.append)
    assert [e.event for e in events] == ["resumed"] * 3
    monkeypatch.setattr(kreisel._version, "__version__", "999.0")
    console = Console(file=io.StringIO(), force_terminal=False, width=200)
    events.clear()
    sweep(_defined(FIXED), GRID, chunk_size=4, scheduler="serial", checkpoint=checkpoint, console=console,
          progress=events.append)
    assert [e.event for e in events] == ["discarded"] * 3 + ["done"] * 3
    shown = console.file.getvalue()
    assert shown.count("computed by other code") == 3 and "now kreisel 999.0" in shown


def test_bound_values_are_part_of_the_code(tmp_path):
    import functools

    from kreisel.sweep.core import _code_fingerprint

    assert _code_fingerprint(_defined(FIXED)) == _code_fingerprint(_defined(FIXED))
    assert _code_fingerprint(_defined(FIXED)) != _code_fingerprint(_defined(FIXED.replace("2.0", "3.0")))
    assert _code_fingerprint(functools.partial(affine, offset=1.0)) != \
        _code_fingerprint(functools.partial(affine, offset=2.0))

    def closure(k):
        return lambda a, b: {"s": k * a}

    assert _code_fingerprint(closure(1.0)) != _code_fingerprint(closure(2.0))


def test_progress_bar_on_a_console():
    console = Console(file=io.StringIO(), force_terminal=False, width=100)
    sweep(affine, GRID, chunk_size=5, scheduler="serial", console=console)
    assert "3/3" in console.file.getvalue()


@pytest.mark.parametrize("kwargs, error, match", [
    ({"grid": {}}, TypeError, "non-empty mapping"),
    ({"grid": {"not a name": [1.0]}}, ValueError, "identifiers"),
    ({"grid": {"a": [[1.0]]}}, ValueError, "1-D"),
    ({"grid": {"a": [np.nan]}}, ValueError, "finite"),
    ({"chunk_size": 0}, ValueError, "chunk_size"),
    ({"retries": -1}, ValueError, "retries"),
    ({"output": "x.csv"}, ValueError, r"\.zarr or \.nc"),
    ({"constants": {"a": 1.0}}, ValueError, "also a grid parameter"),
    ({"scheduler": 3}, TypeError, "scheduler"),
    ({"scheduler": "serial", "n_workers": 2}, ValueError, "n_workers"),
    ({"progress": 1}, TypeError, "progress"),
])
def test_bad_arguments_refused_before_work(kwargs, error, match):
    args = {"grid": GRID, "scheduler": "serial", **kwargs}
    with pytest.raises(error, match=match):
        sweep(affine, **args)


def test_bad_function_results_refused():
    with pytest.raises(ks.SweepError, match="first axis"):
        sweep(lambda a, b: {"s": np.zeros(1)}, GRID, chunk_size=5, scheduler="serial", retries=0)


GOOD = """
model = "lagrange_apex"
[grid.phi_dot]
values = [-1.0, 0.0, 2.0]
[grid.psi_dot]
start = 4.0
stop = 8.0
num = 3
"""


@pytest.mark.parametrize("edit, match", [
    (lambda s: "colour = 1\n" + s, r"my\.toml:1: colour: unknown key"),
    (lambda s: s + "colour = 1\n", r"my\.toml:9: grid\.psi_dot\.colour: unknown key"),
    (lambda s: s.replace('"lagrange_apex"', '"spinning_plate"'), ":2: model: expected one of"),
    (lambda s: s.replace('model = "lagrange_apex"', ''), "model: missing"),
    (lambda s: s.replace("num = 3", "num = 3.0"), r":8: grid\.psi_dot\.num: expected an integer"),
    (lambda s: s.replace("num = 3", "num = 3\ncount = 2"), r":5: grid\.psi_dot: give exactly one"),
    (lambda s: s.replace("stop = 8.0\n", ""), r":5: grid\.psi_dot: missing 'stop'"),
    (lambda s: s.replace("[grid.phi_dot]", "[grid.theta_dot]"), r":3: grid\.theta_dot: unknown key"),
    (lambda s: s + "[constants]\nmgl = \"heavy\"\n", r":10: constants\.mgl: expected a finite number"),
    (lambda s: s + "[constants]\nweight = 1.0\n", r":10: constants\.weight: unknown key"),
    (lambda s: s + "[constants]\ntheta0_deg = 180.0\n", "theta0_deg"),
    (lambda s: s.replace("values = [-1.0, 0.0, 2.0]", "values = []"), r":4: grid\.phi_dot\.values"),
    (lambda s: 'output = "map.csv"\n' + s, r":1: output: must end in"),
    (lambda s: "chunk_size = 0\n" + s, ":1: chunk_size: must be positive"),
    (lambda s: s + "[grid", "my.toml"),
])
def test_bad_sweep_files_refused(edit, match):
    with pytest.raises(SweepFileError, match=match):
        parse_sweep_file(edit(GOOD), "my.toml")


def test_tennis_racket_file_checks_the_body():
    text = ks.example_path("tennis_racket").read_text(encoding="utf-8").replace("start = 1.05", "start = 0.9")
    with pytest.raises(SweepFileError, match="middle_moment must lie strictly between"):
        parse_sweep_file(text, "t.toml")


def test_bundled_files_parse_and_never_write_into_the_package():
    for name in ks.EXAMPLES:
        spec = ks.load_sweep_file(ks.example_path(name))
        assert spec.model == name and spec.output is None


def test_tennis_racket_flip_time_matches_the_closed_form():
    # simulate_batch (DOP853, reduce hook) against the Jacobi-elliptic flip time of EulerTop
    ds = sweep(ks.tennis_racket_flip, {"middle_moment": [1.1, 1.5, 1.9], "tilt_deg": [0.3, 3.0, 30.0]},
               constants={"t_end": 80.0, "n_samples": 1601}, chunk_size=4, scheduler="serial")
    np.testing.assert_allclose(ds.flip_time, ds.flip_time_exact, rtol=1e-9)
    assert float(ds.flip_time.sel(tilt_deg=0.3).min()) > float(ds.flip_time.sel(tilt_deg=30.0).max())


def test_tennis_racket_without_a_flip_gives_nan():
    out = ks.tennis_racket_flip(np.array([1.5]), np.array([0.01]), t_end=5.0, n_samples=11)
    assert np.isnan(out["flip_time"][0]) and out["flip_time_exact"][0] > 5.0


def test_lagrange_map_has_all_three_kinds():
    ds = ks.run_sweep_file(ks.example_path("lagrange_apex"), scheduler="serial")
    kind = ds.kind
    assert np.all(kind.sel(phi_dot=0.0) == ks.APEX_LOCUS_KINDS.index("cusp"))
    assert set(np.unique(kind.values)) == {0, 1, 2}
    theta0 = 60.0   # released with θ̇ = 0: θ0 is a turning point
    on_edge = np.isclose(ds.theta_min_deg, theta0, atol=1e-6) | np.isclose(ds.theta_max_deg, theta0, atol=1e-6)
    assert bool(on_edge.all())
    assert kind.attrs["flag_meanings"] == "monotone cusp loop"


def test_imu_monte_carlo_follows_the_random_walk_law(tmp_path):
    grid = {"angle_random_walk": [0.0, 0.5, 2.0], "trial": np.arange(30)}
    constants = {"duration": 30.0, "seed": 7}
    ds = sweep(ks.imu_attitude_error, grid, constants=constants, chunk_size=7, scheduler="serial")
    again = sweep(ks.imu_attitude_error, grid, constants=constants, chunk_size=30, scheduler="serial")
    np.testing.assert_array_equal(ds.attitude_error_deg, again.attitude_error_deg)   # seeds follow the points
    error = ds.attitude_error_deg
    assert float(error.sel(angle_random_walk=0.0).max()) < 1e-5   # coning drift only
    rms = np.sqrt((error.sel(angle_random_walk=[0.5, 2.0]) ** 2).mean("trial"))
    theory = np.sqrt(3 * 30.0 / 3600.0) * np.array([0.5, 2.0])   # √3 N √T, deg with N in deg/√h, T in h
    np.testing.assert_allclose(rms, theory, rtol=0.35)   # 30 trials: χ with 90 degrees of freedom


def test_bundled_sweeps_run_from_files_and_plot(tmp_path):
    for name in ks.EXAMPLES:
        text = ks.example_path(name).read_text(encoding="utf-8")
        reduced = text.replace("num = 10", "num = 3").replace("num = 25", "num = 3").replace("count = 40", "count = 3")
        path = tmp_path / f"{name}.toml"
        path.write_text(reduced, encoding="utf-8")
        ds = ks.run_sweep_file(path, scheduler="serial", output=tmp_path / f"{name}.zarr")
        assert (tmp_path / f"{name}.zarr").is_dir()
        fig = ks.plot_sweep(ds)
        assert isinstance(fig, Figure) and fig.axes[0].get_title()
