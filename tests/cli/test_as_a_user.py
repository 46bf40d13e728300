"""The ``kreisel`` command run as a user runs it: a subprocess, real files, exit status and standard error."""

import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import kreisel as kr

SRC = pathlib.Path(kr.__file__).resolve().parents[1]

GOOD = """\
title = "short racket"
[body]
moments = [1.0, 2.0, 3.0]
[initial]
omega = [0.01, 1.0, 0.01]
[initial.attitude]
ATTITUDE
[integration]
t_end = 2.0
n_samples = 21
"""


@pytest.mark.parametrize("attitude, line, key, expected", [
    ('seq = "ZXQ"\neuler = [1, 2, 3]', 7, "initial.attitude.seq", "letters x, y, z"),
    ('seq = "ZZX"\neuler = [1, 2, 3]', 7, "initial.attitude.seq", "no axis twice in a row"),
    ("quat = [0, 0, 0, 0]", 7, "initial.attitude.quat", "a unit quaternion"),
    ("matrix = [[1, 0, 0], [0, 2, 0], [0, 0, 1]]", 7, "initial.attitude.matrix", "a rotation matrix"),
    ('quat = [1, 0, 0, 0]\nseq = "ZXZ"', 8, "initial.attitude.seq", "only used with euler"),
])
def test_bad_attitude_values_are_named_before_the_run(kreisel, usage_error, tmp_path, attitude, line, key,
                                                     expected):
    scenario = tmp_path / "spin.toml"
    scenario.write_text(GOOD.replace("ATTITUDE", attitude))
    usage_error(kreisel("simulate", scenario), f"spin.toml:{line}: {key}: expected" if "only" not in expected
                else f"spin.toml:{line}: {key}: {expected}", expected)


def test_scenario_file_defects_are_one_clear_line(kreisel, usage_error, tmp_path):
    good = GOOD.replace("ATTITUDE", "quat = [1, 0, 0, 0]")
    files = {
        "bom.toml": ("\ufeff" + good, None),
        "empty.toml": ("", "the file is empty; a scenario needs [body], [initial] and [integration] tables"),
        "deep.toml": ("a = " + "[" * 5000 + "]" * 5000 + "\n", "nested too deeply"),
        "syntax.toml": (good.replace("t_end = 2.0", "t_end = = 2.0"), "syntax.toml:9: TOML syntax error"),
        "fixed.toml": (good.replace("t_end = 2.0", "t_end = 2.0\nmethod = 'rk4'"), "give integration.dt"),
    }
    for name, (text, message) in files.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
        process = kreisel("simulate", name, cwd=tmp_path)
        if message is None:
            assert process.returncode == 0, process.stderr
        else:
            usage_error(process, f"{name}", message)
    (tmp_path / "binary.toml").write_bytes(b"\x89PNG\r\n\x1a\n\x00\xff")
    usage_error(kreisel("simulate", "binary.toml", cwd=tmp_path), "binary.toml: not a text file")


def test_bundled_scenario_names_work_and_typos_get_the_nearest_name(kreisel, usage_error, tmp_path):
    process = kreisel("simulate", "tennis_racket", cwd=tmp_path)
    assert process.returncode == 0, process.stderr
    assert "2001 samples" in process.stdout
    usage_error(kreisel("simulate", "tenis_racket", cwd=tmp_path), "tenis_racket: no such file",
                "did you mean 'tennis_racket'?")
    usage_error(kreisel("sweep", "lagrange_apx", cwd=tmp_path), "did you mean 'lagrange_apex'?")


def test_examples_copy_twice_needs_force(kreisel, usage_error, tmp_path):
    assert kreisel("examples", "fast_top", cwd=tmp_path).returncode == 0
    (tmp_path / "fast_top.toml").write_text("# my edits\n")
    usage_error(kreisel("examples", "fast_top", cwd=tmp_path), "fast_top.toml already exists", "--force")
    assert (tmp_path / "fast_top.toml").read_text() == "# my edits\n"
    assert kreisel("examples", "fast_top", "--force", cwd=tmp_path).returncode == 0
    assert (tmp_path / "fast_top.toml").read_text() == kr.io.example_path("fast_top").read_text()
    usage_error(kreisel("examples", "fast_tp", cwd=tmp_path), "did you mean 'fast_top'?")


def numbers(text):
    return np.array([[float(x) for x in line.split()] for line in text.strip().splitlines()])


def test_convert_takes_negative_numbers_as_typed(kreisel, usage_error):
    process = kreisel("convert", "--from", "euler:ZXZ", "--to", "quat", "-30", "45", "60", "--degrees")
    assert process.returncode == 0, process.stderr
    np.testing.assert_allclose(numbers(process.stdout)[0], kr.euler_to_quat("ZXZ", [-30, 45, 60], degrees=True),
                               atol=1e-9)
    process = kreisel("convert", "--from", "rotvec", "--to", "quat", "--scalar-last", "-1e-3", "0", "-.5")
    assert process.returncode == 0, process.stderr
    np.testing.assert_allclose(numbers(process.stdout)[0], np.roll(kr.rotvec_to_quat([-1e-3, 0, -0.5]), -1),
                               atol=1e-9)
    usage_error(kreisel("convert", "--from", "euler:ZXZ", "--to", "quat", "-30", "45", "60", "--degree"),
                "no such option: --degree")
    # a misspelt option is named, not reported as the option it was meant to be
    usage_error(kreisel("convert", "--frm", "euler:ZXZ", "--to", "quat", "1", "2", "3"), "no such option: --frm")
    usage_error(kreisel("convert", "--from", "euler:ZXZ", "1", "2", "3"), "missing option --to")


