"""What the viewer runs: scenario TOML from the form, limits on the work, and the JSON of a run.

Every run goes through TOML and :func:`kreisel.io.parse_scenario`, so the form, a loaded file and
the exported scenario obey one schema and one set of error messages.
"""

from __future__ import annotations

import numpy as np

from ..io import ScenarioError, parse_scenario, run_scenario
from ..kinematics import euler_rates
from ..so3 import quat_apply, quat_to_euler
from ..tops import EulerTop, LagrangeTop

METHODS = ("dop853", "splitting", "dmv", "rkmk4", "midpoint", "rk4")
MAX_SAMPLES = 20_000
MAX_STEPS = 2_000_000
MAX_TURNS = 100_000


class RunRefused(ValueError):
    """A request the viewer will not run (too much work, or reads files); the message says why."""


def _vector(values):
    return "[" + ", ".join(repr(float(v)) for v in values) + "]"


def scenario_toml(params):
    """Scenario TOML of the form fields ``params`` (moments, omega, euler_deg, mgl, lever_axis, method, ...).

    Examples
    --------
    >>> text = scenario_toml({"moments": [1, 2, 3], "omega": [0.01, 1, 0.01], "t_end": 10})
    >>> parse_scenario(text).data["body"]["moments"].tolist()
    [1.0, 2.0, 3.0]
    """
    lines = [f'title = {params.get("title") or "Custom rigid body"!r}'.replace("'", '"'), "",
             "[body]", f"moments = {_vector(params['moments'])}", "",
             "[initial]", f"omega = {_vector(params['omega'])}", 'frame = "body"', ""]
    euler = params.get("euler_deg") or [0.0, 0.0, 0.0]
    lines += ["[initial.attitude]", f"euler = {_vector(euler)}", 'seq = "ZXZ"', "degrees = true", ""]
    mgl = float(params.get("mgl") or 0.0)
    if mgl > 0.0:
        lever = [0.0, 0.0, 0.0]
        lever[int(params.get("lever_axis", 2))] = 1.0
        lines += ["[[torque]]", 'kind = "gravity"', f"weight = {mgl!r}", f"lever = {_vector(lever)}", ""]
    lines += ["[integration]", f"t_end = {float(params.get('t_end', 30.0))!r}",
              f"n_samples = {int(params.get('n_samples', 1501))}"]
    if params.get("method"):
        lines.append(f'method = "{params["method"]}"')
    if params.get("dt"):
        lines.append(f"dt = {float(params['dt'])!r}")
    return "\n".join(lines) + "\n"


def form_fields(scenario):
    """The form fields of a rigid-body ``scenario``, or None when the form cannot express it."""
    data = scenario.data
    body = data["body"]
    torques = data.get("torque", [])
    if "moments" not in body or data["initial"]["frame"] != "body" or len(torques) > 1:
        return None
    mgl, lever_axis = 0.0, 2
    if torques:
        entry = torques[0]
        if entry["kind"] != "gravity" or np.count_nonzero(entry["lever"]) != 1:
            return None
        lever_axis = int(np.flatnonzero(entry["lever"])[0])
        mgl = entry["weight"] * abs(float(entry["lever"][lever_axis]))
        if entry["lever"][lever_axis] < 0:
            return None
    from ..io.run import initial_attitude

    euler = np.rad2deg(quat_to_euler("ZXZ", initial_attitude(data["initial"].get("attitude"))))
    grid = data["integration"]
    return {"title": scenario.title, "moments": body["moments"].tolist(), "omega": data["initial"]["omega"].tolist(),
            "euler_deg": [round(float(a), 12) for a in euler], "mgl": mgl, "lever_axis": lever_axis,
            "method": grid.get("method"), "t_end": grid["t_end"], "n_samples": grid["n_samples"],
            "dt": grid.get("dt")}


