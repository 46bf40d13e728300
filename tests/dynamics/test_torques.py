"""Torque models against independent formulas, and the heavy top's constants of motion."""

import numpy as np
import pytest

import kreisel as kr
from kreisel.dynamics import ConstantTorque, GravityTorque, LinearDamping, MagneticTorque

rng = np.random.default_rng(7)
Q = rng.normal(size=4)
Q /= np.linalg.norm(Q)
W = np.array([0.4, -1.2, 0.7])


def test_models_match_independent_formulas(tools):
    R = tools.rotation_matrix(Q)
    lever, dipole, field, c = np.array([0.1, -0.2, 0.5]), np.array([0.3, 0.0, 1.0]), np.array([1e-3, 2e-3, -5e-4]), np.array([1.0, -2.0, 0.5])
    np.testing.assert_allclose(GravityTorque(3.0, lever)(0.0, Q, W), np.cross(lever, R.T @ [0, 0, -3.0]), atol=1e-15)
    np.testing.assert_allclose(MagneticTorque(dipole, field)(0.0, Q, W), np.cross(dipole, R.T @ field), atol=1e-18)
    np.testing.assert_allclose(ConstantTorque(c, "space")(0.0, Q, W), R.T @ c, atol=1e-15)
    np.testing.assert_array_equal(ConstantTorque(c)(0.0, Q, W), c)
    D = np.array([[1.0, 0.2, 0.0], [0.2, 2.0, 0.1], [0.0, 0.1, 0.5]])
    np.testing.assert_allclose(LinearDamping(D)(0.0, Q, W), -D @ W, atol=1e-15)
    np.testing.assert_allclose(LinearDamping([1.0, 2.0, 3.0])(0.0, Q, W), -np.array([1, 2, 3.0]) * W)
    total = GravityTorque(3.0, lever) + ConstantTorque(c, "space") + LinearDamping(0.5)
    expected = np.cross(lever, R.T @ [0, 0, -3.0]) + R.T @ c - 0.5 * W
    np.testing.assert_allclose(total(0.0, Q, W), expected, atol=1e-15)
    assert len(total.models) == 3


@pytest.mark.parametrize("bad", [
    lambda: GravityTorque(-1.0, [0, 0, 1]),
    lambda: GravityTorque(1.0, [0, 1]),
    lambda: LinearDamping(-1.0),
    lambda: LinearDamping(np.ones((2, 2))),
    lambda: ConstantTorque([1, 0, 0], frame="lab"),
    lambda: MagneticTorque([1, 0, np.nan], [0, 0, 1]),
])
def test_models_refuse_bad_parameters(bad):
    with pytest.raises(ValueError):
        bad()


def test_damped_sphere_decays_exponentially():
    t = np.linspace(0, 3, 7)
    tr = kr.simulate([2.0, 2.0, 2.0], t, W, torque=LinearDamping(0.5))
    np.testing.assert_allclose(tr.omega, W * np.exp(-0.25 * t)[:, None], rtol=1e-11, atol=1e-14)
    # the closing implicit kick keeps kick-drift-kick second order for ω-dependent torques
    for method, tol in [("splitting", 1e-6), ("dmv", 1e-7), ("splitting4", 1e-12), ("rk4", 1e-12),
                        ("midpoint", 1e-7), ("rkmk4", 1e-12)]:
        tr = kr.simulate([2.0, 2.0, 2.0], t, W, torque=LinearDamping(0.5), method=method, dt=1e-3)
        np.testing.assert_allclose(tr.omega, W * np.exp(-0.25 * t)[:, None], rtol=tol)


def test_constant_body_torque_on_sphere_is_uniform_acceleration():
    t = np.linspace(0, 2, 5)
    m = np.array([0.2, -0.1, 0.4])
    tr = kr.simulate([2.0, 2.0, 2.0], t, W, torque=ConstantTorque(m))
    np.testing.assert_allclose(tr.omega, W + np.outer(t, m) / 2.0, rtol=1e-12, atol=1e-13)


def test_model_and_callable_agree_and_match_reference(tools):
    model = GravityTorque(2.0, [0.05, 0.0, 0.3]) + MagneticTorque([0.0, 1.0, 0.0], [0.3, 0.0, 0.1])

    def as_callable(t, q, w):
        R = tools.rotation_matrix(q)
        return np.cross([0.05, 0.0, 0.3], R.T @ [0, 0, -2.0]) + np.cross([0.0, 1.0, 0.0], R.T @ [0.3, 0.0, 0.1])

    t = np.linspace(0, 4, 9)
    a = kr.simulate([1.0, 1.5, 2.0], t, W, Q, torque=model)
    b = kr.simulate([1.0, 1.5, 2.0], t, W, Q, torque=as_callable)
    w_ref, q_ref = tools.reference([1.0, 1.5, 2.0], t, W, Q, torque=as_callable)
    np.testing.assert_allclose(a.omega, b.omega, atol=1e-11)
    np.testing.assert_allclose(a.omega, w_ref, atol=1e-10)
    assert tools.quat_distance(a.q, q_ref).max() < 1e-10
    c = kr.simulate([1.0, 1.5, 2.0], t, W, Q, torque=as_callable, method="splitting", dt=0.01)
    d = kr.simulate([1.0, 1.5, 2.0], t, W, Q, torque=model, method="splitting", dt=0.01)
    np.testing.assert_allclose(c.omega, d.omega, atol=1e-12)


def heavy_top_constants(tr, weight, lever):
    """Jz (space), J3 (body), E = T + weight · z_cm for a symmetric top with lever on axis 3."""
    jz = tr.angular_momentum_space[:, 2]
    j3 = tr.angular_momentum_body[:, 2]
    from scipy.spatial.transform import Rotation

    z_cm = Rotation.from_quat(tr.q, scalar_first=True).apply(lever)[:, 2]
    return jz, j3, tr.energy + weight * z_cm


# h ω3 = 0.04: errors ~ rtol for dop853, ~(hω)^p for the fixed-step methods
@pytest.mark.parametrize("method,dt,tol", [("dop853", None, 1e-10), ("rk4", 1e-3, 1e-8),
                                           ("splitting4", 1e-3, 1e-7), ("rkmk4", 1e-3, 1e-8),
                                           ("splitting", 1e-3, 1e-4), ("dmv", 1e-3, 1e-4),
                                           ("midpoint", 1e-3, 1e-4)])
def test_heavy_symmetric_top_constants_of_motion(method, dt, tol):
    # Lagrange top (Theory §6): I1 = I2 about the pivot, centre of mass on the symmetry axis
    weight, lever = 9.81 * 0.5, np.array([0.0, 0.0, 0.2])
    tilt = 0.6
    q0 = [np.cos(tilt / 2), np.sin(tilt / 2), 0.0, 0.0]
    t = np.linspace(0, 5, 26)
    tr = kr.simulate([0.05, 0.05, 0.02], t, [0.3, -0.5, 40.0], q0, torque=GravityTorque(weight, lever),
                     method=method, dt=dt)
    jz, j3, energy = heavy_top_constants(tr, weight, lever)
    for value in (jz, j3, energy):
        assert np.abs(value - value[0]).max() <= tol * max(1.0, abs(value[0]))
    # the top does move: nutation changes the tilt
    assert np.ptp(tr.euler("ZXZ")[:, 1]) > 1e-3
