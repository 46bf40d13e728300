"""Fuzzing of every public function: bad input is refused clearly, extreme input gives right answers or a clear refusal.

The functions come from the ``__all__`` of the numerical subpackages (a new public function is
driven as soon as it is listed). Each call is built from a table of valid arguments keyed by
parameter name (:data:`VALID`, with per-function entries in :data:`SPECIFIC`); then each array
argument in turn is perturbed and the outcome judged:

- non-real dtypes (complex, datetime64, strings, object arrays of strings), NaN and inf, a wrong
  last dimension: a ``ValueError``/``TypeError`` that names the argument, never a bare numpy,
  numba or ``ZeroDivisionError``, never a ``RuntimeWarning`` (they are errors here);
- a non-contiguous view, a read-only array, a bool array of the same values where the values are
  0/1: exactly the result of the plain call (no error);
- an empty batch: a clear refusal naming the argument, or a result without non-finite numbers;
- magnitudes from 1e-300 to 1e300 (hypothesis): for arguments with a known homogeneity
  (:data:`HOMOGENEOUS`: ``f(s x) = s^k f(x)``, e.g. a normalisation, a moment of inertia in the
  mass and length), the result is ``s^k`` times the plain result to 1e-12, or a refusal that says
  the input is out of range; for every other array argument, a finite result or a clear refusal
  that does not call finite, nonzero input "non-finite" or "zero".

Outputs that pass are also checked against an independent invariant where one applies
(:data:`INVARIANTS`: unit quaternions, rotation matrices, round trips).
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import re
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from kreisel._compiled.chunks import StepBudgetExceeded
from kreisel.kinematics import KinematicSingularityWarning

PACKAGES = ["so3", "kinematics", "inertia", "dynamics", "tops", "se3", "frames", "earth", "nav"]
# functions whose arguments are files, callables or kreisel objects are fuzzed where those are made
ELSEWHERE = {
    "write_attitude": "writes a file (tests/nav/test_logs.py)",
}
# fixed, reproducible examples, no example database: the suite costs the same on every run
FUZZ = settings(max_examples=3, derandomize=True, database=None, deadline=None,
                suppress_health_check=list(HealthCheck))

RNG = np.random.default_rng(21)


def _unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _quat(n=()):
    return _unit(RNG.normal(size=n + (4,)))


def _vec(n=()):
    return RNG.normal(size=n + (3,))


def _rotation():
    import kreisel as kr
    return kr.quat_to_matrix(_quat())


def _spd():
    a = RNG.normal(size=(3, 3))
    return a @ a.T + 3.0 * np.eye(3)


def _times(n=5):
    return np.linspace(0.0, 1.0, n)


def _positive():
    return float(RNG.uniform(0.5, 2.0))


def _angles():
    return RNG.uniform(0.2, 1.2, size=3)


def _transform():
    import kreisel as kr
    return kr.RigidTransform.from_rotation_translation(kr.Rotation.from_quat(_quat()), _vec())


def _trajectory():
    import kreisel as kr
    return kr.simulate([1.0, 2.0, 3.0], _times(), [0.1, 1.0, 0.1])


# a valid value for each parameter name (a callable makes a fresh one)
VALID = {
    "p": _quat, "q": _quat, "v": _vec, "R": _rotation, "psi": lambda: 0.5 * _vec(), "axis": _vec,
    "angle": _positive, "a": lambda: 0.3 * _vec(), "b": lambda: 0.3 * _vec(), "Q": _rotation,
    "seq": lambda: "ZXZ", "angles": _angles, "u": lambda: _su2(), "ck": lambda: _cayley_klein(),
    "e": _quat, "g": _vec, "weights": lambda: None, "axes": lambda: np.eye(3), "order": lambda: "intrinsic",
    "group": lambda: "O", "omega": _vec, "Rdot": lambda: _rate_of(_rotation()), "qdot": lambda: RNG.normal(size=4),
    "psidot": _vec, "rates": _vec, "Rddot": lambda: RNG.normal(size=(3, 3)), "qddot": lambda: RNG.normal(size=4),
    "psiddot": _vec, "accelerations": _vec, "r": _vec, "epsilon": _vec, "vector": _vec, "relative_rate": _vec,
    "relative_velocity": _vec, "relative_acceleration": _vec, "velocity": _vec, "masses": lambda: RNG.uniform(
        0.5, 2.0, size=4), "positions": lambda: RNG.normal(size=(4, 3)), "mass": _positive,
    "size": lambda: RNG.uniform(0.5, 2.0, size=3), "radius": _positive, "height": _positive,
    "semi_axes": lambda: RNG.uniform(0.5, 2.0, size=3), "length": _positive, "major_radius": lambda: 2.0,
    "minor_radius": lambda: 0.5, "I_cm": _spd, "r_c": _vec, "I_point": lambda: _spd() + 10.0 * np.eye(3),
    "I": _spd, "rotation": _quat, "body": lambda: np.array([1.0, 2.0, 2.5]), "bodies": lambda: np.array(
        [[1.0, 2.0, 2.5], [2.0, 2.0, 3.0]]), "t": _times, "omega0": lambda: np.array([0.1, 1.0, 0.1]),
    "traj": _trajectory, "magnetic_field": _vec, "phi": lambda: 0.7, "n": lambda: 0.3, "m": lambda: 0.4,
    "xi": lambda: RNG.normal(size=6), "matrix": lambda: _se3_matrix(), "transform": _transform, "offset": _vec,
    "start": _transform, "end": _transform, "fraction": lambda: 0.3, "body_point": _vec,
    "latitude_deg": lambda: 40.0, "speed": lambda: 100.0, "elevation_deg": lambda: 30.0,
    "azimuth_deg": lambda: 20.0, "duration": lambda: 20.0, "amplitude": lambda: 0.1, "half_angle": lambda: 0.1,
    "rate": lambda: 2.0, "sample_time": lambda: 0.01, "n_samples": lambda: 20, "samples_per_update": lambda: 2,
    "q0": _quat, "dtheta": lambda: 0.01 * RNG.normal(size=(8, 3)), "omega_body": lambda: RNG.normal(size=(5, 3)),
    "tau": lambda: np.array([0.1, 1.0]), "sigma": lambda: 0.01, "correlation_time": lambda: 10.0,
    "from_frame": lambda: "NED", "to_frame": lambda: "ENU", "r0": _vec, "v0": _vec, "parts": lambda: _parts(),
    "gyro": lambda: 0.2 * RNG.normal(size=(50, 3)), "accel": lambda: _gravity_with_noise(50),
    "mag": lambda: np.array([0.0, 20.0, -40.0]) + RNG.normal(size=(50, 3)), "q_ref": _quat,
    "reference": lambda: _quat((50,)),
    "A": lambda: _hat(_vec()), "vertices": lambda: _tetrahedron()[0], "faces": lambda: _tetrahedron()[1], "top": lambda: _top(),
}
# where a name means something else in one function: (function, parameter) -> valid value
SPECIFIC = {
    ("quat_power", "p"): lambda: 0.7, ("quat_slerp", "t"): lambda: 0.3, ("mrp_to_quat", "p"): lambda: 0.5 * _vec(),
    ("quat_mean", "q"): lambda: _quat((5,)), ("align_vectors", "a"): lambda: _vec((4,)),
    ("align_vectors", "b"): lambda: _vec((4,)), ("davenport_to_quat", "order"): lambda: "extrinsic",
    ("quat_to_davenport", "order"): lambda: "extrinsic", ("davenport_gimbal_lock", "order"): lambda: "extrinsic",
    ("bortz_coefficient", "angle"): lambda: 0.5, ("centrodes", "angle"): lambda: np.linspace(0.0, 1.0, 7),
    ("centrodes", "t"): lambda: np.linspace(0.0, 1.0, 7), ("centrodes", "position"): lambda: RNG.normal(size=(7, 2)),
    ("velocity_from_momentum", "p"): _vec, ("hamiltonian_terms", "p"): _vec, ("hamiltonian", "p"): _vec,
    ("simulate_drop", "height"): lambda: 50.0, ("eastward_deflection", "height"): lambda: 50.0,
    ("rotvec_to_axis_angle", "psi"): lambda: 0.5 * _vec(), ("quat_identity", "shape"): lambda: (2,),
    ("allan_deviation", "rate"): lambda: RNG.normal(size=(64, 3)), ("attitude_from_rates", "t"): lambda: _times(5),
    ("gibbs_to_quat", "g"): lambda: 0.5 * _vec(), ("solve_free_batch", "t"): _times,
    ("fit_free_rotation", "t"): lambda: np.linspace(0.0, 4.0, 60),
    ("fit_free_rotation", "omega"): lambda: _free_omega(np.linspace(0.0, 4.0, 60)),
    ("poinsot", "t"): _times, ("poinsot", "omega0"): lambda: np.array([0.1, 1.0, 0.1]),
    ("point_trajectory", "t"): lambda: None, ("point_trajectory", "rotation"): lambda: None,
    ("point_trajectory", "translation"): lambda: None, ("point_trajectory", "trajectory"): _trajectory,
    ("jacobi_elliptic", "u"): lambda: 0.7, ("coning_coefficients", "samples_per_update"): lambda: 3,
    # a small step budget: a time span scaled to 1e300 s must stop, not run for an hour
    **{(name, "max_steps"): (lambda: 20_000) for name in ("simulate", "simulate_batch", "simulate_6dof",
                                                          "simulate_particle", "foucault_pendulum")},
    ("convert_attitude_frame", "q"): _quat, ("elliptic_k", "m"): lambda: 0.4, ("elliptic_f", "m"): lambda: 0.4,
    ("elliptic_pi", "m"): lambda: 0.4, ("complete_elliptic_pi", "m"): lambda: 0.4, ("jacobi_elliptic", "m"): lambda: 0.4,
    **{(name, q): (lambda: _quat((5,))) for name in ("attitude_error", "attitude_error_angles") for q in ("q", "q_ref")},
    ("attitude_from_vectors", "accel"): lambda: np.array([0.1, -0.2, 9.8]),
    ("attitude_from_vectors", "mag"): lambda: np.array([0.0, 20.0, -40.0]),
    ("instantaneous_centre", "omega"): lambda: 0.7, ("instantaneous_centre", "velocity"): lambda: RNG.normal(size=2),
}


def _gravity_with_noise(n):
    return np.array([0.0, 0.0, 9.81]) + 0.05 * RNG.normal(size=(n, 3))


def _su2():
    import kreisel as kr
    return kr.quat_to_su2(_quat())


def _cayley_klein():
    import kreisel as kr
    return kr.quat_to_cayley_klein(_quat())


def _hat(v):
    import kreisel as kr
    return kr.hat(v)


def _rate_of(R):
    import kreisel as kr
    return kr.hat(_vec()) @ R


def _se3_matrix():
    import kreisel as kr
    return kr.se3.se3_hat(RNG.normal(size=6))


def _parts():
    import kreisel as kr
    return [kr.inertia.from_points(VALID["masses"](), VALID["positions"]()), kr.inertia.from_points([1.0], [[0, 0, 1.0]])]


def _tetrahedron():
    vertices = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    faces = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    return vertices, faces


def _top():
    import kreisel as kr
    return kr.EulerTop(1.0, 2.0, 2.5)


def _free_omega(t):
    import kreisel as kr
    return kr.EulerTop(1.0, 2.0, 2.5).solve(t, [0.1, 1.0, 0.1]).omega


def public_functions():
    """(qualified name, function) of every public function of the numerical subpackages."""
    seen = {}
    for package in PACKAGES:
        module = importlib.import_module(f"kreisel.{package}")
        for name in module.__all__:
            obj = getattr(module, name)
            if callable(obj) and not inspect.isclass(obj) and name not in ELSEWHERE and name not in seen:
                seen[name] = (f"{package}.{name}", obj)
    return sorted(seen.values())


FUNCTIONS = public_functions()


def valid_arguments(name, fn):
    """Valid keyword arguments for the required (and table-listed optional) parameters of ``fn``."""
    kwargs = {}
    for param in inspect.signature(fn).parameters.values():
        key = (name, param.name)
        if key in SPECIFIC:
            kwargs[param.name] = SPECIFIC[key]()
        elif param.default is inspect.Parameter.empty:
            if param.name not in VALID:
                raise KeyError(f"the fuzz table has no valid value for parameter {param.name!r} of {name}: "
                               "add it to VALID or SPECIFIC")
            kwargs[param.name] = VALID[param.name]()
    return kwargs


# ---------------------------------------------------------------------------- calling and judging


def call(fn, kwargs):
    """``fn(**kwargs)`` with RuntimeWarnings (overflow, ComplexWarning, ...) and kreisel's singularity warnings raised as errors."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        warnings.simplefilter("error", np.exceptions.ComplexWarning)
        warnings.simplefilter("error", KinematicSingularityWarning)
        return fn(**kwargs)


