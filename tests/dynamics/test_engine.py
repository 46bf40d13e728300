"""simulate / simulate_batch / simulate_6dof: bodies, frames, batches, and refused input."""

import numpy as np
import pytest

import kreisel as kr
from kreisel.dynamics import ConstantForce, GravityTorque, LinearDrag

rng = np.random.default_rng(3)


def random_unit_quaternions(n):
    q = rng.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=-1, keepdims=True)


def test_non_diagonal_tensor_matches_full_tensor_reference(tools):
    axes = tools.rotation_matrix(random_unit_quaternions(1)[0])
    tensor = axes @ np.diag([1.0, 2.0, 2.5]) @ axes.T
    w0, q0 = np.array([0.5, 1.0, -0.3]), random_unit_quaternions(1)[0]
    t = np.linspace(0, 6, 13)
    w_ref, q_ref = tools.reference(tensor, t, w0, q0)
    for method, dt, tol in [("dop853", None, 1e-10), ("rk4", 1e-3, 1e-9), ("splitting", 1e-3, 1e-5)]:
        tr = kr.simulate(tensor, t, w0, q0, method=method, dt=dt)
        np.testing.assert_allclose(tr.omega, w_ref, atol=tol)
        assert tools.quat_distance(tr.q, q_ref).max() < tol
        np.testing.assert_allclose(tr.inertia, tensor)
    body = kr.RigidBody(tensor, mass=3.0)
    np.testing.assert_allclose(kr.simulate(body, t, w0, q0).omega, w_ref, atol=1e-10)


def test_callable_torque_on_non_diagonal_body(tools):
    axes = tools.rotation_matrix(random_unit_quaternions(1)[0])
    tensor = axes @ np.diag([1.0, 2.0, 2.5]) @ axes.T
    lever = np.array([0.1, 0.2, 0.3])

    def torque(t, q, w):
        return np.cross(lever, tools.rotation_matrix(q).T @ [0, 0, -1.0]) - 0.1 * w

    t = np.linspace(0, 3, 7)
    w_ref, q_ref = tools.reference(tensor, t, [0.5, 1.0, -0.3], torque=torque)
    tr = kr.simulate(tensor, t, [0.5, 1.0, -0.3], torque=torque)
    np.testing.assert_allclose(tr.omega, w_ref, atol=1e-10)
    model = kr.simulate(tensor, t, [0.5, 1.0, -0.3], torque=GravityTorque(1.0, lever) + kr.dynamics.LinearDamping(0.1))
    np.testing.assert_allclose(model.omega, w_ref, atol=1e-10)


@pytest.mark.parametrize("method,dt", [("dop853", None), ("splitting", 0.01), ("rkmk4", 0.01), ("midpoint", 0.02)])
def test_batch_matches_single_simulations(method, dt):
    bodies = np.array([[1.0, 2.0, 3.0], [1.5, 1.5, 2.0], [2.0, 2.5, 3.0], [1.0, 1.2, 2.1]])
    w0 = rng.normal(size=(4, 3))
    q0 = random_unit_quaternions(4)
    torque = GravityTorque(0.7, [0.0, 0.1, 0.3])
    t = np.linspace(0, 4, 9)
    batch = kr.simulate_batch(bodies, t, w0, q0, torque=torque, method=method, dt=dt)
    assert batch.omega.shape == (4, 9, 3) and batch.q.shape == (4, 9, 4)
    for b in range(4):
        single = kr.simulate(bodies[b], t, w0[b], q0[b], torque=torque, method=method, dt=dt)
        np.testing.assert_allclose(batch.omega[b], single.omega, rtol=0, atol=1e-15)
        np.testing.assert_allclose(batch.q[b], single.q, rtol=0, atol=1e-15)



@pytest.mark.parametrize("method,dt", [("dop853", None), ("splitting", 0.01), ("splitting4", 0.02), ("rk4", 0.01),
                                       ("dmv", 0.01)])
