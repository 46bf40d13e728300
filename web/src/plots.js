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

function fmt(v) { return Math.abs(v) >= 1e4 || (Math.abs(v) < 1e-3 && v !== 0) ? v.toExponential(4) : v.toPrecision(8); }

/** Draw `series` (arrays over `t`) up to sample `upto` inclusive on the time axis `span` (default: all of
 * `t`, which may still be growing while a run streams in); returns the plotted values. */
export function drawPlot(canvas, t, series, colors, upto, span = null) {
  const [ctx, w, h] = sized(canvas);
  ctx.clearRect(0, 0, w, h);
  const plotted = series.map((s) => s.slice(0, upto + 1));
  if (!t.length) return plotted;
  const [lo, hi] = yRange(series);
  const [t0, last] = span || [t[0], t[t.length - 1]];
  const t1 = last > t0 ? last : t0 + 1;
  const left = 4, right = w - 4, top = 14, bottom = h - 4;
  const x = (v) => left + ((v - t0) / (t1 - t0)) * (right - left);
  const y = (v) => bottom - ((v - lo) / (hi - lo)) * (bottom - top);
  ctx.strokeStyle = "#eee";
  ctx.beginPath(); ctx.moveTo(left, y(0)); ctx.lineTo(right, y(0)); ctx.stroke();
  plotted.forEach((values, k) => {
    ctx.strokeStyle = colors[k];
    ctx.lineWidth = 1.4;
    ctx.beginPath();
    // a long run draws about two points per pixel column, not every sample each frame
    const stride = Math.max(1, Math.floor(values.length / (2 * w)));
    ctx.moveTo(x(t[0]), y(values[0]));
    for (let i = stride; i < values.length; i += stride) ctx.lineTo(x(t[i]), y(values[i]));
    if (values.length > 1) ctx.lineTo(x(t[values.length - 1]), y(values[values.length - 1]));
    ctx.stroke();
  });
  ctx.fillStyle = "#666";
  ctx.font = "10px ui-monospace, monospace";
  ctx.fillText(`${fmt(lo)} … ${fmt(hi)}   t = ${t[upto].toFixed(2)} s`, left, 10);
  return plotted;
}