def numbers(value, depth=0):
    """Every float/complex array found in ``value`` (arrays, tuples, dataclasses, result objects)."""
    if depth > 3 or value is None or isinstance(value, (str, bytes, bool)):
        return []
    if isinstance(value, (int, float, complex, np.number)):
        return [np.asarray(value)]
    if isinstance(value, np.ndarray):
        return [value] if value.dtype.kind in "fc" else []
    if isinstance(value, (tuple, list)):
        return [a for v in value for a in numbers(v, depth + 1)]
    if dataclasses.is_dataclass(value):
        return [a for f in dataclasses.fields(value) for a in numbers(getattr(value, f.name), depth + 1)]
    fields = getattr(value, "__dict__", None)
    if isinstance(fields, dict):
        return [a for k, v in fields.items() if not k.startswith("_") for a in numbers(v, depth + 1)]
    return []


def finite(value):
    return all(np.all(np.isfinite(a)) for a in numbers(value))


def same(a, b):
    x, y = numbers(a), numbers(b)
    return len(x) == len(y) and all(u.shape == v.shape and np.array_equal(u, v, equal_nan=True) for u, v in zip(x, y))


def assert_clear_refusal(exc, param, name):
    """``exc`` is a ValueError/TypeError (not a bare numerical one) whose message names ``param``."""
    assert isinstance(exc, (ValueError, TypeError)) and not isinstance(exc, (ZeroDivisionError, FloatingPointError)), (
        f"{name}({param}=...) raised {type(exc).__name__}: {exc}")
    message = str(exc)
    assert re.search(rf"(?<![A-Za-z0-9_]){re.escape(param)}(?![A-Za-z0-9_])", message), (
        f"{name}: the refusal of a bad {param!r} does not name it: {type(exc).__name__}: {message}")


