"""
Lagrange top: effective potential and apex loci (Theory §6.2–§6.5)
===========================================================================

A heavy symmetric top released at θ0 = 0.6 rad with spin 10 rad/s and three
precession rates: the apex moves monotonically, in cusps (released with
θ̇ = φ̇ = 0) or in loops, between the turning points of V_eff(θ).
"""

import matplotlib.pyplot as plt
import numpy as np

import kreisel as kr
from _quick import size

top = kr.LagrangeTop(1.0, 0.5, 1.0)  # I1 about the pivot, I3, m g l
euler0 = [0.0, 0.6, 0.0]
t = np.linspace(0.0, 12.0, size(3000, 400))
fig, axes = plt.subplots(1, 4, figsize=(12, 3.6), layout="constrained")
theta = np.linspace(0.05, np.pi - 0.05, 400)
for k, rates in enumerate(([0.35, 0.0, 10.0], [0.0, 0.0, 10.0], [-0.2, 0.0, 10.0])):
    kind = top.apex_locus_kind(euler0, rates)
    c = top.constants(euler0, rates)
    axes[0].plot(theta, top.effective_potential(theta, c.J3, c.Jz), label=kind)
    apex = kr.quat_apply(top.solve(t, euler0, rates).q, [0.0, 0.0, 1.0])
    axes[k + 1].plot(np.degrees(np.arctan2(apex[:, 1], apex[:, 0])) % 360, np.degrees(np.arccos(apex[:, 2])))
    axes[k + 1].invert_yaxis()
    axes[k + 1].set(title=kind, xlabel="φ (°)", ylabel="θ (°)")
    print(kind, "turning points θ (rad):", top.turning_points(euler0, rates))
axes[0].set(ylim=(None, 60), xlabel="θ (rad)", title="V_eff(θ)")
axes[0].legend(fontsize=8)
plt.show()
