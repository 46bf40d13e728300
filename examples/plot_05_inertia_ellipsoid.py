"""
Inertia tensor, principal axes and the inertia ellipsoid (Theory §4.1–§4.3)
==================================================================================

A box turned into arbitrary axes has a full inertia tensor; its eigenvectors,
the principal axes, recover the edges, and the inertia ellipsoid xᵀ I x = 1 has
semi-axes 1/√I_k along them.
"""

import matplotlib.pyplot as plt
import numpy as np

import kreisel as kr

I_box = kr.inertia.box(2.0, [0.3, 0.2, 0.1])
turn = kr.euler_to_matrix("ZXZ", [0.4, 0.9, -0.3])
I_turned = kr.inertia.rotate(I_box, turn)
moments, axes = kr.inertia.principal_axes(I_turned)
print("principal moments:", moments)
print("about a corner:\n", kr.inertia.parallel_axis(I_box, 2.0, [0.15, 0.1, 0.05]))

ell = kr.inertia.inertia_ellipsoid(I_turned)
fig = plt.figure(figsize=(5.5, 5))
ax = fig.add_subplot(projection="3d")
ax.plot_surface(ell.x, ell.y, ell.z, color="C0", alpha=0.35, linewidth=0)
for k in range(3):
    d = ell.semi_axes[k] * ell.axes[:, k]
    ax.plot(*np.c_[-d, d], color=f"C{k + 1}", linewidth=2)
ax.set_box_aspect(np.ptp(np.stack([ell.x.ravel(), ell.y.ravel(), ell.z.ravel()]), axis=1))
plt.show()
