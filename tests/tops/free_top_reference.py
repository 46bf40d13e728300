"""30-digit references for the exact free top next to the separatrix (run to regenerate the data file).

``python tests/tops/free_top_reference.py`` writes ``data/free_top_reference.npz``:

- ``closed``: ω(t) and q(t) from the Landau–Lifshitz closed form (Theory §5.3) evaluated
  with mpmath's own ``ellipfun``, ``ellipf``, ``ellipk`` and ``ellippi`` at 40 digits, from the
  exact binary values of I and ω0 (so m and 1 − m carry no rounding), for
  I = (1, 2, 3) and the unphysical benchmark body I = (2, 1, 2/3), at separatrix distances
  ±1e-4, ±1e-6, ±1e-10, 1e-12 and 0 (the nearest double), both signs of ω1, plus the exact
  separatrix of I = (3, 4, 6), at t = 0 … 20 s;
- ``taylor``: the same for a subset, by mpmath's Taylor-series ODE solver (``odefun``)
  applied to Euler's equations and q̇ = ½ q ⊗ ω at 30 digits: independent of the closed form.
"""

import pathlib

import mpmath as mp
import numpy as np

DATA = pathlib.Path(__file__).parent / "data" / "free_top_reference.npz"
TIMES = np.linspace(0.0, 20.0, 41)
TAYLOR_TIMES = np.linspace(0.0, 20.0, 5)
BODIES = {"123": (1.0, 2.0, 3.0), "hlw": (2.0, 1.0, 2.0 / 3.0)}
DISTANCES = (1e-4, -1e-4, 1e-6, -1e-6, 1e-10, -1e-10, 1e-12, 0.0)
Q0 = (0.5, 0.5, -0.5, 0.5)


def initial_state(moments, distance, sign1):
    """ω0 (doubles) at the given (J² − 2TI_mid)/(2TI_mid), ω_mid = 1, the smallest-axis component ±0.1."""
    mp.mp.dps = 50
    order = np.argsort(moments)
    small, mid, large = (mp.mpf(moments[i]) for i in order)
    a = mp.mpf(0.1)
    d = mp.mpf(distance)
    # I3(I3 − I2)c² − I1(I2 − I1)a² = d I2 (I1 a² + I2 + I3 c²), solved for c
    c2 = (small * (mid - small) * a**2 + d * mid * (small * a**2 + mid)) / (large * (large - mid) - d * mid * large)
    omega = np.zeros(3)
    omega[order[0]] = sign1 * 0.1
    omega[order[1]] = 1.0
    omega[order[2]] = float(mp.sqrt(c2))
    return omega


def _quat_mul(p, q):
    return [
        p[0] * q[0] - p[1] * q[1] - p[2] * q[2] - p[3] * q[3],
        p[0] * q[1] + p[1] * q[0] + p[2] * q[3] - p[3] * q[2],
        p[0] * q[2] - p[1] * q[3] + p[2] * q[0] + p[3] * q[1],
        p[0] * q[3] + p[1] * q[2] - p[2] * q[1] + p[3] * q[0],
    ]


def _permutation(moments):
    """Signed permutation P (ω_user = P ω_sorted, det P = 1) and its quaternion, exactly."""
    order = np.argsort(moments, kind="stable")
    P = np.zeros((3, 3))
    P[order, np.arange(3)] = 1.0
    if np.linalg.det(P) < 0:
        P[:, 2] *= -1.0
    R = [[mp.mpf(x) for x in row] for row in P]
    tr = R[0][0] + R[1][1] + R[2][2]
    candidates = [1 + tr, 1 + 2 * R[0][0] - tr, 1 + 2 * R[1][1] - tr, 1 + 2 * R[2][2] - tr]
    k = int(np.argmax([float(c) for c in candidates]))
    big = mp.sqrt(candidates[k]) / 2
    if k == 0:
        q = [big, (R[2][1] - R[1][2]) / (4 * big), (R[0][2] - R[2][0]) / (4 * big), (R[1][0] - R[0][1]) / (4 * big)]
    elif k == 1:
        q = [(R[2][1] - R[1][2]) / (4 * big), big, (R[0][1] + R[1][0]) / (4 * big), (R[0][2] + R[2][0]) / (4 * big)]
    elif k == 2:
        q = [(R[0][2] - R[2][0]) / (4 * big), (R[0][1] + R[1][0]) / (4 * big), big, (R[1][2] + R[2][1]) / (4 * big)]
    else:
        q = [(R[1][0] - R[0][1]) / (4 * big), (R[0][2] + R[2][0]) / (4 * big), (R[1][2] + R[2][1]) / (4 * big), big]
    return P, q


