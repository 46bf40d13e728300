"""The viewer's JSON API through FastAPI's test client (no browser, no network)."""


import numpy as np
import pytest

from kreisel.io import parse_scenario
from kreisel.web.presets import PRESETS
from kreisel.web.session import MAX_SAMPLES, form_fields, scenario_toml

TENNIS = {"moments": [1.0, 2.0, 3.0], "omega": [0.01, 1.0, 0.01], "t_end": 20.0, "n_samples": 201,
          "method": "dop853"}
LAGRANGE = {"moments": [1.0, 1.0, 0.5], "omega": [0.0, 0.0, 6.0], "euler_deg": [0.0, 30.0, 0.0], "mgl": 1.0,
            "t_end": 5.0, "n_samples": 101}


@pytest.fixture(scope="module")
def client(app_client):
    return app_client()


def test_presets_list_and_text(client):
    listed = client.get("/api/presets").json()
    assert [p["name"] for p in listed] == list(PRESETS)
    assert all(p["title"] and p["description"] for p in listed)
    assert "[body]" in client.get("/api/presets/tennis_racket").json()["toml"]
    assert client.get("/api/presets/nope").status_code == 404


def test_free_body_run_conserves_and_reports_analysis(client):
    data = client.post("/api/run", json={"form": TENNIS}).json()
    t, q, omega = (np.array(data[k]) for k in ("t", "q", "omega"))
    assert t.shape == (201,) and q.shape == (201, 4) and omega.shape == (201, 3)
    np.testing.assert_allclose(np.linalg.norm(q, axis=1), 1.0, atol=1e-12)
    assert data["energy"][0] == pytest.approx(0.5 * (1e-4 + 2.0 + 3e-4), rel=1e-14)
    integrals = {i["name"]: i for i in data["integrals"]}
    assert list(integrals) == ["T", "J"]  # the free body's first integrals: T and the space vector J
    assert integrals["T"]["initial"] == pytest.approx(1.0002, rel=1e-14)
    assert integrals["T"]["relative"] < 1e-9 and integrals["J"]["relative"] < 1e-9
    # omega_space = R omega_body: |omega| is frame independent
    np.testing.assert_allclose(np.linalg.norm(data["omega_space"], axis=1), np.linalg.norm(omega, axis=1), rtol=1e-12)
    info = data["analysis"]
    assert info["J_norm"] == pytest.approx(np.sqrt(1e-4 + 4.0 + 9e-4), rel=1e-14)
    assert [s["kind"] for s in info["stability"]] == ["stable", "unstable", "stable"]
    # middle-axis growth rate sqrt((I2 - I1)(I3 - I2) / (I1 I3)) |omega| (Theory §5.4)
    assert info["stability"][1]["growth_rate"] == pytest.approx(np.sqrt(1 / 3) * np.linalg.norm(omega[0]), rel=1e-12)
    assert info["lagrange"] is None
    assert data["form"]["moments"] == TENNIS["moments"]


def test_heavy_top_energy_includes_gravity_and_turning_points(client):
    data = client.post("/api/run", json={"form": LAGRANGE}).json()
    # released at theta = 30 degrees with pure spin: E = ½ I3 ω3² + mgl cos θ, and theta_min is the start
    assert data["energy"][0] == pytest.approx(0.5 * 0.5 * 36 + np.cos(np.pi / 6), rel=1e-14)
    integrals = {i["name"]: i for i in data["integrals"]}
    assert list(integrals) == ["E", "J_z", "J_3"]  # the Lagrange top's: E = T + V, J_z and J_3
    assert integrals["E"]["initial"] == pytest.approx(data["energy"][0], rel=1e-15)
    assert integrals["J_3"]["initial"] == pytest.approx(0.5 * 6.0, rel=1e-14)
    assert all(i["relative"] < 1e-8 for i in integrals.values())
    lagrange = data["analysis"]["lagrange"]
    assert lagrange["apex_locus"] == "cusp"
    assert lagrange["theta_min_deg"] == pytest.approx(30.0, abs=1e-9)
    assert lagrange["theta_max_deg"] > 30.0
    assert lagrange["sleeping_threshold_omega3"] == pytest.approx(4.0)  # omega3 > 2 sqrt(I1 mgl) / I3 (Theory §6.6)
    tilt = np.degrees(np.arccos(np.clip([2 * (q[0] ** 2 + q[3] ** 2) - 1 for q in data["q"]], -1, 1)))
    assert tilt.min() >= 30.0 - 1e-6 and tilt.max() <= lagrange["theta_max_deg"] + 1e-6


def test_every_preset_runs(client):
    for name in ("symmetric_top", "lagrange_loops", "kovalevskaya"):
        data = client.post("/api/run", json={"preset": name}).json()
        assert len(data["t"]) > 10, name
    kovalevskaya = client.post("/api/run", json={"preset": "kovalevskaya"}).json()
    integrals = {i["name"]: i for i in kovalevskaya["integrals"]}
    assert list(integrals) == ["E", "J_z", "K"] and integrals["K"]["relative"] < 1e-8
    # K from its definition at the first sample: (p² − q² − c γ1)² + (2pq − c γ2)², c = mgl / I3 = 1
    p, q_, _ = kovalevskaya["omega"][0]
    w, x, y, z = kovalevskaya["q"][0]
    gamma1, gamma2 = 2 * (x * z - w * y), 2 * (y * z + w * x)  # third row of R: R^T e_z
    assert integrals["K"]["initial"] == pytest.approx((p * p - q_ * q_ - gamma1) ** 2 + (2 * p * q_ - gamma2) ** 2,
                                                      rel=1e-12)
    loops = client.post("/api/run", json={"preset": "lagrange_loops"}).json()
    assert loops["analysis"]["lagrange"]["apex_locus"] == "loop"
    from kreisel.web.presets import preset_text

    short = preset_text("foucault").replace("duration = 3600.0", "duration = 600.0")
    foucault = client.post("/api/run", json={"toml": short}).json()
    info = foucault["analysis"]
    assert info["precession_rate_measured"] == pytest.approx(info["precession_rate_theory"], rel=2e-3)


