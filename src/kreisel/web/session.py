"""What the viewer runs: scenario TOML from the form, limits on the work, and the JSON of a run.

Every run goes through TOML and :func:`kreisel.io.parse_scenario`, so the form, a loaded file and
the exported scenario obey one schema and one set of error messages.
"""

from __future__ import annotations

import numpy as np

from ..dynamics import simulate
from ..io import ScenarioError, parse_scenario
from ..io.run import build_body, initial_attitude, torque_model
from ..kinematics import euler_rates
from ..so3 import quat_apply, quat_to_euler
from ..tops import EulerTop, LagrangeTop

METHODS = ("dop853", "splitting", "dmv", "rkmk4", "midpoint", "rk4")
# One JSON reply holds the whole run; a stream holds one chunk at a time on the server, so its limit is
# set by what the browser keeps (about 0.5 kB of JavaScript arrays per sample: 100 MB at the limit).
MAX_SAMPLES = 20_000
MAX_STREAM_SAMPLES = 200_000
CHUNK_SAMPLES = 2_000
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
    euler = np.rad2deg(quat_to_euler("ZXZ", initial_attitude(data["initial"].get("attitude"))))
    grid = data["integration"]
    return {"title": scenario.title, "moments": body["moments"].tolist(), "omega": data["initial"]["omega"].tolist(),
            "euler_deg": [round(float(a), 12) for a in euler], "mgl": mgl, "lever_axis": lever_axis,
            "method": grid.get("method"), "t_end": grid["t_end"], "n_samples": grid["n_samples"],
            "dt": grid.get("dt")}


def check_workload(scenario, max_samples=MAX_SAMPLES):
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
    if grid["n_samples"] > max_samples:
        raise RunRefused(f"integration.n_samples = {grid['n_samples']} is too many: the viewer allows at most "
                         f"{max_samples}" + (" (stream the run to get more)" if max_samples < MAX_STREAM_SAMPLES else ""))
    if grid.get("dt") is not None and grid["t_end"] / grid["dt"] > MAX_STEPS:
        raise RunRefused(f"integration: t_end / dt = {grid['t_end'] / grid['dt']:.3g} steps is too many: "
                         f"the viewer allows at most {MAX_STEPS}")
    turns = grid["t_end"] * float(np.linalg.norm(data["initial"]["omega"])) / (2 * np.pi)
    if turns > MAX_TURNS:
        raise RunRefused(f"integration.t_end: {turns:.3g} turns of the body requested, the viewer allows at most "
                         f"{MAX_TURNS}")


def load(text, max_samples=MAX_SAMPLES):
    """Validate scenario TOML ``text`` and check its workload; ScenarioError or RunRefused."""
    scenario = parse_scenario(text)
    check_workload(scenario, max_samples)
    return scenario


def _gravity(scenario):
    """(weight, lever) of the scenario's single gravity torque, or None."""
    gravity = [e for e in scenario.data.get("torque", []) if e["kind"] == "gravity"]
    return (gravity[0]["weight"], gravity[0]["lever"]) if gravity else None


class Solver:
    """The motion of a rigid-body scenario on any stretch of its time grid.

    ``exact=False`` integrates with :func:`kreisel.simulate` from the state given at the stretch's first
    time; ``exact=True`` evaluates the closed form of the free top (:meth:`kreisel.tops.EulerTop.solve`,
    Theory §5.3), which needs no state: every sample depends on its time only.
    """

    def __init__(self, scenario, exact=False):
        data = scenario.data
        self.title = scenario.title
        self.q0 = initial_attitude(data["initial"].get("attitude"))
        self.omega0 = data["initial"]["omega"]
        if data["initial"]["frame"] == "space":
            self.omega0 = quat_apply(self.q0, self.omega0, inverse=True)
        grid = data["integration"]
        self.t = np.linspace(grid["t_start"], grid["t_start"] + grid["t_end"], grid["n_samples"])
        self.body = build_body(data["body"])
        self.torque = torque_model(data.get("torque", []))
        self.method, self.dt = grid.get("method"), grid.get("dt")
        self.top = None
        if exact:
            tensor = self.body.inertia
            if self.torque is not None or np.count_nonzero(tensor - np.diag(np.diag(tensor))):
                raise RunRefused("exact: the closed-form solution is for a torque-free body whose body axes are "
                                 "principal (give body.moments and no [[torque]])")
            self.top = EulerTop(*np.diag(tensor))

    def run(self):
        """The whole run: the trajectory on the scenario's time grid."""
        traj = self(self.t, self.omega0, self.q0)
        traj.meta["scenario"] = self.title
        return traj

    def __call__(self, t, omega_start, q_start):
        """Trajectory at times ``t`` starting from (ω′, q) at ``t[0]`` (ignored by the exact solution)."""
        if self.top is not None:
            traj = self.top.solve(t - self.t[0], self.omega0, self.q0)
            traj.meta["method"] = "exact"
            return traj
        return simulate(self.body, t, omega_start, q0=q_start, torque=self.torque, method=self.method, dt=self.dt)


