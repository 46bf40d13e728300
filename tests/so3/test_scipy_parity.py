"""Every public name of scipy.spatial.transform has a kreisel counterpart or a documented reason."""

import pickle
from pathlib import Path

import numpy as np
import pytest
import scipy.spatial.transform as st

import kreisel as kr

CONVENTIONS = (Path(__file__).parents[2] / "docs" / "conventions.rst").read_text(encoding="utf-8")
SCIPY_SECTION = CONVENTIONS[CONVENTIONS.index("scipy.spatial.transform, name by name") :]

DUNDERS = {"__init__", "__call__", "__mul__", "__pow__", "__getitem__", "__setitem__", "__len__", "__iter__", "__bool__",
           "__repr__", "__getstate__", "__setstate__", "__reduce__"}  # fmt: skip

#: scipy names without an attribute of the same name in kreisel, and the text of
#: conventions.rst that documents the reason.
EXCEPTIONS = {
    ("Rotation", "__setstate__"): "pickle`` works through the default protocol",
    ("RotationSpline", "interpolator"): "there is no ``PPoly`` object",
}


def scipy_names(cls, sample):
    names = {n for n in dir(cls) if not n.startswith("_")}
    names |= {n for n in vars(cls) if n in DUNDERS}
    if sample is not None:
        names |= {n for n in vars(sample) if not n.startswith("_")}
    return sorted(names)


def pairs():
    knots = st.Rotation.random(3, rng=0)
    samples = {
        "Rotation": (kr.Rotation, None),
        "Slerp": (kr.Slerp, (st.Slerp([0, 1, 2], knots), kr.Slerp([0, 1, 2], kr.Rotation.from_scipy(knots)))),
        "RotationSpline": (
            kr.RotationSpline,
            (st.RotationSpline([0, 1, 2], knots), kr.RotationSpline([0, 1, 2], kr.Rotation.from_scipy(knots))),
        ),
        "RigidTransform": (kr.RigidTransform, None),
    }
    for name, (ours, instances) in samples.items():
        theirs, mine = instances if instances else (None, ours)
        for attribute in scipy_names(getattr(st, name), theirs):
            yield name, attribute, mine


@pytest.mark.parametrize("cls, name, ours", list(pairs()), ids=lambda x: x if isinstance(x, str) else "")
def test_every_scipy_name_has_a_counterpart_or_a_documented_reason(cls, name, ours):
    if (cls, name) in EXCEPTIONS:
        assert not hasattr(ours, name), f"{cls}.{name} now exists: drop it from EXCEPTIONS"
        assert EXCEPTIONS[cls, name] in SCIPY_SECTION
    else:
        assert hasattr(ours, name), f"kreisel's {cls} lacks scipy's {name} and no documented reason"
    # The conventions page's scipy column names it (dunders by their operator or protocol).
    spelled = {"__init__": f"{cls}(", "__call__": f"{cls}(", "__pow__": "** p", "__mul__": "__mul__"}.get(name, name)
    assert spelled in SCIPY_SECTION, f"{cls}.{name} is missing from docs/conventions.rst"


def test_scipy_classes_are_all_covered():
    public = {n for n in dir(st) if not n.startswith("_") and isinstance(getattr(st, n), type)}
    assert public == {"Rotation", "Slerp", "RotationSpline", "RigidTransform"}


def test_pickling_round_trips():
    r = kr.Rotation.random((2, 3), rng=1)
    np.testing.assert_array_equal(pickle.loads(pickle.dumps(r)).as_quat(), r.as_quat())
    t = kr.RigidTransform.random(4, rng=2)
    np.testing.assert_array_equal(pickle.loads(pickle.dumps(t)).as_matrix(), t.as_matrix())


def test_container_methods_behave_as_scipys():
    r = kr.Rotation.random(4, rng=3)
    s = r.to_scipy()
    r[1:3] = kr.Rotation.identity(2)
    s[1:3] = st.Rotation.identity(2)
    np.testing.assert_allclose(r.as_matrix(), s.as_matrix(), atol=1e-15)
    view = r[0:2]
    r[0] = kr.Rotation.identity()
    assert not view[0].approx_equal(kr.Rotation.identity())  # assignment does not reach earlier slices
    s[0] = st.Rotation.identity()
    both = kr.Rotation.concatenate([r, kr.Rotation.identity(), r[0:1]])
    np.testing.assert_allclose(both.as_matrix(), st.Rotation.concatenate([s, st.Rotation.identity(), s[0:1]]).as_matrix(), atol=1e-15)
    assert [x.single for x in r] == [True] * 4 and bool(kr.Rotation.identity(0))
    t = kr.RigidTransform.random(3, rng=4)
    u = t.to_scipy()
    t[0] = kr.RigidTransform.identity()
    u[0] = st.RigidTransform.identity()
    np.testing.assert_allclose(t.as_matrix(), u.as_matrix(), atol=1e-15)
    cat = kr.RigidTransform.concatenate([t, kr.RigidTransform.identity()])
    np.testing.assert_allclose(cat.as_matrix(), st.RigidTransform.concatenate([u, st.RigidTransform.identity()]).as_matrix(), atol=1e-15)
    translation, rotation = u.as_components()
    np.testing.assert_allclose(kr.RigidTransform.from_components(translation, kr.Rotation.from_scipy(rotation)).as_matrix(), t.as_matrix(), atol=1e-15)