def outcome(fn, kwargs):
    try:
        return call(fn, kwargs), None
    except Exception as exc:  # judged by the caller
        return None, exc


def array_parameters(kwargs):
    """Names of the real-array arguments (numbers, vectors, matrices) of a valid call."""
    return [k for k, v in kwargs.items()
            if isinstance(v, (float, int, np.ndarray)) and not isinstance(v, bool) and np.asarray(v).dtype.kind in "fi"]


# arguments whose last axis has no fixed length (samples, elementwise inputs)
FREE_LENGTH = {"t", "tau", "masses", "rate", "magnetic_field", "angle", "omega_body", "dtheta", "positions"}


def perturbations(value, param):
    """(label, perturbed value, what is expected) for the real array argument ``param``."""
    x = np.asarray(value)
    out = [
        ("complex", x + 1j, "refuse"),
        ("datetime64", np.round(x).astype("int64").astype("datetime64[D]"), "refuse"),
        ("strings", x.astype(str), "refuse"),
        ("object strings", np.array(x.astype(str), dtype=object), "refuse"),
        ("nan", np.full(x.shape, np.nan), "refuse"),
        ("inf", np.full(x.shape, np.inf), "refuse"),
        ("empty batch", np.empty((0,) + x.shape, dtype=x.dtype), "empty"),
    ]
    if x.ndim:
        out.append(("read-only", _read_only(x), "same"))
        out.append(("non-contiguous", np.repeat(x, 2, axis=-1)[..., ::2], "same"))
        if param not in FREE_LENGTH:
            out.append(("wrong last dimension", np.concatenate([x, x[..., :1]], axis=-1), "refuse"))
    if np.all((x == 0) | (x == 1)):
        out.append(("bool", x.astype(bool), "same"))
    return out


