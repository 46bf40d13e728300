"""What the viewer runs: scenario TOML from the form, limits on the work, and the JSON of a run.

Every run goes through TOML and :func:`kreisel.io.parse_scenario`, so the form, a loaded file and
the exported scenario obey one schema and one set of error messages.
"""

from __future__ import annotations

import json
import math
import pathlib
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .._compiled.chunks import StepBudgetExceeded
from ..dynamics.engine import METHODS as DYNAMICS_METHODS
from ..dynamics.engine import ADAPTIVE
from ..dynamics import Trajectory, simulate
from ..io import ScenarioError, parse_scenario
from ..io.run import build_body, initial_attitude, torque_model
from ..kinematics import euler_rates
from ..so3 import quat_apply, quat_to_euler
from ..tops import EulerTop, LagrangeTop, first_integrals
from .limits import Limits

METHODS = tuple(DYNAMICS_METHODS)
# One JSON reply holds the whole run; a stream holds one chunk at a time on the server, so its limit is
# set by what the browser keeps (about 0.5 kB of JavaScript arrays per sample: 100 MB at the limit).
MAX_SAMPLES = 20_000
MAX_STREAM_SAMPLES = 200_000
CHUNK_SAMPLES = 2_000
MAX_STEPS = 2_000_000
#: Integration steps one run may take by default (all its chunks together): the viewer's limit.
RUN_STEPS = Limits().max_steps
MAX_TURNS = 100_000


class RunRefused(ValueError):
    """A request the viewer will not run (too much work, or reads files); the message says why."""


def scenario_data(form):
    """The scenario (as TOML data) of the form fields ``form`` (moments, omega, euler_deg, mgl, ...).

    Missing optional fields take the form's defaults; a gravity torque is added when ``mgl > 0``.

    Examples
    --------
    >>> data = scenario_data({"moments": [1, 2, 3], "omega": [0.01, 1, 0.01], "t_end": 10})
    >>> data["integration"], "torque" in data
    ({'t_end': 10.0, 'n_samples': 1501}, False)
    """
    lever = [0.0, 0.0, 0.0]
    lever[int(form.get("lever_axis", 2))] = 1.0
    mgl = float(form.get("mgl") or 0.0)
    if not 0.0 <= mgl < np.inf:
        raise ValueError(f"form.mgl must be a finite number >= 0 (0: no gravity), got {mgl!r}")
    grid = {"t_end": float(form.get("t_end", 30.0)), "n_samples": int(form.get("n_samples", 1501))}
    grid.update({key: form[key] for key in ("method", "dt") if form.get(key) is not None})
    data = {"title": form.get("title") or "Custom rigid body",
            "body": {"moments": [float(v) for v in form["moments"]]},
            "initial": {"omega": [float(v) for v in form["omega"]], "frame": "body",
                        "attitude": {"euler": [float(v) for v in form.get("euler_deg") or (0.0, 0.0, 0.0)],
                                     "seq": "ZXZ", "degrees": True}},
            "integration": grid}
    if mgl > 0.0:
        data["torque"] = [{"kind": "gravity", "weight": mgl, "lever": lever}]
    return data


def toml_text(data):
    """TOML text of ``data`` (tables of str, bool, int, finite float, lists of them, and lists of tables).

    Strings are written as JSON strings, which TOML reads as basic strings with the same escapes.

    Examples
    --------
    >>> print(toml_text({"title": 'a "quoted" title', "body": {"moments": [1.0, 2.0, 3.0]}}), end="")
    title = "a \\"quoted\\" title"
    <BLANKLINE>
    [body]
    moments = [1.0, 2.0, 3.0]
    """
    def value(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, (int, float)) and not isinstance(v, bool):
            if isinstance(v, float) and not math.isfinite(v):
                raise ValueError(f"TOML numbers must be finite, got {v!r}")
            return repr(v)
        if isinstance(v, str):
            return json.dumps(v, ensure_ascii=False)
        return "[" + ", ".join(value(x) for x in v) + "]"

    def table(prefix, entries, header):
        plain = [f"{k} = {value(v)}" for k, v in entries.items() if not isinstance(v, dict) and not _tables(v)]
        lines = ([header] if header and (plain or not entries) else []) + plain
        for k, v in entries.items():
            name = f"{prefix}{k}"
            if isinstance(v, dict):
                lines += ["", *table(name + ".", v, f"[{name}]")]
            elif _tables(v):
                for entry in v:
                    lines += ["", *table(name + ".", entry, f"[[{name}]]")]
        return lines

    return "\n".join(table("", data, None)).lstrip("\n") + "\n"


