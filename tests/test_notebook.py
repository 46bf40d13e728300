"""kreisel.show: the notebook widget's Python side (what it sends to the browser, and what it refuses)."""

import sys

import numpy as np
import pytest

import kreisel as kr
from kreisel.notebook import widget_data


@pytest.fixture(scope="module")
def trajectory():
    return kr.EulerTop(1.0, 2.0, 3.0).solve(np.linspace(0.0, 10.0, 3001), [0.1, 2.0, 0.1])


def test_show_sends_bounded_arrays_of_the_viewer_shapes(trajectory):
    widget = kr.show(trajectory, max_samples=500)
    data = widget.data
    m = len(data["t"])
    assert m == data["n_samples"] == 500
    assert np.asarray(data["q"]).shape == (m, 4)
    for key in ("omega", "omega_space", "J"):
        assert np.asarray(data[key]).shape == (m, 3), key
    assert data["t"][0] == 0.0 and data["t"][-1] == 10.0            # the ends are kept
    kept = np.searchsorted(trajectory.t, data["t"])
    np.testing.assert_array_equal(np.asarray(data["q"]), trajectory.q[kept])
    np.testing.assert_allclose(np.asarray(data["J"]), trajectory.angular_momentum_space[kept], rtol=0, atol=1e-12)
    assert data["analysis"]["T"] == pytest.approx(0.5 * (0.01 + 8.0 + 0.03), rel=1e-12)
    assert data["analysis"]["principal_moments"] == pytest.approx([1.0, 2.0, 3.0])
    assert widget.index == 0 and "render" in widget._esm


def test_short_trajectories_are_sent_whole(trajectory):
    short = kr.Trajectory(trajectory.t[:7], trajectory.q[:7], trajectory.omega[:7], [1.0, 2.0, 3.0])
    assert widget_data(short)["t"] == trajectory.t[:7].tolist()


@pytest.mark.parametrize("bad", [None, np.zeros((10, 4)), kr.Rotation.identity()])
def test_refuses_what_is_not_a_trajectory(bad):
    with pytest.raises(TypeError, match="trajectory must be a kreisel Trajectory"):
        kr.show(bad)


def test_refuses_batches_and_bad_sizes(trajectory):
    batch = kr.simulate_batch(np.array([[1.0, 2.0, 3.0]] * 2), np.linspace(0.0, 1.0, 11), [0.1, 1.0, 0.1])
    with pytest.raises(ValueError, match="single body"):
        kr.show(batch)
    for bad in (1, 2.5, True):
        with pytest.raises(ValueError, match="max_samples"):
            kr.show(trajectory, max_samples=bad)


def test_without_anywidget_the_error_names_the_extra(trajectory, monkeypatch):
    monkeypatch.setitem(sys.modules, "anywidget", None)
    with pytest.raises(ImportError, match=r"kreisel\[notebook\]"):
        kr.show(trajectory)


def test_trajectory_show_is_kreisel_show(trajectory):
    widget = trajectory.show(max_samples=50)
    assert widget.data == kr.show(trajectory, max_samples=50).data


def test_trajectory_show_without_anywidget_names_the_extra(trajectory, monkeypatch):
    monkeypatch.setitem(sys.modules, "anywidget", None)
    with pytest.raises(ImportError, match=r"kreisel\[notebook\]"):
        trajectory.show()


def test_dynamics_does_not_load_the_widget_until_shown():
    import subprocess

    code = ("import sys, numpy as np, kreisel.dynamics as d; "
            "tr = d.Trajectory([0.0, 1.0], [[1, 0, 0, 0]] * 2, [[0, 0, 1]] * 2, [1, 2, 3]); "
            "before = 'kreisel.notebook' in sys.modules; tr.show(); print(before, 'kreisel.notebook' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=300)
    assert out.stdout.split() == ["False", "True"]


def test_heavy_top_sends_gravity_and_its_analysis():
    top = kr.LagrangeTop(1.0, 0.5, 1.0)
    tr = top.solve(np.linspace(0.0, 2.0, 101), [0.0, 0.6, 0.0], [0.0, 0.0, 8.0])
    data = widget_data(tr, gravity=(top.mgl, [0, 0, 1]))
    assert data["gravity"] == {"weight": 1.0, "lever": [0.0, 0.0, 1.0]}
    # total energy T + m g (R l)_z is conserved along the exact solution
    energy = np.asarray(data["energy"])
    np.testing.assert_allclose(energy, energy[0], rtol=1e-9)
    assert data["analysis"]["lagrange"] is not None


@pytest.mark.parametrize("bad, match", [(1.0, "pair"), ((0.0, [0, 0, 1]), "weight"), ((1.0, [0, 0]), "lever"),
                                        ((1.0, [0, 0, 0]), "lever"), ((np.nan, [0, 0, 1]), "weight")])
def test_refuses_bad_gravity(trajectory, bad, match):
    with pytest.raises(ValueError, match=match):
        widget_data(trajectory, gravity=bad)


def test_outside_a_widget_frontend_the_player_is_a_summary_and_a_picture(trajectory):
    """The issue: in a terminal ``traj.show()`` printed ``<…TrajectoryWidget object at 0x…>``."""
    import base64
    import io

    from IPython.core.interactiveshell import InteractiveShell
    from PIL import Image

    widget = trajectory.show(max_samples=200)
    data, _ = InteractiveShell.instance().display_formatter.format(widget)   # what IPython shows
    assert "object at 0x" not in data["text/plain"]
    assert data["text/plain"].startswith("kreisel.show: 3D player of a rigid body, 200 samples, t = 0 … 10 s")
    assert "application/vnd.jupyter.widget-view+json" in data   # a widget frontend still draws the player
    image = Image.open(io.BytesIO(base64.b64decode(data["image/png"])))  # a viewer without widgets, this
    assert image.size[0] > 400 and image.size[1] > 200
    assert repr(widget) == data["text/plain"]


def test_the_static_picture_of_a_heavy_top_is_its_apex_path():
    top = kr.LagrangeTop(1.0, 0.5, 1.0)
    widget = kr.show(top.solve(np.linspace(0.0, 5.0, 201), [0.0, 0.5, 0.0], [0.0, 0.0, 10.0]), gravity=(top.mgl, [0, 0, 1]))
    bundle, _ = widget._repr_mimebundle_()
    assert bundle["text/plain"].startswith("kreisel.show: 3D player of a heavy top")
    assert len(bundle["image/png"]) > 1000


def test_without_matplotlib_the_fallback_is_the_summary_alone(trajectory, monkeypatch):
    widget = trajectory.show(max_samples=20)
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    bundle, _ = widget._repr_mimebundle_()
    assert "image/png" not in bundle and bundle["text/plain"].startswith("kreisel.show: 3D player")
