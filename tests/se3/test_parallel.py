"""The multi-core loops of RigidTransform agree bit for bit with the serial ones and refuse the same inputs.

Lowering ``PARALLEL_THRESHOLD`` (and the piece length) sends small batches
through the loops that large batches take, without allocating 10^4 poses.
"""

import numpy as np
import pytest

from kreisel._compiled import elementwise
from kreisel.se3 import RigidTransform

N = 37  # odd, so the pieces of the multi-core loops end raggedly


def _parallel(monkeypatch):
    monkeypatch.setattr(elementwise, "PARALLEL_THRESHOLD", 1)
    monkeypatch.setattr(elementwise, "PIECE", 5)


@pytest.fixture(scope="module")
def poses():
    rng = np.random.default_rng(11)
    a = RigidTransform.random(N, rng=1, translation_scale=2.0)
    b = RigidTransform.random(N, rng=2, translation_scale=2.0)
    points = rng.normal(size=(N, 3)) * 10.0 ** rng.uniform(-5.0, 5.0, size=(N, 1))
    return a, b, points


def _results(a, b, points):
    one = a[3]
    moved = [a.apply(points), a.apply(points, inverse=True), one.apply(points), one.apply(points, inverse=True),
             a.apply(points[4]), a.apply_vector(points), one.apply_vector(points, inverse=True)]
    product, inverse = a * b, a.inv()
    from_matrix = RigidTransform.from_matrix(a.as_matrix())
    return moved + [t.as_quat() for t in (product, inverse, from_matrix)] + [
        t.translation for t in (product, inverse, from_matrix)]


def test_parallel_matches_serial(poses, monkeypatch):
    serial = _results(*poses)
    _parallel(monkeypatch)
    for fast, slow in zip(_results(*poses), serial, strict=True):
        assert np.array_equal(fast.view(np.uint64), slow.view(np.uint64))


def test_composition_inverse_and_from_matrix_store_plain_arrays(poses, monkeypatch):
    # The next operation reads the packed poses without copying strided views first.
    _parallel(monkeypatch)
    a, b, _ = poses
    for t in (a * b, a.inv(), RigidTransform.from_matrix(a.as_matrix())):
        assert t.as_quat().flags.c_contiguous and t._pose.flags.c_contiguous and t._pose.base is None


@pytest.mark.parametrize("position", [0, N // 2, N - 1])
def test_parallel_refusals_name_the_argument(poses, monkeypatch, position):
    _parallel(monkeypatch)
    a, _, points = poses
    bad = points.copy()
    bad[position, 1] = np.nan
    for move, name in ((a.apply, "points"), (a[0].apply, "points"), (a.apply_vector, "vectors")):
        for inverse in (False, True):
            with pytest.raises(ValueError, match=f"{name} must be finite"):
                move(bad, inverse=inverse)
    matrices = a.as_matrix()
    nonfinite, skewed = matrices.copy(), matrices.copy()
    nonfinite[position, 2, 3] = np.inf
    skewed[position, 0, 1] += 1e-3
    with pytest.raises(ValueError, match="matrix must be finite"):
        RigidTransform.from_matrix(nonfinite)
    with pytest.raises(ValueError, match="matrix must be rigid"):
        RigidTransform.from_matrix(skewed)
    skewed[(position + 7) % N, 0, 0] = np.nan  # finiteness is refused first, as when checked before converting
    with pytest.raises(ValueError, match="matrix must be finite"):
        RigidTransform.from_matrix(skewed)