def _read_only(x):
    y = x.copy()
    y.flags.writeable = False
    return y


def _prepare(qualified):
    fn = dict(FUNCTIONS)[qualified]
    name = qualified.split(".")[1]
    kwargs = valid_arguments(name, fn)
    base, exc = outcome(fn, kwargs)
    assert exc is None, f"{qualified} fails on valid input {kwargs}: {type(exc).__name__}: {exc}"
    assert finite(base), f"{qualified} returns non-finite numbers for valid input {kwargs}"
    return name, fn, kwargs, base


NAMES = [name for name, _ in FUNCTIONS]


def test_every_public_function_is_fuzzed():
    # the numerical subpackages' functions all take part (a new one needs valid values for its parameters)
    assert len(FUNCTIONS) > 100 and "kinematics.screw_axis" in NAMES and "nav.coning_motion" in NAMES


@pytest.mark.parametrize("qualified", NAMES)
def test_malformed_arguments_are_refused_clearly_or_change_nothing(qualified):
    name, fn, kwargs, base = _prepare(qualified)
    if name in INVARIANTS:
        INVARIANTS[name](base, kwargs)
    for param in array_parameters(kwargs):
        for label, value, expected in perturbations(kwargs[param], param):
            result, exc = outcome(fn, {**kwargs, param: value})
            where = f"{qualified}({param}= {label})"
            if expected == "refuse":
                assert exc is not None, f"{where} was accepted: {result!r}"[:400]
                assert_clear_refusal(exc, param, where)
            elif expected == "same":
                assert exc is None, f"{where} raised {type(exc).__name__}: {exc}"
                assert same(result, base), f"{where} gives a different result"
            elif exc is not None:
                assert_clear_refusal(exc, param, where)
            else:
                assert finite(result), f"{where} gives non-finite numbers"


