"""A run nobody would wait for is refused after a measured moment, naming its estimate and --force."""

import os
import pathlib
import re
import subprocess
import sys

import kreisel as kr

SRC = pathlib.Path(kr.__file__).resolve().parents[1]


def test_a_run_of_days_is_refused_with_its_estimate(tmp_path, racket_toml):
    scenario = tmp_path / "long.toml"
    scenario.write_text(racket_toml.replace("t_end = 10.0", "t_end = 1e9")
                        + '[[torque]]\nkind = "gravity"\nweight = 1.0\nlever = [0.0, 0.0, 1.0]\n')
    env = dict(os.environ, PYTHONPATH=str(SRC), COLUMNS="300")
    done = subprocess.run([sys.executable, "-m", "kreisel", "simulate", scenario, "-o", tmp_path / "t.nc"],
                          env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 2, (done.stdout, done.stderr)
    message = done.stderr.strip().splitlines()[-1]
    assert re.search(r"long\.toml: the run needs about [\d.]+ (h|days|years) of computing \(it covered \S+ of its "
                     r"time span in [\d.]+ s\), over the 10 min kreisel runs unasked; shorten integration\.t_end, "
                     r"or pass --force to run it anyway", message), message
    assert not (tmp_path / "t.nc").exists() and done.stdout == ""
