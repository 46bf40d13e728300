// The three.js scene: body, principal axes, omega and J arrows, Poinsot construction, trails, heavy top.
// Coordinates are kreisel's space frame (z up); the body group carries the attitude q (body -> space).
import * as THREE from "three";

const AXIS_COLORS = [0xd03030, 0x30a030, 0x3050d0];

export function webglAvailable() {
  try {
    const c = document.createElement("canvas");
    return !!(window.WebGLRenderingContext && (c.getContext("webgl2") || c.getContext("webgl")));
  } catch (e) {
    return false;
  }
}

const quat = (q) => new THREE.Quaternion(q[1], q[2], q[3], q[0]);
const vec = (v, s = 1) => new THREE.Vector3(v[0] * s, v[1] * s, v[2] * s);

// A trail sized for the whole run; `point(i)` gives sample i, filled in by append() as chunks arrive.
function trail(capacity, color, point) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(3 * capacity), 3));
  geometry.setDrawRange(0, 1);
  const line = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color }));
  line.point = point;
  return line;
}

function arrow(color) {
  const a = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 1, color, 0.12, 0.07);
  a.visible = false;
  return a;
}

function setArrow(a, v) {
  const length = v.length();
  a.visible = length > 1e-9;
  if (a.visible) { a.setDirection(v.clone().divideScalar(length)); a.setLength(length, Math.min(0.15, 0.3 * length), Math.min(0.08, 0.15 * length)); }
}

// Edge lengths of the uniform box with these principal moments: a_i^2 ∝ I_j + I_k - I_i.
function boxSize(moments) {
  const [a, b, c] = moments;
  const edges = [b + c - a, a + c - b, a + b - c].map((v) => Math.sqrt(Math.max(v, 1e-3 * (a + b + c))));
  const top = Math.max(...edges);
  return edges.map((e) => e / top);
}

const css = (hex) => `#${hex.toString(16).padStart(6, "0")}`;
const COLORS = { omega: 0xcc00cc, J: 0x008888, herpolhode: 0x228822, polhode: 0xaa2288, plane: 0x88bb88,
  ellipsoid: 0x6677aa, apex: 0x0077cc, gravity: 0x444444, swing: 0x3050d0, estimate: 0xe08a30, reference: 0x4a78c8 };
// the estimate and the reference side by side, across the default view (the camera looks along (-5.6, 3.4, -2.3))
const BESIDE = new THREE.Vector3(0.52, 0.85, 0).multiplyScalar(0.95);

// A sensor: a flat box longest along its x axis, with its x, y, z axes drawn through it.
function sensor(color, position) {
  const group = new THREE.Group();
  group.position.copy(position);
  group.add(new THREE.Mesh(new THREE.BoxGeometry(1.0, 0.6, 0.16),
    new THREE.MeshStandardMaterial({ color, transparent: true, opacity: 0.8, roughness: 0.6 })));
  for (let k = 0; k < 3; k++) {
    const dir = new THREE.Vector3(k === 0 ? 0.8 : 0, k === 1 ? 0.8 : 0, k === 2 ? 0.8 : 0);
    group.add(new THREE.Line(new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(), dir]),
      new THREE.LineBasicMaterial({ color: AXIS_COLORS[k] })));
  }
  return group;
}

