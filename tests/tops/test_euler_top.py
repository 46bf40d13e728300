import itertools

import numpy as np
import pytest

import kreisel as kr
from kreisel.so3 import quat_apply

Q0 = np.array([0.5, 0.5, -0.5, 0.5])
T_SHORT = np.linspace(0.0, 20.0, 201)


def _space_momentum(tr):
    moments = np.diagonal(tr.inertia)
    return quat_apply(tr.q, moments * tr.omega)


def _assert_matches_reference(reference, moments, omega0, t=T_SHORT, tol=2e-11):
    tr = kr.EulerTop(*moments).solve(t, omega0, Q0)
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
    top = kr.EulerTop(1.0, 1.0, 3.0)
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
    assert [s.kind for s in kr.EulerTop(1.0, 1.0, 3.0).steady_rotations()] == ["neutral", "neutral", "stable"]
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
    with pytest.raises(ValueError, match="q0"):
        top.solve([0.0, 1.0], [1.0, 2.0, 3.0], [1.0, 1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="t must be one-dimensional"):
        top.solve([[0.0, 1.0]], [1.0, 2.0, 3.0])