def closed_form(moments, omega0, q0, times, dps=40):
    """ω (n, 3) and q (n, 4) from the closed form at ``dps`` digits (user axes)."""
    mp.mp.dps = dps
    P, qp = _permutation(moments)
    I1, I2, I3 = (mp.mpf(x) for x in np.sort(moments))
    w = [sum(mp.mpf(P[i, k]) * mp.mpf(omega0[i]) for i in range(3)) for k in range(3)]
    w1, w2, w3 = w
    J2 = (I1 * w1) ** 2 + (I2 * w2) ** 2 + (I3 * w3) ** 2
    T2 = I1 * w1**2 + I2 * w2**2 + I3 * w3**2
    J = mp.sqrt(J2)
    d1, d2, d3 = J2 - T2 * I1, J2 - T2 * I2, T2 * I3 - J2
    if d2 >= 0:
        A1, A2, A3 = mp.sqrt(d3 / (I1 * (I3 - I1))), mp.sqrt(d3 / (I2 * (I3 - I2))), mp.sqrt(d1 / (I3 * (I3 - I1)))
        lam = mp.sqrt((I3 - I2) * d1 / (I1 * I2 * I3))
        m = (I2 - I1) * d3 / ((I3 - I2) * d1)
        ntilde = I3 * (I2 - I1) / (I1 * (I3 - I2))
        s = mp.sign(w3)
        ac, wc, ad = A1, w1, A3
    else:
        A1, A2, A3 = mp.sqrt(d3 / (I1 * (I3 - I1))), mp.sqrt(d1 / (I2 * (I2 - I1))), mp.sqrt(d1 / (I3 * (I3 - I1)))
        lam = mp.sqrt((I2 - I1) * d3 / (I1 * I2 * I3))
        m = (I3 - I2) * d1 / ((I2 - I1) * d3)
        ntilde = I3 * d1 / (I1 * d3)
        s = mp.sign(w1)
        ac, wc, ad = A3, w3, A1
    if d2 == 0:
        sc, sd = mp.sign(w1), mp.sign(w3)
        u0 = mp.asinh(sc * sd * (w2 / A2) / (abs(w1) / A1))
        root = mp.sqrt(ntilde)

        def state(u):
            sech = 1 / mp.cosh(u)
            pi = (u + root * mp.atan(root * mp.tanh(u))) / (1 + ntilde)
            return [sc * A1 * sech, sc * sd * A2 * mp.tanh(u), sd * A3 * sech], pi
    else:
        K = mp.ellipk(m)
        pic = mp.ellippi(-ntilde, m)
        phi0 = mp.atan2(w2 / A2, s * wc / ac)
        j0 = mp.nint(phi0 / mp.pi)
        u0 = mp.ellipf(phi0 - j0 * mp.pi, m) + 2 * j0 * K

        def state(u):
            j = mp.nint(u / (2 * K))
            r = u - 2 * j * K
            sn, cn, dn = (mp.ellipfun(kind, r, m=m) for kind in ("sn", "cn", "dn"))
            parity = (-1) ** int(j)
            sn, cn = parity * sn, parity * cn
            amplitude = mp.atan2(mp.ellipfun("sn", r, m=m), mp.ellipfun("cn", r, m=m))
            pi = mp.ellippi(-ntilde, amplitude, m) + 2 * j * pic
            c, d = s * ac * cn, s * ad * dn
            return ([c, A2 * sn, d] if d2 > 0 else [d, A2 * sn, c]), pi

    _, pi0 = state(u0)

    def model(om, phi):
        half_theta = mp.atan2(mp.sqrt((I1 * om[0]) ** 2 + (I2 * om[1]) ** 2), I3 * om[2]) / 2
        psi = mp.atan2(I1 * om[0], I2 * om[1])
        ch, sh = mp.cos(half_theta), mp.sin(half_theta)
        return [ch * mp.cos((phi + psi) / 2), sh * mp.cos((phi - psi) / 2), sh * mp.sin((phi - psi) / 2),
                ch * mp.sin((phi + psi) / 2)]

    q0_sorted = _quat_mul([mp.mpf(x) for x in q0], qp)
    m0 = model(w, 0)
    C = _quat_mul(q0_sorted, [m0[0], -m0[1], -m0[2], -m0[3]])
    omega_out, q_out = [], []
    scale = J * (I3 - I1) / (I1 * I3 * lam)
    for t in times:
        t = mp.mpf(t)
        om, pi = state(lam * t + u0)
        phi = J * t / I3 + scale * (pi - pi0)
        q = _quat_mul(_quat_mul(C, model(om, phi)), [qp[0], -qp[1], -qp[2], -qp[3]])
        omega_out.append([float(sum(mp.mpf(P[i, k]) * om[k] for k in range(3))) for i in range(3)])
        q_out.append([float(x) for x in q])
    return np.array(omega_out), np.array(q_out)


