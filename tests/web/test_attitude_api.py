"""``GET /api/recording`` with an IMU recording that has a reference: kreisel's estimate beside it, per sample."""

import numpy as np
import pytest

import kreisel as kr
from kreisel.io import ImuRecording


@pytest.fixture(scope="module")
def broad():
    return kr.io.read_imu(kr.io.recording_path("broad_07"))


@pytest.fixture(scope="module")
def replay(app_client, broad):
    client = app_client(recording=broad)
    response = client.get("/api/recording")
    assert response.status_code == 200, response.text
    return response.json()


def test_replay_is_the_estimate_and_the_reference_sample_for_sample(replay, broad):
    rate = (broad.t.size - 1) / (broad.t[-1] - broad.t[0])
    estimate = kr.nav.estimate_attitude(broad.omega, broad.accel, broad.mag, rate=rate)
    assert replay["kind"] == "attitude" and replay["method"] == "kreisel" and replay["magnetometer"]
    assert replay["rate"] == pytest.approx(285.714, rel=1e-5)
    # JSON carries doubles exactly: the page gets the estimator's numbers, not rounded ones
    np.testing.assert_array_equal(replay["t"], broad.t)
    np.testing.assert_array_equal(replay["q"], estimate.q)
    np.testing.assert_array_equal(replay["omega_norm"], np.linalg.norm(broad.omega, axis=1))
    lost = np.isnan(broad.reference).any(axis=1)
    assert lost.sum() == 791 and [row is None for row in replay["q_ref"]] == lost.tolist()
    np.testing.assert_array_equal([row for row in replay["q_ref"] if row is not None], broad.reference[~lost])
    angles = np.degrees(kr.nav.attitude_error_angles(estimate.q, broad.reference))
    for key, expected in zip(("total", "heading", "inclination"), angles):
        shown = np.array([np.nan if v is None else v for v in replay["error_deg"][key]])
        np.testing.assert_array_equal(shown, expected)
    rmse = kr.nav.attitude_error(estimate.q, broad.reference, broad.movement)
    assert [replay["rmse_deg"][k] for k in ("total", "heading", "inclination")] == list(rmse)
    assert replay["rmse_deg"]["over"] == "movement"


def test_the_recording_needs_the_token(app_client, broad):
    client = app_client(recording=broad)
    assert client.get("/api/recording", headers={"Authorization": ""}).status_code == 403
    assert client.get("/api/recording", headers={"Host": "evil.example"}).status_code == 403


def test_a_gyro_only_recording_is_still_fitted(app_client):
    data = app_client(recording=kr.io.read_gyro(kr.io.recording_path("phone_toss"))).get("/api/recording").json()
    assert data["kind"] == "rigid_body" and data["fit"]["intermediate_axis"] == "x"


def test_unevenly_spaced_samples_are_refused_with_the_place(app_client, broad):
    n = 400
    t = np.arange(n) / 100.0
    t[200:] += 0.5  # a half-second gap
    gap = ImuRecording(t, broad.omega[:n], broad.accel[:n], broad.mag[:n], source="gap.npz",
                       reference=broad.reference[1000:1000 + n])
    response = app_client(recording=gap).get("/api/recording")
    assert response.status_code == 400
    assert response.json()["detail"].startswith(
        "gap.npz: samples are not evenly spaced (interval 0.51 s after t = 1.99 s")
