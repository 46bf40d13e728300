"""
Choosing an integrator: work–precision and conservation (Theory §4.5)
===============================================================================

Euler's equations of the free body I = (2, 1, 2/3) with m0 = (cos 1.1, 0,
sin 1.1) (Hairer, Lubich and Wanner's test), integrated by every method of
:func:`kreisel.simulate`. Left: maximal relative energy error against CPU time.
The table printed below gives, for h = 0.1, the energy error and the drift of
‖m‖ (a Casimir) for each fixed-step method.
"""

import time

import matplotlib.pyplot as plt
import numpy as np

import kreisel as kr
from _quick import size

moments = np.array([2.0, 1.0, 2.0 / 3.0])
omega0 = np.array([np.cos(1.1), 0.0, np.sin(1.1)]) / moments
t = np.linspace(0.0, size(1000.0, 50.0), 2001)


def run(**options):
    kr.simulate(moments, t[:2], omega0, allow_unphysical=True, **options)  # compile first
    start = time.perf_counter()
    traj = kr.simulate(moments, t, omega0, allow_unphysical=True, **options)
    seconds = time.perf_counter() - start
    energy = np.max(np.abs(traj.energy / traj.energy[0] - 1))
    m = np.linalg.norm(traj.angular_momentum_body, axis=-1)
    return max(energy, 1e-17), np.max(np.abs(m / m[0] - 1)), seconds


fig, ax = plt.subplots(figsize=(7, 4.5), layout="constrained")
rows = []
for k, method in enumerate(("splitting", "splitting4", "dmv", "rkmk4", "midpoint", "rk4")):
    results = [run(method=method, dt=dt) for dt in size((0.2, 0.1, 0.05, 0.025), (0.2, 0.1))]
    ax.loglog([r[2] for r in results], [r[0] for r in results], "o-", color=f"C{k}", label=method)
    rows.append((method, *results[1][:2]))
results = [run(method="dop853", rtol=rtol) for rtol in size((1e-6, 1e-8, 1e-10, 1e-12), (1e-6, 1e-10))]
ax.loglog([r[2] for r in results], [r[0] for r in results], "s--", color="k", label="dop853 (adaptive)")
ax.set(xlabel="CPU time (s)", ylabel="max relative energy error")
ax.legend(fontsize=8)

print(f"{'method':<12}{'energy error':>15}{'|m| error':>12}   (h = 0.1, T = {t[-1]:g})")
for method, energy, norm in rows:
    print(f"{method:<12}{energy:>15.2e}{norm:>12.2e}")
plt.show()