def test_convert_input_files(kreisel, usage_error, tmp_path):
    angles = tmp_path / "angles.csv"
    angles.write_text("phi,theta,psi\n30,45,60\n-10,20,-30\n")
    process = kreisel("convert", "--from", "euler:ZXZ", "--to", "quat", "--degrees", "-i", angles)
    assert process.returncode == 0, process.stderr
    np.testing.assert_allclose(numbers(process.stdout),
                               kr.euler_to_quat("ZXZ", [[30, 45, 60], [-10, 20, -30]], degrees=True), atol=1e-9)
    ragged = tmp_path / "ragged.csv"
    ragged.write_text("30,45,60\n# a comment\n1,2\n")
    usage_error(kreisel("convert", "--from", "euler:ZXZ", "--to", "quat", "-i", ragged),
                "input line 3: expected 3 numbers per rotation, got 2")
    quats = tmp_path / "q.txt"
    quats.write_text("1 0 0 0\n0 0 0 0\n")
    usage_error(kreisel("convert", "--from", "quat", "--to", "matrix", "-i", quats), "input line 2: invalid quat")
    binary = tmp_path / "data.bin"
    binary.write_bytes(bytes(range(256)))
    usage_error(kreisel("convert", "--from", "quat", "--to", "matrix", "-i", binary), "not a text file")
    usage_error(kreisel("convert", "--from", "euler:ZXZ", "--to", "quat", "-i", angles, "1", "2", "3"),
                "not both")
    usage_error(kreisel("convert", "--from", "quat", "--to", "matrix", "--to", "rotvec", "1", "0", "0", "0"),
                "--to given 2 times")


def test_convert_help_states_the_layouts(kreisel):
    text = " ".join(kreisel("convert", "--help").stdout.split())
    for phrase in ("scalar first", "--scalar-last", "row-major", "the axis, then the angle", "-30 45 60",
                   "mrp | euler_parameters", "euler_parameters e0 e1 e2 e3, the conjugate quaternion"):
        assert phrase in text, phrase


def test_a_heavy_top_reports_its_first_integrals_not_drift(kreisel, tmp_path):
    process = kreisel("simulate", "fast_top", "-o", "fast.nc", cwd=tmp_path)
    assert process.returncode == 0, process.stderr
    assert "drift" not in process.stdout
    assert "first integrals of the heavy symmetric (Lagrange) top" in process.stdout
    rows = {line.split()[0]: line for line in process.stdout.splitlines()[2:5]}
    assert sorted(rows) == ["E", "J_3", "J_z"]
    for line in rows.values():   # each kept to rounding error by the default integrator
        assert float(line.rsplit("change", 1)[1]) < 1e-9
    for kind in ("energy", "polhode"):
        process = kreisel("plot", "fast.nc", "--kind", kind, "-o", f"{kind}.png", cwd=tmp_path)
        assert process.returncode == 0, process.stderr
        assert (tmp_path / f"{kind}.png").stat().st_size > 10_000
    # gravity changes T: the polhode is drawn on axes fitted to the path (on the energy ellipsoid the fast
    # top's ω′, within 0.05 rad/s of its pole, was not to be seen)
    code = ("import kreisel as kr; from kreisel.plot import polhode; ax = polhode(kr.io.load_result('fast.nc')).axes[0]; "
            "print(ax.get_title().replace(chr(10), ' '), ax.get_xlim()[1] - ax.get_xlim()[0])")
    shown = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=dict(os.environ, PYTHONPATH=str(SRC)),
                           capture_output=True, text=True, timeout=600)
    title, width = shown.stdout.rsplit(" ", 1)
    assert "no energy ellipsoid" in title and float(width) < 0.2, shown


def test_plot_says_what_a_foucault_result_holds_and_plots_it(kreisel, usage_error, tmp_path):
    assert kreisel("simulate", "foucault", "-o", "f.nc", cwd=tmp_path).returncode == 0
    process = kreisel("plot", "f.nc", "-o", "f.png", cwd=tmp_path)
    assert process.returncode == 0, process.stderr
    assert (tmp_path / "f.png").stat().st_size > 10_000
    usage_error(kreisel("plot", "f.nc", "--kind", "euler", "-o", "g.png", cwd=tmp_path),
                "f.nc holds a Foucault pendulum result, which plots as azimuth")


def test_serve_opens_a_bundled_scenario_by_name(kreisel, usage_error, serve, tmp_path):
    import httpx

    usage_error(kreisel("serve", "tenis_racket", "--no-browser", cwd=tmp_path), "did you mean 'tennis_racket'?")
    (tmp_path / "data.toml").write_bytes(b"\x89PNG\r\n\x1a\n\x00\xff")
    usage_error(kreisel("serve", "data.toml", "--no-browser", cwd=tmp_path), "data.toml: not a text file")
    with serve("tennis_racket", cwd=tmp_path) as (url, token):
        # the printed URL carries the server's token, and nothing is answered without it
        assert httpx.get(url + "api/initial", timeout=60).status_code == 403
        assert 'title = "Tennis racket' in httpx.get(url + "api/initial" + token, timeout=60).json()["toml"]