def _tables(v):
    return isinstance(v, list) and bool(v) and all(isinstance(x, dict) for x in v)


def scenario_toml(form):
    """Scenario TOML of the form fields ``form``: :func:`toml_text` of :func:`scenario_data`.

    Examples
    --------
    >>> text = scenario_toml({"moments": [1, 2, 3], "omega": [0.01, 1, 0.01], "t_end": 10, "title": 'my "top"'})
    >>> scenario = parse_scenario(text)
    >>> scenario.title, scenario.data["body"]["moments"].tolist()
    ('my "top"', [1.0, 2.0, 3.0])
    """
    return toml_text(scenario_data(form))


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


def _check_turns(data, body):
    """Refuse a run in which the body would turn more than MAX_TURNS times; RunRefused says why.

    Its angular speed is of order |ω0|, plus what the torques give it: the rate 2 √(mgl/I_min) that
    gravity reaches at most (it converts at most 2 mgl of potential energy), and the |τ| t_end / I_min
    a constant torque adds.
    """
    grid = data["integration"]
    smallest = float(np.min(body.principal_moments))
    rate, why = float(np.linalg.norm(data["initial"]["omega"])), ""
    with np.errstate(over="ignore"):
        for entry in data.get("torque", []):
            if entry["kind"] == "gravity":
                rate += 2.0 * math.sqrt(entry["weight"] * float(np.linalg.norm(entry["lever"])) / smallest)
                why = " (with gravity's rate)"
            elif entry["kind"] != "damping":
                rate += float(np.linalg.norm(entry["torque"])) * grid["t_end"] / smallest
                why = " (with the torque's spin-up)"
        turns = grid["t_end"] * rate / (2 * np.pi)
    if not turns <= MAX_TURNS:
        raise RunRefused(f"integration.t_end: {turns:.3g} turns of the body requested{why}, the viewer allows at "
                         f"most {MAX_TURNS}")


