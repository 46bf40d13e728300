// The viewer's page logic: form <-> API, playback clock, plots and readouts.
import { drawPlot } from "./plots.js";
// the scene comes from the widget's module, which carries three.js (web/build.mjs keeps it a separate file)
import { legendRows, Viewer, webglAvailable } from "./widget.js";

const $ = (id) => document.getElementById(id);
// window.kreisel is read by the end-to-end tests: the data, the playback position, what is plotted and
// how the run arrived (streamed: over /api/stream; chunks: chunk messages received; done: all samples in) and,
// for an attitude replay, what the scene shows (shown: the sample index and the two attitudes, scalar first)
const state = (window.kreisel = { data: null, index: 0, time: 0, playing: true, ready: false, error: null,
  streamed: false, chunks: 0, done: false, plotted: { omega: [], energy: [], J: [] }, shown: null });
let socket = null;
let viewer = null;

function status(message, error = false) {
  $("status").textContent = message;
  $("status").className = error ? "error" : "";
  state.error = error ? message : null;
}

async function api(path, body) {
  const response = await fetch(path, body === undefined ? {} : {
    method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) });
  if (!response.ok) {
    let detail = response.statusText;
    try { detail = (await response.json()).detail; } catch (e) { /* not JSON */ }
    throw new Error(typeof detail === "string" ? detail : JSON.stringify(detail));
  }
  return response;
}

const num = (id) => parseFloat($(id).value);

function readForm() {
  const form = {
    moments: ["I1", "I2", "I3"].map(num), omega: ["w1", "w2", "w3"].map(num), euler_deg: ["e1", "e2", "e3"].map(num),
    mgl: num("mgl") || 0, lever_axis: parseInt($("lever").value, 10), t_end: num("tend"),
    n_samples: parseInt($("nsamp").value, 10),
  };
  if ($("method").value && $("method").value !== "exact") form.method = $("method").value;
  return form;
}

function fillForm(form) {
  const set = (ids, values) => ids.forEach((id, k) => ($(id).value = +values[k].toPrecision(10)));
  set(["I1", "I2", "I3"], form.moments);
  set(["w1", "w2", "w3"], form.omega);
  set(["e1", "e2", "e3"], form.euler_deg);
  $("mgl").value = form.mgl;
  $("lever").value = String(form.lever_axis);
  $("method").value = form.method || "";
  $("tend").value = form.t_end;
  $("nsamp").value = form.n_samples;
}

const fmt = (v, digits = 6) => (v === null || v === undefined ? "–" : Number(v).toPrecision(digits));

// The first integrals of the simulated model (free body: T and J; heavy top: E, J_z, and J_3 or K) with their
// largest change over the run: what a correct integration keeps constant.
function integralLines(d) {
  if (!d.integrals) return ["first integrals: when the run is complete"];
  if (!d.integrals.length) return ["first integrals: none (the torque does work)"];
  const lines = ["first integrals (largest change over the run):"];
  for (const i of d.integrals) {
    const value = Array.isArray(i.initial) ? `[${i.initial.map((v) => fmt(v, 5)).join(", ")}]` : fmt(i.initial, 10);
    lines.push(`  ${i.name.padEnd(3)} = ${value} ${i.unit}`.trimEnd(), `        change ${fmt(i.change, 3)} (relative ${fmt(i.relative, 3)})`);
  }
  return lines;
}

// An attitude replay: the estimator, the RMSE against the reference and what the scene shows.
function attitudeLines(d) {
  const r = d.rmse_deg, deg = (v) => `${fmt(v, 4)}°`;
  const sensors = d.magnetometer ? "gyro, accelerometer and magnetometer" : "gyro and accelerometer (no magnetometer)";
  return [`estimated by ${d.method === "kreisel" ? "kreisel's estimator" : d.method} from ${sensors} at ${fmt(d.rate, 5)} Hz`,
    `error against the reference (RMSE over ${r.over === "movement" ? "the movement" : "all samples"}):`,
    `  total ${deg(r.total)}, heading ${deg(r.heading)}, inclination ${deg(r.inclination)}`,
    "orange: the estimate; blue: the reference (hidden where it lost the body)"];
}

// The error angle of the sample shown, as kreisel.nav.attitude_error_angles gives it.
function errorText(d, i) {
  const e = d.error_deg;
  if (e.total[i] === null) return "error: the reference lost the body here";
  return `error ${e.total[i].toFixed(3)}° (heading ${e.heading[i].toFixed(3)}°, inclination ${e.inclination[i].toFixed(3)}°)`;
}