/** What the scene draws for `data`, as [CSS colour, description] rows of the legend. */
export function legendItems(data) {
  if (data.kind === "attitude") {
    const method = data.method === "kreisel" ? "kreisel's estimator" : `${data.method}'s filter`;
    return [[css(COLORS.estimate), `estimated attitude (${method})`],
      [css(COLORS.reference), "reference attitude (motion capture; hidden where it lost the body)"],
      [css(AXIS_COLORS[0]), "sensor x (and east)"], [css(AXIS_COLORS[1]), "sensor y (and north)"],
      [css(AXIS_COLORS[2]), "sensor z (and up)"]];
  }
  if (data.kind === "foucault") {
    return [[css(COLORS.swing), "swing plane (turns with −Ω sin λ)"],
      [css(COLORS.swing), "turning points of the bob, magnified"], ["#aa3322", "bob"]];
  }
  const axes = [[css(AXIS_COLORS[0]), "principal axis 1 (and space x)"], [css(AXIS_COLORS[1]), "principal axis 2 (and space y)"],
    [css(AXIS_COLORS[2]), "principal axis 3 (and space z)"]];
  const arrows = [[css(COLORS.omega), "ω, angular velocity"], [css(COLORS.J), "J, angular momentum"]];
  if (data.gravity) {
    return [...arrows, [css(COLORS.apex), "path of the apex (tip of the lever axis)"],
      [css(COLORS.gravity), "gravity, pivot at the origin"], ...axes];
  }
  return [...arrows, [css(COLORS.plane), "invariable plane (⊥ J, fixed in space)"],
    [css(COLORS.herpolhode), "herpolhode: ω's path on the plane"], [css(COLORS.polhode), "polhode: ω's path in the body"],
    [css(COLORS.ellipsoid), "inertia ellipsoid (as ω·Iω = 2T), rolling on the plane"], ...axes];
}

/** The legend as rows of a swatch (an <i>, a short bar of the colour) and the description. */
export function legendRows(data) {
  return legendItems(data).map(([color, text]) => {
    const row = document.createElement("div");
    const swatch = document.createElement("i");
    swatch.style.cssText = `background:${color};display:inline-block;width:14px;height:4px;margin:0 6px 3px 0;` +
      "vertical-align:middle";
    row.append(swatch, text);
    return row;
  });
}

