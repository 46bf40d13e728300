"""``out=`` on every array function of kreisel.so3, kreisel.kinematics and kreisel.se3.

Data-driven: the functions are enumerated from the modules' ``__all__``; each
is called on sample inputs with and without ``out=`` (bitwise identical
results), with refused ``out`` arrays, and with ``out`` aliasing each input
of the result's shape and dtype. A function added to an ``__all__`` without
a sample input here (or a reason to be left out) fails the enumeration test.
"""

from __future__ import annotations

import inspect
import sys
import tracemalloc
import weakref

import numpy as np
import pytest

import kreisel.kinematics as kinematics
import kreisel.se3 as se3
import kreisel.so3 as so3
from kreisel import release_memory as kr_release
from kreisel._compiled import gufunc, outputs

#: Public functions that return no single array (tuples, objects, constants, parsed names).
NOT_ARRAY_FUNCTIONS = {
    "generators": "a constant (3, 3, 3) array of no input",
    "parse_sequence": "returns (axes, intrinsic)",
    "rotvec_to_axis_angle": "returns (axis, angle)",
    "align_vectors": "returns (quaternions, rssd[, sensitivity])",
    "create_group": "returns quaternions of a group given by name",
    "reduce_quat": "returns (quaternions, left indices, right indices)",
    "three_term_velocity": "returns VelocityTerms",
    "five_term_acceleration": "returns AccelerationTerms",
    "point_trajectory": "returns PointMotion",
    "screw_axis": "returns ScrewAxis",
    "centrodes": "returns Centrodes",
    "change_base_point": "returns a RigidTransform",
    "sclerp": "returns a RigidTransform",
    "release_memory": "frees kreisel's idle memory, returns a byte count",
}

N = 5
_rng = np.random.default_rng(7)


def _unit(x):
    return x / np.linalg.norm(x, axis=-1, keepdims=True)


QUATS = _unit(_rng.normal(size=(N, 4)))
VECTORS = _rng.normal(size=(N, 3))
ANGLES = _rng.uniform(0.3, 1.2, size=(N, 3))  # away from gimbal lock
ROTVECS = 0.5 * _rng.normal(size=(N, 3))
MATRICES = so3.quat_to_matrix(QUATS)
DAVENPORT_AXES = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [np.cos(0.4), 0.0, np.sin(0.4)]])
TWISTS = 0.5 * _rng.normal(size=(N, 6))

#: Inputs by parameter name; SPECIAL overrides them per function.
BY_NAME = {
    "p": _unit(_rng.normal(size=(N, 4))), "q": QUATS, "v": VECTORS, "R": MATRICES, "A": so3.hat(VECTORS),
    "psi": ROTVECS, "axis": _unit(VECTORS), "angle": _rng.uniform(0.1, 3.0, N), "a": ROTVECS, "b": 0.3 * VECTORS,
    "Q": MATRICES, "seq": "ZXZ", "angles": ANGLES, "u": so3.quat_to_su2(QUATS), "ck": so3.quat_to_cayley_klein(QUATS),
    "e": so3.quat_to_euler_parameters(QUATS), "g": so3.quat_to_gibbs(QUATS), "t": np.linspace(0.0, 1.0, N),
    "axes": DAVENPORT_AXES, "order": "e", "omega": VECTORS, "qdot": _rng.normal(size=(N, 4)),
    "qddot": _rng.normal(size=(N, 4)), "psidot": _rng.normal(size=(N, 3)), "psiddot": _rng.normal(size=(N, 3)),
    "rates": _rng.normal(size=(N, 3)), "accelerations": _rng.normal(size=(N, 3)), "Rdot": _rng.normal(size=(N, 3, 3)),
    "Rddot": _rng.normal(size=(N, 3, 3)), "r": _rng.normal(size=(N, 3)), "epsilon": _rng.normal(size=(N, 3)),
    "vector": _rng.normal(size=(N, 3)), "relative_rate": _rng.normal(size=(N, 3)), "velocity": _rng.normal(size=(N, 3)),
    "xi": TWISTS, "matrix": se3.se3_hat(TWISTS),
}
SPECIAL = {
    "quat_power": {"p": 0.3},
    "mrp_to_quat": {"p": so3.quat_to_mrp(QUATS)},
    "quat_identity": {"shape": (N,)},
    "davenport_to_quat": {"angles": so3.quat_to_davenport(DAVENPORT_AXES, "e", QUATS)},
    "davenport_gimbal_lock": {"angles": so3.quat_to_davenport(DAVENPORT_AXES, "e", QUATS)},
    "quat_mean": {"q": QUATS[None]},
    "angular_velocity": {"Rdot": MATRICES @ so3.hat(VECTORS)},
    "angular_acceleration": {"Rdot": MATRICES @ so3.hat(VECTORS)},
    "bch": {"a": 0.1 * ROTVECS, "b": 0.1 * VECTORS},
    "instantaneous_centre": {"omega": _rng.uniform(0.5, 2.0, N), "velocity": _rng.normal(size=(N, 2))},
}


