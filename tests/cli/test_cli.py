"""Every ``kreisel`` command through typer's runner, including the error paths (exit status 2)."""

import pathlib
import re
import sys

import numpy as np
import pytest
from PIL import Image
from typer.testing import CliRunner

import kreisel as kr
from kreisel.cli import app

runner = CliRunner()

def run(*args, input=None):
    return runner.invoke(app, list(args), input=input)


def numbers(text):
    return np.array([[float(x) for x in line.split()] for line in text.strip().splitlines()])


def test_version():
    result = run("--version")
    assert result.exit_code == 0 and kr.__version__ in result.stdout


def test_convert_the_contract_example():
    result = run("convert", "--from", "euler:ZXZ", "--to", "quat", "30", "45", "60", "--degrees")
    assert result.exit_code == 0, result.output
    expected = kr.euler_to_quat("ZXZ", [30, 45, 60], degrees=True)
    np.testing.assert_allclose(numbers(result.stdout)[0], expected, atol=1e-10)


@pytest.mark.parametrize("target", ["matrix", "rotvec", "euler:zyx", "axis_angle", "gibbs", "mrp",
                                    "euler_parameters", "quat"])
def test_convert_round_trips_through_every_representation(target):
    q = kr.euler_to_quat("ZXZ", [0.3, 0.7, -1.2])
    there = run("convert", "--from", "quat", "--to", target, "--", *map(str, q))
    assert there.exit_code == 0, there.output
    back = run("convert", "--from", target, "--to", "quat", "--", *there.stdout.split())
    assert back.exit_code == 0, back.output
    np.testing.assert_allclose(numbers(back.stdout)[0], q, atol=1e-9)


def test_convert_reads_rows_from_stdin_and_prints_complex_su2():
    result = run("convert", "--from", "rotvec", "--to", "su2", input="0 0 0\n# comment\n0, 0, 3.141592653589793\n")
    assert result.exit_code == 0, result.output
    rows = result.stdout.strip().splitlines()
    assert len(rows) == 2 and "j" in rows[1]


@pytest.mark.parametrize("args, turns", [
    (("--from", "euler:ZXZ", "--to", "quat", "30", "45", "60"), "9.5 turns"),
    (("--from", "axis_angle", "--to", "quat", "0", "0", "1", "90"), "14.3 turns"),
    (("--from", "rotvec", "--to", "matrix", "--", "0", "-90", "0"), "14.3 turns"),
])
def test_convert_notes_radians_that_look_like_degrees(args, turns):
    result = run("convert", *args)
    assert result.exit_code == 0, result.output
    assert turns in result.stderr and "pass --degrees" in result.stderr
    assert "--degrees" not in result.stdout


@pytest.mark.parametrize("args", [
    ("--from", "euler:ZXZ", "--to", "quat", "--degrees", "30", "45", "60"),
    ("--from", "euler:ZXZ", "--to", "quat", "0.5", "-6.2", "3.1"),
    ("--from", "quat", "--to", "euler:ZXZ", "0", "0", "0", "1"),
])
def test_convert_no_radians_note_for_angles_within_a_turn_or_in_degrees(args):
    result = run("convert", *args)
    assert result.exit_code == 0, result.output
    assert "radians" not in result.stderr


@pytest.mark.parametrize("quat", [("0", "0", "0", "1"), ("0", "0", "0", "-2"), ("1e-20", "0", "0", "1")])
def test_convert_notes_a_quaternion_that_looks_scalar_last(quat):
    result = run("convert", "--from", "quat", "--to", "rotvec", "--", *quat)
    assert result.exit_code == 0, result.output
    np.testing.assert_allclose(np.abs(numbers(result.stdout)[0]), [0.0, 0.0, np.pi], atol=1e-9)
    assert "read scalar first" in result.stderr and "pass --scalar-last" in result.stderr