def load(text, max_samples=MAX_SAMPLES, exact=False, path=None):
    """Validate scenario TOML ``text`` and check its workload; ScenarioError or RunRefused.

    This is the one check every endpoint makes before it accepts a scenario: besides the schema of
    :func:`kreisel.io.parse_scenario` it builds what a run builds (body, initial attitude, torques, the
    exact solution when ``exact``), so a scenario accepted here does not fail when it starts. ``path``
    names the file in the messages (default ``<scenario>``).
    """
    scenario = parse_scenario(text, path)
    check_workload(scenario, max_samples)
    if scenario.kind == "rigid_body":
        data = scenario.data
        grid = data["integration"]
        if not exact and grid.get("method") not in (None, *ADAPTIVE) and grid.get("dt") is None:
            raise ScenarioError(f"{path or '<scenario>'}: integration.dt: method {grid['method']!r} takes fixed steps and "
                                "needs dt (s)")
        built = {}
        for key, build in (("body", lambda: build_body(data["body"])),
                           ("initial.attitude", lambda: initial_attitude(data["initial"].get("attitude"))),
                           ("torque", lambda: torque_model(data.get("torque", [])))):
            try:
                built[key] = build()
            except ValueError as exc:
                raise ScenarioError(f"{path or '<scenario>'}: {key}: {exc}") from None
        _check_turns(data, built["body"])
        if exact:
            Solver(scenario, exact=True)  # RunRefused when the closed form does not apply
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

    The integration steps actually taken are bounded by ``max_steps`` for the whole run: a stretch may take
    its share of it (in proportion to its duration), and a run that needs more, however fast each step,
    stops with :class:`RunRefused`.
    """

    def __init__(self, scenario, exact=False, max_steps=RUN_STEPS):
        data = scenario.data
        self.max_steps = max_steps
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
        span = self.t[-1] - self.t[0]
        # each output interval of a fixed-step method rounds its step count up: one more step per sample
        budget = math.ceil(self.max_steps * ((t[-1] - t[0]) / span if span > 0 else 1.0)) + t.size
        try:
            return simulate(self.body, t, omega_start, q0=q_start, torque=self.torque, method=self.method,
                            dt=self.dt, max_steps=budget)
        except StepBudgetExceeded as exc:
            raise RunRefused(f"the run needs more than the viewer's budget of {self.max_steps:g} integration steps "
                             f"(it was stopped at t = {exc.t_reached:.4g} s): the motion is too fast or stiff for "
                             "the viewer; shorten t_end, or run it with `kreisel simulate`") from None


class IntegralChanges:
    """The first integrals of the simulated model (:func:`kreisel.tops.first_integrals`: free body T and
    the space J; heavy top E = T + V and J_z; Lagrange top also J_3; Kovalevskaya top also K) and their
    largest change since the first sample, gathered chunk by chunk. A change is the integrator's error,
    not physics.

    Examples
    --------
    >>> import numpy as np
    >>> from kreisel import simulate
    >>> changes = IntegralChanges(None)
    >>> changes.add(simulate([1.0, 2.0, 3.0], np.linspace(0.0, 1.0, 11), [0.1, 1.0, 0.1]))
    >>> [(i["name"], i["relative"] < 1e-10) for i in changes.summary()]
    [('T', True), ('J', True)]
    """

    def __init__(self, torque):
        self.torque = torque
        self.model = None
        self.first = {}
        self.change = {}

    def add(self, traj):
        """Take the samples of ``traj``, the next stretch of the run, into account."""
        found = first_integrals(traj, self.torque)
        if self.model is None:
            self.model = found.model
            self.first = {f.symbol: f for f in found}
            self.change = dict.fromkeys(self.first, 0.0)
        for f in found:
            moved = np.abs(f.values - self.first[f.symbol].initial)
            moved = np.linalg.norm(moved, axis=-1) if f.is_vector else moved
            self.change[f.symbol] = max(self.change[f.symbol], float(np.max(moved)))

    def summary(self):
        """One entry per integral: name, label, unit, first value, largest change, and the change relative to
        the integral's scale (its first value, or |J| or the potential's range where that is zero)."""
        return [{"name": symbol, "label": f.name, "unit": f.unit, "initial": np.asarray(f.initial).tolist(),
                 "change": self.change[symbol], "relative": self.change[symbol] / float(f.scale)}
                for symbol, f in self.first.items()]


def samples(traj: Trajectory, gravity: tuple[float, NDArray[np.float64]] | None) -> dict[str, NDArray[np.float64]]:
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
    """Everything of a rigid-body run's JSON but the samples and the integrals (analysis from ``traj[0]``)."""
    gravity = _gravity(scenario)
    return {"kind": "rigid_body", "title": scenario.title, "method": traj.meta.get("method"),
            "inertia": traj.inertia.tolist(),
            "gravity": None if gravity is None else {"weight": gravity[0], "lever": gravity[1].tolist()},
            "analysis": analysis(traj, gravity)}


def rigid_body_result(scenario, traj):
    """JSON-ready arrays and analysis of a rigid-body run."""
    gravity = _gravity(scenario)
    arrays = samples(traj, gravity)
    integrals = IntegralChanges(torque_model(scenario.data.get("torque", [])))
    integrals.add(traj)
    return {**rigid_body_header(scenario, traj), **_lists(arrays), "integrals": integrals.summary()}


def analysis(traj: Trajectory, gravity: tuple[float, NDArray[np.float64]] | None) -> dict[str, Any]:
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
            out["regime_text"] = regime_text(top, axes.T @ omega0)
        except ValueError:
            out["regime"] = out["regime_text"] = None
    out["lagrange"] = _lagrange(traj, gravity) if gravity is not None else None
    return out