def test_batch_every_keeps_exactly_the_full_runs_samples(method, dt):
    # decimated output: the same steps as the dense run, every k-th sample kept bit for bit
    bodies = np.array([[1.0, 2.0, 3.0], [1.5, 1.5, 2.0], [2.0, 2.5, 3.0]])
    w0, q0 = rng.normal(size=(3, 3)), random_unit_quaternions(3)
    t = np.linspace(0, 3, 61)
    for torque in (None, GravityTorque(0.7, [0.0, 0.1, 0.3])):
        full = kr.simulate_batch(bodies, t, w0, q0, torque=torque, method=method, dt=dt)
        for every in (1, 4, 60):
            kept = kr.simulate_batch(bodies, t, w0, q0, torque=torque, method=method, dt=dt, every=every)
            np.testing.assert_array_equal(kept.t, t[::every])
            np.testing.assert_array_equal(kept.omega, full.omega[:, ::every])
            np.testing.assert_array_equal(kept.q, full.q[:, ::every])
        reduced = kr.simulate_batch(bodies, t, w0, q0, torque=torque, method=method, dt=dt, every=5, chunk_size=2,
                                    reduce=lambda tr: tr.q)
        np.testing.assert_array_equal(reduced, full.q[:, ::5])


@pytest.mark.parametrize("method,dt", [("dop853", None), ("scipy", None), ("splitting4", 0.02), ("rk4", 0.01)])
def test_single_body_every_keeps_exactly_the_full_runs_samples(method, dt):
    # simulate and simulate_6dof decimate like simulate_batch: the same steps, every k-th sample kept
    t = np.linspace(0, 3, 61)
    w0, q0 = rng.normal(size=3), random_unit_quaternions(1)[0]
    inertia = np.array([[2.0, 0.1, 0.0], [0.1, 1.5, 0.2], [0.0, 0.2, 3.0]])  # non-principal: rotated in and out
    full = kr.simulate(inertia, t, w0, q0, torque=GravityTorque(0.7, [0.0, 0.1, 0.3]), method=method, dt=dt)
    six = kr.simulate_6dof(inertia, t, w0, q0, velocity0=[1.0, 0.0, 2.0], force=ConstantForce([0.0, 0.0, -9.8]),
                           method=method, dt=dt)
    for every in (4, 60):
        kept = kr.simulate(inertia, t, w0, q0, torque=GravityTorque(0.7, [0.0, 0.1, 0.3]), method=method, dt=dt,
                           every=every)
        np.testing.assert_array_equal(kept.t, t[::every])
        np.testing.assert_array_equal(kept.omega, full.omega[::every])
        np.testing.assert_array_equal(kept.q, full.q[::every])
        kept6 = kr.simulate_6dof(inertia, t, w0, q0, velocity0=[1.0, 0.0, 2.0], force=ConstantForce([0.0, 0.0, -9.8]),
                                 method=method, dt=dt, every=every)
        for name in ("omega", "q", "position", "velocity"):
            np.testing.assert_array_equal(getattr(kept6, name), getattr(six, name)[::every], err_msg=name)
    with pytest.raises(ValueError, match="every must be a positive integer dividing len"):
        kr.simulate(inertia, t, w0, every=7)


def test_batch_every_refuses_what_would_drop_the_last_time():
    t = np.linspace(0, 1, 11)
    for every, error in ((3, ValueError), (0, ValueError), (-2, ValueError), (2.0, TypeError), (True, TypeError)):
        with pytest.raises(error, match="every must be a positive integer"):
            kr.simulate_batch([[1.0, 2.0, 3.0]], t, [0.1, 1, 0.1], method="rk4", dt=0.1, every=every)

def test_batch_broadcasting_and_reduce():
    bodies = np.array([1.0, 2.0, 3.0]) + np.zeros((2, 3, 1))  # batch (2, 3)
    tilt = np.linspace(0.01, 0.3, 3)
    w0 = np.stack([np.sin(tilt), np.cos(tilt), 0.0 * tilt], axis=-1)   # (3, 3) broadcast over rows
    t = np.linspace(0, 20, 41)
    full = kr.simulate_batch(bodies, t, w0, method="splitting", dt=0.01)
    assert full.omega.shape == (2, 3, 41, 3)
    assert full.inertia.shape == (2, 3, 3, 3)

    def min_middle(tr):   # the flip: ω2 changes sign on the tennis-racket orbit
        return tr.omega[..., 1].min(axis=-1)

    reduced = kr.simulate_batch(bodies, t, w0, method="splitting", dt=0.01, reduce=min_middle, chunk_size=4)
    assert reduced.shape == (2, 3)
    np.testing.assert_array_equal(reduced, full.omega[..., 1].min(axis=-1))
    assert np.all(reduced < 0)