@pytest.mark.parametrize("args", [
    ("--from", "quat", "--to", "rotvec", "--scalar-last", "0", "0", "0", "1"),
    ("--from", "quat", "--to", "rotvec", "1", "0", "0", "0"),
    ("--from", "quat", "--to", "rotvec", "0", "0", "0.6", "0.8"),
])
def test_convert_no_scalar_last_note_for_other_quaternions(args):
    result = run("convert", *args)
    assert result.exit_code == 0, result.output
    assert "scalar" not in result.stderr


@pytest.mark.parametrize("args, message", [
    (("--from", "euler", "--to", "quat", "1", "2", "3"), "euler:SEQ"),
    (("--from", "spinor", "--to", "quat", "1", "2", "3"), "unknown representation"),
    (("--from", "quat", "--to", "matrix", "1", "2", "3"), "takes 4 numbers"),
    (("--from", "quat", "--to", "matrix", "0", "0", "0", "0"), "invalid quat"),
    (("--from", "euler:XYX", "--to", "quat", "--degrees", "1", "2", "3"), None),
    (("--from", "euler:xYz", "--to", "quat", "1", "2", "3"), "all uppercase (intrinsic) or all lowercase"),
])
def test_convert_usage_errors_exit_2(args, message):
    result = run("convert", *args)
    if message is None:
        assert result.exit_code == 0
        return
    assert result.exit_code == 2
    assert message in result.output
    assert "Traceback" not in result.output


def test_simulate_plot_animate(tmp_path, racket_toml):
    scenario = tmp_path / "short.toml"
    scenario.write_text(racket_toml)
    out = tmp_path / "traj.nc"
    result = run("simulate", str(scenario), "-o", str(out))
    assert result.exit_code == 0, result.output
    assert "first integrals of the free body" in result.stdout and out.is_file()
    for kind in ("omega", "energy", "euler", "polhode", "herpolhode", "apex"):
        png = tmp_path / f"{kind}.png"
        result = run("plot", str(out), "--kind", kind, "-o", str(png))
        assert result.exit_code == 0, result.output
        with Image.open(png) as image:
            assert image.size[0] >= 400 and image.size[1] >= 300
            assert np.asarray(image.convert("L")).std() > 5  # not a blank canvas
    gif = tmp_path / "anim.gif"
    result = run("animate", str(out), "-o", str(gif), "--frames", "6")
    assert result.exit_code == 0, result.output
    with Image.open(gif) as image:
        assert image.n_frames == 6


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_simulate_writes_other_formats(tmp_path, racket_toml, suffix):
    scenario = tmp_path / "short.toml"
    scenario.write_text(racket_toml)
    out = tmp_path / f"traj{suffix}"
    assert run("simulate", str(scenario), "-o", str(out)).exit_code == 0
    assert run("plot", str(out), "-o", str(tmp_path / "w.svg")).exit_code == 0


def test_simulate_and_plot_errors(tmp_path, racket_toml):
    bad = tmp_path / "bad.toml"
    bad.write_text(racket_toml.replace("t_end = 10.0", "t_end = 10.0\nspeed = 3"))
    result = run("simulate", str(bad))
    assert result.exit_code == 2 and "integration.speed: unknown key" in result.output
    result = run("simulate", str(tmp_path / "absent.toml"))
    assert result.exit_code == 2 and "absent.toml: no such file" in result.output
    result = run("simulate", str(bad), "-o", str(tmp_path / "x.json"))
    assert result.exit_code == 2 and "unsupported output" in result.output
    junk = tmp_path / "junk.nc"
    junk.write_bytes(b"not netcdf")
    result = run("plot", str(junk), "-o", str(tmp_path / "p.png"))
    assert result.exit_code == 2 and "not a readable NetCDF trajectory file" in result.output
    result = run("plot", str(junk), "--kind", "spectrum", "-o", str(tmp_path / "p.png"))
    assert result.exit_code == 2 and "unknown plot kind" in result.output
    assert "Traceback" not in result.output


