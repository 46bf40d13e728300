"""The NumPy conversions of `kreisel convert` and the compiled kernels of kreisel.so3 agree to the last bits.

kreisel.cli.rotations writes the element kernels' formulas once more over whole columns, so that the
command never loads numba; each side is the reference of the other here: every representation in and out,
on random rotations and on the edge cases where the kernels branch (gimbal lock of all 24 sequences, half
turns, tiny and huge angles, quaternions far from unit size, nearly orthogonal matrices), and the same
inputs refused by both.
"""

import itertools
import math

import numpy as np
import pytest

from kreisel._compiled import kernels
from kreisel.cli import rotations
from kreisel.so3 import Rotation

SEQUENCES = ["".join(s) for s in itertools.product("xyz", repeat=3) if s[0] != s[1] and s[1] != s[2]]
SEQUENCES += [s.upper() for s in SEQUENCES]
rng = np.random.default_rng(20)


def ulps(a, b):
    """Largest difference in units of the last place of the larger magnitude, or of 1 below 1."""
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape
    scale = np.maximum(np.maximum(np.abs(a), np.abs(b)), 1.0)
    return float(np.max(np.abs(a - b) / np.spacing(scale))) if a.size else 0.0


def arctan2_ulps():
    """The largest difference between numpy's ``arctan2`` and the C library's ``atan2``, which the kernels call.

    0 where numpy calls the C library; 1 where numpy has a SIMD loop of its own (numpy 2 on AVX-512 CPUs,
    e.g. AMD Zen 5). The command's angles come from ``np.arctan2``, so their agreement with the kernels is
    bounded by the kernels' own rounding plus this, twice: a rotation angle is twice an arctan2, an Euler
    angle the sum or difference of two.
    """
    y, x = np.random.default_rng(0).uniform(-1.0, 1.0, (2, 100_000))
    return ulps(np.arctan2(y, x), np.vectorize(math.atan2, otypes=[float])(y, x))


ARCTAN2_ULPS = arctan2_ulps()


