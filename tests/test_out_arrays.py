"""``out=`` on every array function of kreisel.so3, kreisel.kinematics and kreisel.se3.

Data-driven: the functions are enumerated from the modules' ``__all__``, the
methods from the public classes there (public methods and ``__call__``); each
is called on sample inputs with and without ``out=`` (bitwise identical
results), with refused ``out`` arrays, and with ``out`` aliasing each input
of the result's shape and dtype. A name added without ``out=`` fails the
enumeration tests unless it is listed as returning no single array, and
every such listing is checked by calling it: a function moved into the list
that does return an array fails too. Left out by construction: alternative
constructors (classmethods, checked to be annotated as returning no array),
properties (which take no arguments) and the named tuples that carry results.
"""

from __future__ import annotations

import inspect
import pathlib
import tracemalloc

import numpy as np
import pytest

import kreisel.kinematics as kinematics
import kreisel.se3 as se3
import kreisel.so3 as so3
from kreisel._compiled import elementwise, outputs

MODULES = (so3, kinematics, se3)
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
    "create_group": {"group": "O"},
    "davenport_to_quat": {"angles": so3.quat_to_davenport(DAVENPORT_AXES, "e", QUATS)},
    "davenport_gimbal_lock": {"angles": so3.quat_to_davenport(DAVENPORT_AXES, "e", QUATS)},
    "quat_mean": {"q": QUATS[None]},
    "angular_velocity": {"Rdot": MATRICES @ so3.hat(VECTORS)},
    "angular_acceleration": {"Rdot": MATRICES @ so3.hat(VECTORS)},
    "bch": {"a": 0.1 * ROTVECS, "b": 0.1 * VECTORS},
    "instantaneous_centre": {"omega": _rng.uniform(0.5, 2.0, N), "velocity": _rng.normal(size=(N, 2))},
}


ROTATIONS = so3.Rotation.from_quat(QUATS)
POSES = se3.RigidTransform.from_rotation_translation(QUATS, VECTORS[::-1].copy())

#: Public functions that return no single array: (why, a sample call whose result is checked not to be one).
NOT_ARRAY_FUNCTIONS = {
    "parse_sequence": ("returns (axes, intrinsic)", lambda: so3.parse_sequence("ZXZ")),
    "rotvec_to_axis_angle": ("returns (axis, angle)", lambda: so3.rotvec_to_axis_angle(ROTVECS)),
    "align_vectors": ("returns (quaternions, rssd[, sensitivity])", lambda: so3.align_vectors(VECTORS, VECTORS[::-1])),
    "reduce_quat": ("returns (quaternions, left indices, right indices)",
                    lambda: so3.reduce_quat(QUATS, right=so3.create_group("C4"))),
    "three_term_velocity": ("returns VelocityTerms", lambda: kinematics.three_term_velocity(VECTORS, ROTVECS, ANGLES)),
    "five_term_acceleration": ("returns AccelerationTerms",
                               lambda: kinematics.five_term_acceleration(VECTORS, ROTVECS, ANGLES, VECTORS, ROTVECS)),
    "point_trajectory": ("returns PointMotion",
                         lambda: kinematics.point_trajectory(VECTORS[0], np.linspace(0.0, 1.0, N), QUATS)),
    "screw_axis": ("returns ScrewAxis", lambda: kinematics.screw_axis(VECTORS, ROTVECS)),
    "centrodes": ("returns Centrodes", lambda: kinematics.centrodes(np.linspace(0.0, 1.0, N), np.linspace(0.0, 2.0, N) ** 2,
                                                                    np.zeros((N, 2)))),
    "change_base_point": ("returns a RigidTransform", lambda: se3.change_base_point(POSES, VECTORS)),
    "sclerp": ("returns a RigidTransform", lambda: se3.sclerp(POSES, POSES[::-1], 0.5)),
}


def _array_functions():
    found = {}
    for module in MODULES:
        for name in module.__all__:
            obj = getattr(module, name)
            if inspect.isclass(obj):
                continue
            assert inspect.isfunction(obj), f"{module.__name__}.{name} is a {type(obj).__name__}: enumerate it here"
            if name not in NOT_ARRAY_FUNCTIONS:
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


def _documented_out(doc):
    """Whether ``doc`` has exactly one ``out`` entry, the last of its Parameters section, as outputs.takes_out writes it."""
    lines = inspect.cleandoc(doc).split("\n")
    entries = [index for index, line in enumerate(lines) if line.startswith("out :")]
    if len(entries) != 1 or lines[entries[0]] != outputs.OUT_HEADER:
        return False
    first = entries[0]
    last = first + 1
    while last < len(lines) and lines[last].startswith("    "):
        last += 1
    entry = " ".join(line.strip() for line in lines[first + 1:last])
    titles = [index - 1 for index in range(1, len(lines)) if set(lines[index]) == {"-"}]
    section = max((index for index in titles if index < first), default=None)
    return (entry.endswith(outputs.OUT_REFERENCE) and section is not None and lines[section] == "Parameters"
            and (last == len(lines) or not lines[last].strip()) and all(index < first or index > last for index in titles))