MISLEADING = re.compile(r"must be finite|non-?finite|must be non-?zero|is zero|must not be zero|NaN", re.I)


@pytest.mark.parametrize("qualified", NAMES)
@FUZZ
@given(data=st.data())
def test_extreme_magnitudes_give_right_answers_or_clear_refusals(qualified, data):
    name, fn, kwargs, base = _prepare(qualified)
    params = array_parameters(kwargs)
    if not params:
        return
    param = data.draw(st.sampled_from(params), label="param")
    exponent = data.draw(st.integers(-300, 300), label="exponent")
    scale = 10.0 ** exponent
    value = np.asarray(kwargs[param], dtype=float) * scale
    result, exc = outcome(fn, {**kwargs, param: value if np.ndim(kwargs[param]) else float(value)})
    where = f"{qualified}({param} × 1e{exponent})"
    if isinstance(exc, (StepBudgetExceeded, KinematicSingularityWarning)):
        # a bounded run of a scaled-up time span; a documented coordinate singularity (gimbal lock,
        # |psi| = 2 pi k: those entries are NaN and this warning says so, Theory §3.5-6)
        return
    degree = HOMOGENEOUS.get((name, param))
    if exc is not None:
        assert_clear_refusal(exc, param, where)
        assert not MISLEADING.search(str(exc)), f"{where}: finite, nonzero input refused as {exc}"
        if degree is not None:
            # refusing is right only where the exact answer is not representable
            logs = [np.log10(np.abs(a[a != 0])) + k * exponent for k, a in zip(degrees(degree, base), numbers(base))]
            assert any(np.any(np.abs(x) > 290) for x in logs), f"{where} refused ({exc}) though the answer is representable"
        return
    assert finite(result), f"{where} gives non-finite numbers without an error"
    if name in INVARIANTS:
        INVARIANTS[name](result, {**kwargs, param: value})
    if degree is not None:
        for got, want, k in zip(numbers(result), numbers(base), degrees(degree, base)):
            factor = scale ** k if abs(k * exponent) < 300 else None
            if factor is None or not np.all(np.isfinite(want * factor)):
                continue
            np.testing.assert_allclose(got, want * factor, rtol=1e-12, atol=1e-300,
                                       err_msg=f"{where} is not {scale:g}^{k} × the plain result")


