"""Recordings as the commands take them: bundled names everywhere, one --units, the same refusals (a subprocess)."""

import numpy as np
import pytest
from PIL import Image

import kreisel as kr
from kreisel.cli._recordings import bundled_recordings


@pytest.fixture(scope="module")
def deg_table(tmp_path_factory):
    """A free top's rates in deg/s under a header that names no unit, as many loggers write them."""
    t = np.linspace(0.0, 0.6, 300)
    omega = np.degrees(kr.EulerTop(0.2, 0.8, 1.0).omega(t, [0.4, 12.0, 0.3]))
    path = tmp_path_factory.mktemp("deg") / "deg.csv"
    np.savetxt(path, np.column_stack([t, omega]), fmt="%.17g", delimiter=",", header="time,gx,gy,gz", comments="")
    return path


@pytest.mark.parametrize("command, typo, name", [
    (("fit",), "phone_tos", "phone_toss"),
    (("plot", "-o", "x.png"), "phone-toss", "phone_toss"),
    (("attitude", "-o", "a.csv"), "broad_7", "broad_07"),
])
def test_a_mistyped_recording_name_gets_the_nearest_bundled_one(kreisel, usage_error, tmp_path, command, typo, name):
    """`kreisel fit phone_tos` said only "cannot read phone_tos (No such file or directory)"."""
    done = kreisel(command[0], typo, *command[1:], cwd=tmp_path)
    usage_error(done, f"{typo}: no such file, and no bundled recording of that name; did you mean '{name}'?")


def test_every_bundled_recording_is_listed_copied_and_read_by_name(kreisel, tmp_path):
    listed = kreisel("examples").stdout
    assert "IMU recordings (kreisel attitude NAME" in listed
    for name, path in bundled_recordings().items():
        assert f"\n  {name} " in listed, name
        copied = kreisel("examples", name, "--to", tmp_path)
        assert copied.returncode == 0 and copied.stdout.strip() == f"wrote {tmp_path / path.name}", copied.stderr
        assert (tmp_path / path.name).read_bytes() == path.read_bytes()
    figure = tmp_path / "broad.png"
    drawn = kreisel("plot", "broad_07", "-o", figure)
    assert drawn.returncode == 0, drawn.stderr
    assert Image.open(figure).size[0] > 500


def test_plot_takes_the_gyro_unit_as_fit_does(kreisel, usage_error, deg_table, tmp_path):
    figure = tmp_path / "rates.png"
    refused = kreisel("plot", deg_table, "-o", figure)
    assert refused.returncode == 2 and "(on the command line: --units deg/s)" in refused.stderr, refused.stderr
    drawn = kreisel("plot", deg_table, "--units", "deg/s", "-o", figure)
    assert drawn.returncode == 0 and drawn.stdout.strip() == f"wrote {figure}", drawn.stderr
    usage_error(kreisel("plot", deg_table, "--units", "furlong/s", "-o", tmp_path / "x.png"),
                "--units: units['gyro'] must be one of rad/s")
    help_text = {command: kreisel(command, "--help").stdout for command in ("plot", "fit", "attitude")}
    units_lines = {command: " ".join(text[text.index("--units"):].split("\n  -")[0].split())
                   for command, text in help_text.items()}
    assert units_lines["plot"] == units_lines["fit"] == units_lines["attitude"], units_lines


def test_plot_refuses_units_for_a_saved_result(kreisel, usage_error, tmp_path, racket_toml):
    (tmp_path / "s.toml").write_text(racket_toml)
    assert kreisel("simulate", "s.toml", "-o", "t.nc", cwd=tmp_path).returncode == 0
    usage_error(kreisel("plot", "t.nc", "--units", "deg/s", "-o", "x.png", cwd=tmp_path),
                "--units are for a gyroscope recording; t.nc holds a saved result")


@pytest.fixture(scope="module")
def other_files(tmp_path_factory):
    """A saved result and a scenario file: kreisel's own files that a newcomer passes where a recording goes."""
    folder = tmp_path_factory.mktemp("other")
    kr.EulerTop(1.0, 2.0, 3.0).solve(np.linspace(0.0, 1.0, 11), [0.1, 1.0, 0.1]).save(folder / "traj.nc")
    (folder / "top.toml").write_text('[body]\nmoments = [1.0, 2.0, 3.0]\n', encoding="utf-8")
    return folder


@pytest.mark.parametrize("command", [("fit",), ("attitude", "-o", "a.csv"), ("serve", "--no-browser", "--recording")])
@pytest.mark.parametrize("name, told", [
    ("traj.nc", "traj.nc is a result file (as kreisel simulate writes), not a sensor recording: "
                "plot it with kreisel plot traj.nc -o fig.png"),
    ("top.toml", "top.toml is a scenario or sweep file, not a sensor recording: kreisel simulate top.toml -o traj.nc"),
])
def test_a_result_or_scenario_given_as_a_recording_is_named_for_what_it_is(
        kreisel, usage_error, other_files, command, name, told):
    """`kreisel fit traj.nc` said "traj.nc: not a text file (control character '\\x02' at character 3)"."""
    done = kreisel(*command, name, cwd=other_files)
    usage_error(done, told)
    assert not (other_files / "a.csv").exists()


def test_plot_of_a_scenario_says_to_simulate_it_first(kreisel, usage_error, other_files):
    done = kreisel("plot", "top.toml", "-o", "x.png", cwd=other_files)
    usage_error(done, "top.toml is a scenario or sweep file, not a result: kreisel simulate top.toml -o traj.nc")
    assert not (other_files / "x.png").exists()