function readout(d) {
  const lines = [`${d.title}`];
  const s = d.analysis;
  if (d.kind === "attitude") {
    lines.push(...attitudeLines(d));
  } else if (d.kind === "foucault") {
    lines.push(`swing plane rate  ${fmt(s.precession_rate_measured)} rad/s`,
      `theory −Ω sin λ    ${fmt(s.precession_rate_theory)} rad/s`,
      `one turn in       ${fmt(s.period_hours, 5)} h`, ...integralLines(d));
  } else {
    lines.push(`method ${d.method}`);
    if (s.regime_text) lines.push(s.regime_text);
    lines.push(...integralLines(d));
    if (d.fit) {
      const f = d.fit, pm = (v, e) => `${fmt(v, 5)} ± ${fmt(e, 2)}`;
      lines.push("fit to the recording (largest moment = 1; ω′ plot: light = measured):",
        ...["x", "y", "z"].map((a, k) => `  I_${a} = ${pm(f.moments[k], f.moments_stderr[k])}`),
        `  ω0 = [${f.omega0.map((v) => fmt(v, 5)).join(", ")}] rad/s`,
        `  bias = [${f.bias.map((v) => fmt(v, 3)).join(", ")}] rad/s`,
        `  RMS ${fmt(f.rms, 3)} rad/s, intermediate axis ${f.intermediate_axis}`, `  ${f.message}`);
    }
    lines.push("steady rotation about principal axes:");
    for (const a of s.stability) {
      const extra = a.kind === "unstable" ? `growth ${fmt(a.growth_rate, 4)}/s` : a.kind === "stable" ? `wobble ${fmt(a.wobble_frequency, 4)} rad/s` : "";
      lines.push(`  I${a.axis} = ${fmt(a.moment, 4)}: ${a.kind} ${extra}`);
    }
    const lg = s.lagrange;
    if (lg) {
      lines.push("Lagrange top:");
      if (lg.theta_min_deg !== undefined) lines.push(`  θ between ${fmt(lg.theta_min_deg, 5)}° and ${fmt(lg.theta_max_deg, 5)}°`, `  apex locus: ${lg.apex_locus}`);
      if (lg.note) lines.push(`  ${lg.note}`);
      lines.push(`  sleeping top ${lg.sleeping_stable ? "stable" : "unstable"} (needs ω3 > ${fmt(lg.sleeping_threshold_omega3, 4)})`);
    }
  }
  $("readout").textContent = lines.join("\n");
}

function legend(d) {
  $("legend").replaceChildren(...legendRows(d));
}

// The preset box names what plays: a recording's replay gets an entry of its own, dropped with the next run.
function showSource(d) {
  let entry = $("preset").querySelector("option[data-recording]");
  if (!d.fit && d.kind !== "attitude") {
    if (entry) entry.remove();
    return;
  }
  if (!entry) {
    entry = new Option("", "");
    entry.dataset.recording = "yes";
    $("preset").add(entry, 0);
  }
  entry.text = `recording: ${d.source.split(/[\\/]/).pop()}`;
  $("preset").value = "";
  $("description").textContent = d.fit ? `${d.title}: the fitted free top, the measurement light in the ω′ plot`
    : `${d.title}: the two sensors turn together, the error angle above`;
}

// Start playing `d`, which may hold only the first chunk of a streamed run.
function show(d) {
  state.data = d;
  state.index = 0;
  state.time = d.t[0];
  state.ready = true;
  showSource(d);
  if (d.form) fillForm(d.form);
  if (d.method === "exact") $("method").value = "exact";
  if (viewer) viewer.load(d);
  readout(d);
  legend(d);
  const foucault = d.kind === "foucault", attitude = d.kind === "attitude";
  $("energy-title").textContent = foucault ? "swing-plane azimuth (rad)" : attitude ? "rotation rate |ω′| from the gyro (rad/s)"
    : d.gravity ? "energy E = T + V (J)" : "kinetic energy T (J)";
  $("omega-title").textContent = foucault ? "tilt of the string at the turning points (rad)"
    : attitude ? "error against the reference (°)" : "ω′ components (rad/s)";
  $("omega-legend").style.display = foucault ? "none" : "";
  $("omega-legend").replaceChildren(...(attitude ? ATTITUDE_LEGEND : OMEGA_LEGEND).map(([color, text]) => {
    const span = document.createElement("span");
    span.style.color = color;
    span.textContent = text;
    return span;
  }));
  $("J-panel").style.display = foucault || attitude ? "none" : "";
  $("attitude-error").style.display = attitude ? "" : "none";
  status(`${d.title}: ${d.t.length} of ${d.n_samples || d.t.length} samples`);
}