def regime_text(top, omega):
    """What a user sees a free body do when spun with principal-axis ω ``omega`` (Theory §5.4), in words.

    Examples
    --------
    >>> from kreisel.tops import EulerTop
    >>> regime_text(EulerTop(1.0, 2.0, 3.0), [0.001, 1.0, 0.001])
    'spun near the middle axis (I2 = 2): unstable, it flips over every 27.5 s'
    >>> regime_text(EulerTop(1.0, 2.0, 3.0), [0.1, 0.1, 1.0])
    'spun near the largest axis (I3 = 3): stable, ω wobbles about it with period 6.28 s'
    """
    omega = np.asarray(omega, dtype=float)
    regime = top.regime(omega)
    order = np.argsort(top.moments)
    names = {order[0]: "smallest", order[1]: "middle", order[2]: "largest"}
    # the axis the spin is nearest to, by the share of ω along it
    near = int(np.argmax(np.abs(omega)))
    axis = f"{names[near]} axis (I{near + 1} = {top.moments[near]:.4g})"
    if regime == "steady":
        return "steady rotation: spun about a principal axis (or a sphere), nothing changes"
    if regime == "separatrix":
        return "on the separatrix: ω creeps towards the middle axis and never completes a flip"
    if regime == "symmetric":
        return f"symmetric body: ω precesses regularly about the symmetry axis, period {top.omega_period(omega):.3g} s"
    if names[near] == "middle":
        return f"spun near the {axis}: unstable, it flips over every {top.dzhanibekov_flip_time(omega):.3g} s"
    return f"spun near the {axis}: stable, ω wobbles about it with period {top.omega_period(omega):.3g} s"


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
            "integrals": [{"name": "C", "label": "Jacobi integral", "unit": "", "initial": float(jacobi[0]),
                           "change": float(abs(jacobi[-1] - jacobi[0])),
                           "relative": float(abs(jacobi[-1] - jacobi[0]) / abs(jacobi[0]))}],
            "analysis": {"precession_rate_measured": float(swing.precession_rate), "precession_rate_theory": rate,
                     "period_hours": float(2 * np.pi / abs(rate) / 3600.0) if rate else None}}


def run(text, exact=False, max_steps=RUN_STEPS):
    """Run scenario TOML ``text``: the JSON answer of ``/api/run`` (raises ScenarioError, RunRefused).

    ``exact=True`` uses the closed form of the free top instead of an integrator; ``max_steps`` bounds
    the integration steps (see :class:`Solver`).
    """
    scenario = load(text, exact=exact)
    if scenario.kind == "foucault":
        answer = foucault_result(scenario)
        answer["form"] = None
    else:
        answer = rigid_body_result(scenario, Solver(scenario, exact, max_steps).run())
        answer["form"] = form_fields(scenario)
    answer["toml"] = text
    return answer


MAX_RECORDING_SAMPLES = 50_000


def fit(recording, name="upload", start=None, stop=None, bias=True):
    """A gyroscope recording with the free top fitted to it, as a run the viewer replays (job ``"fit"``).

    The fitted body moves exactly (:meth:`kreisel.tops.EulerTop.solve`) through the recording's own
    sample times, so the viewer plays the body with its inertia ellipsoid and polhode while the ω′ plot
    shows the measurement (``omega_measured``: bias removed, in the fitted principal axes) with the
    fitted curves; ``fit`` holds :meth:`kreisel.tops.FreeRotationFit.to_dict`, ``source`` the recording's
    name and ``form`` the fitted body as the viewer's form fields (its moments, ω′ and attitude at the
    window's start, exact solution), which the page shows during the replay.

    Parameters
    ----------
    recording : str or GyroRecording
        The text of a recording (any layout :func:`kreisel.io.read_gyro` reads) or a read recording.
    name : str
        The recording's name in messages (for text).
    start, stop : float, optional
        Window of the free flight, s (as in the file).
    bias : bool
        Also fit a constant gyroscope offset.

    Raises
    ------
    ScenarioError
        The text is not a recording, or its samples cannot be fitted (the viewer answers 400).
    RunRefused
        More than :data:`MAX_RECORDING_SAMPLES` samples (the viewer answers 422).

    Examples
    --------
    >>> import kreisel as kr
    >>> data = fit(kr.io.recording_path("phone_toss").read_text(), "phone_toss.csv")
    >>> data["kind"], len(data["t"]) == len(data["omega_measured"]), data["fit"]["intermediate_axis"]
    ('rigid_body', True, 'x')
    """
    import warnings

    from ..io.gyro import GyroFileError, parse_gyro
    from ..tops.fitting import NotFreeRotationWarning, fit_free_rotation

    if isinstance(recording, str):
        try:
            recording = parse_gyro(recording, name)
        except GyroFileError as exc:
            raise ScenarioError(str(exc)) from None
    if len(recording.t) > MAX_RECORDING_SAMPLES:
        raise RunRefused(f"the recording has {len(recording.t)} samples; the viewer fits at most "
                         f"{MAX_RECORDING_SAMPLES}")
    window = None if start is None and stop is None else (start, stop)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NotFreeRotationWarning)  # reported in fit.message
        try:
            result = fit_free_rotation(recording.t, recording.omega, bias=bias, window=window)
        except ValueError as exc:
            raise ScenarioError(f"{recording.source}: {exc}") from None
    traj = result.top.solve(result.t - result.t0, result.axes.T @ result.omega0)
    arrays = samples(traj, None)
    arrays["t"] = result.t
    integrals = IntegralChanges(None)
    integrals.add(traj)
    title = f"free-top fit of {recording.source}"
    # the form shows the fitted body from the window's start, so that Run replays it without the data
    form = {"title": title, "moments": np.diag(traj.inertia).tolist(), "omega": traj.omega[0].tolist(),
            "euler_deg": [0.0, 0.0, 0.0], "mgl": 0.0, "lever_axis": 2, "method": None,
            "t_end": float(result.t[-1] - result.t[0]), "n_samples": int(result.t.size), "dt": None}
    return {
        "kind": "rigid_body", "title": title, "method": "exact", "source": recording.source,
        "inertia": traj.inertia.tolist(), "gravity": None, "analysis": analysis(traj, None), **_lists(arrays),
        "omega_measured": ((result.omega - result.bias) @ result.axes).tolist(),
        "integrals": integrals.summary(), "fit": result.to_dict(), "form": form,
    }


