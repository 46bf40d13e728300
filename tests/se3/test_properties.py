"""Property tests over arbitrary poses: group laws, screws and exp/log round trips."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from kreisel.se3 import RigidTransform, change_base_point

finite = st.floats(-10.0, 10.0, allow_nan=False)
vector = st.tuples(finite, finite, finite).map(np.array)
quaternion = st.tuples(finite, finite, finite, finite).filter(lambda q: np.dot(q, q) > 1e-6).map(np.array)
pose = st.builds(RigidTransform.from_rotation_translation, quaternion, vector)
SETTINGS = settings(max_examples=60, deadline=None)


@SETTINGS
@given(pose, pose, vector)
def test_group_laws_match_matrices(a, b, p):
    m = a.as_matrix() @ b.as_matrix()
    np.testing.assert_allclose((a * b).as_matrix(), m, atol=1e-12)
    np.testing.assert_allclose((a * b).apply(p), a.apply(b.apply(p)), atol=1e-12)
    np.testing.assert_allclose((a * b).inv().as_matrix(), (b.inv() * a.inv()).as_matrix(), atol=1e-12)


@SETTINGS
@given(pose, vector, vector)
def test_base_point_changes_translation_only(t, offset, body_point):
    moved = change_base_point(t, offset)
    np.testing.assert_array_equal(moved.as_quat(), t.as_quat())
    np.testing.assert_allclose(moved.apply(body_point - offset), t.apply(body_point), atol=1e-12)


@SETTINGS
@given(pose)
def test_screw_and_log_round_trips(t):
    s = t.as_screw()
    back = RigidTransform.from_screw(s.axis, s.point, s.angle, s.translation)
    scale = 1.0 + np.abs(t.translation).max()
    np.testing.assert_allclose(back.as_matrix(), t.as_matrix(), atol=1e-12 * scale)
    np.testing.assert_allclose(RigidTransform.from_exp_coords(t.as_exp_coords()).as_matrix(), t.as_matrix(), atol=1e-12 * scale)