// The one-shot JSON run: the fallback where a WebSocket cannot be opened.
async function runOnce(body) {
  try {
    const d = await (await api("/api/run", body)).json();
    state.done = true;
    show(d);
  } catch (e) {
    status(e.message, true);
  }
}

// Stream the run over /api/stream: playback starts with the first chunk while the rest is computed.
function run(body) {
  status("computing…");
  state.ready = false;
  state.done = false;
  state.chunks = 0;
  if (socket) { try { socket.send("cancel"); socket.close(); } catch (e) { /* already closed */ } }
  const ws = (socket = new WebSocket(`${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/api/stream`));
  let d = null, heard = false;
  ws.onopen = () => ws.send(JSON.stringify(body));
  ws.onmessage = (event) => {
    if (ws !== socket) return; // a replaced run still talking
    heard = true;
    const m = JSON.parse(event.data);
    if (m.type === "error") { status(m.detail, true); return; }
    if (m.type === "start") {
      d = m;
      const keys = m.kind === "foucault" ? ["t", "swing_azimuth", "tilt"] : ["t", "q", "omega", "omega_space", "J", "J_norm", "energy", "kinetic"];
      for (const k of keys) d[k] = [];
      d.integrals = null;
      d._keys = keys;
      return;
    }
    if (m.type === "chunk") {
      for (const k of d._keys) for (const v of m[k]) d[k].push(v);
      state.chunks += 1;
      state.streamed = true;
      d._series = null;
      if (state.chunks === 1) show(d);
      else {
        if (viewer) viewer.append();
        status(`${d.title}: ${d.t.length} of ${d.n_samples} samples…`);
      }
      return;
    }
    if (m.type === "done") {
      d.integrals = m.integrals;
      state.done = true;
      readout(d);
      status(`${d.title}: ${d.t.length} samples`);
    }
  };
  ws.onclose = () => {
    if (ws !== socket) return;
    socket = null;
    if (!heard) runOnce(body);
    else if (!state.done && !state.error) status("the stream ended before the run was complete", true);
  };
}

const OMEGA_LEGEND = [["#d33", "ω′₁"], ["#393", "ω′₂"], ["#33d", "ω′₃"]];
const ATTITUDE_LEGEND = [["#222", "total"], ["#93c", "heading"], ["#d33", "inclination"]];

function series(d) {
  if (d.kind === "attitude") {
    const nan = (values) => values.map((v) => (v === null ? NaN : v));
    const e = d.error_deg;
    return { omega: [nan(e.total), nan(e.heading), nan(e.inclination)], energy: [d.omega_norm], J: [[]] };
  }
  if (d.kind === "foucault") return { omega: [d.tilt.map(Math.abs)], energy: [d.swing_azimuth], J: [[]] };
  const col = (k, w = d.omega) => w.map((v) => v[k]);
  const omega = [col(0), col(1), col(2)];
  // a fitted recording: the measurement (light) under the fitted body's ω′
  if (d.omega_measured) omega.unshift(col(0, d.omega_measured), col(1, d.omega_measured), col(2, d.omega_measured));
  return { omega, energy: [d.energy], J: [d.J_norm] };
}

function drawPlots() {
  const d = state.data;
  if (!d) return;
  if (!d._series) d._series = series(d);
  const s = d._series, i = state.index, span = d.t_range || null;
  const attitude = d.kind === "attitude";
  const colors = d.omega_measured ? ["#f2b8b8", "#b8dcb8", "#b8b8f2", "#d33", "#393", "#33d"]
    : attitude ? ATTITUDE_LEGEND.map(([color]) => color) : ["#d33", "#393", "#33d"];
  state.plotted.omega = drawPlot($("plot-omega"), d.t, s.omega, colors, i, span);
  state.plotted.energy = drawPlot($("plot-energy"), d.t, s.energy, ["#b60"], i, span)[0];
  state.plotted.J = drawPlot($("plot-J"), d.t, s.J, ["#088"], i, span)[0];
}

function download(blob, name) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

function indexAt(t, times) {
  let lo = 0, hi = times.length - 1;
  while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (times[mid] <= t) lo = mid; else hi = mid - 1; }
  return lo;
}

