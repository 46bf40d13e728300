// The notebook widget (anywidget) of kreisel.show: the viewer's scene with its legend, a time slider and a
// space/body camera.
// The Python side (kreisel.notebook) sends one JSON object, model.get("data"), shaped like the viewer's
// run results: t, q, omega, omega_space, J and the analysis (principal axes and moments, T, J).
// The built module is self-contained (three.js inside), as anywidget loads it from one string; it also
// exports the scene, which the viewer's page (main.js) imports from it instead of bundling three.js twice.
import { legendRows, Viewer, webglAvailable } from "./scene.js";

export { legendRows, Viewer, webglAvailable } from "./scene.js";

function render({ model, el }) {
  const box = document.createElement("div");
  box.style.cssText = "display:flex;flex-direction:column;gap:4px;max-width:640px;font:12px sans-serif";
  const canvas = document.createElement("canvas");
  canvas.style.cssText = "width:100%;height:400px;display:block";
  const bar = document.createElement("div");
  bar.style.cssText = "display:flex;gap:6px;align-items:center";
  const play = document.createElement("button");
  const slider = document.createElement("input");
  slider.type = "range";
  slider.style.flex = "1";
  const label = document.createElement("span");
  const camera = document.createElement("button");
  camera.title = "camera fixed in space, or riding with the body";
  const legend = document.createElement("div");
  legend.style.cssText = "display:flex;flex-wrap:wrap;gap:2px 14px";
  bar.append(play, slider, label, camera);
  box.append(canvas, bar, legend);
  el.append(box);
  if (!webglAvailable()) {
    box.textContent = "kreisel.show needs WebGL, which this browser does not offer.";
    return;
  }
  const viewer = new Viewer(canvas);
  let data = null, playing = false, frame = 0;
  const draw = () => {
    const i = Number(slider.value);
    viewer.show(i);
    viewer.render();
    label.textContent = `t = ${data.t[i].toPrecision(4)} s`;
    model.set("index", i);
    model.save_changes();
  };
  const load = () => {
    data = model.get("data");
    viewer.load(data);
    legend.replaceChildren(...legendRows(data));
    slider.min = 0;
    slider.max = data.t.length - 1;
    slider.value = Math.min(model.get("index"), data.t.length - 1);
    draw();
  };
  const tick = () => {
    if (!playing) return;
    slider.value = (Number(slider.value) + 1) % data.t.length;
    draw();
    frame = requestAnimationFrame(tick);
  };
  const setPlaying = (on) => {
    playing = on;
    play.textContent = on ? "❚❚" : "▶";
    if (on) frame = requestAnimationFrame(tick);
    else cancelAnimationFrame(frame);
  };
  const setFrame = (frame) => {
    viewer.frame = frame;
    camera.textContent = `camera: ${frame}`;
  };
  camera.onclick = () => { setFrame(viewer.frame === "space" ? "body" : "space"); draw(); };
  play.onclick = () => setPlaying(!playing);
  slider.oninput = () => { setPlaying(false); draw(); };
  model.on("change:data", load);
  setPlaying(false);
  setFrame("space");
  load();
  return () => { setPlaying(false); viewer.clear(); viewer.renderer.dispose(); };
}

export default { render };
