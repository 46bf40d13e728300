"""
Euler angles, quaternions and the nodal line (Theory §2.3–§2.4)
========================================================================

The mechanics Euler angles (φ, θ, ψ) are the intrinsic sequence ``"ZXZ"``:
R = Rz(φ) Rx(θ) Rz(ψ). The same rotation as a scalar-first quaternion, a
rotation vector and back; then the space and body axes with the line of nodes
N = Rz(φ) e_x where the body x′y′ plane cuts the space xy plane.
"""

import matplotlib.pyplot as plt
import numpy as np

import kreisel as kr

angles = np.radians([40.0, 35.0, 25.0])
R = kr.euler_to_matrix("ZXZ", angles)
q = kr.euler_to_quat("ZXZ", angles)
psi = kr.quat_to_rotvec(q)
print("q (scalar first):", np.round(q, 6))
print("rotation vector :", np.round(psi, 6), " angle =", np.degrees(np.linalg.norm(psi)).round(4), "deg")
print("round trip error:", np.abs(kr.quat_to_euler("ZXZ", q) - angles).max())
print("R(q) == R       :", np.allclose(kr.quat_to_matrix(q), R, atol=1e-15))

fig = plt.figure(figsize=(5.5, 5))
ax = fig.add_subplot(projection="3d")
for k, name in enumerate("xyz"):
    e = np.eye(3)[k]
    ax.quiver(0, 0, 0, *e, color="0.6", arrow_length_ratio=0.08)
    ax.text(*(1.08 * e), name, color="0.4")
    ax.quiver(0, 0, 0, *R[:, k], color=f"C{k}", arrow_length_ratio=0.08, linewidth=2)
    ax.text(*(1.1 * R[:, k]), f"{name}′", color=f"C{k}")
node = kr.euler_to_matrix("ZXZ", [angles[0], 0.0, 0.0])[:, 0]
ax.plot(*np.c_[-node, node], "k--")
ax.text(*(1.1 * node), "N")
ax.set_box_aspect((1, 1, 1))
ax.set_title("space axes (grey), body axes (colour)")
plt.show()