def _takes_out(function):
    parameter = inspect.signature(function).parameters.get("out")
    return (parameter is not None and parameter.kind is parameter.KEYWORD_ONLY and parameter.default is None
            and _documented_out(function.__doc__))


def test_every_array_function_takes_out():
    assert {"quat_to_matrix", "generators", "create_group", "quat_slerp", "quat_mean", "left_jacobian", "euler_rates",
            "instantaneous_centre", "se3_hat", "se3_left_jacobian"} <= set(FUNCTIONS)
    missing = sorted(name for name, function in FUNCTIONS.items() if not _takes_out(function))
    assert not missing, f"array functions without a documented keyword-only out=None: {missing}"


def test_the_out_entry_has_one_source():
    """No docstring in the sources types the out entry: outputs.takes_out writes it into each."""
    sources = pathlib.Path(so3.__file__).parents[1]
    typed = [f"{path.relative_to(sources)}:{number}" for path in sorted(sources.rglob("*.py"))
             if path != pathlib.Path(outputs.__file__) for number, line in enumerate(path.read_text(encoding="utf-8").split("\n"), 1)
             if line.strip().startswith("out : ") or outputs.OUT_REFERENCE in line]
    assert typed == [], "write @takes_out instead"
    standard = outputs.out_entry()
    for name, function in [*FUNCTIONS.items(), *METHODS.items()]:
        assert inspect.cleandoc(function.__doc__).count(standard) == 1 or function in (
            so3.create_group, so3.generators, so3.RotationSpline.__call__), name


DOCSTRING = """Summary.

    Longer text.

    {parameters}Returns
    -------
    float

    Examples
    --------
    >>> 1
    1
    """


@pytest.mark.parametrize("dedent", [False, True], ids=["as written", "python 3.13"])
@pytest.mark.parametrize("parameters", ["", "Parameters\n    ----------\n    x : float\n        Input.\n\n    "],
                         ids=["no Parameters section", "with parameters"])
def test_the_out_entry_goes_last_into_parameters(parameters, dedent):
    doc = DOCSTRING.format(parameters=parameters)
    doc = inspect.cleandoc(doc) + "\n" if dedent else doc
    documented = outputs.with_out_entry(doc)
    assert _documented_out(documented)
    indent = "" if dedent else "    "
    x = f"{indent}x : float\n{indent}    Input.\n" if parameters else ""
    assert f"\n\n{indent}Parameters\n{indent}----------\n{x}{outputs.out_entry(indent=indent)}\n\n{indent}Returns\n" in documented
    assert documented.replace(outputs.out_entry(indent=indent) + "\n", "").replace(
        f"{indent}Parameters\n{indent}----------\n\n", "") == doc


def test_takes_out_refuses_what_it_cannot_document():
    def typed(x, *, out=None):
        """Typed by hand.

        Parameters
        ----------
        out : ndarray, optional
            Result.
        """

    def positional(x, out=None):
        """No keyword-only out.

        Examples
        --------
        """

    def no_sections(x, *, out=None):
        """No numpydoc sections."""

    with pytest.raises(ValueError, match="remove the one typed"):
        outputs.takes_out(typed)
    with pytest.raises(TypeError, match="no keyword-only out=None"):
        outputs.takes_out(positional)
    with pytest.raises(ValueError, match="numpydoc sections"):
        outputs.takes_out(no_sections)


@pytest.mark.parametrize("name", sorted(NOT_ARRAY_FUNCTIONS))
def test_functions_left_out_return_no_array(name):
    assert any(name in module.__all__ for module in MODULES), name
    result = NOT_ARRAY_FUNCTIONS[name][1]()
    assert not isinstance(result, np.ndarray), f"{name} returns an array: give it out="


SPLINE = so3.RotationSpline([0.0, 1.0, 3.0], so3.Rotation.from_quat(QUATS[:3]))
SPLINE_TIMES = np.linspace(-0.5, 3.5, 2 * N).reshape(2, N)
#: A sample object of every public class with methods.
INSTANCES = {"Rotation": ROTATIONS, "RigidTransform": POSES, "RotationSpline": SPLINE,
             "Slerp": so3.Slerp([0.0, 1.0, 3.0], so3.Rotation.from_quat(QUATS[:3]))}