@pytest.mark.parametrize(("body", "status", "words"), [
    ({"form": dict(TENNIS, n_samples=MAX_SAMPLES + 1)}, 422, "at most"),
    ({"form": dict(TENNIS, method="rk4", dt=1e-9)}, 422, "steps is too many"),
    ({"form": dict(TENNIS, t_end=1e9)}, 422, "turns"),
    # an integer past int64 (JSON has no limit): refused as more than memory holds, not a server error
    ({"form": dict(TENNIS, n_samples=10**30)}, 400, "integration.n_samples: expected at most"),
    # torques speed the body up: refused before the run instead of after a minute at the step budget
    ({"form": dict(TENNIS, mgl=1e300)}, 422, "turns of the body requested (with gravity's rate)"),
    ({"toml": "[body]\nmoments = [1.0, 2.0, 3.0]\n[initial]\nomega = [0, 0, 1]\n[[torque]]\n"
              "kind = 'constant_body'\ntorque = [0.0, 0.0, 1e9]\n[integration]\nt_end = 10.0\n"},
     422, "turns of the body requested (with the torque's spin-up)"),
    ({"form": dict(TENNIS, moments=[1.0, 1.0, 3.0])}, 400, "not a physical rigid body"),
    ({"form": dict(TENNIS, method="euler")}, 422, "form.method"),
    ({"toml": "[body]\nmesh = '/etc/passwd'\ndensity = 1.0\n[initial]\nomega = [0, 0, 1]\n"
              "[integration]\nt_end = 1.0\n"}, 422, "mesh"),
    ({"toml": "not toml ["}, 400, "<scenario>"),
    ({"preset": "tennis_racket", "toml": "x"}, 400, "exactly one"),
])
def test_bad_requests_are_refused_with_a_reason(client, body, status, words):
    response = client.post("/api/run", json=body)
    assert response.status_code == status
    assert words in response.json()["detail"]


def test_form_toml_round_trip():
    form = dict(LAGRANGE, method="rk4", dt=0.001, lever_axis=2, title="My top")
    scenario = parse_scenario(scenario_toml(form))
    back = form_fields(scenario)
    for key in ("moments", "omega", "mgl", "method", "t_end", "n_samples", "dt", "title"):
        assert back[key] == pytest.approx(form[key]) if isinstance(form[key], (float, list)) else back[key] == form[key]
    np.testing.assert_allclose(back["euler_deg"], form["euler_deg"], atol=1e-12)


def test_export_trajectory_and_scenario(client, tmp_path):
    from kreisel.io import load_trajectory

    response = client.post("/api/export?format=nc", json={"form": TENNIS})
    assert response.status_code == 200
    assert response.headers["content-disposition"].endswith('.nc"')
    path = tmp_path / "run.nc"
    path.write_bytes(response.content)
    traj = load_trajectory(path)
    ran = client.post("/api/run", json={"form": TENNIS}).json()
    np.testing.assert_allclose(traj.q, ran["q"], rtol=0, atol=1e-15)
    csv = client.post("/api/export?format=csv", json={"preset": "symmetric_top"})
    assert csv.status_code == 200 and csv.text.startswith("t,q0,q1,q2,q3,omega_1")  # plain CSV
    (tmp_path / "run.csv").write_bytes(csv.content)  # downloaded alone, without the sidecar kreisel writes
    with pytest.warns(UserWarning, match="inertia recovered from the J and ω′ columns"):
        top = load_trajectory(tmp_path / "run.csv")
    np.testing.assert_allclose(np.linalg.eigvalsh(top.inertia), [1.0, 1.0, 2.0], rtol=1e-12)  # the symmetric top's
    assert client.post("/api/export?format=exe", json={"form": TENNIS}).status_code == 422
    assert client.post("/api/export", json={"preset": "foucault"}).status_code == 400
    toml = client.post("/api/scenario", json={"form": TENNIS}).json()["toml"]
    assert parse_scenario(toml).data["body"]["moments"].tolist() == TENNIS["moments"]


def test_initial_scenario_and_index(app_client):
    from kreisel.web.presets import preset_text

    client = app_client(preset_text("sleeping_top"))
    assert "Sleeping top" in client.get("/api/initial").json()["toml"]
    page = client.get("/")
    assert page.status_code in (200, 503)
    assert "kreisel viewer" in page.text


def test_serve_checks_its_arguments(tmp_path):
    from kreisel.web import serve

    bad = tmp_path / "bad.toml"
    bad.write_text("[body]\nmoments = [1, 2]\n")
    with pytest.raises(ValueError, match=r"bad.toml:2: body.moments"):  # the file by name, as simulate says it
        serve(bad, open_browser=False)
    with pytest.raises(ValueError, match="missing.toml: no such file, and no bundled scenario of that name"):
        serve(tmp_path / "missing.toml", open_browser=False)
    with pytest.raises(ValueError, match="port"):
        serve(port=70000, open_browser=False)


def test_a_scenario_with_an_integer_too_long_to_convert_is_a_400_in_one_line(client):
    from kreisel.web.presets import preset_text

    text = preset_text("tennis_racket").replace("n_samples = 2001", "n_samples = " + "9" * 5000)
    response = client.post("/api/scenario", json={"toml": text})
    assert response.status_code == 400, response.text
    detail = response.json()["detail"]
    assert "integration.n_samples: expected a number, got an integer of 5000 digits" in detail and "\n" not in detail
