"""
Your phone as a free-rotation laboratory (Theory §5.3–§5.4)
===========================================================

A phone tossed end over end about its middle axis flips in flight, and its
gyroscope records the body angular velocity: exactly what Euler's equations
describe. :func:`kreisel.fit_free_rotation` fits the exact free-top solution to
the bundled recording (phyphox CSV, ~400 Hz, 0.05 rad/s noise, a bias on each
axis) and reads off the moment ratios of the phone.
"""

import numpy as np

import kreisel as kr
import kreisel.plot

recording = kr.io.read_gyro(kr.io.recording_path("phone_toss"))
fit = kr.fit_free_rotation(recording.t, recording.omega, bias=True)
slab = np.diag(kr.inertia.box(1.0, (0.071, 0.146, 0.008)))
print("fitted I_x : I_y : I_z =", np.round(fit.moments, 4), "±", np.round(fit.moments_stderr, 4))
print("146 x 71 x 8 mm slab  =", np.round(slab / slab.max(), 4))
print(f"residual RMS {fit.rms:.3f} rad/s, intermediate axis {'xyz'[fit.intermediate_axis]}, {fit.regime}")
fig = kreisel.plot.gyro_fit(fit)
