import itertools
import pathlib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kreisel as kr
from kreisel.so3 import quat_apply, quat_conjugate, quat_multiply, quat_normalize

Q0 = np.array([0.5, 0.5, -0.5, 0.5])
T_SHORT = np.linspace(0.0, 20.0, 201)


def _space_momentum(tr):
    moments = np.diagonal(tr.inertia)
    return quat_apply(tr.q, moments * tr.omega)


def _assert_matches_reference(reference, moments, omega0, t=T_SHORT, tol=2e-11):
    tr = kr.EulerTop(*moments, allow_unphysical=True).solve(t, omega0, Q0)
    omega_ref, q_ref = reference(moments, omega0, Q0, t)
    scale = np.linalg.norm(omega0)
    np.testing.assert_allclose(tr.omega, omega_ref, rtol=0, atol=tol * scale)
    np.testing.assert_allclose(tr.q, q_ref, rtol=0, atol=tol * max(1.0, scale * t[-1]))
    return tr


SIGNS = list(itertools.product([1.0, -1.0], repeat=3))


@pytest.mark.parametrize("signs", SIGNS)
def test_case_a_about_largest_axis_every_sign(reference, signs):
    omega0 = np.array(signs) * [0.3, 0.2, 1.0]
    tr = _assert_matches_reference(reference, (1.0, 2.0, 3.0), omega0)
    assert tr.meta["regime"] == "about_largest_axis"


@pytest.mark.parametrize("signs", SIGNS)
def test_case_b_about_smallest_axis_every_sign(reference, signs):
    omega0 = np.array(signs) * [1.0, 0.2, 0.3]
    tr = _assert_matches_reference(reference, (1.0, 2.0, 3.0), omega0)
    assert tr.meta["regime"] == "about_smallest_axis"


@pytest.mark.parametrize("omega0", [[0.05, 1.0, 0.04], [-0.01, 1.0, 0.08], [0.9, -0.1, 0.05], [0.02, 0.3, -1.0]])
def test_large_amplitude_and_near_middle_axis(reference, omega0):
    _assert_matches_reference(reference, (1.0, 2.0, 3.0), np.array(omega0), tol=1e-10)


@pytest.mark.parametrize("signs", SIGNS)
def test_separatrix_every_sign(reference, signs):
    # I = (3, 4, 6): I3(I3 - I2) = 4 I1(I2 - I1), so ω1 = 2 ω3 lies exactly on J² = 2T I2
    omega0 = np.array(signs) * [2.0, 0.3, 1.0]
    top = kr.EulerTop(3.0, 4.0, 6.0)
    assert top.regime(omega0) == "separatrix"
    # the separatrix is unstable: the reference itself departs from it after t ~ 10
    _assert_matches_reference(reference, (3.0, 4.0, 6.0), omega0, t=np.linspace(0, 8, 81), tol=1e-10)


@pytest.mark.parametrize("permutation", list(itertools.permutations(range(3))))
@pytest.mark.parametrize("omega_sorted", [[0.3, 0.2, 1.0], [1.0, -0.2, 0.3]])
def test_unsorted_moments(reference, permutation, omega_sorted):
    moments = np.array([1.0, 2.0, 3.0])[list(permutation)]
    omega0 = np.array(omega_sorted)[list(permutation)]
    _assert_matches_reference(reference, moments, omega0)


@pytest.mark.parametrize(
    "moments", [(1.0, 1.0, 3.0), (3.0, 1.0, 1.0), (1.0, 3.0, 3.0), (2.0, 0.5, 2.0), (2.0, 2.0, 2.0)]
)
@pytest.mark.parametrize("omega0", [[0.3, -0.2, 1.0], [1.0, 0.0, 0.0], [0.0, 0.0, -2.0]])
def test_symmetric_and_spherical(reference, moments, omega0):
    tr = _assert_matches_reference(reference, moments, np.array(omega0))
    assert tr.meta["regime"] in ("symmetric", "steady")


@pytest.mark.parametrize("omega0", [[0.0, 0.0, 0.0], [1.5, 0.0, 0.0], [0.0, -1.5, 0.0], [0.0, 0.0, 1.5]])
def test_steady_rotations_about_principal_axes(reference, omega0):
    tr = _assert_matches_reference(reference, (1.0, 2.0, 3.0), np.array(omega0))
    assert tr.meta["regime"] == "steady"