def test_an_output_in_a_missing_directory_is_refused_before_the_run(tmp_path, racket_toml):
    # simulate used to run the whole scenario and then end in a traceback (exit 1) when saving
    scenario = tmp_path / "short.toml"
    scenario.write_text(racket_toml)
    missing = tmp_path / "absent"
    result = run("simulate", str(scenario), "-o", str(missing / "traj.nc"))
    assert result.exit_code == 2, result.output
    assert f"-o: directory {str(missing)!r} does not exist" in result.output
    assert "first integrals" not in result.output and "Traceback" not in result.output
    traj = tmp_path / "traj.nc"
    assert run("simulate", str(scenario), "-o", str(traj)).exit_code == 0
    for args in (("plot", str(traj), "-o", str(missing / "p.png")),
                 ("animate", str(traj), "-o", str(missing / "a.gif"), "--frames", "2")):
        result = run(*args)
        assert result.exit_code == 2 and "-o: directory" in result.output, result.output
    assert not missing.exists()
    folder = tmp_path / "folder.nc"  # os.replace of the finished file onto it failed after the run
    folder.mkdir()
    result = run("simulate", str(scenario), "-o", str(folder))
    assert result.exit_code == 2 and f"-o: {str(folder)!r} is a directory" in result.output, result.output
    assert "first integrals" not in result.output and "Traceback" not in result.output


def test_examples_list_and_copy(tmp_path):
    result = run("examples")
    assert result.exit_code == 0
    for name in kr.io.EXAMPLES:
        assert name in result.stdout
    assert run("examples", "tennis_racket", "--to", str(tmp_path)).exit_code == 0
    copied = tmp_path / "tennis_racket.toml"
    assert kr.io.load_scenario(copied).title
    copied.write_text("# my edits")
    result = run("examples", "tennis_racket", "--to", str(tmp_path))
    assert result.exit_code == 2 and copied.read_text() == "# my edits"  # never clobbered
    assert run("examples", "spinning_plate").exit_code == 2


def test_unknown_command_is_a_usage_error():
    assert run("spin").exit_code == 2


def test_serve_refuses_bad_input_before_starting(tmp_path):
    result = run("serve", str(tmp_path / "absent.toml"), "--no-browser")
    assert result.exit_code == 2 and "absent.toml: no such file" in result.output
    result = run("serve", "--port", "70000", "--no-browser")
    assert result.exit_code == 2 and "port" in result.output


def test_sweep_writes_to_the_working_directory_and_plots(tmp_path, monkeypatch):
    text = """
model = "lagrange_apex"
[grid.phi_dot]
values = [-0.2, 0.0, 0.35]
[grid.psi_dot]
values = [10.0, 20.0]
[constants]
I1 = 1.0
I3 = 0.5
mgl = 1.0
theta0_deg = 34.0
"""
    sweep_file = tmp_path / "small.toml"
    sweep_file.write_text(text)
    monkeypatch.chdir(tmp_path)
    result = run("sweep", str(sweep_file), "--scheduler", "serial", "--plot", "map.png")
    assert result.exit_code == 0, result.output
    assert (tmp_path / "small.zarr").is_dir() and (tmp_path / "map.png").stat().st_size > 0
    result = run("sweep", "lagrange_apex", "--scheduler", "serial", "-o", str(tmp_path / "bundled.nc"))
    assert result.exit_code == 0, result.output
    assert (tmp_path / "bundled.nc").is_file()
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace("mgl = 1.0", "mgl = 1.0\ncolour = 1"))
    result = run("sweep", str(bad), "--scheduler", "serial")
    assert result.exit_code == 2 and "colour" in result.output


