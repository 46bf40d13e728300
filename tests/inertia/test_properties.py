"""MassProperties, from_points and composites of parts at poses."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation as ScipyRotation

import kreisel as kr
from kreisel.inertia import primitive_meshes as meshes

I = kr.inertia


def test_from_points_is_central():
    rng = np.random.default_rng(0)
    m = rng.uniform(0.5, 2.0, 12)
    r = rng.normal(size=(12, 3)) + [5.0, -2.0, 1.0]
    p = I.from_points(m, r)
    np.testing.assert_allclose(p.com, np.average(r, axis=0, weights=m), rtol=1e-14)
    # the origin-based tensor is the central one shifted back (parallel-axis theorem)
    np.testing.assert_allclose(I.points(m, r), p.about([0.0, 0.0, 0.0]), rtol=1e-13)
    body = kr.RigidBody.from_points(m, r)
    np.testing.assert_allclose(body.inertia, p.inertia, rtol=1e-15)


def test_composite_of_rotated_boxes_equals_mesh_of_the_same_solid():
    # an L-shaped solid: two boxes, the second rotated a quarter turn about z
    size = np.array([3.0, 1.0, 0.5])
    quarter = ScipyRotation.from_rotvec([0, 0, np.pi / 2])
    v, f = meshes.box_mesh(size)
    parts_mesh = [(v + [1.5, 0.5, 0.25], f), (quarter.apply(v) + [0.5, 2.5, 0.25], f)]
    density = 2.0
    box_part = I.MassProperties(density * size.prod(), np.zeros(3), I.box(density * size.prod(), size))
    composite = I.combine(
        [(box_part, [1.5, 0.5, 0.25]), (box_part, [0.5, 2.5, 0.25], quarter.as_matrix())]
    )
    vertices = np.concatenate([pv for pv, _ in parts_mesh])
    faces = np.concatenate([parts_mesh[0][1], parts_mesh[1][1] + len(v)])
    union = I.from_mesh(vertices, faces, density=density)
    assert composite.mass == pytest.approx(union.mass, rel=1e-15)
    np.testing.assert_allclose(composite.com, union.com, rtol=1e-14)
    np.testing.assert_allclose(composite.inertia, union.inertia, rtol=1e-13, atol=1e-13)
    # the same with quaternion and rotation-object poses, and as a RigidBody
    q = np.roll(quarter.as_quat(), 1)
    for rotation in (q, quarter):
        again = I.combine([(box_part, [1.5, 0.5, 0.25]), (box_part, [0.5, 2.5, 0.25], rotation)])
        np.testing.assert_allclose(again.inertia, composite.inertia, rtol=1e-14, atol=1e-14)
    body = kr.RigidBody.from_parts([(box_part, [1.5, 0.5, 0.25]), (box_part, [0.5, 2.5, 0.25], q)])
    np.testing.assert_allclose(body.inertia, composite.inertia, rtol=1e-14, atol=1e-14)


def test_combine_accepts_rigid_bodies_at_their_centre_of_mass():
    ball = kr.RigidBody.solid_sphere(1.0, 0.1)
    dumbbell = I.combine([(ball, [-1.0, 0, 0]), (ball, [1.0, 0, 0])])
    point_pair = I.points([1.0, 1.0], [[-1.0, 0, 0], [1.0, 0, 0]])
    np.testing.assert_allclose(dumbbell.inertia, point_pair + 2 * ball.inertia, rtol=1e-15)
    np.testing.assert_array_equal(dumbbell.com, 0.0)


def test_transformed_and_about():
    part = I.from_mesh(*meshes.cone_mesh(1.0, 2.0, 9))
    R = ScipyRotation.from_rotvec([0.3, -0.5, 0.8]).as_matrix()
    moved = part.transformed([1.0, 2.0, 3.0], R)
    np.testing.assert_allclose(moved.com, R @ part.com + [1.0, 2.0, 3.0], rtol=1e-15)
    np.testing.assert_allclose(moved.inertia, R @ part.inertia @ R.T, atol=1e-15)
    point = np.array([0.5, -1.0, 2.0])
    np.testing.assert_allclose(moved.about(point), I.parallel_axis(moved.inertia, moved.mass, moved.com - point))


@pytest.mark.parametrize(
    "parts, error, message",
    [
        ([], ValueError, "at least one part"),
        ([np.eye(3)], TypeError, r"parts\[0\]"),
        ([("box", [0, 0, 0])], TypeError, "MassProperties or RigidBody"),
        ([(kr.RigidBody([1.0, 1.0, 1.0]), [0, 0])], ValueError, "position"),
        ([(kr.RigidBody([1.0, 1.0, 1.0]), [0, 0, 0], np.eye(3) * 2)], ValueError, r"rotation matrices: max \|R\^T R - 1\|"),
        ([I.MassProperties(1.0, np.zeros(3), np.array([[1.0, 0.5, 0], [0, 1, 0], [0, 0, 1]]))], ValueError, "symmetric"),
        ([I.MassProperties(0.0, np.zeros(3), np.eye(3))], ValueError, "nonzero"),
        ([I.MassProperties(-1.0, np.zeros(3), -np.eye(3))], ValueError, "positive total mass"),
        (
            [I.MassProperties(1.0, np.zeros(3), 0.4 * np.eye(3)), I.MassProperties(-0.5, np.zeros(3), -np.eye(3))],
            ValueError,
            "semi-definite",
        ),
    ],
)
def test_combine_refusals(parts, error, message):
    with pytest.raises(error, match=message):
        I.combine(parts)


def test_from_points_refusals():
    with pytest.raises(ValueError, match="positive sum"):
        I.from_points([0.0, 0.0], np.zeros((2, 3)))
    with pytest.raises(ValueError, match=r"\(N, 3\)"):
        I.from_points([1.0, 1.0], np.zeros((3, 3)))


def test_from_points_at_extreme_magnitudes_is_exact_or_refused_as_out_of_range():
    # positions ~1e160 square to inf on their own; with masses ~1e-250 the tensor (~1e70) is representable
    mpmath = pytest.importorskip("mpmath")
    m = np.array([1.0, 3.0, 2.0]) * 1e-250
    r = np.array([[0.0, 1.0, 2.0], [4.0, 0.0, -1.0], [1.0, 1.0, 1.0]]) * 1e160
    p = I.from_points(m, r)
    M = [mpmath.mpf(x) for x in m]
    com = [sum(M[n] * mpmath.mpf(r[n, i]) for n in range(3)) / sum(M) for i in range(3)]
    d = [[mpmath.mpf(r[n, i]) - com[i] for i in range(3)] for n in range(3)]
    exact = [[sum(M[n] * ((i == j) * sum(x * x for x in d[n]) - d[n][i] * d[n][j]) for n in range(3))
              for j in range(3)] for i in range(3)]
    np.testing.assert_allclose(p.com, [float(c) for c in com], rtol=1e-15)
    np.testing.assert_allclose(p.inertia, np.array(exact, dtype=float), rtol=1e-14, atol=1e-14 * float(exact[0][0]))
    with pytest.raises(ValueError, match="out of range"):
        I.from_points(m * 1e250, r)
    with pytest.raises(ValueError, match="out of range"):
        I.from_points([1.0, 1.0], [[-1e308, 0.0, 0.0], [1e308, 0.0, 0.0]])
