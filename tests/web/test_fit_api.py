"""The viewer's recording fit: POST /api/fit and the recording given to ``kreisel serve --recording``."""

import json
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest
from fastapi.testclient import TestClient

import kreisel as kr
from kreisel.web import create_app

from .conftest import authorization

PHONE = kr.io.recording_path("phone_toss")


def local(app):
    return TestClient(app, base_url="http://127.0.0.1", headers=authorization(app))


@pytest.fixture(scope="module")
def client():
    return local(create_app())


def test_fit_upload_replays_the_fitted_body_through_the_data(client):
    reply = client.post("/api/fit", json={"text": PHONE.read_text(), "name": "Gyroscope.csv"})
    assert reply.status_code == 200, reply.text
    data = reply.json()
    t, q, omega, measured = (np.array(data[k]) for k in ("t", "q", "omega", "omega_measured"))
    recording = kr.io.read_gyro(PHONE)
    np.testing.assert_array_equal(t, recording.t)
    assert q.shape == (t.size, 4) and omega.shape == measured.shape == (t.size, 3)
    fit = data["fit"]
    assert fit["intermediate_axis"] == "x" and fit["free_rotation"]
    # the fitted body's ω′ follows the measurement (bias removed) to the noise level
    assert np.sqrt(np.mean((omega - measured) ** 2)) == pytest.approx(fit["rms"], rel=1e-6)
    assert data["kind"] == "rigid_body" and data["method"] == "exact"
    assert all(integral["relative"] < 1e-12 for integral in data["integrals"])


def test_fit_window_and_bias_options(client):
    text = PHONE.read_text()
    data = client.post("/api/fit", json={"text": text, "start": 4.4, "stop": 4.8, "bias": False}).json()
    assert 4.4 <= data["t"][0] and data["t"][-1] <= 4.8 and data["fit"]["bias"] == [0.0, 0.0, 0.0]


@pytest.mark.parametrize(
    "body, status, detail",
    [
        ({"text": "0 1 2 3\n0.1 1 x 3\n", "name": "bad.csv"}, 400, "bad.csv:2: not a number"),
        ({"text": "", "name": "empty.csv"}, 400, "empty.csv: empty"),
        ({"text": "0 0.1 0.2 0.3\n1 0.1 0.2 0.3\n", "name": "short.csv"}, 400, "short.csv: too few samples"),
        ({"name": "x.csv"}, 422, "text"),
        ({"text": "0 1 2 3\n", "bias": "yes"}, 422, "bias"),
    ],
)
def test_fit_refusals(client, body, status, detail):
    reply = client.post("/api/fit", json=body)
    assert reply.status_code == status
    assert detail in str(reply.json()["detail"])


def test_initial_recording():
    assert local(create_app()).get("/api/recording").json() is None
    data = local(create_app(recording=kr.io.read_gyro(PHONE))).get("/api/recording").json()
    assert data["fit"]["n_samples"] == len(data["t"]) and data["title"].endswith("phone_toss.csv")
    # the form shows the fitted body at the window's start, and running it replays the fit exactly
    form = data["form"]
    assert data["source"].endswith(PHONE.name) and form["moments"] == np.diag(data["inertia"]).tolist()
    assert form["omega"] == data["omega"][0] and form["n_samples"] == len(data["t"])
    client = local(create_app())
    replay = client.post("/api/run", json={"form": {**form, "n_samples": 101}, "exact": True}).json()
    np.testing.assert_allclose(replay["q"][-1], data["q"][-1], atol=1e-9)


def test_serve_refuses_an_unreadable_recording(tmp_path):
    from kreisel.web import serve

    with pytest.raises(ValueError, match="recording: cannot read"):
        serve(recording=tmp_path / "missing.csv", open_browser=False)
    bad = tmp_path / "bad.csv"
    bad.write_text("0 1 2\n")
    with pytest.raises(ValueError, match="recording: .*too few columns"):
        serve(recording=bad, open_browser=False)


def test_kreisel_fit_and_the_viewer_fit_a_recording_alike(tmp_path):
    # the reproducer: `kreisel serve --recording` fitted the gyro bias and `kreisel fit` did not, so one
    # recording gave two sets of moments
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(kr.__file__).resolve().parents[1]))
    for args, name in (((), "default.json"), (("--no-bias",), "no_bias.json")):
        done = subprocess.run([sys.executable, "-m", "kreisel", "fit", "phone_toss", *args, "--json",
                               str(tmp_path / name)], cwd=tmp_path, env=env, capture_output=True, text=True,
                              timeout=300)
        assert done.returncode == 0, done.stderr
    cli = json.loads((tmp_path / "default.json").read_text())
    viewer = local(create_app(recording=kr.io.read_gyro(PHONE))).get("/api/recording").json()["fit"]
    assert cli["moments"] == viewer["moments"] and cli["bias"] == viewer["bias"] and any(cli["bias"])
    assert json.loads((tmp_path / "no_bias.json").read_text())["bias"] == [0.0, 0.0, 0.0]
