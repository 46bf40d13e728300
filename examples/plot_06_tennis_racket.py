"""
Tennis-racket theorem (Theory §5.4)
============================================

The free (Euler) top I = (1, 2, 3) spun near each principal axis. Rotation about
the largest and smallest axes is stable; about the middle axis the body flips
over periodically (Dzhanibekov effect). :class:`kreisel.tops.EulerTop` is the
exact elliptic-function solution, so no time stepping is involved.
"""

import matplotlib.pyplot as plt
import numpy as np

import kreisel as kr
from _quick import size

top = kr.EulerTop(1.0, 2.0, 3.0)
print([s.kind for s in top.steady_rotations()])
t = np.linspace(0.0, 60.0, size(4000, 600))
starts = {"axis 1": [1.0, 0.01, 0.01], "axis 2": [0.01, 1.0, 0.01], "axis 3": [0.01, 0.01, 1.0]}
fig, axes = plt.subplots(3, 1, figsize=(8, 6), sharex=True, layout="constrained")
for ax, (label, omega0) in zip(axes, starts.items()):
    traj = top.solve(t, omega0)
    ax.plot(t, traj.omega)
    ax.set_title(f"spun near {label}", fontsize=10)
axes[0].legend(["ω′1", "ω′2", "ω′3"], ncol=3, loc="upper right")
axes[-1].set_xlabel("t (s)")
print("flip time 2K(m)/λ =", top.dzhanibekov_flip_time(starts["axis 2"]), "s")
plt.show()
