"""The one rule for inertia input (``kreisel._validation.INERTIA_TOLERANCE``): the same borderline
tensors and principal moments get the same verdict at every entry point that takes them."""

import numpy as np
import pytest

import kreisel as kr
from kreisel._validation import INERTIA_TOLERANCE
from kreisel.web import session

TOL = INERTIA_TOLERANCE
T = [0.0, 1e-3]
OMEGA = [0.1, 0.2, 0.3]


def _viewer(body):
    data = {"title": "probe", "body": body, "initial": {"omega": OMEGA, "frame": "body"},
            "integration": {"t_end": 1e-3, "n_samples": 2}}
    session.load(session.toml_text(data))


#: entry points taking three principal moments (the tops only where they have that form)
MOMENT_ENTRIES = {
    "RigidBody": lambda m: kr.RigidBody(m),
    "RigidBody(diag)": lambda m: kr.RigidBody(np.diag(m)),
    "simulate": lambda m: kr.simulate(m, T, OMEGA, method="rk4", dt=1e-3),
    "simulate(tensor)": lambda m: kr.simulate(np.diag(m), T, OMEGA, method="rk4", dt=1e-3),
    "simulate_batch": lambda m: kr.simulate_batch([m, [1.0, 2.0, 3.0]], T, OMEGA, method="rk4", dt=1e-3),
    "simulate_6dof": lambda m: kr.simulate_6dof(m, T, OMEGA, method="rk4", dt=1e-3),
    "EulerTop": lambda m: kr.EulerTop(*m),
    "solve_free_batch": lambda m: kr.tops.solve_free_batch([m], T, OMEGA),
    "LagrangeTop": lambda m: kr.LagrangeTop(m[0], m[2], 1.0),
    "SymmetricTop": lambda m: kr.tops.SymmetricTop(m[0], m[2]),
    "viewer(moments)": lambda m: _viewer({"moments": m.tolist()}),
    "viewer(tensor)": lambda m: _viewer({"tensor": np.diag(m).tolist()}),
}
_SYMMETRIC_ONLY = {"LagrangeTop", "SymmetricTop"}

#: (moments, accepted): the triangle excess I_3 - (I_1 + I_2) and the smallest moment relative to the sum
MOMENT_CASES = {
    "plate equality": ([1.0, 1.0, 2.0], True),
    "triangle just inside": ([1.0, 1.0, 2.0 + 0.95 * TOL * 4.0], True),   # excess 0.95 TOL of the sum
    "triangle just outside": ([1.0, 1.0, 2.0 + 1.05 * TOL * 4.0], False),  # excess 1.05 TOL of the sum
    "rod, a zero moment": ([0.0, 1.0, 1.0], False),
    "rod, moment 0.5 TOL of the sum": ([1e-9, 1.0, 1.0], False),
    "thin but not a rod, 5 TOL": ([1e-8, 1.0, 1.0], True),
    "negative moment": ([-1e-3, 1.0, 1.0], False),
    "far outside": ([1.0, 1.0, 5.0], False),
}


def _verdict(call, value):
    try:
        call(value)
    except ValueError:
        return False
    return True


@pytest.mark.parametrize(("entry", "case"), [(entry, case) for entry in MOMENT_ENTRIES for case in MOMENT_CASES
                                             if entry not in _SYMMETRIC_ONLY  # a symmetric top: (I1, I1, I3)
                                             or MOMENT_CASES[case][0][0] == MOMENT_CASES[case][0][1]])
def test_principal_moments_get_one_verdict_everywhere(entry, case):
    moments, accepted = MOMENT_CASES[case]
    assert _verdict(MOMENT_ENTRIES[entry], np.array(moments)) is accepted


