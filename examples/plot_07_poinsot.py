"""
Poinsot construction: polhode and herpolhode (Theory §5.5–§5.6)
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

# the invariable plane lies at the fixed distance √(2T)/|J| from the fixed point
J = np.linalg.norm(traj.angular_momentum_space, axis=-1)
rho = kr.quat_apply(traj.q, traj.omega) / np.sqrt(2 * traj.energy[:, None])
distance = np.einsum("ij,ij->i", rho, traj.angular_momentum_space / J[:, None])
print("max relative deviation of the plane distance:", np.max(np.abs(distance * J / np.sqrt(2 * traj.energy) - 1)))
