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



def test_an_animation_that_cannot_be_written_raises_without_a_matplotlib_warning(tmp_path, trajectory, recwarn):
    # matplotlib warns when an animation is collected unsaved; one made before the file failed to open was
    import gc

    with pytest.raises(ValueError, match="does not exist"):
        animate(trajectory, tmp_path / "gone" / "a.gif", frames=2)
    gc.collect()
    assert not [w for w in recwarn if issubclass(w.category, UserWarning)], [str(w.message) for w in recwarn]

def test_euler_plot_avoids_the_gimbal_lock_of_the_tennis_racket_and_unwraps():
    import kreisel as kr
    from kreisel.plot import euler, regular_sequence

    racket = kr.EulerTop(1.0, 2.0, 3.0).solve(np.linspace(0.0, 60.0, 601), [0.01, 1.0, 0.01])
    seq = regular_sequence(racket.q)
    R = kr.quat_to_matrix(racket.q)
    outer = ("XYZ".index(seq[0]), "XYZ".index(seq[2]))
    # at least 30° from the lock all along, where ZXZ starts at its lock (θ = 0)
    assert np.min(np.arccos(np.abs(R[:, outer[0], outer[1]]))) > np.radians(30.0)
    assert np.min(np.arccos(np.abs(R[:, 2, 2]))) < np.radians(1.0)
    fig = euler(racket)
    assert seq in fig.axes[0].get_title()
    for line in fig.axes[0].lines:
        assert np.max(np.abs(np.diff(line.get_ydata()))) < 90.0   # no ±180° jumps


def test_apex_and_polhode_label_every_axis():
    import kreisel as kr
    from kreisel.plot import apex, polhode

    tr = kr.EulerTop(1.0, 2.0, 3.0).solve(np.linspace(0.0, 20.0, 201), [0.01, 1.0, 0.01])
    for fig in (apex(tr), polhode(tr)):
        for ax in fig.axes:
            assert ax.get_xlabel() and ax.get_ylabel()
            if ax.name == "3d":
                assert ax.get_zlabel()
                fig.canvas.draw()
                box = ax.zaxis.label.get_window_extent()
                assert 0 <= box.x0 and box.x1 <= fig.bbox.width   # the third label is not clipped
