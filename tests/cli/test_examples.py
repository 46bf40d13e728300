"""``kreisel examples`` lists everything bundled, and ``kreisel plot`` draws a recording, as a user runs them."""

import pathlib

import numpy as np
from PIL import Image

import kreisel as kr
from kreisel.io.gyro import recording_path


def test_examples_lists_scenarios_the_recording_and_the_sweeps(kreisel):
    done = kreisel("examples")
    assert done.returncode == 0, done.stderr
    headings = [line for line in done.stdout.splitlines() if line and not line.startswith(" ")]
    assert [h.split(" (")[0] for h in headings] == ["scenarios", "gyroscope recordings", "IMU recordings", "sweeps"]
    recordings = done.stdout.split("gyroscope recordings")[1].split("IMU recordings")[0]
    assert "phone_toss" in recordings and "tossed about its middle axis" in recordings
    sweeps = done.stdout.split("\nsweeps")[1]
    for name in ("tennis_racket", "lagrange_apex", "imu_monte_carlo"):
        assert f"  {name}" in sweeps


def test_examples_copies_the_recording_out(kreisel, tmp_path):
    done = kreisel("examples", "phone_toss", "--to", tmp_path)
    assert done.returncode == 0 and done.stdout.strip() == f"wrote {tmp_path / 'phone_toss.csv'}", done.stderr
    assert (tmp_path / "phone_toss.csv").read_bytes() == recording_path("phone_toss").read_bytes()
    again = kreisel("examples", "phone_toss", "--to", tmp_path)
    assert again.returncode == 2 and "already exists; pass --force" in again.stderr


def test_examples_makes_the_to_directory_as_the_cli_reference_shows(kreisel, tmp_path):
    """`kreisel examples lagrange_cusps --to scenarios/`, the reference's example, said the directory did not exist."""
    done = kreisel("examples", "lagrange_cusps", "--to", "scenarios/", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    copied = tmp_path / "scenarios" / "lagrange_cusps.toml"
    assert copied.read_text(encoding="utf-8") == kr.io.example_path("lagrange_cusps").read_text(encoding="utf-8")
    nested = kreisel("examples", "phone_toss", "--to", tmp_path / "a" / "b")
    assert nested.returncode == 0 and (tmp_path / "a" / "b" / "phone_toss.csv").is_file(), nested.stderr


def test_examples_refuses_a_file_as_the_to_directory_and_makes_nothing_for_a_bad_name(kreisel, tmp_path):
    (tmp_path / "notes.txt").write_text("mine", encoding="utf-8")
    done = kreisel("examples", "tennis_racket", "--to", tmp_path / "notes.txt")
    assert done.returncode == 2 and "is a file; name the directory to copy into" in done.stderr
    assert (tmp_path / "notes.txt").read_text(encoding="utf-8") == "mine"
    wrong = kreisel("examples", "tenis_racket", "--to", tmp_path / "new")
    assert wrong.returncode == 2 and "did you mean 'tennis_racket'" in wrong.stderr
    assert not (tmp_path / "new").exists()


def test_examples_names_a_sweeps_file_instead_of_no_such_example(kreisel, tmp_path):
    done = kreisel("examples", "imu_monte_carlo", "--to", tmp_path)
    assert done.returncode == 2 and not list(tmp_path.iterdir())
    assert "'imu_monte_carlo' is a bundled sweep, which `kreisel sweep imu_monte_carlo` runs" in done.stderr
    named = pathlib.Path(done.stderr.split("to edit it, copy ")[1].strip())
    assert named.name == "imu_monte_carlo.toml"
    assert 'description = "Monte Carlo of strapdown attitude' in named.read_text(encoding="utf-8")


def test_plot_draws_a_recordings_rates_and_the_fit_window(kreisel, tmp_path):
    t = np.linspace(0.0, 1.0, 201)
    rates = np.degrees(kr.EulerTop(0.2, 0.8, 1.0).omega(t, [0.5, 6.0, 0.3]))
    table = tmp_path / "deg.csv"
    np.savetxt(table, np.column_stack([t, rates]), delimiter=",", header="time,gx (deg/s),gy (deg/s),gz (deg/s)", comments="")
    for args in ((table,), (table, "--start", "0.2", "--stop", "0.6"), ("phone_toss", "--kind", "rates")):
        figure = tmp_path / "rates.png"
        done = kreisel("plot", *args, "-o", figure, "--force")
        assert done.returncode == 0 and done.stdout.strip() == f"wrote {figure}", done.stderr
        assert Image.open(figure).size[0] > 500
    outside = kreisel("plot", table, "--start", "2", "-o", tmp_path / "x.png")
    assert outside.returncode == 2 and "holds no sample: the record spans t = 0 … 1 s" in outside.stderr
    wrong = kreisel("plot", table, "--kind", "apex", "-o", tmp_path / "x.png")
    assert wrong.returncode == 2 and "a gyroscope recording, which plots as rates" in wrong.stderr


def test_plot_of_neither_a_result_nor_a_recording_says_both(kreisel, tmp_path):
    junk = tmp_path / "notes.csv"
    junk.write_text("shopping list\nmilk, eggs\n")
    done = kreisel("plot", junk, "-o", tmp_path / "x.png")
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert "nor is it a gyroscope recording" in done.stderr, done.stderr