# ---------------------------------------------------------------------------- laws and invariants

# f(..., s x, ...) = s^k f(..., x, ...) for s > 0: (function, parameter) -> k
HOMOGENEOUS = {
    ("quat_normalize", "q"): 0, ("quat_norm", "q"): 1, ("quat_conjugate", "q"): 1, ("quat_multiply", "p"): 1,
    ("quat_multiply", "q"): 1, ("quat_inverse", "q"): -1, ("quat_apply", "v"): 1, ("hat", "v"): 1, ("vee", "A"): 1,
    ("axis_angle_to_rotvec", "axis"): 0, ("quat_to_euler", "q"): 0, ("quat_to_matrix", "q"): 0,
    ("quat_to_rotvec", "q"): 0, ("quat_rate", "omega"): 1, ("angular_velocity_from_quat_rate", "qdot"): 1,
    ("angular_velocity", "Rdot"): 1, ("euler_rates", "omega"): 1, ("angular_velocity_from_euler_rates", "rates"): 1,
    ("point_velocity", "omega"): 1, ("point_velocity", "r"): 1,
    ("moment_about_axis", "axis"): 0, ("moment_about_axis", "I"): 1, ("principal_axes", "I"): None,
    ("inertia_ellipsoid", "I"): None, ("rotate", "I"): 1, ("box", "mass"): 1, ("solid_sphere", "mass"): 1,
    ("solid_sphere", "radius"): 2, ("thin_rod", "length"): 2, ("thin_rod", "mass"): 1, ("thin_disk", "radius"): 2,
    ("thin_ring", "radius"): 2, ("solid_cylinder", "mass"): 1, ("solid_ellipsoid", "semi_axes"): 2,
    ("box", "size"): 2, ("angular_velocity_enu", "omega"): 1, ("foucault_precession_rate", "omega"): 1,
    ("larmor_precession_rate", "magnetic_field"): 1, ("gauss_markov_allan_deviation", "sigma"): 1,
    ("allan_deviation", "rate"): (0, 1), ("canonical_momentum", "mass"): 1, ("inertial_forces", "mass"): 1,
    ("quat_to_gibbs", "q"): 0, ("quat_to_mrp", "q"): 0, ("quat_to_su2", "q"): None,
}
HOMOGENEOUS = {k: v for k, v in HOMOGENEOUS.items() if v is not None}


def degrees(degree, result):
    """The degree of each number array of ``result``: one for all, or a tuple, one per output (taus, adev)."""
    return degree if isinstance(degree, tuple) else [degree] * len(numbers(result))


def _unit_quaternion(q, kwargs):
    np.testing.assert_allclose(np.linalg.norm(q, axis=-1), 1.0, rtol=0, atol=4e-16 * 4)


def _rotation_matrix(R, kwargs):
    R = np.asarray(R)
    np.testing.assert_allclose(R @ np.swapaxes(R, -1, -2), np.broadcast_to(np.eye(3), R.shape), atol=2e-15)
    np.testing.assert_allclose(np.linalg.det(R), 1.0, atol=2e-15)


def _axis_angle(result, kwargs):
    axis, angle = result
    np.testing.assert_allclose(np.linalg.norm(axis, axis=-1), 1.0, atol=2e-16 * 4)