def test_sweep_streams_into_zarr_on_request(tmp_path):
    import xarray as xr

    text = """
model = "lagrange_apex"
chunk_size = 2
[grid.phi_dot]
values = [-0.2, 0.0, 0.35]
[grid.psi_dot]
values = [10.0, 20.0]
"""
    sweep_file = tmp_path / "small.toml"
    sweep_file.write_text(text)
    result = run("sweep", str(sweep_file), "--scheduler", "serial", "--stream", "-o", str(tmp_path / "s.zarr"))
    assert result.exit_code == 0, result.output
    result = run("sweep", str(sweep_file), "--scheduler", "serial", "-o", str(tmp_path / "m.zarr"))
    assert result.exit_code == 0, result.output
    with xr.open_zarr(tmp_path / "s.zarr") as streamed, xr.open_zarr(tmp_path / "m.zarr") as memory:
        xr.testing.assert_identical(streamed.load(), memory.load())
    # the file's stream = true is overridden by --no-stream; a NetCDF output cannot be streamed into
    sweep_file.write_text("stream = true\n" + text)
    result = run("sweep", str(sweep_file), "--scheduler", "serial", "--no-stream", "-o", str(tmp_path / "m.nc"))
    assert result.exit_code == 0, result.output
    result = run("sweep", str(sweep_file), "--scheduler", "serial", "-o", str(tmp_path / "s.nc"))
    assert result.exit_code == 2 and ".zarr" in result.output and not (tmp_path / "s.nc").exists()


@pytest.mark.parametrize("args, message", [
    (["fit", "phone_toss", "--plot", "fit.png"], 'kreisel fit --plot needs matplotlib: pip install "kreisel[plot]"'),
    (["sweep", "tennis_racket", "--plot", "map.png"],
     'kreisel sweep needs xarray, distributed, zarr and matplotlib: pip install "kreisel[sweep,plot]"'),
    (["sweep", "tennis_racket", "--scheduler", "serial", "-o", "map.nc", "--plot", "map.png"],
     'kreisel sweep needs xarray and matplotlib: pip install "kreisel[sweep,plot]"'),
])
def test_a_plot_option_names_its_extra_with_the_commands_ones_before_any_work(tmp_path, monkeypatch, args, message):
    # as without the extras (tests/test_core_install.py): not the sweep's extra, then after a whole sweep the plot's
    for package in ("matplotlib", "xarray", "distributed", "zarr"):
        monkeypatch.setitem(sys.modules, package, None)
    monkeypatch.chdir(tmp_path)
    result = run(*args)
    assert result.exit_code == 2 and result.output.strip() == f"error: {message}", result.output
    assert list(tmp_path.iterdir()) == []


def test_convert_reads_a_csv_file(tmp_path):
    rows = tmp_path / "angles.csv"
    rows.write_text("# phi, theta, psi in degrees\n30, 45, 60\n0, 90, 0\n")
    result = run("convert", "--from", "euler:ZXZ", "--to", "rotvec", "--degrees", "--input", str(rows))
    assert result.exit_code == 0, result.output
    expected = kr.Rotation.from_euler("ZXZ", [[30, 45, 60], [0, 90, 0]], degrees=True).as_rotvec(degrees=True)
    np.testing.assert_allclose(numbers(result.stdout), expected, atol=1e-8)
    result = run("convert", "--from", "quat", "--to", "matrix", "--input", str(tmp_path / "absent.csv"))
    assert result.exit_code == 2 and "cannot read" in result.output


@pytest.fixture
def runaway(racket_toml):
    """The short scenario without its sampling: each test adds its own."""
    return racket_toml.replace("n_samples = 101\n", "")


@pytest.mark.parametrize("extra,message", [
    ('n_samples = 11\nmethod = "rk4"\ndt = 1e-300\n', r"needs 1e\+301 steps, about .* years"),
    ("n_samples = 1000000000000\n", r"integration.n_samples: expected at most \d+ samples on this machine: "
                                   r"1000000000000 samples would need 192 TB"),
])
def test_simulate_refuses_runaway_scenarios_before_work(tmp_path, runaway, extra, message):
    path = tmp_path / "runaway.toml"
    path.write_text(runaway + extra, encoding="utf-8")
    result = run("simulate", str(path))
    assert result.exit_code == 2
    assert re.search(message, " ".join(result.output.split())), result.output