def _rows(x):
    """Rows of ``x`` as JSON lists, None where a row is not finite (the reference lost the body)."""
    return [row.tolist() if np.isfinite(row).all() else None for row in x]


def attitude_replay(recording):
    """An IMU recording's attitude estimated by kreisel beside its reference, as a replay (job ``"attitude_replay"``).

    The attitude frame ← sensor is estimated with :func:`kreisel.nav.estimate_attitude` (kreisel's
    default, causal estimator; the magnetometer when the recording has one) and compared per sample with
    the recording's reference (BROAD's motion capture) by :func:`kreisel.nav.attitude_error_angles`.

    Parameters
    ----------
    recording : ImuRecording
        With gyro, accelerometer and ``reference`` (:func:`kreisel.io.read_imu`), evenly sampled.

    Returns
    -------
    dict
        ``kind`` ``"attitude"``, ``title``, ``source``, ``method``, ``magnetometer`` (whether one was used),
        ``rate`` (Hz), ``t``, ``q`` (estimate,
        scalar-first rows), ``q_ref`` (rows, None where the reference lost the body), ``omega_norm`` (the
        gyro's rate |ω′|, rad/s), ``error_deg`` (``total``, ``heading``, ``inclination`` per sample, None
        where lost) and ``rmse_deg`` (the three RMSEs of :func:`kreisel.nav.attitude_error` and ``over``: ``"movement"`` or ``"all"``).

    Raises
    ------
    ScenarioError
        No accelerometer or no reference, unevenly spaced samples, or samples the estimator refuses.
    RunRefused
        More than :data:`MAX_RECORDING_SAMPLES` samples.

    Examples
    --------
    >>> import kreisel as kr
    >>> data = attitude_replay(kr.io.read_imu(kr.io.recording_path("broad_07")))
    >>> data["kind"], len(data["t"]) == len(data["q"]) == len(data["q_ref"]), round(data["rate"], 3)
    ('attitude', True, 285.714)
    >>> data["q_ref"][0], data["rmse_deg"]["over"]
    (None, 'movement')
    """
    from ..nav import attitude_error, attitude_error_angles, estimate_attitude

    name = recording.source
    if recording.accel is None or recording.reference is None:
        raise ScenarioError(f"{name}: an attitude replay needs an accelerometer and a reference attitude")
    n = len(recording.t)
    if n > MAX_RECORDING_SAMPLES:
        raise RunRefused(f"the recording has {n} samples; the viewer replays at most {MAX_RECORDING_SAMPLES}")
    try:
        rate = recording.sampling_rate()
    except ValueError as exc:
        raise ScenarioError(str(exc)) from None
    try:
        estimate = estimate_attitude(recording.omega, recording.accel, recording.mag, rate=rate)
        errors = np.degrees(attitude_error_angles(estimate.q, recording.reference))
        rmse = attitude_error(estimate.q, recording.reference, recording.movement)
    except ValueError as exc:
        raise ScenarioError(f"{name}: {exc}") from None
    title = f"attitude of {pathlib.PurePath(name).name}: kreisel's estimate and the reference"
    return {
        "kind": "attitude", "title": title, "source": name, "method": estimate.method,
        "magnetometer": recording.mag is not None, "rate": rate,
        "t": recording.t.tolist(), "q": estimate.q.tolist(), "q_ref": _rows(recording.reference),
        "omega_norm": np.linalg.norm(recording.omega, axis=1).tolist(),
        "error_deg": {key: [float(v) if np.isfinite(v) else None for v in values]
                      for key, values in zip(("total", "heading", "inclination"), errors)},
        "rmse_deg": {"total": rmse[0], "heading": rmse[1], "inclination": rmse[2],
                     "over": "all" if recording.movement is None else "movement"},
    }