@pytest.mark.parametrize(
    "moments, omega0", [((1.0, 2.0, 3.0), [0.3, 0.2, 1.0]), ((2.0, 3.0, 1.0), [0.3, 1.2, 0.2]), ((3.0, 4.0, 6.0), [2.0, 0.3, 1.0])]
)
def test_late_times_conserve_to_rounding(reference, moments, omega0):
    top = kr.EulerTop(*moments)
    t = np.array([0.0, 1e3, 1e4, 1e5, 1e5 + 0.5])
    tr = top.solve(t, omega0, Q0)
    energy = top.energy(np.asarray(omega0, float))
    np.testing.assert_allclose(tr.energy, energy, rtol=1e-13)
    momentum = _space_momentum(tr)
    np.testing.assert_allclose(momentum, np.broadcast_to(momentum[0], momentum.shape), rtol=0, atol=1e-13 * np.linalg.norm(momentum[0]))
    np.testing.assert_allclose(np.linalg.norm(tr.q, axis=-1), 1.0, rtol=0, atol=1e-15)
    # still a solution at late times: restarting the reference from the state at 1e5 agrees
    omega_ref, q_ref = reference(moments, tr.omega[3], tr.q[3], t[3:])
    np.testing.assert_allclose(tr.omega[4], omega_ref[1], atol=1e-10)
    np.testing.assert_allclose(tr.q[4], q_ref[1], atol=1e-10)


def test_batch_of_initial_states_broadcasts(reference):
    top = kr.EulerTop(1.0, 2.0, 3.0)
    omega0 = np.array([[[0.3, 0.2, 1.0]], [[1.0, 0.2, 0.3]]])  # (2, 1, 3)
    q0 = np.array([Q0, [1.0, 0.0, 0.0, 0.0]])  # (2, 4)
    tr = top.solve(T_SHORT[:20], omega0, q0)
    assert tr.q.shape == (2, 2, 20, 4) and tr.omega.shape == (2, 2, 20, 3)
    single = top.solve(T_SHORT[:20], omega0[1, 0], q0[0])
    np.testing.assert_array_equal(tr.q[1, 0], single.q)


def test_first_integrals_and_period(reference):
    top = kr.EulerTop(1.0, 2.0, 3.0)
    omega0 = np.array([0.3, 0.2, 1.0])
    assert top.energy(omega0) == pytest.approx(0.5 * (0.09 + 0.08 + 3.0))
    assert top.angular_momentum(omega0) == pytest.approx(np.sqrt(0.09 + 0.16 + 9.0))
    period = top.omega_period(omega0)
    omega_ref, _ = reference((1.0, 2.0, 3.0), omega0, Q0, [0.0, period, 2 * period])
    np.testing.assert_allclose(omega_ref[1:], [omega0, omega0], atol=1e-11)
    # a quarter period earlier ω2 passes through a maximum only at the true period
    omega_ref, _ = reference((1.0, 2.0, 3.0), omega0, Q0, [0.0, 0.5 * period])
    assert not np.allclose(omega_ref[1], omega0, atol=1e-3)
    assert np.isinf(top.omega_period([0.0, 2.0, 0.0]))


def test_symmetric_period_is_body_precession():
    top = kr.EulerTop(1.0, 1.0, 3.0, allow_unphysical=True)
    assert top.omega_period([0.3, 0.1, 0.5]) == pytest.approx(2 * np.pi / (2.0 * 0.5))


@pytest.mark.parametrize("moments", [(1.0, 2.0, 3.0), (3.0, 1.0, 2.0), (0.4, 0.9, 1.1)])
def test_tennis_racket_theorem(reference, moments):
    top = kr.EulerTop(*moments)
    middle = int(np.argsort(moments)[1])
    steady = top.steady_rotations(spin=2.0)
    assert [s.kind == "unstable" for s in steady] == [k == middle for k in range(3)]
    assert [s.lyapunov_stable for s in steady] == [k != middle for k in range(3)]
    # growth rate against the slope of log|perturbation| of the reference integration
    # tiny perturbation, late enough that the decaying mode is gone (e^{-2σt} < 1e-9)
    omega0 = np.full(3, 1e-12)
    omega0[middle] = 2.0
    t = np.array([10.0, 15.0]) * 1.1547 / steady[middle].growth_rate
    omega_ref, _ = reference(moments, omega0, Q0, np.concatenate([[0.0], t]), atol=1e-25)
    perturbation = np.linalg.norm(np.delete(omega_ref[1:], middle, axis=1), axis=1)
    slope = np.log(perturbation[1] / perturbation[0]) / (t[1] - t[0])
    assert slope == pytest.approx(steady[middle].growth_rate, rel=1e-6)
    # wobble about a stable axis: the period of ω tends to 2π / frequency
    for k in range(3):
        if k != middle:
            omega0 = np.full(3, 1e-6)
            omega0[k] = 2.0
            assert top.omega_period(omega0) == pytest.approx(2 * np.pi / steady[k].wobble_frequency, rel=1e-9)


