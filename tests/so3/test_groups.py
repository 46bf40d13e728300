"""Rotation groups and reduction, against scipy and the group axioms."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation as S

from kreisel import Rotation

GROUPS = ["I", "O", "T", "C1", "C2", "C5", "D1", "D2", "D3", "D6"]


def same_set(a, b):
    overlap = np.abs(a.as_quat() @ b.as_quat().T)
    return len(a) == len(b) and np.allclose(overlap.max(axis=0), 1.0) and np.allclose(overlap.max(axis=1), 1.0)


@pytest.mark.parametrize("group", GROUPS)
@pytest.mark.parametrize("axis", ["X", "y", "Z"])
def test_groups_equal_scipys_and_are_closed(group, axis):
    g = Rotation.create_group(group, axis=axis)
    assert same_set(g, Rotation.from_scipy(S.create_group(group, axis)))
    np.testing.assert_array_equal(g[0].as_quat(), [1.0, 0.0, 0.0, 0.0])
    products = (g[:, None] * g[None, :]).as_quat().reshape(-1, 4)
    assert np.allclose(np.abs(products @ g.as_quat().T).max(axis=1), 1.0)  # closed
    assert same_set(g.inv(), g)  # inverses inside


def test_group_orders_and_bad_names():
    assert [len(Rotation.create_group(n)) for n in ["I", "O", "T", "C7", "D7"]] == [60, 24, 12, 7, 14]
    for bad, match in [("Q", "group"), ("C0", "group"), ("D", "group"), (3, "group")]:
        with pytest.raises(ValueError, match=match):
            Rotation.create_group(bad)
    with pytest.raises(ValueError, match="axis"):
        Rotation.create_group("C3", axis="W")


@pytest.mark.parametrize("sides", [("left",), ("right",), ("left", "right")])
def test_reduce_matches_scipy_and_brute_force(sides):
    g = Rotation.create_group("O")
    r = Rotation.random(30, rng=31)
    kwargs = {side: g for side in sides}
    reduced, li, ri = r.reduce(**kwargs, return_indices=True)
    s_reduced, s_li, s_ri = r.to_scipy().reduce(**{k: v.to_scipy() for k, v in kwargs.items()}, return_indices=True)
    np.testing.assert_allclose(reduced.magnitude(), s_reduced.magnitude(), atol=1e-12)
    if len(sides) == 1:
        # With both sides many pairs (l, r) tie up to rounding; with one side the choice is unique.
        assert reduced.approx_equal(Rotation.from_scipy(s_reduced), atol=1e-12).all()
        for mine, theirs, side in ((li, s_li, "left"), (ri, s_ri, "right")):
            if side in sides:
                np.testing.assert_array_equal(mine, theirs)
            else:
                assert mine is None and theirs is None
    chosen_l = g[li] if li is not None else Rotation.identity(30)
    chosen_r = g[ri] if ri is not None else Rotation.identity(30)
    assert (chosen_l * r * chosen_r).approx_equal(reduced, atol=1e-12).all()
    # Brute force: the smallest angle over all l r r'.
    ls = g if "left" in sides else Rotation.identity(1)
    rs = g if "right" in sides else Rotation.identity(1)
    smallest = (ls[:, None, None] * r[None, :, None] * rs[None, None, :]).magnitude().min(axis=(0, 2))
    np.testing.assert_allclose(reduced.magnitude(), smallest, atol=1e-12)


def test_reduce_without_groups_and_single():
    r = Rotation.random(rng=32)
    same, li, ri = r.reduce(return_indices=True)
    assert same.approx_equal(r) and li is None and ri is None
    one = r.reduce(Rotation.create_group("T"), Rotation.create_group("T"))
    assert one.single