class Drift:
    """Largest change of energy, |J| and the direction of the space J since the first sample, gathered chunk
    by chunk; the relative figures of :meth:`kreisel.dynamics.Trajectory.drift` plus the potential energy."""

    def __init__(self):
        self.energy0 = self.J0 = None
        self.energy = self.J_norm = self.direction = 0.0

    def add(self, energy, J):
        if self.energy0 is None:
            self.energy0, self.J0 = energy[0], J[0]
        norms = np.linalg.norm(J, axis=-1)
        angle = np.arctan2(np.linalg.norm(np.cross(J, self.J0), axis=-1), J @ self.J0)
        self.energy = max(self.energy, float(np.max(np.abs(energy - self.energy0))))
        self.J_norm = max(self.J_norm, float(np.max(np.abs(norms - np.linalg.norm(self.J0)))))
        self.direction = max(self.direction, float(np.max(angle)))

    def summary(self, free):
        J0 = float(np.linalg.norm(self.J0))
        return {"energy": self.energy / float(abs(self.energy0) or 1.0), "J_norm": self.J_norm / (J0 or 1.0),
                "direction": self.direction if free else None}


def samples(traj, gravity):
    """The arrays the viewer shows at each sample: t, q, ω′, ω space, J space, |J|, energy and kinetic energy."""
    kinetic = traj.energy
    potential = np.zeros_like(kinetic)
    if gravity is not None:
        weight, lever = gravity
        # gravity along space -z: V = m g (R l)_z about the pivot (Theory §6.1)
        potential = weight * quat_apply(traj.q, lever)[:, 2]
    J = traj.angular_momentum_space
    return {"t": traj.t, "q": traj.q, "omega": traj.omega, "omega_space": traj.omega_space, "J": J,
            "J_norm": np.linalg.norm(J, axis=-1), "energy": kinetic + potential, "kinetic": kinetic}


def _lists(arrays):
    return {key: value.tolist() for key, value in arrays.items()}


def rigid_body_header(scenario, traj):
    """Everything of a rigid-body run's JSON but the samples and the drift (theory quantities from ``traj[0]``)."""
    gravity = _gravity(scenario)
    return {"kind": "rigid_body", "title": scenario.title, "method": traj.meta.get("method"),
            "inertia": traj.inertia.tolist(),
            "gravity": None if gravity is None else {"weight": gravity[0], "lever": gravity[1].tolist()},
            "seed": theory_quantities(traj, gravity)}


def rigid_body_result(scenario, traj):
    """JSON-ready arrays and theory quantities of a rigid-body run."""
    gravity = _gravity(scenario)
    arrays = samples(traj, gravity)
    drift = Drift()
    drift.add(arrays["energy"], arrays["J"])
    return {**rigid_body_header(scenario, traj), **_lists(arrays), "drift": drift.summary(gravity is None)}