def _array_functions():
    found = {}
    for module in (so3, kinematics, se3):
        for name in module.__all__:
            obj = getattr(module, name)
            if inspect.isfunction(obj) and name not in NOT_ARRAY_FUNCTIONS:
                found[name] = obj
    return found


FUNCTIONS = _array_functions()


def _arguments(name):
    function = FUNCTIONS[name]
    special = SPECIAL.get(name, {})
    arguments = {}
    for parameter in inspect.signature(function).parameters.values():
        if parameter.name in special:
            arguments[parameter.name] = special[parameter.name]
        elif parameter.default is inspect.Parameter.empty and parameter.kind is not parameter.KEYWORD_ONLY:
            arguments[parameter.name] = BY_NAME[parameter.name]
    return arguments


def test_every_array_function_takes_out():
    for name, function in FUNCTIONS.items():
        parameter = inspect.signature(function).parameters.get("out")
        assert parameter is not None and parameter.kind is parameter.KEYWORD_ONLY, name
        assert parameter.default is None, name
        assert "out : ndarray, optional" in function.__doc__, name
    assert not set(NOT_ARRAY_FUNCTIONS) - {n for m in (so3, kinematics, se3) for n in m.__all__}


#: Public methods of the exported classes that return no single array.
NOT_ARRAY_METHODS = {
    "Rotation.reduce": "returns a Rotation (and indices)",
    "Rotation.as_axis_angle": "returns (axis, angle)",
    "Rotation.to_scipy": "returns a scipy Rotation",
    "Rotation.inv": "returns a Rotation",
    "Rotation.mean": "returns a Rotation",
    "Rotation.slerp": "returns a Rotation",
    "RigidTransform.as_components": "returns (Rotation, translation)",
    "RigidTransform.as_screw": "returns a Screw",
    "RigidTransform.to_scipy": "returns a scipy RigidTransform",
    "RigidTransform.mean": "returns a RigidTransform",
    "RigidTransform.inv": "returns a RigidTransform",
    "RigidTransform.change_base_point": "returns a RigidTransform",
}

ROTATIONS = so3.Rotation.from_quat(QUATS)
POSES = se3.RigidTransform.from_rotation_translation(QUATS, VECTORS[::-1].copy())
#: The object and positional arguments of each array method (the defaults of the others).
METHOD_CALLS = {
    "Rotation.as_quat": (ROTATIONS, (False, False)),
    "Rotation.as_euler": (ROTATIONS, ("ZXZ", True)),
    "Rotation.as_davenport": (ROTATIONS, (DAVENPORT_AXES, "e")),
    "Rotation.apply": (ROTATIONS, (VECTORS, True)),
    "Rotation.approx_equal": (ROTATIONS, (so3.Rotation.from_quat(QUATS[::-1].copy()), 1.0)),
    "RigidTransform.apply": (POSES, (VECTORS, True)),
    "RigidTransform.apply_vector": (POSES, (VECTORS,)),
}


def _array_methods():
    found = {}
    for module in (so3, kinematics, se3):
        for class_name in module.__all__:
            cls = getattr(module, class_name)
            if inspect.isclass(cls):
                for name, member in vars(cls).items():
                    qualified = f"{class_name}.{name}"
                    if not name.startswith("_") and inspect.isfunction(member) and qualified not in NOT_ARRAY_METHODS:
                        found[qualified] = member
    return found


METHODS = _array_methods()


def _method_call(qualified):
    """``call(**keywords)`` of the method on its sample object and arguments."""
    default = POSES if qualified.startswith("RigidTransform.") else ROTATIONS
    obj, args = METHOD_CALLS.get(qualified, (default, ()))
    return lambda **keywords: METHODS[qualified](obj, *args, **keywords)