def test_six_dof_free_body():
    body = kr.RigidBody([1.0, 2.0, 3.0], mass=2.0)
    t = np.linspace(0, 2, 5)
    g = np.array([0, 0, -9.81])
    for method, dt in [("dop853", None), ("splitting", 0.01), ("rk4", 0.01)]:
        tr = kr.simulate_6dof(body, t, [0.1, 1.0, 0.1], position0=[1, 2, 3], velocity0=[0.5, 0, 2.0],
                              force=ConstantForce(2.0 * g), method=method, dt=dt)
        expected = np.array([1, 2, 3]) + np.outer(t, [0.5, 0, 2.0]) + 0.5 * np.outer(t ** 2, g)
        np.testing.assert_allclose(tr.position, expected, atol=1e-11)
        rot = kr.simulate(body, t, [0.1, 1.0, 0.1], method=method, dt=dt)
        np.testing.assert_allclose(tr.omega, rot.omega, atol=1e-12)
    drag = kr.simulate_6dof(body, t, [0, 0, 0.0], velocity0=[1.0, 0, 0], force=LinearDrag(0.4))
    np.testing.assert_allclose(drag.velocity[:, 0], np.exp(-0.2 * t), rtol=1e-11)
    # a body-fixed thrust turns with the body: spinning about z, the thrust along body x averages out
    spin = kr.simulate_6dof(body, [0.0, 2 * np.pi], [0, 0, 1.0], force=ConstantForce([1.0, 0, 0], "body"))
    np.testing.assert_allclose(spin.velocity[-1], 0.0, atol=1e-11)


def test_six_dof_callable_force_matches_model():
    body = kr.RigidBody([1.0, 2.0, 3.0], mass=2.0)
    t = np.linspace(0, 1, 3)

    def force(t, q, w, r, v):
        return np.array([0.0, 0.0, -19.62]) - 0.4 * v

    a = kr.simulate_6dof(body, t, [0.1, 1, 0.1], velocity0=[1, 0, 0], force=force)
    b = kr.simulate_6dof(body, t, [0.1, 1, 0.1], velocity0=[1, 0, 0],
                         force=ConstantForce([0, 0, -19.62]) + LinearDrag(0.4))
    np.testing.assert_allclose(a.position, b.position, atol=1e-12)


BAD_SIMULATE = [
    (dict(body=[1.0, 2.0, -3.0]), ValueError, "positive"),
    (dict(body=[1.0, 1.0, 5.0]), ValueError, "triangle"),
    (dict(body=[[1.0, 0.5, 0], [0, 2, 0], [0, 0, 3]]), ValueError, "symmetric"),
    (dict(body=[1.0, 2.0]), ValueError, "body"),
    (dict(body="steel"), TypeError, "body"),
    (dict(omega0=[0.1, np.nan, 0.0]), ValueError, "omega0"),
    (dict(omega0=[0.1, 0.2]), ValueError, "omega0"),
    (dict(q0=[0.0, 0.0, 0, 0]), ValueError, "q0 must be nonzero"),
    (dict(q0=[np.inf, 0, 0, 0]), ValueError, "q0"),
    (dict(t=[0.0, 1.0, 1.0]), ValueError, "increasing"),
    (dict(t=[[0.0, 1.0]]), ValueError, "t must"),
    (dict(method="euler"), ValueError, "unknown method"),
    (dict(method=4), TypeError, "method"),
    (dict(method="rk4"), ValueError, "dt"),
    (dict(method="rk4", dt=-0.1), ValueError, "dt"),
    (dict(dt=0.1), ValueError, "dt"),
    (dict(torque=5.0), TypeError, "torque"),
    (dict(torque=lambda t, q, w: np.zeros(2)), ValueError, "shape"),
    (dict(torque=lambda t, q, w: "x"), TypeError, "torque"),
    (dict(torque=lambda t, q, w: np.array([np.nan, 0, 0])), ValueError, "non-finite"),
    (dict(rtol=0.0), ValueError, "rtol"),
    # float() parsed these strings: a tolerance or step typed as text ran silently
    (dict(method="splitting", dt="0.01"), TypeError, "dt must be real numbers"),
    (dict(rtol="1e-8"), TypeError, "rtol must be real numbers"),
    (dict(atol="1e-8"), TypeError, "atol must be real numbers"),
    (dict(method="splitting", dt=[0.01, 0.02]), ValueError, "dt must be a single number"),
]