def export(text, exact, format, folder, max_steps=RUN_STEPS):
    """Run scenario TOML ``text`` and write its trajectory as ``format`` ("nc" or "csv") into ``folder``.

    Returns the path written (named after the scenario's title); ``max_steps`` as in :class:`Solver`.
    """
    from ..io import save_result

    scenario = load(text, MAX_STREAM_SAMPLES, exact)
    if scenario.kind != "rigid_body":
        raise RunRefused("only rigid-body runs export as a trajectory file")
    traj = Solver(scenario, exact, max_steps).run()
    name = "".join(c if c.isalnum() else "_" for c in scenario.title.lower()).strip("_") or "trajectory"
    return str(save_result(traj, pathlib.Path(folder) / f"{name}.{format}"))


def stream(text, exact=False, chunk_samples=CHUNK_SAMPLES, max_steps=RUN_STEPS):
    """Validate ``text`` now, then return a generator of the run's messages, one chunk of work per message.

    ``max_steps`` bounds the integration steps of the whole run (see :class:`Solver`).

    Messages: ``{"type": "start", ...}`` (what :func:`run` answers but the samples and the integrals, plus
    ``n_samples``, ``n_chunks`` and ``t_range``, the first and last time), then
    ``{"type": "chunk", "index", "offset", t, q, omega, ...}`` with consecutive samples, then
    ``{"type": "done", "integrals": ...}``. The integrators restart each chunk from the last state of the
    previous one: dop853's error control then restarts too, so a streamed run agrees with :func:`run` to
    the integrator's tolerance (not bit for bit); fixed-step methods take the same steps either way (each
    interval between samples is stepped alone), and the exact solution is evaluated per sample, so those
    agree to round-off.

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
    scenario = load(text, MAX_STREAM_SAMPLES, exact)
    solver = None if scenario.kind == "foucault" else Solver(scenario, exact, max_steps)
    return _messages(scenario, solver, text, chunk_samples)


def _messages(scenario, solver, text, chunk_samples):
    if solver is None:
        # the pendulum's turning points come from one event-located integration: a single chunk
        result = foucault_result(scenario)
        arrays = {key: result.pop(key) for key in ("t", "swing_azimuth", "tilt")}
        integrals = result.pop("integrals")
        yield {"type": "start", **result, "form": None, "toml": text, "n_samples": len(arrays["t"]), "n_chunks": 1,
               "t_range": [arrays["t"][0], arrays["t"][-1]]}
        yield {"type": "chunk", "index": 0, "offset": 0, **arrays}
        yield {"type": "done", "integrals": integrals}
        return
    t = solver.t
    # chunk k holds samples [bounds[k], bounds[k + 1]); its integration starts at the sample before
    bounds = list(range(0, t.size, chunk_samples)) + [t.size]
    gravity = _gravity(scenario)
    integrals = IntegralChanges(solver.torque)
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
        integrals.add(traj)
        yield {"type": "chunk", "index": index, "offset": first, **_lists(arrays)}
    yield {"type": "done", "integrals": integrals.summary()}


__all__ = ["METHODS", "MAX_SAMPLES", "MAX_STREAM_SAMPLES", "CHUNK_SAMPLES", "RunRefused", "ScenarioError",
           "Solver", "IntegralChanges", "samples", "regime_text", "scenario_data", "scenario_toml", "toml_text", "form_fields", "load", "run",
           "export", "stream", "attitude_replay"]