def test_every_array_method_takes_out():
    assert {"Rotation.as_matrix", "Rotation.apply", "RigidTransform.as_matrix", "RigidTransform.apply"} <= set(METHODS)
    for name, method in METHODS.items():
        parameter = inspect.signature(method).parameters.get("out")
        assert parameter is not None and parameter.kind is parameter.KEYWORD_ONLY, name
        assert parameter.default is None, name
        assert "out : ndarray, optional" in method.__doc__, name
    assert set(NOT_ARRAY_METHODS) <= {f"{cls.__name__}.{name}" for cls in (so3.Rotation, se3.RigidTransform)
                                      for name in vars(cls)}


@pytest.mark.parametrize("name", sorted(METHODS))
def test_methods_out_gives_the_same_bits_and_wrong_out_is_refused(name):
    call = _method_call(name)
    expected = np.asarray(call())
    out = _garbage_like(expected)
    assert call(out=out) is out
    assert out.dtype == expected.dtype and out.tobytes() == expected.tobytes()
    other_dtype = np.float32 if expected.dtype != np.float32 else np.float64
    for error, wrong in [(ValueError, np.empty(expected.shape + (2,), expected.dtype)),
                         (TypeError, np.empty(expected.shape, other_dtype)), (TypeError, expected.tolist())]:
        with pytest.raises(error, match="out"):
            call(out=wrong)


def test_method_out_may_be_the_vectors():
    for qualified in ("Rotation.apply", "RigidTransform.apply", "RigidTransform.apply_vector"):
        obj, (vectors, *rest) = METHOD_CALLS[qualified]
        expected = METHODS[qualified](obj, vectors, *rest)
        buffer = vectors.copy()
        assert METHODS[qualified](obj, buffer, *rest, out=buffer) is buffer
        assert buffer.tobytes() == expected.tobytes(), qualified


def _garbage_like(result):
    out = np.empty_like(result)
    out[...] = 7 if result.dtype == bool else np.nan
    return out


@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_out_gives_the_same_bits_and_is_returned(name):
    arguments = _arguments(name)
    expected = np.asarray(FUNCTIONS[name](**arguments))
    out = _garbage_like(expected)
    got = FUNCTIONS[name](**arguments, out=out)
    assert got is out
    assert got.dtype == expected.dtype and got.shape == expected.shape
    assert got.tobytes() == expected.tobytes()


@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_wrong_out_is_refused_naming_out(name):
    arguments = _arguments(name)
    expected = np.asarray(FUNCTIONS[name](**arguments))
    other_dtype = np.float32 if expected.dtype != np.float32 else np.float64
    wrong = [
        (ValueError, np.empty(expected.shape + (2,), expected.dtype)),
        (ValueError, np.empty((N + 1,) + expected.shape[1:], expected.dtype) if expected.ndim else np.empty(2, expected.dtype)),
        (TypeError, np.empty(expected.shape, other_dtype)),
        (TypeError, expected.tolist()),
    ]
    read_only = np.empty_like(expected)
    read_only.flags.writeable = False
    wrong.append((ValueError, read_only))
    for error, out in wrong:
        with pytest.raises(error, match="out"):
            FUNCTIONS[name](**arguments, out=out)


@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_out_may_be_an_input(name):
    arguments = _arguments(name)
    expected = np.asarray(FUNCTIONS[name](**arguments))
    aliased = 0
    for key, value in arguments.items():
        if isinstance(value, np.ndarray) and value.shape == expected.shape and value.dtype == expected.dtype:
            buffer = value.copy()
            got = FUNCTIONS[name](**{**arguments, key: buffer}, out=buffer)
            assert got is buffer
            assert got.tobytes() == expected.tobytes(), key
            aliased += 1
    if name in {"quat_multiply", "quat_normalize", "quat_apply", "quat_conjugate", "compose_rotvec", "quat_rate"}:
        assert aliased, "the sample inputs must exercise aliasing here"


# The multi-core loops (batches of at least PARALLEL_THRESHOLD) read each
# element whole before writing it, so out may be an input; any other overlap
# is copied first.
LARGE = gufunc.PARALLEL_THRESHOLD


_big = np.random.default_rng(3)
BIG_Q = _unit(_big.normal(size=(LARGE, 4)))
BIG_V = _big.normal(size=(LARGE, 3))