def theory_quantities(traj, gravity):
    """T, J, stability of the principal axes and, for a Lagrange top, the nutation range (Theory §5, §6)."""
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
    """JSON-ready samples of a Foucault run: swing-plane azimuth and tilt at each turning point (Theory §8.3).

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


def run(text, exact=False):
    """Run scenario TOML ``text``: the JSON answer of ``/api/run`` (raises ScenarioError, RunRefused).

    ``exact=True`` uses the closed form of the free top instead of an integrator.
    """
    scenario = load(text)
    if scenario.kind == "foucault":
        answer = foucault_result(scenario)
        answer["form"] = None
    else:
        answer = rigid_body_result(scenario, Solver(scenario, exact).run())
        answer["form"] = form_fields(scenario)
    answer["toml"] = text
    return answer


def stream(text, exact=False, chunk_samples=CHUNK_SAMPLES):
    """Validate ``text`` now, then return a generator of the run's messages, one chunk of work per message.

    Messages: ``{"type": "start", ...}`` (what :func:`run` answers but the samples and the drift, plus
    ``n_samples``, ``n_chunks`` and ``t_range``, the first and last time), then
    ``{"type": "chunk", "index", "offset", t, q, omega, ...}`` with consecutive samples, then
    ``{"type": "done", "drift": ...}``. The integrators restart each chunk from the last state of the
    previous one: dop853's error control then restarts too, so a streamed run agrees with :func:`run` to
    the integrator's tolerance (not bit for bit; ~3e-11 on the tennis racket at rtol 1e-12); fixed-step
    methods take the same steps either way (each interval between samples is stepped alone), and the
    exact solution is evaluated per sample, so those agree to round-off.

    Examples
    --------
    >>> from kreisel.web.presets import preset_text
    >>> messages = list(stream(preset_text("tennis_racket"), exact=True, chunk_samples=500))
    >>> [m["type"] for m in messages]
    ['start', 'chunk', 'chunk', 'chunk', 'chunk', 'chunk', 'done']
    >>> sum(len(m["t"]) for m in messages if m["type"] == "chunk") == messages[0]["n_samples"]
    True
    """
    if not isinstance(chunk_samples, int) or chunk_samples < 2:
        raise ValueError(f"chunk_samples must be an integer >= 2, got {chunk_samples!r}")
    scenario = load(text, MAX_STREAM_SAMPLES)
    solver = None if scenario.kind == "foucault" else Solver(scenario, exact)
    return _messages(scenario, solver, text, chunk_samples)


def _messages(scenario, solver, text, chunk_samples):
    if solver is None:
        # the pendulum's turning points come from one event-located integration: a single chunk
        result = foucault_result(scenario)
        arrays = {key: result.pop(key) for key in ("t", "swing_azimuth", "tilt")}
        drift = result.pop("drift")
        yield {"type": "start", **result, "form": None, "toml": text, "n_samples": len(arrays["t"]), "n_chunks": 1,
               "t_range": [arrays["t"][0], arrays["t"][-1]]}
        yield {"type": "chunk", "index": 0, "offset": 0, **arrays}
        yield {"type": "done", "drift": drift}
        return
    t = solver.t
    # chunk k holds samples [bounds[k], bounds[k + 1]); its integration starts at the sample before
    bounds = list(range(0, t.size, chunk_samples)) + [t.size]
    gravity = _gravity(scenario)
    drift = Drift()
    omega, q = solver.omega0, solver.q0
    for index, (first, stop) in enumerate(zip(bounds[:-1], bounds[1:])):
        start = max(first - 1, 0)
        traj = solver(t[start:stop], omega, q)
        omega, q = traj.omega[-1], traj.q[-1]
        if index == 0:
            yield {"type": "start", **rigid_body_header(scenario, traj), "form": form_fields(scenario),
                   "toml": text, "n_samples": int(t.size), "n_chunks": len(bounds) - 1,
                   "t_range": [float(t[0]), float(t[-1])]}
        arrays = {key: value[first - start:] for key, value in samples(traj, gravity).items()}
        drift.add(arrays["energy"], arrays["J"])
        yield {"type": "chunk", "index": index, "offset": first, **_lists(arrays)}
    yield {"type": "done", "drift": drift.summary(gravity is None)}


__all__ = ["METHODS", "MAX_SAMPLES", "MAX_STREAM_SAMPLES", "CHUNK_SAMPLES", "RunRefused", "ScenarioError",
           "Solver", "Drift", "samples", "scenario_toml", "form_fields", "load", "run", "stream"]