def _rotvec_of(quaternion):
    """Invariant of a map to a rotation vector: its exponential is the rotation of the input quaternion."""
    def check(psi, kwargs):
        import kreisel as kr
        q = kr.quat_normalize(quaternion(kwargs))
        back = kr.rotvec_to_quat(psi)
        assert np.all(np.linalg.norm(psi, axis=-1) <= np.pi * (1 + 1e-15))
        np.testing.assert_allclose(np.abs(np.sum(back * q, axis=-1)), 1.0, atol=1e-14)
    return check


INVARIANTS = {
    "quat_normalize": _unit_quaternion, "rotvec_to_quat": _unit_quaternion, "matrix_to_quat": _unit_quaternion,
    "euler_to_quat": _unit_quaternion, "gibbs_to_quat": _unit_quaternion, "mrp_to_quat": _unit_quaternion,
    "su2_to_quat": _unit_quaternion, "cayley_klein_to_quat": _unit_quaternion, "quat_slerp": _unit_quaternion,
    "davenport_to_quat": _unit_quaternion, "euler_parameters_to_quat": _unit_quaternion,
    "quat_to_matrix": _rotation_matrix, "rotvec_to_matrix": _rotation_matrix, "euler_to_matrix": _rotation_matrix,
    "orthonormalize": _rotation_matrix, "euler_parameters_to_matrix": _rotation_matrix,
    "enu_to_ecef_matrix": _rotation_matrix, "quat_to_rotvec": _rotvec_of(lambda kw: kw["q"]),
    "rotvec_to_axis_angle": _axis_angle,
}


# ---------------------------------------------------------------------------- computed angles
# A rotation depends on its angle modulo 2π. Where that angle is computed (the length of a rotation
# vector or twist, an exponent or interpolation parameter times an angle), its rounding error of
# ~1e-16 of its size exceeds 2π by |ψ| ~ 6e16: beyond ROTVEC_RANGE (1e8 rad) every such entry point
# refuses, below it the result is the exact rotation of the given doubles (mpmath) to the rounding of
# the computed angle.

mpmath = pytest.importorskip("mpmath")
_DIRECTION = np.array([0.3123456789, -0.7765432198, 0.5469871234])   # general: its length is not exact
_SCALES = [1e-300, 1e-160, 1e-20, 1e-4, 0.7, 3.0, 1e4, 9.9e7, 1.02e8, 1e12, 1e155, 1e300]


def _mp_quat(psi):
    """exp of the rotation vector ``psi`` (doubles taken exactly) as (cos(a/2), n sin(a/2)) in mpmath."""
    x, y, z = (mpmath.mpf(float(c)) for c in psi)
    a = mpmath.sqrt(x * x + y * y + z * z)
    s = mpmath.sin(a / 2) / a if a else mpmath.mpf(0.5)
    return [mpmath.cos(a / 2), s * x, s * y, s * z], a


def _mp_angle_axis(q):
    """Angle in [0, π] and unit axis of the quaternion ``q`` (doubles taken exactly)."""
    q0, q1, q2, q3 = (mpmath.mpf(float(c)) for c in q)
    if q0 < 0:
        q0, q1, q2, q3 = -q0, -q1, -q2, -q3
    v = mpmath.sqrt(q1 * q1 + q2 * q2 + q3 * q3)
    return 2 * mpmath.atan2(v, q0), [q1 / v, q2 / v, q3 / v]


def _mp_matrix(q):
    q0, q1, q2, q3 = q
    return [[q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3, 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2)],
            [2 * (q1 * q2 + q0 * q3), q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3, 2 * (q2 * q3 - q0 * q1)],
            [2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3]]


def _scaled_turn(q, factor):
    """exp(factor log q) in mpmath, and |factor| times the angle of q."""
    angle, (n1, n2, n3) = _mp_angle_axis(q)
    half = mpmath.mpf(float(factor)) * angle / 2
    return [mpmath.cos(half), n1 * mpmath.sin(half), n2 * mpmath.sin(half), n3 * mpmath.sin(half)], abs(2 * half)


