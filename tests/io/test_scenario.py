"""Scenario files: every bundled example validates; every defect is named with file, key and line."""

import numpy as np
import pytest

import kreisel as kr
from kreisel.io import EXAMPLES, ScenarioError, example_path, load_scenario, parse_scenario, run_scenario

@pytest.mark.parametrize("name", EXAMPLES)
def test_bundled_examples_validate(name):
    scenario = load_scenario(example_path(name))
    assert scenario.kind in ("rigid_body", "foucault", "coning")
    assert scenario.title


def test_defaults_are_filled(racket_toml):
    s = parse_scenario(racket_toml)
    assert s.data["integration"]["t_start"] == 0.0
    assert s.data["initial"]["frame"] == "body"
    np.testing.assert_array_equal(s.data["body"]["moments"], [1.0, 2.0, 3.0])


@pytest.mark.parametrize("edit, message", [
    (("moments = [1.0, 2.0, 3.0]", "moments = [1.0, 2.0, 3.0]\ncolour = 'red'"), r"<scenario>:4: body.colour: unknown key"),
    (("t_end = 10.0", "t_end = 'long'"), r"<scenario>:\d+: integration.t_end: expected a finite number"),
    (("t_end = 10.0", "t_end = -5.0"), r"integration.t_end: must be positive"),
    (("n_samples = 101", "n_samples = 5.5"), r"integration.n_samples: expected an integer"),
    (("omega = [0.01, 1.0, 0.01]", "omega = [0.01, 1.0]"), r"initial.omega: expected a list of 3"),
    (("omega = [0.01, 1.0, 0.01]", "omega = [0.01, true, 0.01]"), r"initial.omega: expected a list of 3"),
    (("omega = [0.01, 1.0, 0.01]", "frame = 'body'"), r"missing required key 'omega'"),
    (("moments = [1.0, 2.0, 3.0]", "moments = [1.0, 1.0, 3.0]"), r"body.moments: not a physical rigid body"),
    (("moments = [1.0, 2.0, 3.0]", "moments = [1.0, 2.0, 3.0]\nshape = 'box'"), r"exactly one of moments, tensor"),
    (("t_end = 10.0", "t_end = 10.0\nmethod = 'leapfrog'"), r"integration.method: expected one of"),
    (("[body]", "kind = 'coning'\n[body]"), r"kind = 'coning' needs a \[coning\] table"),
])
def test_defects_are_named(racket_toml, edit, message):
    old, new = edit
    with pytest.raises(ScenarioError, match=message):
        parse_scenario(racket_toml.replace(old, new))


def test_syntax_error_and_missing_file(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[body\nmoments = 1")
    with pytest.raises(ScenarioError, match="bad.toml"):
        load_scenario(bad)
    with pytest.raises(ScenarioError, match="absent.toml: no such file, and no bundled scenario of that name"):
        load_scenario(tmp_path / "absent.toml")


def test_torque_entries_are_checked(racket_toml):
    text = racket_toml + "\n[[torque]]\nkind = 'gravity'\nweight = 1.0\n"
    with pytest.raises(ScenarioError, match=r"torque\[0\].kind: torque kind 'gravity' needs 'lever'"):
        parse_scenario(text)
    with pytest.raises(ScenarioError, match=r"torque\[0\].torque: not used by torque kind 'gravity'"):
        parse_scenario(text + "lever = [0, 0, 1]\ntorque = [1, 0, 0]\n")


def test_rigid_body_run_matches_the_exact_top(racket_toml):
    traj = run_scenario(parse_scenario(racket_toml))
    exact = kr.EulerTop(1.0, 2.0, 3.0).solve(traj.t, [0.01, 1.0, 0.01])
    np.testing.assert_allclose(traj.omega, exact.omega, atol=1e-9)


def test_space_frame_omega_and_euler_attitude_are_converted(racket_toml):
    text = racket_toml.replace("omega = [0.01, 1.0, 0.01]", "omega = [0.0, 0.0, 2.0]\nframe = 'space'\n"
                        "[initial.attitude]\neuler = [0.0, 90.0, 0.0]\nseq = 'ZXZ'\ndegrees = true")
    traj = run_scenario(parse_scenario(text))
    # body z is space -y; space ω = 2 e_z is body (0, 2, 0), a steady rotation about axis 2
    np.testing.assert_allclose(traj.omega[0], [0.0, 2.0, 0.0], atol=1e-14)
    np.testing.assert_allclose(traj.q[0], kr.euler_to_quat("ZXZ", [0.0, np.pi / 2, 0.0]), atol=1e-15)


def test_shape_body_and_gravity_torque_conserve_the_lagrange_constants():
    text = """
[body]
shape = "solid_cylinder"
radius = 0.5
height = 0.2
mass = 2.0
[initial]
omega = [0.0, 0.0, 20.0]
[initial.attitude]
euler = [0.0, 0.5, 0.0]
[[torque]]
kind = "gravity"
weight = 1.0
lever = [0.0, 0.0, 0.1]
[integration]
t_end = 3.0
n_samples = 31
"""
    traj = run_scenario(parse_scenario(text))
    # J3 and Jz are conserved under gravity about the pivot for a symmetric body
    j3 = traj.angular_momentum_body[:, 2]
    jz = traj.angular_momentum_space[:, 2]
    np.testing.assert_allclose(j3, j3[0], rtol=1e-10)
    np.testing.assert_allclose(jz, jz[0], rtol=1e-9)


def test_foucault_and_coning_scenarios_run():
    foucault = run_scenario(parse_scenario(
        "kind = 'foucault'\n[foucault]\nlength = 1.0\nlatitude_deg = 45.0\nduration = 300.0\n"
        "amplitude = 0.05\nomega = 0.01\n"))
    assert foucault.attrs["precession_rate_measured"] == pytest.approx(foucault.attrs["precession_rate_theory"],
                                                                       rel=0.02)
    coning = run_scenario(parse_scenario(
        "kind = 'coning'\n[coning]\nhalf_angle_deg = 1.0\nrate_hz = 1.0\nsample_time = 0.02\nn_samples = 1000\n"
        "samples_per_update = 1\n"))
    drift = np.linalg.norm(coning["attitude_error"].values[-1]) / float(coning["time"].values[-1])
    assert drift == pytest.approx(coning.attrs["drift_theory"], rel=0.03)