def check_workload(scenario):
    """Refuse scenarios that read files or would take more than a few seconds; RunRefused says why."""
    data = scenario.data
    if scenario.kind == "coning":
        raise RunRefused("coning scenarios have no body to show; run them with `kreisel simulate`")
    if scenario.kind == "foucault":
        spec = data["foucault"]
        swings = spec["duration"] / (2 * np.pi * np.sqrt(spec["length"] / 9.80665))
        if swings > 5_000:
            raise RunRefused(f"foucault.duration: {swings:.0f} swings requested, the viewer allows at most 5000")
        return
    if "mesh" in data["body"]:
        raise RunRefused("body.mesh: the viewer does not read mesh files; use moments, tensor or shape")
    grid = data["integration"]
    if grid["n_samples"] > MAX_SAMPLES:
        raise RunRefused(f"integration.n_samples = {grid['n_samples']} is too many: the viewer allows at most "
                         f"{MAX_SAMPLES}")
    if grid.get("dt") is not None and grid["t_end"] / grid["dt"] > MAX_STEPS:
        raise RunRefused(f"integration: t_end / dt = {grid['t_end'] / grid['dt']:.3g} steps is too many: "
                         f"the viewer allows at most {MAX_STEPS}")
    turns = grid["t_end"] * float(np.linalg.norm(data["initial"]["omega"])) / (2 * np.pi)
    if turns > MAX_TURNS:
        raise RunRefused(f"integration.t_end: {turns:.3g} turns of the body requested, the viewer allows at most "
                         f"{MAX_TURNS}")


def load(text):
    """Validate scenario TOML ``text`` and check its workload; ScenarioError or RunRefused."""
    scenario = parse_scenario(text)
    check_workload(scenario)
    return scenario


def _gravity(scenario):
    """(weight, lever) of the scenario's single gravity torque, or None."""
    gravity = [e for e in scenario.data.get("torque", []) if e["kind"] == "gravity"]
    return (gravity[0]["weight"], gravity[0]["lever"]) if gravity else None


def rigid_body_result(scenario, traj):
    """JSON-ready arrays and seed quantities of a rigid-body run."""
    gravity = _gravity(scenario)
    kinetic = traj.energy
    potential = np.zeros_like(kinetic)
    if gravity is not None:
        weight, lever = gravity
        # gravity along space -z: V = m g (R l)_z about the pivot (seed 六.1)
        potential = weight * quat_apply(traj.q, lever)[:, 2]
    energy = kinetic + potential
    J = traj.angular_momentum_space
    J_norm = np.linalg.norm(J, axis=-1)
    scale_e = abs(energy[0]) if energy[0] != 0 else 1.0
    return {
        "kind": "rigid_body", "title": scenario.title, "method": traj.meta.get("method"),
        "t": traj.t.tolist(), "q": traj.q.tolist(), "omega": traj.omega.tolist(),
        "omega_space": traj.omega_space.tolist(), "J": J.tolist(), "J_norm": J_norm.tolist(),
        "energy": energy.tolist(), "kinetic": kinetic.tolist(),
        "inertia": traj.inertia.tolist(),
        "gravity": None if gravity is None else {"weight": gravity[0], "lever": gravity[1].tolist()},
        "drift": {"energy": float(np.max(np.abs(energy - energy[0])) / scale_e),
                  "J_norm": float(np.max(np.abs(J_norm - J_norm[0])) / (J_norm[0] or 1.0)),
                  "direction": float(traj.drift()["direction"]) if gravity is None else None},
        "seed": seed_quantities(traj, gravity),
    }