_Q = np.array([0.8, 0.1, -0.5, 0.3]) / np.linalg.norm([0.8, 0.1, -0.5, 0.3])
_V = np.array([0.4, -1.1, 2.0])


def _exp_coords_case(s):
    import kreisel as kr
    psi = s * _DIRECTION
    T = kr.se3.RigidTransform.from_exp_coords(np.r_[psi, _V])
    q, a = _mp_quat(psi)
    x, y, z = (mpmath.mpf(float(c)) for c in psi)
    v = [mpmath.mpf(float(c)) for c in _V]
    A = (1 - mpmath.cos(a)) / a**2 if a else mpmath.mpf(0.5)
    B = (a - mpmath.sin(a)) / a**3 if a else mpmath.mpf(1) / 6
    c = [y * v[2] - z * v[1], z * v[0] - x * v[2], x * v[1] - y * v[0]]
    cc = [y * c[2] - z * c[1], z * c[0] - x * c[2], x * c[1] - y * c[0]]
    r = [v[i] + A * c[i] + B * cc[i] for i in range(3)]
    return np.r_[T.rotation.as_quat(), T.translation], q + r, a


# name -> (argument scaled, case(scale) -> (result, mpmath reference, the angle computed))
COMPUTED_ANGLES = {
    "rotvec_to_quat": ("psi", lambda s: (__import__("kreisel").rotvec_to_quat(s * _DIRECTION),) + _mp_quat(s * _DIRECTION)),
    "rotvec_to_matrix": ("psi", lambda s: (lambda q, a: (__import__("kreisel").rotvec_to_matrix(s * _DIRECTION),
                                                          _mp_matrix(q), a))(*_mp_quat(s * _DIRECTION))),
    "Rotation.from_rotvec": ("rotvec", lambda s: (__import__("kreisel").so3.Rotation.from_rotvec(s * _DIRECTION)
                                                   .as_quat(),) + _mp_quat(s * _DIRECTION)),
    "RigidTransform.from_exp_coords": ("exp_coords", _exp_coords_case),
    "quat_power": ("p", lambda s: (__import__("kreisel").quat_power(_Q, 0.77 * s),) + _scaled_turn(_Q, 0.77 * s)),
    "quat_slerp": ("t", lambda s: (__import__("kreisel").quat_slerp([1.0, 0, 0, 0], _Q, 0.77 * s),)
                   + _scaled_turn(_Q, 0.77 * s)),
}


@pytest.mark.parametrize("name", sorted(COMPUTED_ANGLES))
def test_computed_angles_give_the_exact_rotation_or_are_refused_beyond_the_range(name):
    from kreisel._validation import ROTVEC_RANGE
    param, case = COMPUTED_ANGLES[name]
    with mpmath.workdps(340):   # a^2 of 1e300 and its sine need ~330 digits
        for scale in _SCALES:
            where = f"{name}({param} ~ {scale:g})"
            try:
                result, reference, angle = call(case, {"s": scale})
            except ValueError as exc:
                assert_clear_refusal(exc, param, where)
                assert "out of range" in str(exc) and "modulo 2*pi" in str(exc), where
                assert scale > ROTVEC_RANGE / 3, f"{where} refused within the range: {exc}"
                continue
            assert scale < ROTVEC_RANGE * 3, f"{where} accepted beyond the range: {result}"
            want = np.array(mpmath.matrix(reference).tolist(), dtype=float).reshape(np.shape(result))
            # the rounding of the computed angle (~1.5 ulp of it) moves the result by as much
            tol = 2e-16 * 4 * max(1.0, float(angle)) + 2e-16 * 4 * np.abs(want).max()
            if name.startswith(("Rotation", "RigidTransform")) and np.dot(result[:4], want[:4]) < 0:
                want[:4] = -want[:4]   # the classes may store -q for q (the same rotation)
            error = np.abs(result - want).max()
            assert error <= tol, f"{where}: error {error:.3g} > {tol:.3g}"
