"""Run a validated :class:`~kreisel.io.scenario.Scenario`.

A rigid-body scenario gives a :class:`~kreisel.dynamics.trajectory.Trajectory`;
the Foucault and coning scenarios give an ``xarray.Dataset`` of their own
observables. :func:`summary` turns either into a few lines for the terminal.
"""

from __future__ import annotations

import numpy as np

from .. import earth, nav
from .._optional import require
from ..dynamics import Trajectory, simulate
from ..dynamics.torques import ConstantTorque, GravityTorque, LinearDamping
from ..inertia import RigidBody
from ..so3 import quat_apply, quat_conjugate, quat_multiply, quat_to_rotvec
from ..so3.rotation import Rotation

__all__ = [
    "build_body",
    "initial_attitude",
    "torque_model",
    "run_scenario",
    "trajectory_integrals",
    "summary",
]


def build_body(body, base=None):
    """A :class:`RigidBody` from a scenario's ``[body]`` table (``base``: directory of mesh paths)."""
    mass = body["mass"]
    if "moments" in body:
        return RigidBody(body["moments"], mass=mass)
    if "tensor" in body:
        return RigidBody(body["tensor"], mass=mass)
    if "mesh" in body:
        meshio = require("meshio", extra="io", feature="a mesh body")
        path = (base / body["mesh"]) if base is not None else body["mesh"]
        mesh = meshio.read(path)
        faces = mesh.cells_dict.get("triangle")
        if faces is None:
            raise ValueError(f"body.mesh: {path} has no triangle cells")
        return RigidBody.from_mesh(mesh.points, faces, density=body["density"])
    shape = body["shape"]
    args = {"box": ("size",), "solid_sphere": ("radius",), "solid_cylinder": ("radius", "height"),
            "solid_ellipsoid": ("semi_axes",)}[shape]
    return getattr(RigidBody, shape)(mass, *(body[a] for a in args))


def initial_attitude(attitude):
    """Quaternion from a scenario's ``[initial.attitude]`` table (identity when empty)."""
    if not attitude:
        return np.array([1.0, 0.0, 0.0, 0.0])
    if "quat" in attitude:
        return Rotation.from_quat(attitude["quat"]).as_quat()
    if "rotvec" in attitude:
        return Rotation.from_rotvec(attitude["rotvec"]).as_quat()
    if "matrix" in attitude:
        return Rotation.from_matrix(attitude["matrix"]).as_quat()
    return Rotation.from_euler(attitude["seq"], attitude["euler"], degrees=attitude["degrees"]).as_quat()


def torque_model(entries):
    """The sum of the compiled torque models listed in ``[[torque]]`` (None if empty)."""
    models = []
    for entry in entries:
        kind = entry["kind"]
        if kind == "gravity":
            models.append(GravityTorque(entry["weight"], entry["lever"]))
        elif kind == "constant_body":
            models.append(ConstantTorque(entry["torque"], frame="body"))
        elif kind == "constant_space":
            models.append(ConstantTorque(entry["torque"], frame="space"))
        else:
            models.append(LinearDamping(entry["coefficient"]))
    if not models:
        return None
    total = models[0]
    for model in models[1:]:
        total = total + model
    return total


def run_scenario(scenario, progress=None):
    """Run ``scenario``; a Trajectory (rigid body) or an ``xarray.Dataset`` (Foucault, coning).

    ``progress(fraction)``, if given, is told how far a long rigid-body run has got (0 … 1).

    Examples
    --------
    The bundled tennis racket: spun almost about its middle axis, the spin ω′₂
    flips sign again and again while the energy T = ½ ω′·I ω′ stays put:

    >>> import numpy as np
    >>> from kreisel.io import example_path, load_scenario
    >>> traj = run_scenario(load_scenario(example_path("tennis_racket")))
    >>> traj.t.shape, bool(traj.omega[:, 1].min() < -0.99 < 0.99 < traj.omega[:, 1].max())
    ((2001,), True)
    >>> bool(np.allclose(traj.energy, 0.5 * (1.0 * 0.01**2 + 2.0 * 1.0**2 + 3.0 * 0.01**2), rtol=1e-10))
    True
    """
    if scenario.kind == "rigid_body":
        return _rigid_body(scenario, progress)
    return _RUNNERS[scenario.kind](scenario)


def _rigid_body(scenario, progress=None):
    data = scenario.data
    base = scenario.path.parent if scenario.path is not None else None
    body = build_body(data["body"], base)
    q0 = initial_attitude(data["initial"].get("attitude"))
    omega0 = data["initial"]["omega"]
    if data["initial"]["frame"] == "space":
        omega0 = quat_apply(q0, omega0, inverse=True)
    grid = data["integration"]
    t = np.linspace(grid["t_start"], grid["t_start"] + grid["t_end"], grid["n_samples"])
    tell = None if progress is None else (lambda t_now: progress((t_now - t[0]) / (t[-1] - t[0])))
    traj = simulate(body, t, omega0, q0=q0, torque=torque_model(data.get("torque", [])),
                    method=grid.get("method"), dt=grid.get("dt"), progress=tell)
    traj.meta["scenario"] = scenario.title
    # the torque as data, so that a saved run still knows its first integrals (trajectory_integrals)
    traj.meta["torques"] = [{k: np.asarray(v).tolist() if k != "kind" else v for k, v in entry.items()}
                            for entry in data.get("torque", [])]
    return traj