def test_simulate_refuses_a_free_run_out_of_the_adaptive_methods_reach(tmp_path, runaway):
    path = tmp_path / "forever.toml"
    path.write_text(runaway.replace("t_end = 10.0", "t_end = 1e300") + "n_samples = 11\n", encoding="utf-8")
    result = run("simulate", str(path))
    assert result.exit_code == 2, result.output
    assert re.search(r"cannot run: t = 0 … 1e\+300 is out of reach of the adaptive method 'dop853'.*"
                     r"max_steps = 4e\+08 \(by default about 10 minutes of computing, at most 1e\+10\)", " ".join(result.output.split())), result.output


def test_simulate_reports_progress_of_a_long_run(tmp_path, runaway, monkeypatch):
    from kreisel._compiled import chunks
    from kreisel.dynamics import engine
    from kreisel.io import run as io_run

    path = tmp_path / "long.toml"
    path.write_text(runaway + 'n_samples = 3\nmethod = "rk4"\ndt = 1e-2\n', encoding="utf-8")
    monkeypatch.setattr(chunks, "CHUNK_SECONDS", 0.0)
    monkeypatch.setattr(engine, "_FIRST_CHUNK_STEPS", 1)
    seen = []
    original = io_run.run_scenario

    def spy(spec, progress=None):
        return original(spec, progress=lambda done: (seen.append(done), progress(done)))

    monkeypatch.setattr(io_run, "run_scenario", spy)
    result = run("simulate", str(path))
    assert result.exit_code == 0, result.output
    assert len(seen) > 10 and 0 <= seen[0] and seen[-1] < 1 and np.all(np.diff(seen) >= 0)


def _no_work(*args, **kwargs):
    raise AssertionError("the command started its work before refusing its output")


# (command line with {out} for the output or {dir} for its directory, output name, module and function doing the
# command's work)
_WRITERS = [
    (["simulate", "tennis_racket", "-o", "{out}"], "traj.nc", "kreisel.io.run", "run_scenario"),
    (["plot", "traj.nc", "-o", "{out}"], "p.png", "kreisel.io.results", "load_result"),
    (["animate", "traj.nc", "-o", "{out}"], "a.gif", "kreisel.io.results", "load_trajectory"),
    (["fit", "phone_toss", "--json", "{out}"], "fit.json", "kreisel.io.gyro", "read_gyro"),
    (["fit", "phone_toss", "--plot", "{out}"], "fit.png", "kreisel.io.gyro", "read_gyro"),
    (["sweep", "lagrange_apex", "--scheduler", "serial", "-o", "{out}"], "map.nc", "kreisel.sweep", "run_sweep_file"),
    (["sweep", "lagrange_apex", "--scheduler", "serial", "-o", "m.nc", "--plot", "{out}"], "map.png",
     "kreisel.sweep", "run_sweep_file"),
    (["tour", "--out", "{dir}"], "index.html", "kreisel.tour", "run_tour"),
    (["tour", "--notebooks", "{dir}"], "01_rotations.ipynb", "kreisel.tour.notebooks", "write_notebooks"),
]


@pytest.mark.parametrize("args, name, module, function", _WRITERS, ids=lambda v: v if isinstance(v, str) else None)
def test_an_existing_output_is_refused_before_any_work_without_force(tmp_path, monkeypatch, args, name, module,
                                                                     function):
    import importlib

    monkeypatch.setattr(importlib.import_module(module), function, _no_work)
    monkeypatch.chdir(tmp_path)
    out = tmp_path / "out" / name
    out.parent.mkdir()
    out.write_text("the user's file")
    option = next(args[k - 1] for k, arg in enumerate(args) if arg in ("{out}", "{dir}"))
    result = run(*[{"{out}": str(out), "{dir}": str(out.parent)}.get(arg, arg) for arg in args])
    assert result.exit_code == 2, result.output
    assert result.output.strip() == f"error: {option}: {str(out)!r} already exists; pass --force to replace it"
    assert out.read_text() == "the user's file"
    assert sorted(p.name for p in out.parent.iterdir()) == [name]  # no temporary left