@pytest.mark.parametrize("change,error,words", BAD_SIMULATE)
def test_bad_input_is_refused_before_integrating(change, error, words):
    args = dict(body=[1.0, 2.0, 3.0], t=[0.0, 1.0], omega0=[0.1, 1.0, 0.1])
    args.update(change)
    with pytest.raises(error, match=words):
        kr.simulate(**args)


def test_torque_callable_checked_once_before_integration():
    calls = []

    def torque(t, q, w):
        calls.append(t)
        return np.zeros(4)

    with pytest.raises(ValueError, match="shape"):
        kr.simulate([1.0, 2.0, 3.0], [0.0, 10.0], [0.1, 1.0, 0.1], torque=torque)
    assert calls == [0.0]


def test_batch_bad_input():
    t = [0.0, 1.0]
    with pytest.raises(TypeError, match="built-in torque model"):
        kr.simulate_batch([[1.0, 2.0, 3.0]], t, [0.1, 1, 0.1], torque=lambda t, q, w: np.zeros(3))
    with pytest.raises(ValueError, match="broadcast"):
        kr.simulate_batch(np.ones((2, 3)), t, np.ones((3, 3)))
    with pytest.raises(ValueError, match="triangle"):
        kr.simulate_batch([[1.0, 2.0, 3.0], [1.0, 1.0, 3.0]], t, [0.1, 1, 0.1])
    with pytest.raises(ValueError, match="scipy"):
        kr.simulate_batch([[1.0, 2.0, 3.0]], t, [0.1, 1, 0.1], method="scipy")
    with pytest.raises(ValueError, match="first axis"):
        kr.simulate_batch(np.ones((3, 3)) + [0, 1, 1], t, [0.1, 1, 0.1], reduce=lambda tr: 1.0)
    # an empty omega0 or q0 batch against one body: refused by name (was numpy's "need at least one array")
    for omega0, q0 in ((np.zeros((0, 3)), None), ([0.1, 1, 0.1], np.zeros((2, 0, 4)))):
        with pytest.raises(ValueError, match=r"broadcast to an empty batch \(.*0.*\); give at least one body"):
            kr.simulate_batch([1.0, 2.0, 3.0], t, omega0, q0=q0)


def test_integration_failure_is_reported():
    # a step far beyond the implicit iteration's reach
    with pytest.raises(RuntimeError, match="dt"):
        kr.simulate([1.0, 2.0, 3.0], [0.0, 10.0], [10.0, 50.0, 10.0], method="dmv", dt=1.0)


@pytest.mark.parametrize("method,dt", [("dop853", None), ("rk4", 0.01)])
def test_time_origin_and_single_sample(method, dt):
    # the initial state sits at t[0], whatever its value; one sample returns it unchanged
    a = kr.simulate([1.0, 2.0, 3.0], [0.0, 1.5], [0.1, 1.0, 0.1], method=method, dt=dt)
    b = kr.simulate([1.0, 2.0, 3.0], [10.0, 11.5], [0.1, 1.0, 0.1], method=method, dt=dt)
    np.testing.assert_allclose(a.omega, b.omega, atol=1e-13)
    one = kr.simulate([1.0, 2.0, 3.0], [3.0], [0.1, 1.0, 0.1], method=method, dt=dt)
    np.testing.assert_array_equal(one.omega, [[0.1, 1.0, 0.1]])
    np.testing.assert_array_equal(one.q, [[1.0, 0.0, 0.0, 0.0]])
