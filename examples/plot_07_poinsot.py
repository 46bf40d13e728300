"""
Poinsot construction: polhode and herpolhode (seed 五.5–五.6)
========================================================================

ρ = ω/√(2T) lies on the inertia ellipsoid and the ellipsoid rolls without
slipping on the invariable plane normal to J. The figures come straight from
:mod:`kreisel.plot`.
"""

import numpy as np

import kreisel as kr
import kreisel.plot
from _quick import size

top = kr.EulerTop(1.0, 2.0, 3.0)
traj = top.solve(np.linspace(0.0, 100.0, size(4000, 500)), [0.4, 0.2, 1.0])
polhode = kreisel.plot.polhode(traj)
herpolhode = kreisel.plot.herpolhode(traj)
