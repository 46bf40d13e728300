"""
Strapdown attitude under coning (Theory §3.3, §3.5)
============================================================

Gyro angle increments of a coning motion (half angle 1°, 1 Hz) integrated by
the N-sample coning algorithms of :func:`kreisel.nav.attitude_from_increments`.
The attitude error grows linearly (coning drift); more samples per update
shrink it by orders of magnitude.
"""

import matplotlib.pyplot as plt
import numpy as np

import kreisel as kr
from _quick import size

alpha, rate, ts = np.radians(1.0), 2 * np.pi, 0.01
motion = kr.nav.coning_motion(alpha, rate, ts, size(4800, 1200))
fig, ax = plt.subplots(figsize=(7, 3.8), layout="constrained")
for n in (1, 2, 3, 4):
    q = kr.nav.attitude_from_increments(motion.q[0], motion.dtheta, n)
    error = kr.quat_to_rotvec(kr.quat_multiply(kr.quat_conjugate(motion.q[::n]), q))
    ax.semilogy(motion.t[::n], np.linalg.norm(error, axis=-1) + 1e-17, label=f"N = {n}")
    print(f"N = {n}: predicted drift {kr.nav.coning_drift(alpha, rate, ts, n):.3e} rad/s")
ax.set(xlabel="t (s)", ylabel="attitude error (rad)")
ax.legend()
plt.show()
