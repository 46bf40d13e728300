"""first_integrals: the model's conserved quantities, checked against the tops' own closed forms."""

import numpy as np
import pytest

import kreisel as kr
from kreisel.dynamics import ConstantTorque, GravityTorque, LinearDamping
from kreisel.tops import first_integrals


def _state_of(traj, k):
    """ZXZ angles and their rates of sample k, from the attitude and body ω (Theory §3.6)."""
    euler = kr.quat_to_euler("ZXZ", traj.q[k])
    rates = kr.euler_rates("ZXZ", euler, traj.omega[k], frame="body")
    return euler, rates


def test_lagrange_top_integrals_match_the_closed_form_constants():
    top = kr.LagrangeTop(1.0, 0.5, 2.0)
    gravity = GravityTorque(2.0, [0.0, 0.0, 1.0])
    q0 = kr.euler_to_quat("ZXZ", [0.3, 0.7, -0.2])
    traj = kr.simulate([1.0, 1.0, 0.5], np.linspace(0.0, 4.0, 41), [0.4, -0.3, 9.0], q0=q0, torque=gravity)
    found = first_integrals(traj, gravity)
    assert found.model == "heavy symmetric (Lagrange) top"
    values = {f.symbol: f.values for f in found}
    for k in (0, 17, 40):
        constants = top.constants(*_state_of(traj, k))
        np.testing.assert_allclose([values["E"][k], values["J_z"][k], values["J_3"][k]],
                                   [constants.E, constants.Jz, constants.J3], rtol=1e-9)
    assert max(f.relative_change() for f in found) < 1e-9
    assert np.ptp(traj.energy) > 1e-2   # T alone changes


def test_kovalevskaya_integrals_match_the_top_and_survive_a_rotated_lever():
    top = kr.KovalevskayaTop(1.0, 1.5)
    q0 = kr.euler_to_quat("ZXZ", [0.0, 0.7, 0.35])
    t = np.linspace(0.0, 5.0, 51)
    along_x = GravityTorque(1.5, [1.0, 0.0, 0.0])
    traj = kr.simulate([2.0, 2.0, 1.0], t, [0.3, 0.7, 1.5], q0=q0, torque=along_x)
    found = first_integrals(traj, along_x)
    assert found.model == "Kovalevskaya top" and [f.symbol for f in found] == ["E", "J_z", "K"]
    up = kr.quat_apply(traj.q, [0.0, 0.0, 1.0], inverse=True)
    reference = top.integrals(traj.omega, up)
    np.testing.assert_allclose(found.integrals[2].values, reference.kovalevskaya, rtol=1e-12)
    np.testing.assert_allclose(found.integrals[0].values, reference.energy, rtol=1e-12)
    # the same body with its centre of mass at 40° in the equatorial plane: K in the turned axes
    turn = kr.rotvec_to_quat([0.0, 0.0, np.radians(40.0)])
    lever = kr.quat_apply(turn, [1.0, 0.0, 0.0])
    tilted = GravityTorque(1.5, lever)
    q_turned = kr.quat_multiply(q0, kr.quat_conjugate(turn))
    turned = kr.simulate([2.0, 2.0, 1.0], t, kr.quat_apply(turn, [0.3, 0.7, 1.5]), q0=q_turned, torque=tilted)
    np.testing.assert_allclose(first_integrals(turned, tilted).integrals[2].values, reference.kovalevskaya,
                               rtol=1e-8, atol=1e-12)


def test_free_body_and_driven_body():
    traj = kr.EulerTop(1.0, 2.0, 3.0).solve(np.linspace(0.0, 10.0, 101), [0.01, 1.0, 0.01])
    free = first_integrals(traj)
    assert free.model == "free body" and [f.symbol for f in free] == ["T", "J"]
    np.testing.assert_allclose(free.integrals[1].initial, [0.01, 2.0, 0.03])
    assert max(f.relative_change() for f in free) < 1e-12
    assert first_integrals(traj, GravityTorque(0.0, [0.0, 0.0, 1.0])).model == "free body"
    for torque in (LinearDamping(0.1), ConstantTorque([0.0, 0.0, 1.0]), GravityTorque(1.0, [0, 0, 1]) + LinearDamping(1)):
        assert first_integrals(traj, torque).model == "driven body" and len(first_integrals(traj, torque)) == 0


@pytest.mark.parametrize("lever, model", [([0.0, 0.3, 0.0], "heavy top"), ([0.0, 0.0, 0.3], "heavy symmetric (Lagrange) top")])
def test_j3_only_when_the_lever_is_on_the_symmetry_axis(lever, model):
    gravity = GravityTorque(1.0, lever)
    traj = kr.simulate([1.0, 1.0, 1.8], np.linspace(0.0, 2.0, 21), [0.2, 0.1, 3.0], torque=gravity)
    found = first_integrals(traj, gravity)
    assert found.model == model
    assert max(f.relative_change() for f in found) < 1e-9