def test_symmetric_and_spherical_stability_follow_the_chapter():
    assert [s.kind for s in kr.EulerTop(1.0, 1.0, 1.5).steady_rotations()] == ["neutral", "neutral", "stable"]
    assert [s.kind for s in kr.EulerTop(2.0, 2.0, 2.0).steady_rotations()] == ["neutral"] * 3


def test_dzhanibekov_flip_time_counts_reversals(reference):
    moments = (1.0, 2.0, 3.0)
    top = kr.EulerTop(*moments)
    omega0 = np.array([1e-3, 1.0, 2e-3])
    flip = top.dzhanibekov_flip_time(omega0)
    t = np.linspace(0.0, 4.5 * flip, 20001)
    tr = top.solve(t, omega0)
    omega_ref, _ = reference(moments, omega0, Q0, t)
    np.testing.assert_allclose(tr.omega, omega_ref, atol=1e-9)
    w2 = omega_ref[:, 1]
    crossings = t[:-1][np.sign(w2[1:]) != np.sign(w2[:-1])]
    assert len(crossings) == 4
    np.testing.assert_allclose(np.diff(crossings), flip, rtol=1e-3)
    # near the separatrix λ tends to the linear growth rate and 2K ≈ ln(16/(1 - m))
    sigma = top.steady_rotations(1.0)[1].growth_rate
    assert flip * sigma > 10.0
    with pytest.raises(ValueError, match="tumbling"):
        top.dzhanibekov_flip_time([0.0, 1.0, 0.0])