def seed_quantities(traj, gravity):
    """T, J, stability of the principal axes and, for a Lagrange top, the nutation range (seed 五, 六)."""
    from ..inertia import principal_axes

    moments, axes = principal_axes(traj.inertia)
    omega0 = traj.omega[0]
    out = {"T": float(traj.energy[0]), "J": traj.angular_momentum_space[0].tolist(),
           "J_norm": float(np.linalg.norm(traj.angular_momentum_space[0])),
           "principal_moments": moments.tolist(), "principal_axes": axes.tolist()}
    # the steady-rotation analysis refers to principal axes, so omega is expressed in them
    top = EulerTop(*moments)
    spin = float(np.linalg.norm(omega0))
    out["stability"] = [{"axis": s.axis + 1, "moment": s.moment, "kind": s.kind, "growth_rate": s.growth_rate,
                         "wobble_frequency": s.wobble_frequency} for s in top.steady_rotations(spin or 1.0)]
    if gravity is None:
        try:
            out["regime"] = top.regime(axes.T @ omega0)
        except ValueError:
            out["regime"] = None
    out["lagrange"] = _lagrange(traj, gravity) if gravity is not None else None
    return out


def _lagrange(traj, gravity):
    """Turning points, apex locus and sleeping-top test when the body is a Lagrange top, else None."""
    weight, lever = gravity
    I = np.diag(traj.inertia)
    symmetric = np.allclose(traj.inertia, np.diag(I)) and lever[0] == lever[1] == 0.0 and lever[2] > 0.0
    if not symmetric or not np.isclose(I[0], I[1], rtol=1e-12):
        return None
    top = LagrangeTop(I[0], I[2], weight * lever[2])
    out = {"sleeping_threshold_omega3": float(top.sleeping_top_threshold()),
           "sleeping_stable": bool(top.sleeping_top_stable(traj.omega[0, 2]))}
    euler0 = quat_to_euler("ZXZ", traj.q[0])
    try:
        rates0 = euler_rates("ZXZ", euler0, traj.omega[0], frame="body")
        theta_min, theta_max = top.turning_points(euler0, rates0)
        out.update(theta_min_deg=float(np.rad2deg(theta_min)), theta_max_deg=float(np.rad2deg(theta_max)),
                   apex_locus=top.apex_locus_kind(euler0, rates0))
    except ValueError as exc:  # upright start: ZXZ angles are singular on the vertical
        out["note"] = str(exc)
    return out


def foucault_result(scenario):
    """JSON-ready samples of a Foucault run: swing-plane azimuth and tilt at each turning point (seed 八.3).

    Calls :func:`kreisel.earth.foucault_pendulum` directly: the viewer wants the Jacobi integral at start
    and end only, which the io layer's dataset does not carry.
    """
    from ..earth import foucault_pendulum, foucault_precession_rate

    spec = scenario.data["foucault"]
    extra = {"omega": spec["omega"]} if "omega" in spec else {}
    swing = foucault_pendulum(spec["length"], spec["latitude_deg"], spec["duration"], spec["amplitude"], **extra)
    rate = float(foucault_precession_rate(spec["latitude_deg"], **extra))
    jacobi = np.asarray(swing.jacobi, dtype=float)
    return {"kind": "foucault", "title": scenario.title, "t": swing.t.tolist(),
            "swing_azimuth": swing.swing_azimuth.tolist(), "tilt": swing.tilt.tolist(), "length": spec["length"],
            "drift": {"jacobi": float(abs(jacobi[-1] - jacobi[0]) / abs(jacobi[0]))},
            "seed": {"precession_rate_measured": float(swing.precession_rate), "precession_rate_theory": rate,
                     "period_hours": float(2 * np.pi / abs(rate) / 3600.0) if rate else None}}


def run(text):
    """Run scenario TOML ``text``: the JSON answer of ``/api/run`` (raises ScenarioError, RunRefused)."""
    scenario = load(text)
    if scenario.kind == "foucault":
        answer = foucault_result(scenario)
        answer["form"] = None
    else:
        answer = rigid_body_result(scenario, run_scenario(scenario))
        answer["form"] = form_fields(scenario)
    answer["toml"] = text
    return answer


__all__ = ["METHODS", "MAX_SAMPLES", "RunRefused", "ScenarioError", "scenario_toml", "form_fields", "load", "run"]