export class Viewer {
  constructor(canvas) {
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setClearColor(0xf7f7f5);
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.05, 100);
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(5.6, -3.4, 2.6);
    this.camera.lookAt(0, 0, 0.3);
    this.scene.add(new THREE.AmbientLight(0xffffff, 0.55));
    const sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(3, -2, 5);
    this.scene.add(sun);
    this.world = new THREE.Group();
    this.scene.add(this.world);
    this.frame = "space";
  }

  resize() {
    const c = this.renderer.domElement;
    const w = c.clientWidth, h = c.clientHeight;
    if (w && h && (c.width !== Math.round(w * this.renderer.getPixelRatio()) || this.camera.aspect !== w / h)) {
      this.renderer.setSize(w, h, false);
      this.camera.aspect = w / h;
      this.camera.updateProjectionMatrix();
    }
  }

  clear() {
    for (const child of [...this.world.children]) {
      this.world.remove(child);
      child.traverse((o) => { o.geometry?.dispose(); o.material?.dispose?.(); });
    }
  }

  load(data) {
    this.clear();
    this.data = data;
    const space = new THREE.AxesHelper(0.6);
    this.world.add(space);
    if (data.kind === "foucault") return this.loadFoucault(data);
    if (data.kind === "attitude") return this.loadAttitude(data);
    const heavy = !!data.gravity;
    const info = data.analysis;
    const P = info.principal_axes; // columns: principal axes in body components
    const principal = new THREE.Matrix4().set(P[0][0], P[0][1], P[0][2], 0, P[1][0], P[1][1], P[1][2], 0,
      P[2][0], P[2][1], P[2][2], 0, 0, 0, 0, 1);
    this.body = new THREE.Group();
    this.world.add(this.body);
    const size = boxSize(info.principal_moments).map((e) => e * (heavy ? 1.0 : 1.3));
    const box = new THREE.Mesh(new THREE.BoxGeometry(...size),
      new THREE.MeshStandardMaterial({ color: 0xe0b060, transparent: true, opacity: heavy ? 0.9 : 0.55, roughness: 0.6 }));
    box.applyMatrix4(principal);
    this.body.add(box);
    const axes = new THREE.Group();
    for (let k = 0; k < 3; k++) {
      const dir = new THREE.Vector3(P[0][k], P[1][k], P[2][k]);
      const g = new THREE.BufferGeometry().setFromPoints([dir.clone().multiplyScalar(-1.1), dir.clone().multiplyScalar(1.1)]);
      axes.add(new THREE.Line(g, new THREE.LineBasicMaterial({ color: AXIS_COLORS[k] })));
    }
    this.body.add(axes);
    // one scale for omega, the ellipsoid, the invariable plane and both trails (Poinsot construction)
    const T = info.T;
    const semi = info.principal_moments.map((I) => Math.sqrt((2 * Math.abs(T)) / I));
    this.s = T > 0 ? 1.5 / Math.max(...semi) : 1;
    this.omegaArrow = arrow(COLORS.omega);
    this.JArrow = arrow(COLORS.J);
    this.world.add(this.omegaArrow, this.JArrow);
    this.J0 = Math.max(1e-300, info.J_norm);
    const n = data.n_samples || data.t.length;
    if (heavy) {
      const lever = vec(data.gravity.lever);
      const lhat = lever.clone().normalize();
      const k = lhat.x ? 0 : lhat.y ? 1 : 2;
      box.position.copy(lhat.clone().multiplyScalar(0.5 * size[k]));
      const pivot = new THREE.Mesh(new THREE.SphereGeometry(0.05, 16, 12), new THREE.MeshStandardMaterial({ color: 0x333333 }));
      this.world.add(pivot);
      const g = new THREE.ArrowHelper(new THREE.Vector3(0, 0, -1), new THREE.Vector3(-1.6, 1.6, 1.2), 0.8, COLORS.gravity, 0.15, 0.08);
      this.world.add(g);
      const apex = lhat.clone().multiplyScalar(size[k] * 1.05);
      this.trails = [trail(n, COLORS.apex, (i) => apex.clone().applyQuaternion(quat(data.q[i])))];
      const sphere = new THREE.Mesh(new THREE.SphereGeometry(size[k] * 1.05, 32, 16),
        new THREE.MeshBasicMaterial({ color: 0x8899aa, wireframe: true, transparent: true, opacity: 0.12 }));
      this.world.add(sphere, ...this.trails);
      this.bodyTrails = [];
    } else {
      const ellipsoid = new THREE.Mesh(new THREE.SphereGeometry(1, 32, 20),
        new THREE.MeshBasicMaterial({ color: COLORS.ellipsoid, wireframe: true, transparent: true, opacity: 0.25 }));
      ellipsoid.scale.set(...semi.map((a) => a * this.s));
      ellipsoid.applyMatrix4(principal);
      this.body.add(ellipsoid);
      const Jhat = vec(info.J).normalize();
      const plane = new THREE.Mesh(new THREE.CircleGeometry(2.2, 48),
        new THREE.MeshBasicMaterial({ color: COLORS.plane, transparent: true, opacity: 0.22, side: THREE.DoubleSide }));
      plane.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), Jhat);
      plane.position.copy(Jhat.clone().multiplyScalar((2 * T / info.J_norm) * this.s));
      this.world.add(plane);
      this.trails = [trail(n, COLORS.herpolhode, (i) => vec(data.omega_space[i], this.s))]; // herpolhode
      this.bodyTrails = [trail(n, COLORS.polhode, (i) => vec(data.omega[i], this.s))]; // polhode
      this.world.add(...this.trails);
      this.body.add(...this.bodyTrails);
    }
    this.filled = 0;
    this.append();
  }

  /** Add the samples that arrived since the last call to the trails. */
  append() {
    const d = this.data, upto = Math.min(d.t.length, d.n_samples || d.t.length);
    for (const tr of this.trails.concat(this.bodyTrails)) {
      const position = tr.geometry.attributes.position;
      for (let i = this.filled; i < upto; i++) { const p = tr.point(i); position.setXYZ(i, p.x, p.y, p.z); }
      position.needsUpdate = true;
      if (this.filled < upto) tr.geometry.computeBoundingSphere();
    }
    this.filled = upto;
  }

  // An estimated attitude and its reference: two sensors side by side, each turned by its own attitude.
  loadAttitude() {
    this.body = sensor(COLORS.estimate, BESIDE.clone().negate());
    this.reference = sensor(COLORS.reference, BESIDE);
    this.world.add(this.body, this.reference);
    this.trails = [];
    this.bodyTrails = [];
    this.filled = this.data.t.length;
  }

  /** The attitudes the scene shows now, scalar first: {estimate, reference} (reference null where hidden). */
  attitudes() {
    const q = (o) => [o.quaternion.w, o.quaternion.x, o.quaternion.y, o.quaternion.z];
    return { estimate: q(this.body), reference: this.reference.visible ? q(this.reference) : null };
  }

  loadFoucault(data) {
    const L = 2.0;
    this.body = null;
    const ground = new THREE.Mesh(new THREE.CircleGeometry(1.2, 64),
      new THREE.MeshBasicMaterial({ color: 0xccccbb, side: THREE.DoubleSide }));
    this.world.add(ground);
    this.bob = new THREE.Mesh(new THREE.SphereGeometry(0.08, 16, 12), new THREE.MeshStandardMaterial({ color: 0xaa3322 }));
    this.string = new THREE.Line(new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(0, 0, L), new THREE.Vector3()]),
      new THREE.LineBasicMaterial({ color: 0x333333 }));
    this.swingPlane = new THREE.Line(new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(-1.2, 0, 0.01), new THREE.Vector3(1.2, 0, 0.01)]),
      new THREE.LineBasicMaterial({ color: COLORS.swing }));
    // turning points on the floor, exaggerated: the rosette of the swing plane's slow turn
    const gain = 1.0 / Math.max(...data.tilt.map(Math.abs));
    this.footprints = data.t.map((_, i) => {
      const sign = i % 2 ? -1 : 1, r = sign * Math.abs(data.tilt[i]) * gain;
      return new THREE.Vector3(r * Math.cos(data.swing_azimuth[i]), r * Math.sin(data.swing_azimuth[i]), 0.02);
    });
    this.trails = [trail(this.footprints.length, COLORS.swing, (i) => this.footprints[i])];
    this.bodyTrails = [];
    this.world.add(this.bob, this.string, this.swingPlane, ...this.trails);
    this.L = L;
    this.filled = 0;
    this.append();
  }

  show(i) {
    const d = this.data;
    if (!d) return;
    for (const tr of this.trails.concat(this.bodyTrails)) tr.geometry.setDrawRange(0, Math.min(i + 1, this.filled));
    if (d.kind === "foucault") {
      const p = this.footprints[i];
      const bob = new THREE.Vector3(p.x * 0.5, p.y * 0.5, 0.3);
      this.bob.position.copy(bob);
      this.string.geometry.setFromPoints([new THREE.Vector3(0, 0, this.L), bob]);
      this.swingPlane.rotation.z = d.swing_azimuth[i];
      this.world.quaternion.identity();
      return;
    }
    const q = quat(d.q[i]);
    this.body.quaternion.copy(q);
    if (d.kind === "attitude") {
      const ref = d.q_ref[i];
      this.reference.visible = ref !== null;
      if (ref !== null) this.reference.quaternion.copy(quat(ref));
      if (this.frame === "body") this.world.quaternion.copy(q.clone().invert());
      else this.world.quaternion.identity();
      return;
    }
    setArrow(this.omegaArrow, vec(d.omega_space[i], this.s));
    setArrow(this.JArrow, vec(d.J[i], 1.8 / this.J0));
    // body-frame camera: undo the attitude so the body stands still and space turns around it
    if (this.frame === "body") this.world.quaternion.copy(q.clone().invert());
    else this.world.quaternion.identity();
  }

  render() {
    this.resize();
    this.renderer.render(this.scene, this.camera);
  }
}