def test_refusals_name_the_argument_and_give_the_numbers():
    with pytest.raises(ValueError, match=r"^body: principal moments \[1\. 1\. 5\.\] violate the triangle inequality"):
        kr.simulate([1.0, 1.0, 5.0], T, OMEGA)
    with pytest.raises(ValueError, match=r"^inertia: principal moments \[0\. 1\. 1\.\] must all be positive"):
        kr.RigidBody([0.0, 1.0, 1.0])
    with pytest.raises(ValueError, match=r"^LagrangeTop moments \(I1, I1, I3\): .* triangle inequality"):
        kr.LagrangeTop(1.0, 2.5, 1.0)
    with pytest.raises(ValueError, match=r"^I must be symmetric .* 1e-08 of the largest entry"):
        kr.inertia.principal_axes(_asymmetric(1e-8))


def test_allow_unphysical_skips_only_the_triangle_inequality_and_everywhere_alike():
    for call in (lambda m: kr.simulate(m, T, OMEGA, method="rk4", dt=1e-3, allow_unphysical=True),
                 lambda m: kr.simulate_batch([m], T, OMEGA, method="rk4", dt=1e-3, allow_unphysical=True),
                 lambda m: kr.simulate_6dof(m, T, OMEGA, method="rk4", dt=1e-3, allow_unphysical=True),
                 lambda m: kr.EulerTop(*m, allow_unphysical=True)):
        assert _verdict(call, [1.0, 1.0, 5.0]) and not _verdict(call, [1e-10, 1.0, 5.0])


def test_allow_unphysical_and_the_rate_maps_degrees_take_only_booleans():
    # truthy text skipped the triangle inequality, or read radians as degrees, silently
    for call in (lambda f: kr.simulate([1.0, 1.0, 5.0], T, OMEGA, method="rk4", dt=1e-3, allow_unphysical=f),
                 lambda f: kr.EulerTop(1.0, 1.0, 5.0, allow_unphysical=f)):
        with pytest.raises(TypeError, match="allow_unphysical must be True or False, got 'no'"):
            call("no")
    angles, rates = [0.1, 0.5, 0.2], [0.0, 0.0, 1.0]
    for call in (lambda f: kr.euler_rate_matrix("ZXZ", angles, frame="body", degrees=f),
                 lambda f: kr.euler_rate_matrix_inverse("ZXZ", angles, frame="body", degrees=f),
                 lambda f: kr.euler_rates("ZXZ", angles, rates, frame="body", degrees=f),
                 lambda f: kr.angular_velocity_from_euler_rates("ZXZ", angles, rates, frame="body", degrees=f),
                 lambda f: kr.euler_rates_singular("ZXZ", angles, degrees=f),
                 lambda f: kr.angular_acceleration_from_euler("ZXZ", angles, rates, rates, frame="body", degrees=f)):
        for bad in ("no", None):
            with pytest.raises(TypeError, match="degrees must be True or False"):
                call(bad)
        call(False)


def _asymmetric(relative):
    """A symmetric tensor with largest entry 3 and I_01 - I_10 = ``relative`` times 3."""
    tensor = np.array([[2.0, 0.5, 0.0], [0.5, 2.0, 0.0], [0.0, 0.0, 3.0]])
    tensor[1, 0] += 3.0 * relative
    return tensor


#: entry points taking an inertia tensor
TENSOR_ENTRIES = {
    **{key: MOMENT_ENTRIES[key] for key in ("RigidBody", "simulate", "simulate_6dof")},
    "viewer(tensor)": lambda a: _viewer({"tensor": a.tolist()}),
    "principal_axes": kr.inertia.principal_axes,
    "rotate": lambda a: kr.inertia.rotate(a, [1.0, 0.0, 0.0, 0.0]),
    "parallel_axis": lambda a: kr.inertia.parallel_axis(a, 1.0, [1.0, 0.0, 0.0]),
    "moment_about_axis": lambda a: kr.inertia.moment_about_axis(a, [0.0, 0.0, 1.0]),
    "inertia_ellipsoid": kr.inertia.inertia_ellipsoid,
    "combine": lambda a: kr.inertia.combine([kr.inertia.MassProperties(1.0, np.zeros(3), a)]),
}
TENSOR_CASES = {"asymmetric by 1e-10": (1e-10, True), "asymmetric by 0.9 TOL": (0.9 * TOL, True),
                "asymmetric by 1.1 TOL": (1.1 * TOL, False), "asymmetric by 1e-8": (1e-8, False)}


