"""
Inertia tensor, principal axes and the inertia ellipsoid (Theory §4.1–§4.3)
==================================================================================

A box turned into arbitrary axes has a full inertia tensor; its eigenvectors,
the principal axes, recover the edges, and the inertia ellipsoid xᵀ I x = 1 has
semi-axes 1/√I_k along them.
"""

import kreisel as kr

I_box = kr.inertia.box(2.0, [0.3, 0.2, 0.1])
turn = kr.euler_to_matrix("ZXZ", [0.4, 0.9, -0.3])
I_turned = kr.inertia.rotate(I_box, turn)
moments, axes = kr.inertia.principal_axes(I_turned)
print("principal moments:", moments)
print("about a corner:\n", kr.inertia.parallel_axis(I_box, 2.0, [0.15, 0.1, 0.05]))

fig = kr.plot.inertia_ellipsoid(I_turned, title="inertia ellipsoid of a turned box")