def taylor(moments, omega0, q0, times, dps=30):
    """ω and q by mpmath.odefun (Taylor series) on Euler's equations, at ``dps`` digits."""
    mp.mp.dps = dps
    I = [mp.mpf(x) for x in moments]

    def rhs(_, y):
        w1, w2, w3, a, b, c, d = y
        return [(I[1] - I[2]) * w2 * w3 / I[0], (I[2] - I[0]) * w3 * w1 / I[1], (I[0] - I[1]) * w1 * w2 / I[2],
                (-b * w1 - c * w2 - d * w3) / 2, (a * w1 + c * w3 - d * w2) / 2, (a * w2 - b * w3 + d * w1) / 2,
                (a * w3 + b * w2 - c * w1) / 2]

    f = mp.odefun(rhs, 0, [mp.mpf(x) for x in omega0] + [mp.mpf(x) for x in q0])
    out = np.array([[float(x) for x in f(mp.mpf(t))] for t in times])
    return out[:, :3], out[:, 3:]


def cases():
    """(name, moments, ω0) of every reference case."""
    out = []
    for key, moments in BODIES.items():
        for distance in DISTANCES:
            for sign1 in (1.0, -1.0):
                out.append((f"{key}_{distance:g}_{sign1:+g}", moments, initial_state(moments, distance, sign1)))
    out.append(("346_exact_separatrix", (3.0, 4.0, 6.0), np.array([2.0, 0.3, -1.0])))
    return out


TAYLOR_CASES = ("123_1e-10_+1", "123_-1e-10_-1", "hlw_1e-12_-1", "346_exact_separatrix")


def main():
    arrays = {"times": TIMES, "taylor_times": TAYLOR_TIMES, "q0": np.array(Q0)}
    for name, moments, omega0 in cases():
        arrays[f"{name}/moments"] = np.array(moments)
        arrays[f"{name}/omega0"] = omega0
        arrays[f"{name}/omega"], arrays[f"{name}/q"] = closed_form(moments, omega0, Q0, TIMES)
        if name in TAYLOR_CASES:
            arrays[f"{name}/taylor_omega"], arrays[f"{name}/taylor_q"] = taylor(moments, omega0, Q0, TAYLOR_TIMES)
        print(name, flush=True)
    DATA.parent.mkdir(exist_ok=True)
    np.savez_compressed(DATA, **arrays)


if __name__ == "__main__":
    main()
