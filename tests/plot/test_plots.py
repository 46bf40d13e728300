"""kreisel.plot: every figure draws the trajectory's own data; files are refused or written whole."""

import numpy as np
import pytest
from matplotlib.figure import Figure

import kreisel as kr
from kreisel import plot
from kreisel.plot.animation import animate, box_half_extents


@pytest.fixture(scope="module")
def trajectory():
    return kr.EulerTop(1.0, 2.0, 3.0).solve(np.linspace(0.0, 30.0, 301), [0.2, 1.0, 0.1])


@pytest.mark.parametrize("kind", sorted(plot.KINDS))
def test_every_kind_returns_a_figure_with_data(trajectory, kind):
    fig = plot.KINDS[kind](trajectory)
    assert isinstance(fig, Figure)
    lines = [line for ax in fig.axes for line in ax.get_lines()]
    assert lines and max(len(line.get_xdata()) for line in lines) >= len(trajectory)


def test_omega_plot_shows_the_body_components(trajectory):
    ax = plot.omega(trajectory).axes[0]
    for k, line in enumerate(ax.get_lines()):
        np.testing.assert_array_equal(line.get_ydata(), trajectory.omega[:, k])


def test_box_of_the_principal_moments():
    # a uniform box with half edges (a, b, c) has I1 ∝ b² + c²: the extents reproduce the moments' ratios
    moments = np.array([1.0, 2.0, 2.5])
    a, b, c = box_half_extents(moments)
    ratios = np.array([b * b + c * c, a * a + c * c, a * a + b * b])
    np.testing.assert_allclose(ratios / ratios[0], moments / moments[0], rtol=1e-12)


def test_refusals(tmp_path, trajectory):
    with pytest.raises(ValueError, match="must end in one of"):
        plot.save(plot.energy(trajectory), tmp_path / "fig.jpg")
    with pytest.raises(ValueError, match=r"\.gif or \.mp4"):
        animate(trajectory, tmp_path / "a.avi")
    batch = kr.EulerTop(1.0, 2.0, 3.0).solve(np.linspace(0, 1, 3), [[0.1, 1, 0], [0, 1, 0.1]])
    with pytest.raises(ValueError, match="one body"):
        animate(batch, tmp_path / "a.gif")
    assert list(tmp_path.iterdir()) == []