@pytest.mark.parametrize("case", TENSOR_CASES)
@pytest.mark.parametrize("entry", TENSOR_ENTRIES)
def test_symmetry_gets_one_verdict_everywhere(entry, case):
    relative, accepted = TENSOR_CASES[case]
    assert _verdict(TENSOR_ENTRIES[entry], _asymmetric(relative)) is accepted


def test_the_tolerance_scales_with_the_body():
    """Relative to the largest entry and the sum: the verdicts hold at 1e-300 and 1e300 kg m² alike."""
    for scale in (1e-300, 1e300):
        assert _verdict(MOMENT_ENTRIES["RigidBody"], scale * np.array([1.0, 1.0, 2.0 + 0.95 * TOL * 4.0]))
        assert not _verdict(MOMENT_ENTRIES["RigidBody"], scale * np.array([1.0, 1.0, 2.0 + 1.05 * TOL * 4.0]))
        assert _verdict(MOMENT_ENTRIES["RigidBody"], scale * _asymmetric(0.9 * TOL))
        assert not _verdict(MOMENT_ENTRIES["RigidBody"], scale * _asymmetric(1.1 * TOL))


def test_the_symmetric_part_of_a_tensor_near_the_largest_double_does_not_overflow():
    from kreisel._validation import check_inertia_tensor

    scale = 2.0**1022  # largest entry 3 * 2**1022: I + Iᵀ would overflow
    with np.errstate(all="raise"):
        symmetric = check_inertia_tensor(scale * _asymmetric(0.5 * TOL), "I")
    np.testing.assert_array_equal(symmetric, symmetric.T)
    np.testing.assert_array_equal(symmetric, scale * check_inertia_tensor(_asymmetric(0.5 * TOL), "I"))
    with np.errstate(all="raise"):
        assert kr.RigidBody(np.diag([1e308, 1e308, 1e308])).principal_moments.tolist() == [1e308] * 3


def test_checked_callable_refuses_bad_returns_naming_the_callable():
    """One check (``kreisel._validation.checked_callable``) for the torque, force and particle-force callables."""
    from kreisel._validation import checked_callable

    good = checked_callable(lambda t, y: [1, 2, 3], "force")
    out = good(0.5, np.zeros(6))
    assert out.dtype == np.float64 and out.tolist() == [1.0, 2.0, 3.0]
    with pytest.raises(TypeError, match=r"torque callable must return a real array of shape \(3,\), got str"):
        checked_callable(lambda t, y: "abc", "torque")(0.0, None)
    with pytest.raises(ValueError, match=r"force callable must return shape \(3,\), got \(2,\) at t = 0.25"):
        checked_callable(lambda t, y: [1.0, 2.0], "force")(0.25, None)
    with pytest.raises(ValueError, match=r"force callable returned a non-finite value .* at t = 1.0"):
        checked_callable(lambda t, y: [np.nan, 0.0, 0.0], "force")(1.0, None)
    # the particle simulator uses the shared check, not a private name of kreisel.dynamics
    import kreisel.frames.particle as particle
    import kreisel.dynamics.engine as engine
    assert particle.checked_callable is checked_callable is engine.checked_callable
    assert not hasattr(engine, "_checked_callable")


