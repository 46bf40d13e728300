"""``kreisel fit``: summary, plot, JSON, window, and the error paths (exit status 2)."""

import json

import numpy as np
from PIL import Image
from typer.testing import CliRunner

import kreisel as kr
from kreisel.cli import app

runner = CliRunner()


def run(*args):
    return runner.invoke(app, list(args))


def test_fit_bundled_recording_with_plot_and_json(tmp_path):
    plot, record = tmp_path / "fit.png", tmp_path / "fit.json"
    result = run("fit", "phone_toss", "--bias", "--plot", str(plot), "--json", str(record))
    assert result.exit_code == 0, result.output
    for text in ("I_x = 0.81", "I_z = 1 (reference)", "ω0 at t = 4.2731 s", "gyro bias", "residual RMS 0.0",
                 "intermediate axis x", "energy T with the fitted moments", "|J| with the fitted moments"):
        assert text in result.stdout, text
    assert Image.open(plot).size[0] > 500
    data = json.loads(record.read_text())
    truth = np.diag(kr.inertia.box(1.0, (0.071, 0.146, 0.008)))
    np.testing.assert_allclose(data["moments"], truth / truth.max(), atol=4 * max(data["moments_stderr"]))
    assert data["intermediate_axis"] == "x" and data["free_rotation"] and len(data["bias"]) == 3


def test_fit_window_of_a_longer_table(tmp_path):
    moments = np.array([0.2, 0.8, 1.0])
    t = np.linspace(0.0, 3.0, 1200)
    omega = kr.EulerTop(*moments).omega(t - 1.0, [0.4, 12.0, 0.3])
    omega[(t < 1.0) | (t > 2.0)] = np.random.default_rng(0).normal(0.0, 4.0, (np.sum((t < 1.0) | (t > 2.0)), 3))
    path = tmp_path / "long.txt"
    np.savetxt(path, np.column_stack([t, omega]), header="t wx wy wz")
    whole = run("fit", str(path))
    assert whole.exit_code == 1 and "not a free rotation" in whole.output
    cut = run("fit", str(path), "--start", "1.0", "--stop", "2.0", "--json", str(tmp_path / "cut.json"))
    assert cut.exit_code == 0, cut.output
    np.testing.assert_allclose(json.loads((tmp_path / "cut.json").read_text())["moments"], moments, atol=1e-6)


def test_fit_errors_exit_2_with_one_line(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("0 1 2 3\n0.1 1 oops 3\n")
    short = tmp_path / "short.csv"
    np.savetxt(short, np.column_stack([np.arange(5.0), np.ones((5, 3))]))
    cases = [
        (("fit", str(tmp_path / "missing.csv")), "missing.csv: no such file"),
        (("fit", str(bad)), "bad.csv:2: not a number: 'oops'"),
        (("fit", str(short)), "too few samples"),
        (("fit", "phone_toss", "--start", "9", "--stop", "1"), "t_start < t_stop"),
        (("fit", "phone_toss", "--plot", str(tmp_path / "fit.gif")), "--plot: unsupported output"),
        (("fit", "phone_toss", "--json", str(tmp_path / "nowhere" / "a.json")), "--json: directory"),
    ]
    for args, message in cases:
        result = run(*args)
        assert result.exit_code == 2, (args, result.output)
        assert message in result.output and result.output.strip().count("\n") == 0, result.output
        assert "Traceback" not in result.output


def test_a_deg_per_second_file_is_refused_then_fitted_with_units(kreisel, tmp_path):
    """Issue 34: `kreisel fit deg.csv` (header time,gx,gy,gz, values in deg/s) fitted ω0 = +692 rad/s."""
    moments = np.array([0.2, 0.8, 1.0])
    t = np.linspace(0.0, 0.6, 300)
    omega = np.degrees(kr.EulerTop(*moments).omega(t, [0.4, 12.0, 0.3]))
    rows = "\n".join(",".join(f"{v:.17g}" for v in (ti, *w)) for ti, w in zip(t, omega))
    (tmp_path / "deg.csv").write_text(f"time,gx,gy,gz\n{rows}\n")
    refused = kreisel("fit", "deg.csv", cwd=tmp_path)
    assert refused.returncode == 2 and "Traceback" not in refused.stderr, refused.stderr
    assert refused.stderr.count("\n") == 1, refused.stderr
    assert "deg.csv: the gyro's |ω| reaches 691.9 rad/s (its numbers taken as rad/s: no unit is given)" \
        in refused.stderr
    assert "look like deg/s: read them with units='deg/s' (on the command line: --units deg/s)" in refused.stderr
    fitted = kreisel("fit", "deg.csv", "--units", "deg/s", "--json", "fit.json", cwd=tmp_path)
    assert fitted.returncode == 0, fitted.stderr
    result = json.loads((tmp_path / "fit.json").read_text())
    np.testing.assert_allclose(result["moments"], moments, atol=1e-6)
    np.testing.assert_allclose(result["omega0"], [0.4, 12.0, 0.3], atol=1e-6)
    bad = kreisel("fit", "deg.csv", "--units", "furlong/s", cwd=tmp_path)
    assert bad.returncode == 2 and "--units: units['gyro'] must be one of rad/s" in bad.stderr


def test_fit_says_how_it_read_the_file(tmp_path):
    header = "time (s),gyro x (°/s),gyro y (°/s),gyro z (°/s)"
    t = np.linspace(0.0, 1.0, 300)
    omega = np.degrees(kr.EulerTop(0.2, 0.8, 1.0).omega(t, [0.4, 12.0, 0.3]))
    rows = "\n".join(",".join(f"{v:.17g}" for v in (ti, *w)) for ti, w in zip(t, omega))
    path = tmp_path / "latin1.csv"
    path.write_text(f"{header}\n{rows}\n", encoding="latin-1")
    result = run("fit", str(path))
    assert result.exit_code == 0, result.output
    assert f"{path}: decoded as Latin-1" in result.stdout and "I_x = 0.20000" in result.stdout


def test_fit_of_a_toss_whose_energy_falls_says_so(kreisel, tmp_path):
    """The issue: T fell ~20 %/s with the fitted moments and ``kreisel fit`` said free rotation explains the data."""
    rng = np.random.default_rng(3)
    t = np.sort(rng.uniform(0.0, 0.65, 260))
    moments = np.diag(kr.inertia.box(0.17, (0.071, 0.146, 0.008)))
    omega = kr.EulerTop(*moments).omega(t, [13.0, 0.45, 0.35]) * np.exp(-0.1 * t)[:, None]
    path = tmp_path / "toss.csv"
    np.savetxt(path, np.column_stack([t, omega + rng.normal(0.0, 0.05, omega.shape)]), delimiter=",",
               header="t,wx,wy,wz", comments="")
    # without the bias: a fitted constant offset absorbs much of a decay this slow (T -2 %/s left)
    done = kreisel("fit", path, "--no-bias")
    assert done.returncode == 1, done.stdout + done.stderr
    assert "free rotation explains the data" not in done.stdout + done.stderr
    assert "warning: free rotation does not explain the data" in done.stderr
    assert "energy T falls" in done.stderr and "air drag" in done.stderr