let last = performance.now();
function frame(now) {
  const d = state.data;
  const dt = Math.min(0.1, (now - last) / 1000);
  last = now;
  if (d && state.ready) {
    const [first, end] = d.t_range || [d.t[0], d.t[d.t.length - 1]];
    const last = d.t[d.t.length - 1];
    if (state.playing) {
      // the whole run plays in about 40 s at speed 1; while it streams in, playback waits at the last sample
      state.time += dt * Math.pow(10, num("speed")) * ((end - first) / 40);
      if (state.time > last) {
        state.time = last;
        if (state.done) { state.playing = false; $("play").textContent = "Play"; }
      }
      state.index = indexAt(state.time, d.t);
    }
    if (viewer) { viewer.frame = $("camera").value; viewer.show(state.index); }
    drawPlots();
    $("hud").textContent = `t = ${d.t[state.index].toFixed(3)} s   (${state.index + 1}/${d.n_samples || d.t.length})`;
    $("scrub").max = String(d.t.length - 1);
    $("scrub").value = String(state.index);
    if (d.kind === "attitude") {
      $("attitude-error").textContent = errorText(d, state.index);
      state.shown = { index: state.index, ...(viewer ? viewer.attitudes() : {}) };
    } else state.shown = null;
  }
  if (viewer) viewer.render();
  requestAnimationFrame(frame);
}

async function init() {
  if (webglAvailable()) {
    try { viewer = new Viewer($("scene")); } catch (e) { viewer = null; }
  }
  if (!viewer) { $("nowebgl").style.display = "block"; $("scene").style.display = "none"; }
  state.webgl = !!viewer;
  const methods = await (await api("/api/methods")).json();
  for (const m of methods) $("method").add(new Option(m, m), $("method").options.length - 1);
  const presets = await (await api("/api/presets")).json();
  for (const p of presets) $("preset").add(new Option(p.title, p.name));
  const describe = () => ($("description").textContent = presets.find((p) => p.name === $("preset").value)?.description || "");
  $("preset").onchange = () => { describe(); run({ preset: $("preset").value }); };
  $("run").onclick = () => run({ form: readForm(), exact: $("method").value === "exact" });
  $("play").onclick = () => {
    if (!state.data) return;
    if (!state.playing && state.index >= state.data.t.length - 1) state.time = state.data.t[0];
    state.playing = !state.playing;
    $("play").textContent = state.playing ? "Pause" : "Play";
  };
  $("step").onclick = () => {
    if (!state.data) return;
    state.playing = false; $("play").textContent = "Play";
    state.index = Math.min(state.index + 1, state.data.t.length - 1);
    state.time = state.data.t[state.index];
  };
  $("restart").onclick = () => { if (state.data) { state.time = state.data.t[0]; state.index = 0; } };
  // dragging the time slider pauses the replay at the sample it points to
  $("scrub").oninput = () => {
    if (!state.data) return;
    state.playing = false; $("play").textContent = "Play";
    state.index = Math.min(parseInt($("scrub").value, 10), state.data.t.length - 1);
    state.time = state.data.t[state.index];
  };
  $("speed").oninput = () => ($("speedval").textContent = `${Math.pow(10, num("speed")).toPrecision(2)}×`);
  const exportAs = async (format) => {
    if (!state.data) return;
    try {
      const response = await api(`/api/export?format=${format}`, { toml: state.data.toml, exact: state.data.method === "exact" });
      const name = /filename="([^"]+)"/.exec(response.headers.get("content-disposition") || "")?.[1] || `trajectory.${format}`;
      download(await response.blob(), name);
    } catch (e) { status(e.message, true); }
  };
  $("export-nc").onclick = () => exportAs("nc");
  $("export-csv").onclick = () => exportAs("csv");
  $("export-toml").onclick = () => state.data && download(new Blob([state.data.toml], { type: "application/toml" }), "scenario.toml");
  $("load").onchange = async () => {
    const file = $("load").files[0];
    if (file) run({ toml: await file.text() });
  };
  // a recording: fitted (or its attitude estimated) on the server, then played like a run (one reply, no stream)
  const showFit = (d) => {
    if (socket) { try { socket.send("cancel"); socket.close(); } catch (e) { /* already closed */ } socket = null; }
    state.done = true; state.playing = true; $("play").textContent = "Pause";
    show(d);
  };
  $("fit").onclick = async () => {
    const file = $("recording").files[0];
    if (!file) { status("choose a recording file first", true); return; }
    const bound = (id) => ($(id).value === "" ? null : num(id));
    status("fitting…");
    try {
      showFit(await (await api("/api/fit", { text: await file.text(), name: file.name, start: bound("fit-start"),
        stop: bound("fit-stop"), bias: $("fit-bias").checked })).json());
    } catch (e) { status(e.message, true); }
  };
  requestAnimationFrame(frame);
  const recording = await (await api("/api/recording")).json();
  const initial = (await (await api("/api/initial")).json()).toml;
  if (recording) showFit(recording);
  else if (initial) run({ toml: initial });
  else { $("preset").value = "tennis_racket"; describe(); run({ preset: "tennis_racket" }); }
}

init().catch((e) => status(`viewer failed to start: ${e.message}`, true));
