// Small canvas line plots: no chart library, just enough to watch omega, energy and |J| evolve.

function sized(canvas) {
  const ratio = window.devicePixelRatio || 1;
  const w = Math.max(1, Math.round(canvas.clientWidth * ratio));
  const h = Math.max(1, Math.round(canvas.clientHeight * ratio));
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  const ctx = canvas.getContext("2d");
  ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  return [ctx, canvas.clientWidth, canvas.clientHeight];
}

// The y range covers the whole run, so a conserved quantity plots as a flat line; a floor on the
// span keeps round-off from being blown up to full height.
function yRange(series) {
  let lo = Infinity, hi = -Infinity;
  for (const s of series) for (const v of s) { if (v < lo) lo = v; if (v > hi) hi = v; }
  const mid = 0.5 * (lo + hi);
  const span = Math.max(hi - lo, 1e-6 * Math.abs(mid), 1e-12);
  return [mid - 0.55 * span, mid + 0.55 * span];
}

// Tick labels with as many digits as tell them apart: a conserved quantity's axis spans a tiny range
// about a large value, and every label would otherwise read the same. Values within round-off of zero
// on a symmetric axis print as 0.
function tickLabels(values, span) {
  const size = Math.max(...values.map(Math.abs));
  const digits = Math.min(15, Math.max(3, Math.ceil(Math.log10(size / span)) + 3));
  return values.map((v) => {
    if (Math.abs(v) < 1e-9 * span) return "0";
    const a = Math.abs(v);
    return a >= 1e5 || a < 1e-3 ? v.toExponential(Math.min(digits, 15) - 1) : Number(v.toPrecision(digits)).toString();
  });
}

const timeLabel = (v) => `${Number(v.toPrecision(4))} s`;

/** Draw `series` (arrays over `t`) up to sample `upto` inclusive on the time axis `span` (default: all of
 * `t`, which may still be growing while a run streams in); returns the plotted values. The y axis is
 * labelled at its ends and middle, the time axis in seconds, and the current time is marked. */
export function drawPlot(canvas, t, series, colors, upto, span = null) {
  const [ctx, w, h] = sized(canvas);
  ctx.clearRect(0, 0, w, h);
  const plotted = series.map((s) => s.slice(0, upto + 1));
  if (!t.length) return plotted;
  const [lo, hi] = yRange(series);
  const [t0, last] = span || [t[0], t[t.length - 1]];
  const t1 = last > t0 ? last : t0 + 1;
  ctx.font = "11px ui-monospace, monospace";
  const labels = tickLabels([hi, 0.5 * (lo + hi), lo], hi - lo);
  const left = 8 + Math.max(...labels.map((l) => ctx.measureText(l).width)), right = w - 8, top = 8, bottom = h - 20;
  const x = (v) => left + ((v - t0) / (t1 - t0)) * (right - left);
  const y = (v) => bottom - ((v - lo) / (hi - lo)) * (bottom - top);
  // frame, grid and labels
  ctx.strokeStyle = "#e4e4e4";
  ctx.lineWidth = 1;
  ctx.fillStyle = "#555";
  ctx.textBaseline = "middle";
  ctx.textAlign = "right";
  [hi, 0.5 * (lo + hi), lo].forEach((v, k) => {
    ctx.beginPath(); ctx.moveTo(left, y(v)); ctx.lineTo(right, y(v)); ctx.stroke();
    ctx.fillText(labels[k], left - 4, y(v));
  });
  ctx.textAlign = "center";
  ctx.textBaseline = "top";
  for (const v of [t0, 0.5 * (t0 + t1), t1]) ctx.fillText(timeLabel(v), Math.min(Math.max(x(v), left + 16), right - 16), bottom + 4);
  plotted.forEach((values, k) => {
    ctx.strokeStyle = colors[k];
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    // a long run draws about two points per pixel column, not every sample each frame
    const stride = Math.max(1, Math.floor(values.length / (2 * w)));
    ctx.moveTo(x(t[0]), y(values[0]));
    for (let i = stride; i < values.length; i += stride) ctx.lineTo(x(t[i]), y(values[i]));
    if (values.length > 1) ctx.lineTo(x(t[values.length - 1]), y(values[values.length - 1]));
    ctx.stroke();
  });
  // the current time
  ctx.strokeStyle = "#999";
  ctx.setLineDash([3, 3]);
  ctx.beginPath(); ctx.moveTo(x(t[upto]), top); ctx.lineTo(x(t[upto]), bottom); ctx.stroke();
  ctx.setLineDash([]);
  return plotted;
}