def trajectory_integrals(traj):
    """First integrals (:func:`kreisel.tops.first_integrals`) of a run of :func:`run_scenario`, saved or not.

    The torque comes from the trajectory's ``meta["torques"]``; a trajectory
    simulated under some other torque (``meta["torque"]`` names one) is
    reported as a driven body without integrals.

    Examples
    --------
    >>> from kreisel.io import example_path, load_scenario
    >>> found = trajectory_integrals(run_scenario(load_scenario(example_path("kovalevskaya"))))
    >>> found.model, [f.symbol for f in found]
    ('Kovalevskaya top', ['E', 'J_z', 'K'])
    """
    from ..tops import first_integrals

    entries = traj.meta.get("torques")
    if entries is None:
        driven = traj.meta.get("torque", "none") != "none"
        return first_integrals(traj, torque=_UNKNOWN_TORQUE if driven else None)
    return first_integrals(traj, torque=torque_model(entries))


_UNKNOWN_TORQUE = object()


def _foucault(scenario):
    xr = require("xarray", extra="io", feature="the Foucault scenario")
    spec = scenario.data["foucault"]
    extra = {"omega": spec["omega"]} if "omega" in spec else {}
    swing = earth.foucault_pendulum(spec["length"], spec["latitude_deg"], spec["duration"], spec["amplitude"],
                                    **extra)
    rate = earth.foucault_precession_rate(spec["latitude_deg"], **extra)
    return xr.Dataset(
        {"swing_azimuth": ("time", swing.swing_azimuth), "tilt": ("time", swing.tilt)},
        coords={"time": swing.t},
        attrs={"kreisel": "Foucault pendulum", "scenario": scenario.title,
               "jacobi_relative_drift": float(abs(swing.jacobi[1] / swing.jacobi[0] - 1)),
               "precession_rate_measured": swing.precession_rate, "precession_rate_theory": float(rate)},
    )


def _coning(scenario):
    xr = require("xarray", extra="io", feature="the coning scenario")
    spec = scenario.data["coning"]
    n_update = spec["samples_per_update"]
    n = spec["n_samples"] - spec["n_samples"] % n_update
    alpha, rate = np.deg2rad(spec["half_angle_deg"]), 2 * np.pi * spec["rate_hz"]
    motion = nav.coning_motion(alpha, rate, spec["sample_time"], n)
    estimate = nav.attitude_from_increments(motion.q[0], motion.dtheta, samples_per_update=n_update)
    truth = motion.q[::n_update]
    error = quat_to_rotvec(quat_multiply(quat_conjugate(truth), estimate))
    return xr.Dataset(
        {"q_true": (("time", "quaternion"), truth), "q_estimate": (("time", "quaternion"), estimate),
         "attitude_error": (("time", "axis"), error)},
        coords={"time": motion.t[::n_update], "quaternion": ["q0", "q1", "q2", "q3"], "axis": ["x", "y", "z"]},
        attrs={"kreisel": "coning", "scenario": scenario.title,
               "drift_theory": float(nav.coning_drift(alpha, rate, spec["sample_time"], n_update))},
    )


_RUNNERS = {"rigid_body": _rigid_body, "foucault": _foucault, "coning": _coning}


def summary(result):
    """Lines describing a run: its first integrals and how much the run changed them, or measured rates.

    Examples
    --------
    A heavy top keeps E = T + V, J_z and J_3 (not T or |J|):

    >>> from kreisel.io import example_path, load_scenario
    >>> lines = summary(run_scenario(load_scenario(example_path("fast_top"))))
    >>> print("\\n".join(lines[:2]))
    4001 samples, t = 0 … 40 s, method dop853
    first integrals of the heavy symmetric (Lagrange) top, and their largest relative change:
    >>> [line.split()[0] for line in lines[2:]]
    ['E', 'J_z', 'J_3']
    """
    if isinstance(result, Trajectory):
        lines = [f"{len(result)} samples, t = {result.t[0]:g} … {result.t[-1]:g} s, "
                 f"method {result.meta.get('method', '?')}"]
        found = trajectory_integrals(result)
        if not len(found):
            T, J = result.energy, np.linalg.norm(result.angular_momentum_body, axis=-1)
            return lines + [f"no first integrals: the torque ({result.meta.get('torque', '?')}) does work",
                            f"T = {float(T[..., 0]):.6g} … {float(T[..., -1]):.6g} J, "
                            f"|J| = {float(J[..., 0]):.6g} … {float(J[..., -1]):.6g} kg m²/s"]
        lines.append(f"first integrals of the {found.model}, and their largest relative change:")
        for integral in found:
            value = np.round(integral.initial, 12) + 0.0
            shown = f"[{', '.join(f'{v:.6g}' for v in value)}]" if integral.is_vector else f"{float(value):.10g}"
            lines.append(f"{integral.symbol:<4} {integral.name:<42} {shown} {integral.unit}, "
                         f"change {float(integral.relative_change()):.2e}")
        return lines
    kind = result.attrs.get("kreisel")
    if kind == "Foucault pendulum":
        measured, theory = result.attrs["precession_rate_measured"], result.attrs["precession_rate_theory"]
        return [f"swing plane turns at {measured:.6e} rad/s (theory −Ω sin λ = {theory:.6e} rad/s)",
                f"Jacobi integral relative drift {result.attrs['jacobi_relative_drift']:.3e}"]
    final = np.linalg.norm(result["attitude_error"].values[-1])
    duration = float(result["time"].values[-1] - result["time"].values[0])
    return [f"attitude error after {duration:g} s: {final:.3e} rad "
            f"(drift {final / duration:.3e} rad/s; classical coefficient {result.attrs['drift_theory']:.3e} rad/s)"]