@pytest.mark.parametrize(("call", "width"), [
    (lambda x, **kw: so3.quat_multiply(BIG_Q, x, **kw), 4),
    (lambda x, **kw: so3.quat_normalize(x, **kw), 4),
    (lambda x, **kw: so3.quat_apply(BIG_Q, x, **kw), 3),
    (lambda x, **kw: so3.rotvec_to_quat(BIG_V, **kw) if x.shape[-1] == 4 else None, 4),
])
def test_large_batches_with_exact_and_partial_overlap(call, width):
    source = _unit(np.random.default_rng(4).normal(size=(LARGE + 2, width)))
    reference = call(source[1:-1].copy())
    for shift in (0, 1, -1):
        buffer = source.copy()
        x, out = buffer[1:-1], buffer[1 + shift:LARGE + 1 + shift]
        got = call(x, out=out)
        assert got is out
        assert got.tobytes() == reference.tobytes(), shift


@pytest.mark.parametrize("name", ["quat_multiply", "quat_apply", "quat_to_matrix", "quat_rate", "rotvec_rate",
                                  "euler_rates", "euler_to_matrix", "rotvec_to_matrix", "matrix_to_quat"])
def test_out_allocates_no_result_sized_array(name):
    rng = np.random.default_rng(5)
    batch = 4000
    arguments = {key: (np.ascontiguousarray(np.repeat(value[:1], batch, axis=0))
                       if isinstance(value, np.ndarray) and value.shape[:1] == (N,) else value)
                 for key, value in _arguments(name).items()}
    arguments = {key: value + 0.0 * rng.random() if isinstance(value, np.ndarray) else value
                 for key, value in arguments.items()}
    out = np.asarray(FUNCTIONS[name](**arguments))
    FUNCTIONS[name](**arguments, out=out)  # warm up: compilation, caches
    tracemalloc.start()
    try:
        FUNCTIONS[name](**arguments, out=out)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < out.nbytes / 4, (peak, out.nbytes)


def test_large_results_are_recycled(monkeypatch):
    monkeypatch.setattr(outputs, "RECYCLED_BYTES", 8 * 1000)
    monkeypatch.setattr(outputs, "IDLE_BYTES", 3 * 8 * 9000)
    monkeypatch.setattr(outputs, "_idle", [])
    q = QUATS[np.arange(1000) % N]
    expected = np.stack([so3.quat_to_matrix(x) for x in q])
    first = so3.quat_to_matrix(q)
    assert first.tobytes() == expected.tobytes()
    slab = first.base._slab
    view = first[3]
    del first
    assert outputs._idle == []  # a view keeps the slab leased
    del view
    assert len(outputs._idle) == 1 and outputs._idle[0] is slab
    second = so3.quat_to_matrix(q)
    assert second.base._slab is slab and outputs._idle == []
    assert second.tobytes() == expected.tobytes()
    # smaller results below the threshold are ordinary arrays
    assert so3.quat_to_matrix(q[:10]).base is None
    # the pool keeps at most IDLE_BYTES of unused slabs, the most recently released
    held = [so3.quat_to_matrix(q) for _ in range(5)]
    slabs = [h.base._slab for h in held]
    while held:
        held.pop(0)
    del second
    assert [id(s) for s in outputs._idle] == [id(s) for s in (slabs[3], slabs[4], slab)]


def _resident_bytes():
    with open("/proc/self/statm") as statm:
        return int(statm.read().split()[1]) * 4096


def test_release_memory_gives_idle_slabs_back(monkeypatch):
    monkeypatch.setattr(outputs, "_idle", [])
    q = QUATS[np.arange(600_000) % N]  # a 43 MB result: recycled by default
    held = so3.quat_to_matrix(q)
    slab = weakref.ref(held.base._slab)
    del held
    assert slab() is not None and outputs._idle == [slab()]
    resident = _resident_bytes() if sys.platform == "linux" else None
    assert kr_release() == 600_000 * 9 * 8
    assert slab() is None and outputs._idle == []
    if resident is not None:  # the pages went back to the operating system, not to malloc's heap
        assert resident - _resident_bytes() > 0.9 * 600_000 * 9 * 8
    assert kr_release() == 0
    # a result still alive is not touched, and its slab is kept again when it dies
    alive = so3.quat_to_matrix(q)
    assert kr_release() == 0
    assert alive.tobytes() == so3.quat_to_matrix(q[:10]).tobytes() * 60_000
    del alive
    assert len(outputs._idle) == 1