@pytest.mark.parametrize("call, message", [
    (lambda: kr.frames.inertial_forces([1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0], mass=[1.0, -2.0]), "mass must be > 0, got -2.0"),
    (lambda: kr.frames.hamiltonian([1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0], mass=0.0), "mass must be > 0, got 0.0"),
    (lambda: kr.frames.simulate_particle([0.0, 1.0], [1.0, 0, 0], [0, 0, 0], [0, 0, 1.0], mass=-1), "mass must be > 0, got -1.0"),
    (lambda: kr.earth.foucault_pendulum(-1.0, 45.0, 10.0, 0.1), "length must be > 0, got -1.0"),
    (lambda: kr.earth.foucault_pendulum(1.0, 45.0, 0.0, 0.1), "duration must be > 0, got 0.0"),
    (lambda: kr.earth.foucault_pendulum(1.0, 45.0, 10.0, 0.1, g=-9.8), "g must be > 0, got -9.8"),
    (lambda: kr.earth.foucault_pendulum([1.0, 2.0], 45.0, 10.0, 0.1), r"length must be a single number, got an array"),
    (lambda: kr.larmor_precession_rate(1.0, mass=[1e-30, 0.0]), "mass must be > 0, got 0.0"),
    (lambda: kr.nav.coning_motion(0.1, 1.0, -1e-3, 8), "sample_time must be > 0, got -0.001"),
    (lambda: kr.simulate([1, 2, 3], [0.0, 1.0], [0, 0, 1.0], method="rk4", dt=-0.1), "dt must be > 0, got -0.1"),
    (lambda: kr.simulate([1, 2, 3], [0.0, 1.0], [0, 0, 1.0], method="rk4", dt=np.inf), r"dt must be finite"),
    (lambda: kr.simulate([1, 2, 3], [0.0, 1.0], [0, 0, 1.0], atol=0.0), "atol must be > 0, got 0.0"),
    (lambda: kr.simulate([1, 2, 3], [0.0, 1.0], [0, 0, 1.0], rtol=np.nan), r"rtol must be in \[1e-15, 1\), got nan"),
    (lambda: kr.frames.simulate_particle([0.0, 1.0], [1.0, 0, 0], [0, 0, 0], [0, 0, 1.0], rtol=-1e-9),
     "rtol must be > 0, got -1e-09"),
    (lambda: kr.frames.simulate_particle([0.0, 1.0], [1.0, 0, 0], [0, 0, 0], [0, 0, 1.0], atol=np.inf),
     "atol must be finite"),
    # max_step's default inf means no bound; NaN and non-positive steps are not bounds
    (lambda: kr.frames.simulate_particle([0.0, 1.0], [1.0, 0, 0], [0, 0, 0], [0, 0, 1.0], max_step=np.nan),
     "max_step must be > 0, got nan"),
    (lambda: kr.frames.simulate_particle([0.0, 1.0], [1.0, 0, 0], [0, 0, 0], [0, 0, 1.0], max_step=-np.inf),
     "max_step must be > 0, got -inf"),
])
def test_positive_quantities_are_refused_naming_the_argument_and_the_value(call, message):
    # one check (kreisel._validation.positive_array / positive_float) for every physical quantity that must be > 0
    with pytest.raises(ValueError, match=message):
        call()


def test_a_bound_may_be_inf_where_asked_and_a_tolerance_is_a_number_in_its_range():
    from kreisel._validation import check_tolerance, positive_float

    assert positive_float(np.inf, "max_step", allow_inf=True) == np.inf
    with pytest.raises(ValueError, match="max_step must be finite"):
        positive_float(np.inf, "max_step")
    with pytest.raises(TypeError, match="max_step must be real numbers"):
        positive_float("1", "max_step", allow_inf=True)
    assert check_tolerance(0.5) == 0.5
    with pytest.raises(TypeError, match="tol must be real numbers"):  # float() used to parse text
        check_tolerance("0.1")
    with pytest.raises(ValueError, match=r"tol must be in \[0, 1\), got 1.0"):
        check_tolerance(1.0)


def test_one_long_turn_refusal_for_every_owner():
    # EulerTop, LagrangeTop, the rotating-frame particle, the Foucault pendulum and the gyro fit share it
    import pathlib
    import re

    from kreisel._validation import MAX_TURN, refuse_long_turn

    refuse_long_turn(MAX_TURN, "t", "the body turns through up to")
    for turn in (np.nextafter(MAX_TURN, np.inf), np.inf, np.nan):
        with pytest.raises(ValueError, match=r"^t and omega are out of range: the body turns through up to .* rad, "
                                             r"more than 1e\+15 rad, where double precision no longer fixes"):
            refuse_long_turn(turn, "t and omega", "the body turns through up to")
    package = pathlib.Path(kr.__file__).parent
    owners = [p.relative_to(package).as_posix() for p in package.rglob("*.py") if re.search(r"\bMAX_TURN\b", p.read_text())]
    assert owners == ["_validation.py"]