def test_force_replaces_an_existing_output_atomically(tmp_path, racket_toml):
    scenario = tmp_path / "short.toml"
    scenario.write_text(racket_toml)
    traj = tmp_path / "traj.nc"
    traj.write_text("an old run")
    mode = traj.stat().st_mode
    result = run("simulate", str(scenario), "-o", str(traj), "--force")
    assert result.exit_code == 0 and result.stdout.rstrip().endswith(f"wrote {traj}"), result.output
    assert len(kr.io.load_trajectory(traj)) == 101 and traj.stat().st_mode == mode
    assert sorted(p.name for p in tmp_path.iterdir()) == ["short.toml", "traj.nc"]
    png = tmp_path / "omega.png"
    png.write_text("an old figure")
    assert run("plot", str(traj), "-o", str(png), "--force").exit_code == 0
    with Image.open(png) as image:
        assert image.format == "PNG"


def test_a_directory_in_place_of_a_zarr_store_is_refused_even_with_force(tmp_path):
    folder = tmp_path / "photos.zarr"
    folder.mkdir()
    (folder / "holiday.jpg").write_text("keep me")
    result = run("sweep", "lagrange_apex", "--scheduler", "serial", "-o", str(folder), "--force")
    assert result.exit_code == 2 and "is a directory but not a Zarr store" in result.output, result.output
    assert (folder / "holiday.jpg").read_text() == "keep me"


def test_a_sweep_store_is_replaced_with_force_and_its_summary_is_text(tmp_path):
    import xarray as xr

    sweep_file = tmp_path / "small.toml"
    sweep_file.write_text('model = "lagrange_apex"\n[grid.phi_dot]\nvalues = [-0.2, 0.35]\n'
                          '[grid.psi_dot]\nvalues = [10.0, 20.0, 30.0]\n')
    store = tmp_path / "s.zarr"
    for extra in ([], ["--force"]):
        result = run("sweep", str(sweep_file), "--scheduler", "serial", "-o", str(store), *extra)
        assert result.exit_code == 0, result.output
        assert result.stdout.splitlines() == ["6 points: phi_dot 2 values from -0.2 to 0.35, "
                                              "psi_dot 3 values from 10 to 30", f"wrote {store}"]
    with xr.open_zarr(store) as dataset:
        assert dict(dataset.sizes) == {"phi_dot": 2, "psi_dot": 3}
    result = run("sweep", str(sweep_file), "--scheduler", "serial", "-o", str(store))
    assert result.exit_code == 2 and "already exists; pass --force" in result.output


@pytest.mark.skipif(not pathlib.Path("/proc/self").is_dir(), reason="needs a directory no file can be created in")
def test_an_output_directory_that_cannot_be_written_is_refused_before_the_run(monkeypatch):
    monkeypatch.setattr(kr.io.run, "run_scenario", _no_work)
    result = run("simulate", "tennis_racket", "-o", "/proc/traj.nc")
    assert result.exit_code == 2 and result.output.startswith("error: -o: cannot write in '/proc'"), result.output


def test_an_error_while_writing_is_one_line_with_status_1(tmp_path, monkeypatch, racket_toml):
    import errno

    scenario = tmp_path / "short.toml"
    scenario.write_text(racket_toml)
    traj = tmp_path / "traj.nc"
    assert run("simulate", str(scenario), "-o", str(traj)).exit_code == 0

    def full(*args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(kr.plot, "save", full)
    result = run("plot", str(traj), "-o", str(tmp_path / "p.png"))
    assert result.exit_code == 1, result.output
    assert result.output.strip() == f"error: -o: cannot write {str(tmp_path / 'p.png')!r} (No space left on device)"
