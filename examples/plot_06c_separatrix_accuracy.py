"""
Exact next to the separatrix (Theory §5.3)
==========================================

Started close to the middle axis, the free top tumbles along a polhode that
nearly touches the separatrix J² = 2T I₂, where the elliptic parameter m → 1
and every formula written with m loses the digits of 1 − m.
:class:`kreisel.tops.EulerTop` carries m1 = 1 − m from the data to the
elliptic functions, so its error stays at rounding level however close the
start is; :meth:`~kreisel.tops.EulerTop.accuracy` states the bound it
guarantees. DOP853 at rtol 1e-12 (:func:`kreisel.simulate`) is shown for
comparison. The reference is the same closed form evaluated by mpmath at
40 digits from the exact binary ω0.
"""

import matplotlib.pyplot as plt
import mpmath as mp
import numpy as np
from _quick import size

import kreisel as kr

moments = (1.0, 2.0, 3.0)
top = kr.EulerTop(*moments)
t = np.linspace(0.0, 20.0, size(41, 11))


def start(distance):
    """ω0 = (0.1, 1, c) at (J² − 2TI₂)/(2TI₂) = distance for I = (1, 2, 3)."""
    c2 = (0.01 + distance * 2.0 * (0.01 + 2.0)) / (3.0 - 6.0 * distance)
    return np.array([0.1, 1.0, np.sqrt(c2)])


def reference_omega(omega0, times):
    """ω(t) about the largest axis (J² > 2TI₂) from mpmath's ellipf/ellipfun at 40 digits."""
    mp.mp.dps = 40
    I1, I2, I3 = (mp.mpf(x) for x in moments)
    w1, w2, w3 = (mp.mpf(x) for x in omega0)
    J2 = (I1 * w1) ** 2 + (I2 * w2) ** 2 + (I3 * w3) ** 2
    T2 = I1 * w1**2 + I2 * w2**2 + I3 * w3**2
    d1, d3 = J2 - T2 * I1, T2 * I3 - J2
    a1, a2, a3 = mp.sqrt(d3 / (I1 * (I3 - I1))), mp.sqrt(d3 / (I2 * (I3 - I2))), mp.sqrt(d1 / (I3 * (I3 - I1)))
    lam = mp.sqrt((I3 - I2) * d1 / (I1 * I2 * I3))
    m = (I2 - I1) * d3 / ((I3 - I2) * d1)
    u0 = mp.ellipf(mp.atan2(w2 / a2, w1 / a1), m)
    rows = []
    for x in times:
        u = lam * mp.mpf(x) + u0
        rows.append([float(a1 * mp.ellipfun("cn", u, m=m)), float(a2 * mp.ellipfun("sn", u, m=m)),
                     float(a3 * mp.ellipfun("dn", u, m=m))])
    return np.array(rows)


distances = np.logspace(-2, -14, size(13, 4))
exact_error, dop853_error, bound, actual = [], [], [], []
for distance in distances:
    omega0 = start(distance)
    actual.append(top.separatrix_distance(omega0))
    reference = reference_omega(omega0, t)
    exact_error.append(np.abs(top.solve(t, omega0).omega - reference).max())
    dop853_error.append(np.abs(kr.simulate(moments, t, omega0, method="dop853", rtol=1e-12).omega - reference).max())
    bound.append(top.accuracy(omega0, duration=t[-1]).omega_error * np.linalg.norm(omega0))

fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
ax.loglog(actual, np.maximum(exact_error, 1e-17), "o-", label="kreisel EulerTop.solve")
ax.loglog(actual, dop853_error, "s-", label="DOP853, rtol 1e-12")
ax.loglog(actual, bound, "--", color="0.5", label="EulerTop.accuracy bound")
ax.set_xlabel("distance from the separatrix (J² − 2TI₂)/(2TI₂)")
ax.set_ylabel("max |Δω| over 0 ≤ t ≤ 20 s (rad/s)")
ax.invert_xaxis()
ax.legend()
print("largest kreisel error:", max(exact_error), " largest DOP853 error:", max(dop853_error))
plt.show()
