"""Notebooks: :func:`show` plays a trajectory in 3D inside Jupyter (JupyterLab, VS Code).

The widget is an `anywidget <https://anywidget.dev>`_ whose front end is the web
viewer's own scene (``web/src/widget.js``, bundled into ``kreisel/web/static``):
the body with its principal axes, ω and J, the inertia ellipsoid (as the energy
ellipsoid ω·Iω = 2T) rolling on the invariable plane, polhode and herpolhode
(Theory §5.5), or for a heavy top the pivot, gravity and the path of the apex;
a legend, a time slider and a space/body camera.
Install it with ``pip install "kreisel[notebook]"``.
"""

from __future__ import annotations

import importlib.resources
import importlib.util
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._optional import require
from .dynamics import Trajectory
from .web.session import analysis, samples

if TYPE_CHECKING:
    from anywidget import AnyWidget

__all__ = ["show", "widget_data"]

#: Most samples sent to the browser; longer trajectories are thinned evenly (first and last kept).
MAX_SAMPLES = 2000


def _gravity(gravity: tuple[float, ArrayLike] | None) -> tuple[float, NDArray[np.float64]] | None:
    """``(weight, lever)`` checked: weight > 0 in N, lever a non-zero (3,) vector in body axes, m."""
    if gravity is None:
        return None
    try:
        weight, lever = gravity
        weight, lever = float(weight), np.asarray(lever, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"gravity must be a pair (weight, lever), got {gravity!r}") from None
    if not (np.isfinite(weight) and weight > 0):
        raise ValueError(f"gravity: weight must be a positive number of newtons, got {weight!r}")
    if lever.shape != (3,) or not np.all(np.isfinite(lever)) or not np.any(lever):
        raise ValueError(f"gravity: lever must be a finite non-zero 3-vector in body axes, got {lever.tolist()!r}")
    return weight, lever


def widget_data(trajectory: Trajectory, max_samples: int = MAX_SAMPLES,
                gravity: tuple[float, ArrayLike] | None = None) -> dict[str, Any]:
    """The JSON-ready arrays the widget draws: the viewer's samples and analysis of ``trajectory``.

    Parameters
    ----------
    trajectory : Trajectory
        A single body (no batch axes).
    max_samples : int
        At most this many samples are kept, evenly spaced in index.
    gravity : (float, (3,) array_like), optional
        ``(weight, lever)`` of a heavy top about its pivot: weight m g in N and the lever from the
        pivot to the centre of mass in body axes, m (gravity along space −z). A
        :class:`~kreisel.tops.LagrangeTop` has ``(top.mgl, [0, 0, 1])``.

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
    gravity = _gravity(gravity)
    n = trajectory.t.size
    keep = np.unique(np.linspace(0, n - 1, min(n, int(max_samples))).round().astype(int))
    thinned = Trajectory(trajectory.t[keep], trajectory.q[keep], trajectory.omega[keep], trajectory.inertia)
    arrays = samples(thinned, gravity)
    heavy = None if gravity is None else {"weight": gravity[0], "lever": gravity[1].tolist()}
    return {"kind": "rigid_body", "gravity": heavy, "n_samples": int(keep.size), "analysis": analysis(thinned, gravity),
            **{key: np.asarray(value).tolist() for key, value in arrays.items()}}


def _widget_class() -> type[AnyWidget]:
    require("anywidget", extra="notebook", feature="kreisel.show")
    require("traitlets", extra="notebook", feature="kreisel.show")
    # imported by name once require has vouched for them: type checkers then see the classes
    import anywidget
    import traitlets

    class TrajectoryWidget(anywidget.AnyWidget):
        """The 3D player of :func:`show`; ``index`` is the sample on screen.

        Where no widget can be drawn (a terminal, a notebook viewer, an HTML export), its
        representation falls back to a summary line and, with matplotlib, a static figure:
        the frontend picks the richest form it can show.
        """

        _esm = (importlib.resources.files("kreisel.web") / "static" / "widget.js").read_text(encoding="utf-8")
        data = traitlets.Dict().tag(sync=True)
        index = traitlets.Int(0).tag(sync=True)

        def __repr__(self) -> str:
            return _summary(self.data)

        def _repr_mimebundle_(self, **kwargs: Any) -> tuple[dict[str, Any], dict[str, Any]]:
            # anywidget gives (data, metadata), ipywidgets data alone, either None without a view
            bundle: Any = super()._repr_mimebundle_(**kwargs) or {}
            data, metadata = bundle if isinstance(bundle, tuple) else (bundle, {})
            data = {**data, "text/plain": _summary(self.data)}
            picture = _static_png(self.data)
            if picture is not None:
                data["image/png"] = picture
            return data, metadata

    return TrajectoryWidget


def _summary(data: dict[str, Any]) -> str:
    kind = "heavy top" if data.get("gravity") else "rigid body"
    t = data.get("t") or [0.0]
    return (f"kreisel.show: 3D player of a {kind}, {data.get('n_samples', len(t))} samples, t = {t[0]:g} … {t[-1]:g} s "
            "(drawn in a notebook with widgets: JupyterLab, Jupyter Notebook 7, VS Code)")


def _static_png(data: dict[str, Any]) -> str | None:
    """The picture shown where the widget cannot be: base64 PNG of the apex path (heavy top) or of ω′(t).

    None without matplotlib (the notebook extra installs it; the widget needs it not).
    """
    if importlib.util.find_spec("matplotlib") is None:
        return None
    import base64
    import io

    from . import plot

    traj = Trajectory(np.asarray(data["t"]), np.asarray(data["q"]), np.asarray(data["omega"]),
                      data["analysis"]["principal_moments"])
    # kreisel.plot is not annotated: its figure functions are held as typed callables
    draw: Callable[[Trajectory], Any] = plot.apex if data.get("gravity") else plot.omega
    fig = draw(traj)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=90)
    return base64.b64encode(buffer.getvalue()).decode("ascii")


def show(trajectory: Trajectory, max_samples: int = MAX_SAMPLES,
         gravity: tuple[float, ArrayLike] | None = None) -> AnyWidget:
    """Play ``trajectory`` in 3D in a notebook: body, principal axes, ω, J, Poinsot construction, time slider.

    Parameters
    ----------
    trajectory : Trajectory
        A single body (no batch axes), e.g. from :func:`kreisel.simulate` or
        :meth:`kreisel.EulerTop.solve`.
    max_samples : int
        Longer trajectories are thinned evenly to this many samples.
    gravity : (float, (3,) array_like), optional
        ``(weight, lever)`` of a heavy top (see :func:`widget_data`): the scene shows the pivot,
        gravity and the path of the apex instead of the free body's Poinsot construction.

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
    >>> top = kr.LagrangeTop(1.0, 0.5, 1.0)
    >>> heavy = kr.show(top.solve(np.linspace(0.0, 5.0, 201), [0.0, 0.5, 0.0], [0.0, 0.0, 10.0]), gravity=(top.mgl, [0, 0, 1]))
    >>> heavy.data["gravity"]
    {'weight': 1.0, 'lever': [0.0, 0.0, 1.0]}
    """
    data = widget_data(trajectory, max_samples, gravity)
    return _widget_class()(data=data)