def random_quats(n):
    q = rng.standard_normal((n, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def edge_quats():
    """Unit quaternions where the kernels branch: identity, half turns, tiny angles, both signs of q0."""
    axes = np.eye(3)
    rows = [[1.0, 0, 0, 0], [-1.0, 0, 0, 0]]
    for angle in (np.pi, np.pi - 1e-9, 1e-3, 1e-9, 1e-20, 2 * np.pi - 1e-9):
        for axis in [*axes, np.ones(3) / np.sqrt(3)]:
            rows.append([np.cos(angle / 2), *(np.sin(angle / 2) * axis)])
    rows = np.array(rows)
    return np.concatenate([rows, -rows])


def test_the_constants_are_the_kernels():
    assert (rotations.SIZE_LOW, rotations.SIZE_HIGH) == (kernels.SIZE_LOW, kernels.SIZE_HIGH)


def test_quaternions_in_at_every_scale():
    q = random_quats(2000)
    scales = np.array([1.0, 3e-300, 1e-141, 1e-139, 1e139, 1e141, 1e300])
    raw = np.concatenate([q * s for s in scales] + [edge_quats() * 7.0])
    assert ulps(rotations.to_quat("quat", "", raw), Rotation.from_quat(raw).as_quat()) <= 1
    assert ulps(rotations.to_quat("euler_parameters", "", raw), Rotation.from_euler_parameters(raw).as_quat()) <= 1


def test_matrices_in_exact_and_nearly_orthogonal():
    q = np.concatenate([random_quats(2000), edge_quats()])
    exact = Rotation.from_quat(q).as_matrix()
    assert ulps(rotations.to_quat("matrix", "", exact), Rotation.from_matrix(exact).as_quat()) <= 1
    # a defect above rounding level projects the whole batch (SVD) in both
    nearly = exact + 1e-9 * rng.standard_normal(exact.shape)
    assert ulps(rotations.to_quat("matrix", "", nearly), Rotation.from_matrix(nearly).as_quat()) <= 1


@pytest.mark.parametrize("degrees", [False, True])
def test_rotation_vectors_and_axis_angles_in(degrees):
    directions = rng.standard_normal((500, 3))
    lengths = np.array([0.0, 1e-300, 1e-20, 9.99e-5, 1e-4, 1.01e-4, 1.0, np.pi, 2 * np.pi, 10.0, 1e4, 1e7])
    psi = (directions[:, None, :] * lengths[None, :, None]).reshape(-1, 3)
    got = rotations.to_quat("rotvec", "", psi, degrees)
    assert ulps(got, Rotation.from_rotvec(psi, degrees=degrees).as_quat()) <= 1
    # longer than 1e8 rad: the rotation is lost to the rounding of the length, refused by both alike
    for length in (2e8, 1e141, 1e300):
        for convert in (lambda p: rotations.to_quat("rotvec", "", p, False), Rotation.from_rotvec):
            with pytest.raises(ValueError, match="rotvec is out of range"):
                convert(directions[:3] * length)
    axis_angle = np.concatenate([directions * 1e-3, rng.uniform(-400, 400, (500, 1))], axis=1)
    expected = Rotation.from_axis_angle(axis_angle[:, :3], axis_angle[:, 3], degrees=degrees).as_quat()
    assert ulps(rotations.to_quat("axis_angle", "", axis_angle, degrees), expected) <= 1


def test_gibbs_and_mrp_in():
    v = rng.standard_normal((1000, 3)) * np.logspace(-8, 8, 1000)[:, None]
    assert ulps(rotations.to_quat("gibbs", "", v), Rotation.from_gibbs(v).as_quat()) <= 1
    assert ulps(rotations.to_quat("mrp", "", v), Rotation.from_mrp(v).as_quat()) <= 1


@pytest.mark.parametrize("seq", SEQUENCES)
def test_euler_angles_both_ways_through_gimbal_lock(seq):
    proper = seq[0].lower() == seq[2].lower()
    singular = [0.0, np.pi] if proper else [-np.pi / 2, np.pi / 2]
    middle = np.concatenate([[s + d for s in singular for d in (0.0, 1e-9, -1e-9, 1e-300)],
                             rng.uniform(*((0, np.pi) if proper else (-np.pi / 2, np.pi / 2)), 200)])
    outer = rng.uniform(-np.pi, np.pi, (middle.size, 2))
    angles = np.stack([outer[:, 0], middle, outer[:, 1]], axis=1)
    assert ulps(rotations.euler_quat(seq, angles), Rotation.from_euler(seq, angles).as_quat()) <= 1
    degrees = np.degrees(angles)
    assert ulps(rotations.to_quat("euler", seq, degrees, True), Rotation.from_euler(seq, degrees, degrees=True).as_quat()) <= 1
    r = Rotation.from_quat(np.concatenate([Rotation.from_euler(seq, angles).as_quat(), random_quats(200), edge_quats()]))
    q, expected = r.as_quat(), r.as_euler(seq)
    assert ulps(rotations.quat_euler(seq, q), expected) <= 2 + 2 * ARCTAN2_ULPS
    # in degrees: the same angles, to the radians' bound and the rounding of converting back
    assert ulps(np.radians(rotations.from_quat(q, "euler", seq, degrees=True)), expected) <= 3 + 2 * ARCTAN2_ULPS


@pytest.mark.parametrize("name", ["quat", "matrix", "rotvec", "axis_angle", "gibbs", "mrp", "euler_parameters",
                                  "su2", "cayley_klein"])
def test_every_representation_out(name):
    q = np.concatenate([random_quats(2000), edge_quats()])
    if name == "gibbs":
        q = q[q[:, 0] != 0.0]
    r = Rotation.from_quat(q)
    if name == "axis_angle":
        axis, angle = r.as_axis_angle()
        expected = np.concatenate([axis, angle[:, None]], axis=1)
    else:
        expected = getattr(r, f"as_{name}")().reshape(len(q), -1)
    bound = 1 + 2 * ARCTAN2_ULPS if name in ("rotvec", "axis_angle") else 1
    assert ulps(rotations.from_quat(r.as_quat(), name), expected) <= bound
    if name in ("rotvec", "axis_angle"):
        got = rotations.from_quat(r.as_quat(), name, degrees=True)
        angles = slice(-3, None) if name == "rotvec" else slice(-1, None)
        got[:, angles] = np.radians(got[:, angles])
        assert ulps(got, expected) <= bound + 1


@pytest.mark.parametrize("name, values", [
    ("quat", [[0.0, 0, 0, 0]]), ("quat", [[np.nan, 1, 0, 0]]), ("quat", [[np.inf, 0, 0, 0]]),
    ("euler_parameters", [[0.0, 0, 0, 0]]),
    ("matrix", [np.diag([1.0, 1.0, -1.0])]), ("matrix", [np.diag([1.0, 1.0, 1.001])]),
    ("matrix", [np.full((3, 3), np.nan)]), ("matrix", [np.zeros((3, 3))]), ("matrix", [np.eye(3) * 1e200]),
    ("matrix", [np.diag([1.0, 1.0, -1.0 - 1e-8])]),
    ("rotvec", [[np.nan, 0, 0]]), ("axis_angle", [[0.0, 0, 0, 1]]), ("axis_angle", [[1.0, 0, 0, np.inf]]),
    ("gibbs", [[np.inf, 0, 0]]), ("mrp", [[0, np.nan, 0]]), ("euler", [[0.0, np.nan, 0]]),
])
def test_the_same_inputs_are_refused(name, values):
    values = np.array(values)
    with pytest.raises(ValueError) as ours:
        rotations.to_quat(name, "ZXZ", values)
    reader = {"quat": Rotation.from_quat, "euler_parameters": Rotation.from_euler_parameters,
              "matrix": Rotation.from_matrix, "rotvec": Rotation.from_rotvec, "gibbs": Rotation.from_gibbs,
              "mrp": Rotation.from_mrp, "euler": lambda v: Rotation.from_euler("ZXZ", v),
              "axis_angle": lambda v: Rotation.from_axis_angle(v[:, :3], v[:, 3])}[name]
    with pytest.raises(ValueError) as theirs:
        reader(values)
    assert str(ours.value) == str(theirs.value)


def test_half_turns_have_no_gibbs_vector_in_either():
    q = np.array([[0.0, 0.0, 1.0, 0.0]])
    with pytest.raises(ValueError, match="half-turn"):
        rotations.from_quat(q, "gibbs")
    with pytest.raises(ValueError, match="half-turn"):
        Rotation.from_quat(q).as_gibbs()
