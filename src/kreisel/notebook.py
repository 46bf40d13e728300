"""Notebooks: :func:`show` plays a trajectory in 3D inside Jupyter (JupyterLab, VS Code).

The widget is an `anywidget <https://anywidget.dev>`_ whose front end is the web
viewer's own scene (``web/src/widget.js``, bundled into ``kreisel/web/static``):
the body with its principal axes, ω and J, the energy ellipsoid on the
invariable plane, polhode and herpolhode (Theory §5.5), with a time slider.
Install it with ``pip install "kreisel[notebook]"``.
"""

from __future__ import annotations

import importlib.resources

import numpy as np

from ._optional import require
from .dynamics import Trajectory
from .web.session import analysis, samples

__all__ = ["show", "widget_data"]

#: Most samples sent to the browser; longer trajectories are thinned evenly (first and last kept).
MAX_SAMPLES = 2000


def widget_data(trajectory, max_samples=MAX_SAMPLES):
    """The JSON-ready arrays the widget draws: the viewer's samples and analysis of ``trajectory``.

    Parameters
    ----------
    trajectory : Trajectory
        A single body (no batch axes).
    max_samples : int
        At most this many samples are kept, evenly spaced in index.

    Returns
    -------
    dict
        ``t`` (m,), ``q`` (m, 4), ``omega`` and ``omega_space`` and ``J`` (m, 3) as lists, with
        ``analysis`` (T, J, principal moments and axes) taken at the first sample.

    Examples
    --------
    >>> import numpy as np, kreisel as kr
    >>> tr = kr.EulerTop(1.0, 2.0, 3.0).solve(np.linspace(0.0, 10.0, 5001), [0.1, 2.0, 0.1])
    >>> data = widget_data(tr, max_samples=100)
    >>> len(data["t"]), data["t"][-1], len(data["q"][0])
    (100, 10.0, 4)
    """
    if not isinstance(trajectory, Trajectory):
        raise TypeError(f"trajectory must be a kreisel Trajectory, got {type(trajectory).__name__}")
    if trajectory.batch_shape:
        raise ValueError(f"trajectory must be a single body, got batch shape {trajectory.batch_shape}; "
                         "show one element, e.g. a Trajectory built from traj.q[0], traj.omega[0]")
    if isinstance(max_samples, bool) or not isinstance(max_samples, (int, np.integer)) or max_samples < 2:
        raise ValueError(f"max_samples must be an integer >= 2, got {max_samples!r}")
    n = trajectory.t.size
    keep = np.unique(np.linspace(0, n - 1, min(n, int(max_samples))).round().astype(int))
    thinned = Trajectory(trajectory.t[keep], trajectory.q[keep], trajectory.omega[keep], trajectory.inertia)
    arrays = samples(thinned, None)
    return {"kind": "rigid_body", "gravity": None, "n_samples": int(keep.size), "analysis": analysis(thinned, None),
            **{key: np.asarray(value).tolist() for key, value in arrays.items()}}


def _widget_class():
    anywidget = require("anywidget", extra="notebook", feature="kreisel.show")
    traitlets = require("traitlets", extra="notebook", feature="kreisel.show")

    class TrajectoryWidget(anywidget.AnyWidget):
        """The 3D player of :func:`show`; ``index`` is the sample on screen."""

        _esm = (importlib.resources.files("kreisel.web") / "static" / "widget.js").read_text(encoding="utf-8")
        data = traitlets.Dict().tag(sync=True)
        index = traitlets.Int(0).tag(sync=True)

    return TrajectoryWidget


def show(trajectory, max_samples=MAX_SAMPLES):
    """Play ``trajectory`` in 3D in a notebook: body, principal axes, ω, J, Poinsot construction, time slider.

    Parameters
    ----------
    trajectory : Trajectory
        A single body (no batch axes), e.g. from :func:`kreisel.simulate` or
        :meth:`kreisel.EulerTop.solve`.
    max_samples : int
        Longer trajectories are thinned evenly to this many samples.

    Returns
    -------
    anywidget.AnyWidget
        Displayed when it is the last expression of a cell.

    Examples
    --------
    >>> import numpy as np, kreisel as kr
    >>> tr = kr.EulerTop(1.0, 2.0, 3.0).solve(np.linspace(0.0, 10.0, 501), [0.1, 2.0, 0.1])
    >>> widget = kr.show(tr)
    >>> len(widget.data["t"]), widget.index
    (501, 0)
    """
    data = widget_data(trajectory, max_samples)
    return _widget_class()(data=data)
