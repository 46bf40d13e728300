"""Scenario files: every bundled example validates; every defect is named with file, key and line."""

import json
import math
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

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


def _simulate(tmp_path, text, name="s.toml"):
    """``kreisel simulate`` of scenario ``text`` as a user runs it: the completed process."""
    (tmp_path / name).write_text(text, encoding="utf-8")
    src = pathlib.Path(kr.__file__).resolve().parents[1]
    return subprocess.run([sys.executable, "-m", "kreisel", "simulate", name], cwd=tmp_path, capture_output=True,
                          text=True, timeout=600, env=dict(os.environ, PYTHONPATH=str(src), COLUMNS="200"))


def _one_line(process, start):
    assert process.returncode == 2, (process.stdout, process.stderr)
    assert "Traceback" not in process.stderr and process.stderr.count("\n") == 1, process.stderr
    assert process.stderr.startswith("error: " + start), process.stderr
    return process.stderr


ATTITUDE = "omega = [0.01, 1.0, 0.01]\n[initial.attitude]\n"


@pytest.mark.parametrize("edit, start, hint", [
    # more digits than Python converts to an int: a 63-line traceback from inside tomllib
    (("n_samples = 101", "n_samples = " + "9" * 5000), "s.toml:8: integration.n_samples: expected a number",
     "integer of 5000 digits"),
    (("moments = [1.0, 2.0, 3.0]", "moments = [1.0, 2.0,\n  " + "3" * 5000 + "]"),
     "s.toml:3: body.moments: expected a number", "at most"),
    # 30 rad for what was meant as 30 degrees
    (("omega = [0.01, 1.0, 0.01]\n", ATTITUDE + "euler = [0, 30, 0]\n"), "s.toml:7: initial.attitude.euler: expected",
     "set degrees = true"),
    (("omega = [0.01, 1.0, 0.01]\n", ATTITUDE + "quat = [1, 0.2, 0, 0]\n"), "s.toml:7: initial.attitude.quat: expected",
     "norm 1.0198039"),
    (("n_samples = 101", "n_samples = 1"), "s.toml:8: integration.n_samples: must be at least 2", "got 1"),
])
def test_scenario_traps_are_one_line_naming_file_line_and_key(tmp_path, racket_toml, edit, start, hint):
    assert hint in _one_line(_simulate(tmp_path, racket_toml.replace(*edit)), start)


def test_angles_and_quaternions_within_the_limits_still_run(racket_toml):
    for attitude in ("euler = [0, 6.28, -6.28]", "euler = [0, 30, 0]\ndegrees = true", "quat = [0.7071068, 0, 0, 0.7071068]"):
        scenario = parse_scenario(racket_toml.replace("omega = [0.01, 1.0, 0.01]\n", ATTITUDE + attitude + "\n"))
        assert scenario.data["initial"]["attitude"]
    with pytest.raises(ScenarioError, match=r"<scenario>:7: initial\.attitude\.quat: .* of norm 0\.99999041"):
        parse_scenario(racket_toml.replace("omega = [0.01, 1.0, 0.01]\n", ATTITUDE + "quat = [0.7071, 0, 0, 0.7071]\n"))


def test_a_run_that_would_not_fit_in_memory_is_refused_at_once_naming_size_and_remedy(tmp_path, racket_toml):
    from kreisel._validation import memory_budget

    # the user's 1e8 samples ran 82 s to a 17.5 GB peak; on a larger machine ask for more than fits
    n = max(10**8, memory_budget() // 192 + 1)
    process = _simulate(tmp_path, racket_toml.replace("n_samples = 101", f"n_samples = {n}"))
    message = _one_line(process, "s.toml:8: integration.n_samples: expected at most ")
    assert f"{n} samples would need" in message and "lower n_samples" in message
    coning = "kind = 'coning'\n[coning]\nhalf_angle_deg = 1.0\nrate_hz = 1.0\nsample_time = 0.01\nn_samples = 1\n"
    with pytest.raises(ScenarioError, match=r"<scenario>:6: coning\.n_samples: expected at least samples_per_update"):
        parse_scenario(coning)


class _Literal(str):
    """TOML text written as it is (an integer too long for Python to convert)."""


def _toml(value):
    """``value`` written as a TOML value (strings as JSON writes them, which TOML reads alike)."""
    if isinstance(value, _Literal):
        return value
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf") if math.isinf(value) else repr(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k} = {_toml(v)}" for k, v in value.items()) + "}"
    return "[" + ", ".join(map(_toml, value)) + "]"


# every key of a rigid-body and a coning scenario with a good value, table by table
_GOOD = {
    "rigid": {"": {"title": '"t"', "kind": '"rigid_body"'},
              "body": {"moments": "[1.0, 2.0, 3.0]", "mass": "1.0"},
              "initial": {"omega": "[0.01, 1.0, 0.01]", "frame": '"body"'},
              "initial.attitude": {"euler": "[0.1, 0.2, 0.3]", "seq": '"ZXZ"', "degrees": "false"},
              "[torque]": {"kind": '"gravity"', "weight": "1.0", "lever": "[0.0, 0.0, 0.1]"},
              "integration": {"t_end": "1.0", "t_start": "0.0", "n_samples": "11", "method": '"rk4"', "dt": "0.01"}},
    "coning": {"": {"kind": '"coning"'},
               "coning": {"half_angle_deg": "1.0", "rate_hz": "1.0", "sample_time": "0.01", "n_samples": "100",
                          "samples_per_update": "2"}},
}
_SCALARS = (st.integers(min_value=-10**30, max_value=10**30) | st.floats() | st.booleans() | st.text(max_size=6)
            | st.sampled_from(["ZXZ", "body", "space", "gravity", "rk4", "dop853", _Literal("9" * 5000), 1e308, -0.0, 2**63]))
_VALUES = st.recursive(_SCALARS, lambda inner: st.lists(inner, max_size=4)
                       | st.dictionaries(st.from_regex(r"[a-z]{1,3}", fullmatch=True), inner, max_size=2), max_leaves=10)


@settings(max_examples=300, deadline=None)
@given(data=st.data())
def test_any_value_of_any_scenario_key_is_accepted_or_refused_in_one_line(data):
    tables = _GOOD[data.draw(st.sampled_from(sorted(_GOOD)), label="scenario")]
    table = data.draw(st.sampled_from(sorted(tables)), label="table")
    key = data.draw(st.sampled_from(sorted(tables[table])), label="key")
    value = data.draw(_VALUES, label="value")
    lines = []
    for name, keys in tables.items():
        if name:
            lines.append(f"[{name}]")
        lines += [f"{k} = {_toml(value) if (name, k) == (table, key) else good}" for k, good in keys.items()]
    try:
        parse_scenario("\n".join(lines) + "\n", "s.toml")
    except ScenarioError as exc:
        assert str(exc).startswith("s.toml") and "\n" not in str(exc), str(exc)
