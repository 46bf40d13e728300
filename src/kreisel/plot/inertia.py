"""Figure of the inertia ellipsoid of an inertia tensor (Theory §4.3)."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from .. import inertia

__all__ = ["inertia_ellipsoid"]


def inertia_ellipsoid(I, title="inertia ellipsoid xᵀ I x = 1"):
    """The ellipsoid ``xᵀ I x = 1`` with its principal semi-axes ``1/√I_k`` drawn in colour.

    Parameters
    ----------
    I : (3, 3) array_like
        Inertia tensor, kg m² (:func:`kreisel.inertia.inertia_ellipsoid` samples the surface).
    title : str

    Returns
    -------
    matplotlib.figure.Figure
        One 3-D axes with equal scales, labelled in 1/√(kg m²).

    Examples
    --------
    >>> import kreisel as kr
    >>> fig = inertia_ellipsoid(kr.inertia.box(2.0, [0.3, 0.2, 0.1]))
    >>> fig.axes[0].get_title()
    'inertia ellipsoid xᵀ I x = 1'
    """
    ellipsoid = inertia.inertia_ellipsoid(I)
    fig = Figure(figsize=(5.5, 5), layout="constrained")
    ax = fig.add_subplot(projection="3d")
    ax.plot_surface(ellipsoid.x, ellipsoid.y, ellipsoid.z, color="C0", alpha=0.35, linewidth=0)
    for k in range(3):
        d = ellipsoid.semi_axes[k] * ellipsoid.axes[:, k]
        ax.plot(*np.c_[-d, d], color=f"C{k + 1}", linewidth=2)
    ax.set_box_aspect(np.ptp(np.stack([ellipsoid.x.ravel(), ellipsoid.y.ravel(), ellipsoid.z.ravel()]), axis=1))
    unit = "(1/√(kg m²))"
    ax.set(xlabel=f"x {unit}", ylabel=f"y {unit}", zlabel=f"z {unit}", title=title)
    return fig
