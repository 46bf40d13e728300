"""A few rotation conversions, printed readably (``make demo``)."""

import numpy as np

import kreisel as kr


def main():
    np.set_printoptions(precision=6, suppress=True)
    angles = np.deg2rad([30.0, 45.0, 60.0])
    print("Seed mechanics Euler angles (phi, theta, psi) = (30°, 45°, 60°), R = Rz(phi) Rx(theta) Rz(psi)")
    q = kr.euler_to_quat("ZXZ", angles)
    print("  quaternion [q0, q1, q2, q3] =", q)
    print("  rotation matrix R =\n", kr.euler_to_matrix("ZXZ", angles))
    psi = kr.quat_to_rotvec(q)
    print("  rotation vector psi =", psi, f"(angle {np.degrees(np.linalg.norm(psi)):.4f}°)")
    print("  back to ZXZ angles (deg) =", kr.matrix_to_euler("ZXZ", kr.quat_to_matrix(q), degrees=True))
    body_axis = kr.quat_apply(q, [0.0, 0.0, 1.0])
    print("  body 3-axis in space =", body_axis, "(last column of R)")
    print("Double cover: rotvec_to_quat(2π e_z) =", kr.rotvec_to_quat([0.0, 0.0, 2 * np.pi]))


if __name__ == "__main__":
    main()