def test_bad_input_is_refused():
    with pytest.raises(ValueError, match="I2"):
        kr.EulerTop(1.0, -2.0, 3.0)
    with pytest.raises(ValueError, match="I3"):
        kr.EulerTop(1.0, 2.0, np.nan)
    top = kr.EulerTop(1.0, 2.0, 3.0)
    with pytest.raises(ValueError, match="omega0"):
        top.solve([0.0, 1.0], [1.0, 2.0])
    with pytest.raises(ValueError, match="q0 must be nonzero quaternions"):
        top.solve([0.0, 1.0], [1.0, 2.0, 3.0], [0.0, 0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="t must be one-dimensional"):
        top.solve([[0.0, 1.0]], [1.0, 2.0, 3.0])
    # an empty trajectory used to come back, whose repr and drift() then raised IndexError
    with pytest.raises(ValueError, match=r"t must be one-dimensional with at least one time, got shape \(0,\)"):
        top.solve([], [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="t must be one-dimensional with at least one time"):
        kr.LagrangeTop(1.0, 0.5, 1.0).solve([], [0.0, 0.5, 0.0], [0.0, 0.0, 10.0])
    with pytest.raises(ValueError, match="t must be one-dimensional with at least one time"):
        kr.Trajectory([], np.zeros((0, 4)), np.zeros((0, 3)), [1.0, 2.0, 3.0])


# ---- exact everywhere: next to the separatrix and next to the axes -------------------------------
EPS = np.finfo(float).eps
REFERENCE = np.load(pathlib.Path(__file__).parent / "data" / "free_top_reference.npz")
CASES = sorted({key.split("/")[0] for key in REFERENCE.files if "/" in key})


def _attitude_angle(q, q_ref):
    """Rotation angle of q_ref⁻¹ q, rad (sign of the quaternion irrelevant)."""
    d = quat_multiply(quat_conjugate(q_ref), q)
    return 2.0 * np.arctan2(np.linalg.norm(d[..., 1:], axis=-1), np.abs(d[..., 0]))


@pytest.mark.parametrize("case", CASES)
def test_matches_30_digit_reference_next_to_the_separatrix(case):
    moments, omega0 = REFERENCE[f"{case}/moments"], REFERENCE[f"{case}/omega0"]
    t, q0 = REFERENCE["times"], REFERENCE["q0"]
    top = kr.EulerTop(*moments, allow_unphysical=True)
    tr = top.solve(t, omega0, q0)
    # ω(0) = ω0 to a few ulp of |ω0|, and to the last bit where a component is exactly zero
    np.testing.assert_allclose(tr.omega[0], omega0, rtol=0, atol=4 * EPS * np.linalg.norm(omega0))
    np.testing.assert_allclose(np.abs(tr.q[0]), np.abs(q0), rtol=0, atol=4 * EPS)
    assert np.max(np.abs(tr.omega - REFERENCE[f"{case}/omega"])) <= 1e-12
    assert np.max(_attitude_angle(tr.q, REFERENCE[f"{case}/q"])) <= 1e-11
    # the guaranteed bounds hold
    accuracy = top.accuracy(omega0, duration=t[-1])
    assert np.max(np.abs(tr.omega - REFERENCE[f"{case}/omega"])) <= accuracy.omega_error * np.linalg.norm(omega0)
    assert np.max(_attitude_angle(tr.q, REFERENCE[f"{case}/q"])) <= accuracy.attitude_error


@pytest.mark.parametrize("case", sorted({key.split("/")[0] for key in REFERENCE.files if "/taylor" in key}))
def test_closed_form_reference_agrees_with_taylor_integration(case):
    # the stored closed-form values and an independent 30-digit Taylor integration of Euler's equations
    at = np.searchsorted(REFERENCE["times"], REFERENCE["taylor_times"])
    np.testing.assert_allclose(REFERENCE[f"{case}/taylor_omega"], REFERENCE[f"{case}/omega"][at], rtol=0, atol=1e-15)
    assert np.max(_attitude_angle(REFERENCE[f"{case}/taylor_q"], REFERENCE[f"{case}/q"][at])) <= 1e-14
    moments, omega0 = REFERENCE[f"{case}/moments"], REFERENCE[f"{case}/omega0"]
    tr = kr.EulerTop(*moments, allow_unphysical=True).solve(REFERENCE["taylor_times"], omega0, REFERENCE["q0"])
    assert np.max(np.abs(tr.omega - REFERENCE[f"{case}/taylor_omega"])) <= 1e-12


@pytest.mark.parametrize("case", CASES[::3])
def test_integrals_exact_at_late_times_next_to_the_separatrix(case):
    moments, omega0 = REFERENCE[f"{case}/moments"], REFERENCE[f"{case}/omega0"]
    top = kr.EulerTop(*moments, allow_unphysical=True)
    tr = top.solve([0.0, 1e5 - 0.5, 1e5], omega0, REFERENCE["q0"])
    np.testing.assert_allclose(tr.energy, top.energy(omega0), rtol=1e-13)
    momentum = _space_momentum(tr)
    np.testing.assert_allclose(momentum, np.broadcast_to(momentum[0], momentum.shape), rtol=0,
                               atol=1e-13 * np.linalg.norm(momentum[0]))


def test_known_failures_next_to_the_axes():
    top = kr.EulerTop(1.0, 2.0, 3.0)
    tr = top.solve([0.0, 1.0, 10.0], [1e-9, 1.0, 0.0], [1.0, 0.0, 0.0, 0.0])
    np.testing.assert_array_equal(tr.omega[0], [1e-9, 1.0, 0.0])
    np.testing.assert_allclose(tr.energy, 1.0, rtol=1e-15)
    tr = top.solve([0.0, 1.0, 10.0], [0.0, 1.0, 1e-9])
    assert np.all(np.isfinite(tr.q)) and tr.omega[0, 2] == pytest.approx(1e-9, rel=4 * EPS)
    # ω1 ω3 < 0 about the largest axis: the start lies past a quarter period
    omega0 = np.array([-0.1, 1.0, 0.0577350269])
    np.testing.assert_allclose(top.solve([0.0], omega0).omega[0], omega0, rtol=0, atol=4 * EPS)


FINITE_SCALE = st.floats(min_value=-300.0, max_value=-6.0)


@settings(max_examples=150, deadline=None)
@given(
    moments=st.sampled_from([(1.0, 2.0, 3.0), (3.0, 1.0, 2.0), (2.0, 1.0, 2.0 / 3.0)]),
    axis=st.integers(0, 2),
    spin=st.floats(min_value=0.05, max_value=20.0),
    signs=st.tuples(*[st.sampled_from([-1.0, 1.0])] * 3),
    offsets=st.tuples(*[st.one_of(st.just(None), FINITE_SCALE)] * 2),
)
def test_every_start_next_to_a_principal_axis(moments, axis, spin, signs, offsets):
    omega0 = np.zeros(3)
    omega0[axis] = spin
    others = [k for k in range(3) if k != axis]
    for k, exponent in zip(others, offsets):
        if exponent is not None:
            omega0[k] = spin * 10.0**exponent
    omega0 *= signs
    top = kr.EulerTop(*moments, allow_unphysical=True)
    t = np.array([0.0, 0.3, 7.0, 150.0, 4e3])
    tr = top.solve(t, omega0, Q0)
    np.testing.assert_allclose(tr.omega[0], omega0, rtol=4 * EPS, atol=4 * EPS * spin)
    assert np.all(np.isfinite(tr.q)) and np.all(np.isfinite(tr.omega))
    np.testing.assert_allclose(tr.energy, top.energy(omega0), rtol=1e-14)
    np.testing.assert_allclose(np.linalg.norm(_space_momentum(tr), axis=-1), top.angular_momentum(omega0), rtol=1e-14)
    np.testing.assert_allclose(np.linalg.norm(tr.q, axis=-1), 1.0, rtol=0, atol=4 * EPS)


@pytest.mark.parametrize("offset", [1e-152, 1e-154, 1e-155, 1e-160])
def test_a_start_whose_parameter_m1_is_subnormal_has_a_finite_attitude(offset):
    # next to the intermediate axis, k′ ~ 1e-154 makes m1 = k′² subnormal, where R_J of Π(ν | m) overflowed
    top = kr.EulerTop(1.0, 2.0, 3.0)
    omega0 = np.array([0.0, -1.0, -offset])
    tr = top.solve(np.array([0.0, 0.3, 7.0, 150.0, 4e3]), omega0, Q0)
    assert np.all(np.isfinite(tr.q))
    np.testing.assert_allclose(np.linalg.norm(_space_momentum(tr), axis=-1), top.angular_momentum(omega0), rtol=1e-14)


def test_triangle_inequality_is_one_rule_with_simulate():
    with pytest.raises(ValueError, match="triangle inequality") as from_top:
        kr.EulerTop(1.0, 1.0, 5.0)
    with pytest.raises(ValueError, match="triangle inequality") as from_simulate:
        kr.simulate([1.0, 1.0, 5.0], [0.0, 1.0], [0.0, 0.0, 1.0])
    assert str(from_top.value).split(": ", 1)[1] == str(from_simulate.value).split(": ", 1)[1]
    top = kr.EulerTop(1.0, 1.0, 5.0, allow_unphysical=True)
    assert top.regime([0.1, 0.0, 1.0]) == "symmetric"


def test_regimes_are_named_constants():
    top = kr.EulerTop(1.0, 2.0, 3.0)
    assert top.regime([0.1, 1.0, 0.2]) == kr.tops.Regime.ABOUT_LARGEST_AXIS.label == "about_largest_axis"
    assert str(kr.tops.Regime.SEPARATRIX) == "separatrix"
    assert top.separatrix_distance([1e-8, 1.0, 0.0]) == pytest.approx(-2.5e-17, rel=1e-14)
    assert top.separatrix_distance([0.0, 0.0, 1.0]) != top.separatrix_distance([0.0, 0.0, 1.0])  # NaN: steady


def test_batch_of_bodies_is_one_call_and_matches_single_solves():
    rng = np.random.default_rng(3)
    bodies = np.array([[1.0, 2.0, 3.0], [2.0, 2.0, 3.0], [3.0, 1.0, 2.5], [1.5, 1.5, 1.5], [3.0, 4.0, 6.0]])
    omega0 = rng.normal(size=(5, 3))
    omega0[4] = [2.0, 0.3, 1.0]  # exactly on the separatrix of (3, 4, 6)
    q0 = quat_normalize(rng.normal(size=(5, 4)))
    t = np.linspace(0.0, 30.0, 7)
    tr = kr.tops.solve_free_batch(bodies, t, omega0, q0)
    assert tr.omega.shape == (5, 7, 3) and tr.q.shape == (5, 7, 4)
    assert tr.meta["regime"][1] == "symmetric" and tr.meta["regime"][3] == "steady"
    assert tr.meta["regime"][4] == "separatrix"
    for b in range(5):
        single = kr.EulerTop(*bodies[b]).solve(t, omega0[b], q0[b])
        np.testing.assert_array_equal(tr.omega[b], single.omega)
        np.testing.assert_array_equal(tr.q[b], single.q)
    with pytest.raises(ValueError, match="triangle inequality"):
        kr.tops.solve_free_batch([[1.0, 1.0, 5.0]], t, [0.0, 0.0, 1.0])



_Q0 = np.array([0.5, 0.5, -0.5, 0.5])


@pytest.mark.parametrize("same", [3.0 * _Q0, kr.Rotation.from_quat(_Q0), kr.quat_to_matrix(_Q0)],
                         ids=["scaled quaternion", "Rotation", "matrix"])
def test_q0_accepts_every_rotation_input_of_simulate(same):
    top = kr.EulerTop(1.0, 2.0, 3.0)
    reference = top.solve([0.0, 0.5], [0.3, 1.0, 0.2], _Q0)
    np.testing.assert_allclose(top.solve([0.0, 0.5], [0.3, 1.0, 0.2], same).q, reference.q, rtol=0, atol=1e-15)


def test_solve_free_batch_at_extreme_moments_and_turns():
    # the motion depends on the moments' ratios only: bodies scaled by 2^±1000 move exactly alike
    bodies = np.array([[1.0, 2.0, 3.0], [2.0, 2.0, 3.0]])
    t = np.linspace(0.0, 2.0, 5)
    base = kr.tops.solve_free_batch(bodies, t, [0.1, 1.0, 0.1])
    for k in (1000, -1060):
        scaled = kr.tops.solve_free_batch(np.ldexp(bodies, k), t, [0.1, 1.0, 0.1])
        np.testing.assert_array_equal(scaled.omega, base.omega)
        np.testing.assert_array_equal(scaled.q, base.q)
    # more than 1e15 rad over t: rounding alone would leave the attitude undetermined
    with pytest.raises(ValueError, match=r"t and omega0 are out of range: the body turns through up to 6\.06e\+22 rad"):
        kr.tops.solve_free_batch(bodies, t * 1e22, [0.1, 1.0, 0.1])


@pytest.mark.parametrize("count", [1, 3])
def test_long_sample_arrays_are_solved_in_interruptible_calls_with_the_same_bits(monkeypatch, count):
    # issue 33: EulerTop(1, 2, 3).solve on 3e7 samples exited 17 s after SIGINT (one compiled call)
    from kreisel.tops import _free_top, euler_top

    t = np.linspace(0.0, 50.0, 1001)
    bodies = np.array([[1.0, 2.0, 3.0], [2.0, 2.0, 3.0], [1.0, 2.5, 3.0]])[:count]
    whole = euler_top.solve_free_batch(bodies, t, [0.3, 0.2, 1.0]) if count > 1 else None
    single = kr.EulerTop(1.0, 2.0, 3.0).solve(t, [0.3, 0.2, 1.0])
    monkeypatch.setattr(euler_top, "SAMPLES_PER_CALL", 64)
    calls = []
    in_regime = _free_top.body_in_regime

    def counted(regime):
        return lambda *args: calls.append(args[3].size) or in_regime(regime)(*args)

    monkeypatch.setattr(_free_top, "body_in_regime", counted)
    np.testing.assert_array_equal(kr.EulerTop(1.0, 2.0, 3.0).solve(t, [0.3, 0.2, 1.0]).q, single.q)
    assert max(calls) == 64 and sum(calls) == t.size
    if count > 1:
        chunked = euler_top.solve_free_batch(bodies, t, [0.3, 0.2, 1.0])
        np.testing.assert_array_equal(chunked.q, whole.q)
        np.testing.assert_array_equal(chunked.omega, whole.omega)
