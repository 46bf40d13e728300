"""RotationSpline and Slerp against scipy, finite differences and their defining properties."""

import numpy as np
import pytest
from scipy.spatial.transform import RotationSpline as ScipySpline
from scipy.spatial.transform import Slerp as ScipySlerp

import kreisel as kr
from kreisel import Rotation, RotationSpline, Slerp


@pytest.fixture
def knots(rng):
    times = np.cumsum(rng.uniform(0.2, 1.5, size=8))
    return times, Rotation.random(8, rng=21)


def vee(W):
    return np.stack([W[..., 2, 1], W[..., 0, 2], W[..., 1, 0]], axis=-1)


def test_matches_scipy_in_both_frames(knots):
    times, rotations = knots
    ours, theirs = RotationSpline(times, rotations), ScipySpline(times, rotations.to_scipy())
    t = np.linspace(times[0] - 0.3, times[-1] + 0.3, 2001)  # extrapolates at both ends, like scipy
    R = ours(t)
    np.testing.assert_allclose(R.as_matrix(), theirs(t).as_matrix(), atol=1e-13)
    for order in (1, 2):
        body = ours(t, order, frame="body")
        np.testing.assert_allclose(body, theirs(t, order), rtol=1e-11, atol=1e-11)
        np.testing.assert_allclose(ours(t, order, frame="space"), R.apply(body), atol=1e-12)


def test_rates_are_the_derivatives_of_the_curve(knots):
    times, rotations = knots
    spline = RotationSpline(times, rotations)
    t = np.linspace(times[0] + 0.01, times[-1] - 0.01, 101)
    h = 1e-5
    R = lambda s: spline(s).as_matrix()  # noqa: E731
    Rdot = (R(t + h) - R(t - h)) / (2 * h)
    Rt = np.swapaxes(R(t), -1, -2)
    np.testing.assert_allclose(spline(t, 1, frame="body"), vee(Rt @ Rdot), atol=2e-8)
    np.testing.assert_allclose(spline(t, 1, frame="space"), vee(Rdot @ Rt), atol=2e-8)
    for frame in ("body", "space"):
        w = lambda s: spline(s, 1, frame=frame)  # noqa: E731
        np.testing.assert_allclose(spline(t, 2, frame=frame), (w(t + h) - w(t - h)) / (2 * h), atol=2e-7)


class ConvergedSpline(RotationSpline):
    # scipy's 10 iterations leave ~1e-4 jumps in the acceleration for these knots.
    MAX_ITER = 100


def test_interpolates_the_knots_and_is_c2_across_them(knots):
    times, rotations = knots
    spline = ConvergedSpline(times, rotations)
    assert spline(times).approx_equal(rotations, atol=1e-12).all()
    inner = times[1:-1]
    for order in (1, 2):
        for frame in ("body", "space"):
            left = spline(inner - 1e-9, order, frame=frame)
            right = spline(inner + 1e-9, order, frame=frame)
            np.testing.assert_allclose(left, right, atol=1e-6)


def test_shapes_and_the_multi_core_path(knots):
    times, rotations = knots
    spline = RotationSpline(times, rotations)
    assert spline(times[2]).single and spline(times[2], 1, frame="body").shape == (3,)
    grid = np.linspace(times[0], times[-1], 12).reshape(3, 4)
    assert spline(grid).shape == (3, 4) and spline(grid, 2, frame="space").shape == (3, 4, 3)
    many = np.linspace(times[0], times[-1], 50000)
    np.testing.assert_array_equal(spline(many, 1, frame="space")[::4999], spline(many[::4999], 1, frame="space"))
    two = RotationSpline(times[:2], rotations[:2])  # two knots: constant rate, as scipy
    np.testing.assert_allclose(
        two(grid.ravel(), 1, frame="body"), ScipySpline(times[:2], rotations[:2].to_scipy())(grid.ravel(), 1), atol=1e-13
    )


def test_slerp_matches_scipy_and_refuses_extrapolation(knots):
    times, rotations = knots
    ours, theirs = Slerp(times, rotations), ScipySlerp(times, rotations.to_scipy())
    t = np.linspace(times[0], times[-1], 500)
    np.testing.assert_allclose(ours(t).as_matrix(), theirs(t).as_matrix(), atol=1e-14)
    # Constant angular velocity within a segment.
    seg = np.linspace(times[2], times[3], 5)
    steps = (ours(seg[:-1]).inv() * ours(seg[1:])).magnitude()
    np.testing.assert_allclose(steps, steps[0], atol=1e-13)
    with pytest.raises(ValueError, match="within"):
        ours(times[-1] + 0.1)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda t, r: RotationSpline(t, r)(t, 1), "frame must be given"),
        (lambda t, r: RotationSpline(t, r)(t, 3, frame="body"), "order"),
        (lambda t, r: RotationSpline(t, r)(t, 1, frame="world"), "frame"),
        (lambda t, r: RotationSpline(t[::-1], r), "strictly increasing"),
        (lambda t, r: RotationSpline(t[:3], r), r"times must have shape \(8,\)"),
        (lambda t, r: RotationSpline(t[:1], r[:1]), "at least 2"),
        (lambda t, r: RotationSpline(t, r[0]), "1-D batch"),
        (lambda t, r: Slerp(t, r.as_quat()), "kreisel Rotation"),
        (lambda t, r: RotationSpline(t, r)(np.nan), "times must be finite"),
    ],
)
def test_bad_input_is_refused(knots, call, match):
    with pytest.raises((ValueError, TypeError), match=match):
        call(*knots)


def test_exported_at_top_level():
    assert kr.RotationSpline is RotationSpline and kr.Slerp is Slerp