#: The object and positional arguments of a method call (otherwise: the sample object, no arguments).
METHOD_CALLS = {
    "Rotation.as_quat": (ROTATIONS, (False, False)),
    "Rotation.as_euler": (ROTATIONS, ("ZXZ", True)),
    "Rotation.as_davenport": (ROTATIONS, (DAVENPORT_AXES, "e")),
    "Rotation.apply": (ROTATIONS, (VECTORS, True)),
    "Rotation.approx_equal": (ROTATIONS, (so3.Rotation.from_quat(QUATS[::-1].copy()), 1.0)),
    "Rotation.slerp": (ROTATIONS, (ROTATIONS[::-1], 0.3)),
    "RigidTransform.apply": (POSES, (VECTORS, True)),
    "RigidTransform.apply_vector": (POSES, (VECTORS,)),
    "RigidTransform.change_base_point": (POSES, (VECTORS,)),
    "RotationSpline.__call__": (SPLINE, (SPLINE_TIMES, 2, "space")),
    "Slerp.__call__": (INSTANCES["Slerp"], (SPLINE_TIMES.clip(0.0, 3.0),)),
}

#: Public methods of the exported classes that return no single array (each checked by calling it).
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
    "Slerp.__call__": "returns a Rotation",
}


def _public_classes():
    classes = {}
    for module in MODULES:
        for name in module.__all__:
            cls = getattr(module, name)
            if inspect.isclass(cls) and not issubclass(cls, (Warning, tuple)):  # named tuples carry results
                classes[name] = cls
    return classes


CLASSES = _public_classes()


def _own_and_inherited(cls):
    """``{name: attribute}`` of ``cls`` and its bases but ``object`` (a shared base's methods count too)."""
    members = {}
    for owner in reversed(cls.__mro__[:-1]):
        members.update(vars(owner))
    return members


def _all_methods():
    """Every public method and ``__call__`` of the public classes, by ``Class.name``."""
    found = {}
    for class_name, cls in CLASSES.items():
        for name, member in _own_and_inherited(cls).items():
            if (not name.startswith("_") or name == "__call__") and inspect.isfunction(member):
                found[f"{class_name}.{name}"] = member
    return found


ALL_METHODS = _all_methods()
METHODS = {name: method for name, method in ALL_METHODS.items() if name not in NOT_ARRAY_METHODS}


def _method_call(qualified):
    """``call(**keywords)`` of the method on its sample object and arguments."""
    obj, args = METHOD_CALLS.get(qualified, (INSTANCES[qualified.split(".")[0]], ()))
    return lambda **keywords: ALL_METHODS[qualified](obj, *args, **keywords)


def test_every_array_method_takes_out():
    assert set(CLASSES) == set(INSTANCES)
    assert {"Rotation.as_matrix", "Rotation.apply", "RigidTransform.as_matrix", "RigidTransform.apply",
            "RotationSpline.__call__"} <= set(METHODS)
    missing = sorted(name for name, method in METHODS.items() if not _takes_out(method))
    assert not missing, f"array methods without a documented keyword-only out=None: {missing}"


@pytest.mark.parametrize("name", sorted(NOT_ARRAY_METHODS))
def test_methods_left_out_return_no_array(name):
    assert name in ALL_METHODS, name
    result = _method_call(name)()
    assert not isinstance(result, np.ndarray), f"{name} returns an array: give it out="


def test_constructors_return_no_array():
    for class_name, cls in CLASSES.items():
        for name, member in _own_and_inherited(cls).items():
            if isinstance(member, (classmethod, staticmethod)) and not name.startswith("_"):
                returns = str(inspect.signature(member.__func__).return_annotation)
                assert returns in (class_name, "Self") or returns.startswith("tuple"), (class_name, name, returns)


def test_spline_out_for_each_order_and_frame():
    for order, frame in ((1, "body"), (1, "space"), (2, "body"), (2, "space")):
        expected = SPLINE(SPLINE_TIMES, order, frame)
        out = np.full(SPLINE_TIMES.shape + (3,), np.nan)
        assert SPLINE(SPLINE_TIMES, order, frame, out=out) is out
        assert out.tobytes() == expected.tobytes()
        strided = np.full(SPLINE_TIMES.shape + (6,), np.nan)[..., ::2]  # not contiguous: filled through a copy
        assert SPLINE(SPLINE_TIMES, order, frame, out=strided).tobytes() == expected.tobytes()
    # out over the memory of the times it reads: as if it did not overlap
    buffer = np.zeros((2 * N, 3))
    buffer[:, 0] = SPLINE_TIMES.ravel()
    expected = SPLINE(buffer[:, 0].copy(), 1, "body")
    assert SPLINE(buffer[:, 0], 1, "body", out=buffer) is buffer
    assert buffer.tobytes() == expected.tobytes()
    with pytest.raises(ValueError, match="out is for the angular rates"):
        SPLINE(SPLINE_TIMES, 0, out=np.empty(SPLINE_TIMES.shape + (4,)))


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
LARGE = elementwise.PARALLEL_THRESHOLD


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
