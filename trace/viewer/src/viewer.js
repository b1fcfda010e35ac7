// skinmesh trace viewer: reads the trace document embedded in the page
// (<script id="skinmesh-trace" type="application/json">, format in trace/FORMAT.md)
// and shows the mesh step by step with three.js.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { LineSegments2 } from 'three/examples/jsm/lines/LineSegments2.js';
import { LineSegmentsGeometry } from 'three/examples/jsm/lines/LineSegmentsGeometry.js';
import { LineMaterial } from 'three/examples/jsm/lines/LineMaterial.js';

const LAYERS = ['skin', 'front', 'critical', 'arcs', 'spheres', 'quality'];
const DEFAULT_LAYERS = { skin: true, front: true, critical: true, arcs: true, spheres: false, quality: false };
const QUALITY_MODES = ['min_angle', 'L', 'U'];
const NEVER = 0x7fffffff; // "died = -1" stored as a step that is never reached

const HEX = {
  surface: 0xebe5d1,
  added: 0xf0a23a,
  backTint: 0x8d99ab,
  notFinal: 0xb0b0b0,
  wire: 0x2a2a2a,
  front: 0xe00000,
  focus: 0xffd400,
  arcLive: 0x2b2b2b,
  arcDead: 0x555555,
  background: 0xdfe4ea,
  index: [0xe00000, 0x1f5fd6, 0x0a9a2a],  // minimum, saddle, maximum (the paper's colours)
};

// Colour ramps in sRGB (the legend draws the same stops as a CSS gradient).
const RAMPS = {
  angle: [[0, '#d7191c'], [0.25, '#f08a24'], [0.5, '#e8d534'], [0.75, '#35a853'], [1, '#2b6fd0']],
  ratio: [[0, '#d7191c'], [0.5, '#e8d534'], [1, '#35a853']],
};

function $(id) { return document.getElementById(id); }

function hexToRgb(h) {
  const n = parseInt(h.slice(1), 16);
  return [(n >> 16) & 255, (n >> 8) & 255, n & 255].map((x) => x / 255);
}

// 256-entry lookup table of linear RGB for a ramp.
function rampLut(stops) {
  const lut = new Float32Array(256 * 3);
  const c = new THREE.Color();
  for (let i = 0; i < 256; i++) {
    const t = i / 255;
    let k = 0;
    while (k < stops.length - 2 && t > stops[k + 1][0]) k++;
    const [t0, h0] = stops[k];
    const [t1, h1] = stops[k + 1];
    const u = t1 > t0 ? Math.min(1, Math.max(0, (t - t0) / (t1 - t0))) : 0;
    const a = hexToRgb(h0);
    const b = hexToRgb(h1);
    c.setRGB(a[0] + (b[0] - a[0]) * u, a[1] + (b[1] - a[1]) * u, a[2] + (b[2] - a[2]) * u, THREE.SRGBColorSpace);
    lut[3 * i] = c.r;
    lut[3 * i + 1] = c.g;
    lut[3 * i + 2] = c.b;
  }
  return lut;
}

function linear(hex) {
  const c = new THREE.Color(hex);
  return [c.r, c.g, c.b];
}

function num(x, fallback) {
  return typeof x === 'number' && Number.isFinite(x) ? x : fallback;
}

function fmt(x) {
  if (typeof x === 'number') {
    if (Number.isInteger(x)) return x.toLocaleString('en-US');
    return String(Math.round(x * 1000) / 1000);
  }
  if (x === null || x === undefined) return '–';
  return String(x);
}

// ---------------------------------------------------------------------------
// The trace, preprocessed into typed arrays; builds the mesh at a step.
class Model {
  constructor(t) {
    this.t = t;
    const V = Array.isArray(t.vertices) ? t.vertices : [];
    this.nV = Math.floor(V.length / 3);
    this.base = new Float32Array(V.slice(0, 3 * this.nV));
    this.pos = new Float32Array(this.base);
    this.posStep = -1;
    this.posVersion = 0;

    // Moves sorted by step (stable: later records win within a step).
    const M = Array.isArray(t.moves) ? t.moves : [];
    const nM = Math.floor(M.length / 5);
    const order = [];
    for (let i = 0; i < nM; i++) {
      const v = M[5 * i];
      if (Number.isInteger(v) && v >= 0 && v < this.nV) order.push(i);
    }
    order.sort((i, j) => M[5 * i + 1] - M[5 * j + 1] || i - j);
    this.nMoves = order.length;
    this.mvVertex = new Int32Array(order.length);
    this.mvStep = new Float64Array(order.length);
    this.mvPos = new Float32Array(3 * order.length);
    order.forEach((i, k) => {
      this.mvVertex[k] = M[5 * i];
      this.mvStep[k] = M[5 * i + 1];
      this.mvPos[3 * k] = M[5 * i + 2];
      this.mvPos[3 * k + 1] = M[5 * i + 3];
      this.mvPos[3 * k + 2] = M[5 * i + 4];
    });
    this.movePtr = 0;

    // Steps.
    this.steps = Array.isArray(t.steps) && t.steps.length ? t.steps : [{ stage: '', op: '', text: '' }];
    const S = this.steps.length;
    this.S = S;

    // Faces.
    const F = Array.isArray(t.faces) ? t.faces : [];
    const FS = Array.isArray(t.face_steps) ? t.face_steps : [];
    const nF = Math.min(Math.floor(F.length / 3), Math.floor(FS.length / 2));
    this.nF = nF;
    this.faces = new Uint32Array(3 * nF);
    this.born = new Int32Array(nF);
    this.died = new Int32Array(nF);
    const diff = new Float64Array(S + 1);
    for (let f = 0; f < nF; f++) {
      const a = F[3 * f];
      const b = F[3 * f + 1];
      const c = F[3 * f + 2];
      this.faces[3 * f] = a;
      this.faces[3 * f + 1] = b;
      this.faces[3 * f + 2] = c;
      let born = FS[2 * f];
      let died = FS[2 * f + 1];
      born = Number.isFinite(born) ? born : NEVER;
      died = died === -1 || !Number.isFinite(died) ? NEVER : died;
      const valid = a >= 0 && b >= 0 && c >= 0 && a < this.nV && b < this.nV && c < this.nV;
      if (!valid) born = NEVER;
      this.born[f] = born;
      this.died[f] = died;
      // alive on steps max(born, 0) .. min(died, S) - 1
      const lo = Math.max(born, 0);
      const hi = Math.min(died, S);
      if (lo < hi) {
        diff[lo] += 1;
        diff[hi] -= 1;
      }
    }
    this.aliveCount = new Int32Array(S);
    let run = 0;
    let maxAlive = 0;
    for (let s = 0; s < S; s++) {
      run += diff[s];
      this.aliveCount[s] = run;
      if (run > maxAlive) maxAlive = run;
    }
    this.cap = Math.max(1, maxAlive);

    // Work buffers.
    this.alive = new Int32Array(this.cap);
    this.nAlive = 0;
    this.vnormal = new Float32Array(Math.max(3, 3 * this.nV));
    this.fnormal = new Float32Array(3 * this.cap);
    this.bucketStart = new Int32Array(this.nV + 1);
    this.bucketFill = new Int32Array(Math.max(1, this.nV));
    this.bucketOther = new Uint32Array(3 * this.cap);
    this.stamp = new Uint32Array(Math.max(1, this.nV));
    this.stampId = 0;
    this.edges = new Uint32Array(6 * this.cap); // unique edges, vertex pairs
    this.nEdges = 0;
    this.frontEdges = new Uint32Array(6 * this.cap);
    this.nFront = 0;
    this.nVerts = 0;
    this.meanEdge = 0;
    this.faceColorCache = {};

    // Bounds.
    this.bounds = this.computeBounds();

    // The typed arrays replace the document's big arrays.
    for (const k of ['vertices', 'vertex_step', 'moves', 'faces', 'face_steps']) t[k] = null;
  }

  computeBounds() {
    const b = this.t.bounds;
    const ok = (p) => Array.isArray(p) && p.length === 3 && p.every((x) => Number.isFinite(x));
    const min = new THREE.Vector3(Infinity, Infinity, Infinity);
    const max = new THREE.Vector3(-Infinity, -Infinity, -Infinity);
    if (b && ok(b.min) && ok(b.max)) {
      min.fromArray(b.min);
      max.fromArray(b.max);
    }
    const add = (x, y, z) => {
      if (!Number.isFinite(x + y + z)) return;
      min.x = Math.min(min.x, x); min.y = Math.min(min.y, y); min.z = Math.min(min.z, z);
      max.x = Math.max(max.x, x); max.y = Math.max(max.y, y); max.z = Math.max(max.z, z);
    };
    if (!(min.x <= max.x)) {
      for (let i = 0; i < this.nV; i++) add(this.base[3 * i], this.base[3 * i + 1], this.base[3 * i + 2]);
      for (let k = 0; k < this.nMoves; k++) add(this.mvPos[3 * k], this.mvPos[3 * k + 1], this.mvPos[3 * k + 2]);
    }
    // The Morse-Smale complex may reach beyond the mesh's box.
    for (const c of this.critical()) if (ok(c.p)) add(c.p[0], c.p[1], c.p[2]);
    if (!(min.x <= max.x)) {
      min.set(-1, -1, -1);
      max.set(1, 1, 1);
    }
    return new THREE.Box3(min, max);
  }

  critical() { return Array.isArray(this.t.critical) ? this.t.critical : []; }
  lines() { return Array.isArray(this.t.lines) ? this.t.lines : []; }

  // Vertex positions at step s (moves with step <= s applied, in order).
  ensurePositions(s) {
    if (s < this.posStep) {
      this.pos.set(this.base);
      this.movePtr = 0;
      this.posVersion++;
    }
    const P = this.pos;
    let changed = false;
    while (this.movePtr < this.nMoves && this.mvStep[this.movePtr] <= s) {
      const k = this.movePtr++;
      const v = this.mvVertex[k];
      P[3 * v] = this.mvPos[3 * k];
      P[3 * v + 1] = this.mvPos[3 * k + 1];
      P[3 * v + 2] = this.mvPos[3 * k + 2];
      changed = true;
    }
    if (changed) this.posVersion++;
    this.posStep = s;
  }

  // The mesh at step s: alive faces, normals, unique edges, boundary edges.
  build(s) {
    this.ensurePositions(s);
    const { faces, born, died, nF, alive } = this;
    let n = 0;
    for (let f = 0; f < nF; f++) {
      if (born[f] <= s && s < died[f]) {
        if (n === alive.length) break; // cannot happen: cap is the maximum count
        alive[n++] = f;
      }
    }
    this.nAlive = n;

    // Area-weighted vertex normals, face normals, vertex count.
    const P = this.pos;
    const N = this.vnormal;
    const FN = this.fnormal;
    N.fill(0);
    const stamp = this.stamp;
    const id = ++this.stampId;
    let nVerts = 0;
    for (let i = 0; i < n; i++) {
      const f = alive[i];
      const a = faces[3 * f];
      const b = faces[3 * f + 1];
      const c = faces[3 * f + 2];
      const ax = P[3 * a], ay = P[3 * a + 1], az = P[3 * a + 2];
      const ux = P[3 * b] - ax, uy = P[3 * b + 1] - ay, uz = P[3 * b + 2] - az;
      const vx = P[3 * c] - ax, vy = P[3 * c + 1] - ay, vz = P[3 * c + 2] - az;
      const nx = uy * vz - uz * vy;
      const ny = uz * vx - ux * vz;
      const nz = ux * vy - uy * vx;
      N[3 * a] += nx; N[3 * a + 1] += ny; N[3 * a + 2] += nz;
      N[3 * b] += nx; N[3 * b + 1] += ny; N[3 * b + 2] += nz;
      N[3 * c] += nx; N[3 * c + 1] += ny; N[3 * c + 2] += nz;
      const len = Math.hypot(nx, ny, nz) || 1;
      FN[3 * i] = nx / len; FN[3 * i + 1] = ny / len; FN[3 * i + 2] = nz / len;
      if (stamp[a] !== id) { stamp[a] = id; nVerts++; }
      if (stamp[b] !== id) { stamp[b] = id; nVerts++; }
      if (stamp[c] !== id) { stamp[c] = id; nVerts++; }
    }
    this.nVerts = nVerts;

    // Edges: bucket every edge (lo, hi) by its lower vertex (counting sort), then count
    // equal hi within a bucket; an edge used by exactly one alive face is a boundary edge.
    const start = this.bucketStart;
    start.fill(0);
    for (let i = 0; i < n; i++) {
      const f = alive[i];
      const a = faces[3 * f], b = faces[3 * f + 1], c = faces[3 * f + 2];
      start[(a < b ? a : b) + 1]++;
      start[(b < c ? b : c) + 1]++;
      start[(c < a ? c : a) + 1]++;
    }
    const nV = this.nV;
    for (let v = 0; v < nV; v++) start[v + 1] += start[v];
    const fillPtr = this.bucketFill;
    fillPtr.set(start.subarray(0, nV));
    const other = this.bucketOther;
    for (let i = 0; i < n; i++) {
      const f = alive[i];
      const a = faces[3 * f], b = faces[3 * f + 1], c = faces[3 * f + 2];
      if (a < b) other[fillPtr[a]++] = b; else other[fillPtr[b]++] = a;
      if (b < c) other[fillPtr[b]++] = c; else other[fillPtr[c]++] = b;
      if (c < a) other[fillPtr[c]++] = a; else other[fillPtr[a]++] = c;
    }
    const E = this.edges;
    const B = this.frontEdges;
    let ne = 0;
    let nb = 0;
    for (let v = 0; v < nV; v++) {
      const lo = start[v], hi = start[v + 1];
      for (let i = lo; i < hi; i++) {
        const w = other[i];
        let seen = false;
        for (let j = lo; j < i; j++) if (other[j] === w) { seen = true; break; }
        if (seen) continue; // counted at its first occurrence
        let uses = 1;
        for (let j = i + 1; j < hi; j++) if (other[j] === w) uses++;
        E[2 * ne] = v; E[2 * ne + 1] = w; ne++;
        if (uses === 1) { B[2 * nb] = v; B[2 * nb + 1] = w; nb++; }
      }
    }
    this.nEdges = ne;
    this.nFront = nb;

    // Mean edge length (sampled), for the wireframe's opacity.
    let sum = 0;
    let k = 0;
    const stride = Math.max(1, Math.floor(ne / 4096));
    for (let i = 0; i < ne; i += stride, k++) {
      const a = E[2 * i], b = E[2 * i + 1];
      sum += Math.hypot(P[3 * a] - P[3 * b], P[3 * a + 1] - P[3 * b + 1], P[3 * a + 2] - P[3 * b + 2]);
    }
    this.meanEdge = k ? sum / k : 0;
  }

  // Per face record colours (linear RGB) for a quality measure.
  faceColors(mode) {
    if (this.faceColorCache[mode]) return this.faceColorCache[mode];
    const q = this.t.quality && Array.isArray(this.t.quality[mode]) ? this.t.quality[mode] : null;
    const lut = rampLut(mode === 'min_angle' ? RAMPS.angle : RAMPS.ratio);
    const grey = linear(HEX.notFinal);
    const bound = num(this.t.min_angle_bound, 20);
    const out = new Float32Array(3 * Math.max(1, this.nF));
    for (let f = 0; f < this.nF; f++) {
      let r = grey[0], g = grey[1], b = grey[2];
      if (q && this.died[f] === NEVER && f < q.length && Number.isFinite(q[f])) {
        let t;
        if (mode === 'min_angle') t = (q[f] - bound) / (60 - bound);
        else t = q[f] > 0 ? Math.log2(q[f]) : 0;
        const i = Math.round(255 * Math.min(1, Math.max(0, t)));
        r = lut[3 * i]; g = lut[3 * i + 1]; b = lut[3 * i + 2];
      }
      out[3 * f] = r; out[3 * f + 1] = g; out[3 * f + 2] = b;
    }
    this.faceColorCache[mode] = out;
    return out;
  }
}

// ---------------------------------------------------------------------------
function loadTrace() {
  const el = $('skinmesh-trace');
  const text = el ? el.textContent.trim() : '';
  if (!text.startsWith('{')) return { error: 'No trace is embedded in this page (it is the viewer template).' };
  let t;
  try {
    t = JSON.parse(text);
  } catch (e) {
    return { error: 'The embedded trace is not valid JSON: ' + e.message };
  }
  if (!t || typeof t !== 'object' || t.format !== 'skinmesh-trace') {
    return { error: 'The embedded document is not a skinmesh trace.' };
  }
  return { trace: t };
}

function showMessage(text) {
  const m = $('message');
  m.textContent = text;
  m.hidden = false;
}

class Viewer {
  constructor(trace) {
    this.trace = trace;
    this.model = new Model(trace);
    this.step = 0;
    this.layers = Object.assign({}, DEFAULT_LAYERS);
    this.qualityMode = 'min_angle';
    this.playing = false;
    this.builtStep = -1;
    this.renderPending = false;
    this.ready = false;

    this.initRenderer();
    this.initScene();
    this.initPanel();
  }

  // ----- three.js setup -----
  initRenderer() {
    const canvas = $('canvas');
    const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    renderer.setClearColor(HEX.background, 1);
    this.renderer = renderer;

    const box = this.model.bounds;
    this.centre = box.getCenter(new THREE.Vector3());
    this.radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 1e-3);

    const hd = this.trace.height_direction;
    const up = new THREE.Vector3(0, 0, 1);
    if (Array.isArray(hd) && hd.length === 3 && hd.every(Number.isFinite) && Math.hypot(hd[0], hd[1], hd[2]) > 1e-9) {
      up.fromArray(hd).normalize();
    }
    this.up = up;
    const ref = Math.abs(up.x) < 0.9 ? new THREE.Vector3(1, 0, 0) : new THREE.Vector3(0, 1, 0);
    this.e1 = ref.clone().addScaledVector(up, -ref.dot(up)).normalize();
    this.e2 = new THREE.Vector3().crossVectors(up, this.e1);

    const camera = new THREE.PerspectiveCamera(35, 1, this.radius * 0.01, this.radius * 200);
    camera.up.copy(up);
    this.camera = camera;
    this.controls = new OrbitControls(camera, canvas);
    this.controls.target.copy(this.centre);
    this.controls.addEventListener('change', () => this.requestRender());
  }

  initScene() {
    const scene = new THREE.Scene();
    this.scene = scene;
    const R = this.radius;
    const m = this.model;

    scene.add(new THREE.HemisphereLight(0xffffff, 0x50525a, 1.1));
    const head = new THREE.DirectionalLight(0xffffff, 2.0);
    head.position.set(-0.4, 0.6, 1); // relative to the camera: upper left, in front
    this.camera.add(head);
    scene.add(this.camera);

    // Skin: non-indexed triangles (per-face colours), front and back materials.
    const cap = m.cap;
    const geo = new THREE.BufferGeometry();
    const mk = (n) => new THREE.BufferAttribute(new Float32Array(n), 3).setUsage(THREE.DynamicDrawUsage);
    geo.setAttribute('position', mk(9 * cap));
    geo.setAttribute('normal', mk(9 * cap));
    geo.setAttribute('color', mk(9 * cap));
    geo.setDrawRange(0, 0);
    const common = { vertexColors: true, roughness: 0.72, metalness: 0.0, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 };
    this.meshFront = new THREE.Mesh(geo, new THREE.MeshStandardMaterial(Object.assign({ side: THREE.FrontSide }, common)));
    this.meshBack = new THREE.Mesh(geo, new THREE.MeshStandardMaterial(Object.assign({ side: THREE.BackSide, color: HEX.backTint }, common)));
    this.meshGeo = geo;

    // Wireframe: indexed lines over the vertex position array.
    const wgeo = new THREE.BufferGeometry();
    this.wirePos = new THREE.BufferAttribute(m.pos.length ? m.pos : new Float32Array(3), 3).setUsage(THREE.DynamicDrawUsage);
    wgeo.setAttribute('position', this.wirePos);
    this.wireIndex = new THREE.BufferAttribute(m.edges, 1).setUsage(THREE.DynamicDrawUsage);
    wgeo.setIndex(this.wireIndex);
    wgeo.setDrawRange(0, 0);
    this.wire = new THREE.LineSegments(wgeo, new THREE.LineBasicMaterial({ color: HEX.wire, transparent: true, opacity: 0.3, depthWrite: false }));
    this.wirePosVersion = -1;

    for (const o of [this.meshFront, this.meshBack, this.wire]) {
      o.frustumCulled = false;
      scene.add(o);
    }

    // Front: thick red boundary edges and the focus point.
    this.lineMaterials = [];
    const frontMat = new LineMaterial({ color: HEX.front, linewidth: 3 });
    this.lineMaterials.push(frontMat);
    this.front = new LineSegments2(new LineSegmentsGeometry(), frontMat);
    this.front.visible = false;
    scene.add(this.front);

    const rc = Math.max(R * 0.016, 1e-3); // critical point radius
    this.rc = rc;
    const sphereGeo = new THREE.SphereGeometry(1, 20, 14);
    this.focus = new THREE.Mesh(sphereGeo, new THREE.MeshStandardMaterial({ color: HEX.focus, emissive: 0x5a4a00, roughness: 0.4 }));
    this.focus.scale.setScalar(rc * 1.1);
    this.focus.visible = false;
    scene.add(this.focus);

    // Critical points.
    const crit = m.critical().filter((c) => Array.isArray(c.p) && c.p.length === 3);
    this.critCount = crit.length;
    const live = crit.filter((c) => c.live !== false);
    const dead = crit.filter((c) => c.live === false);
    const mat4 = new THREE.Matrix4();
    const col = new THREE.Color();
    const instanced = (list, material, radiusOf) => {
      const im = new THREE.InstancedMesh(sphereGeo, material, list.length);
      list.forEach((c, i) => {
        const r = radiusOf(c);
        mat4.makeScale(r, r, r).setPosition(c.p[0], c.p[1], c.p[2]);
        im.setMatrixAt(i, mat4);
        im.setColorAt(i, col.setHex(HEX.index[c.index] !== undefined ? HEX.index[c.index] : 0x888888));
      });
      im.instanceMatrix.needsUpdate = true;
      if (im.instanceColor) im.instanceColor.needsUpdate = true;
      im.computeBoundingSphere();
      return im;
    };
    this.critical = new THREE.Group();
    if (live.length) this.critical.add(instanced(live, new THREE.MeshStandardMaterial({ roughness: 0.45 }), () => rc));
    if (dead.length) {
      this.critical.add(instanced(dead, new THREE.MeshStandardMaterial({ roughness: 0.45, transparent: true, opacity: 0.4, depthWrite: false }), () => rc * 0.55));
    }
    scene.add(this.critical);

    // Protecting spheres.
    const withSphere = crit.filter((c) => num(c.sphere, 0) > 0);
    this.sphereCount = withSphere.length;
    this.spheres = new THREE.Group();
    if (withSphere.length) {
      const sg = new THREE.SphereGeometry(1, 28, 18);
      const solid = instanced(withSphere, new THREE.MeshStandardMaterial({ transparent: true, opacity: 0.16, depthWrite: false, roughness: 0.9 }), (c) => c.sphere);
      solid.geometry = sg;
      const wf = instanced(withSphere, new THREE.MeshBasicMaterial({ wireframe: true, transparent: true, opacity: 0.22, depthWrite: false }), (c) => c.sphere);
      wf.geometry = new THREE.SphereGeometry(1, 14, 9);
      solid.computeBoundingSphere();
      wf.computeBoundingSphere();
      this.spheres.add(solid, wf);
    }
    scene.add(this.spheres);

    // Arcs (integral lines).
    this.arcs = new THREE.Group();
    const segs = (list) => {
      const out = [];
      for (const l of list) {
        const p = Array.isArray(l.points) ? l.points : [];
        const k = Math.floor(p.length / 3);
        for (let i = 0; i + 1 < k; i++) out.push(p[3 * i], p[3 * i + 1], p[3 * i + 2], p[3 * i + 3], p[3 * i + 4], p[3 * i + 5]);
      }
      return out;
    };
    const lines = m.lines();
    const liveSegs = segs(lines.filter((l) => l.live !== false));
    const deadSegs = segs(lines.filter((l) => l.live === false));
    this.arcCount = lines.length;
    if (liveSegs.length) {
      const g = new LineSegmentsGeometry();
      g.setPositions(liveSegs);
      const mat = new LineMaterial({ color: HEX.arcLive, linewidth: 2 });
      this.lineMaterials.push(mat);
      this.arcs.add(new LineSegments2(g, mat));
    }
    if (deadSegs.length) {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(deadSegs, 3));
      this.arcs.add(new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: HEX.arcDead, transparent: true, opacity: 0.35, depthWrite: false })));
    }
    scene.add(this.arcs);

    this.surfaceRgb = linear(HEX.surface);
    this.addedRgb = linear(HEX.added);
  }

  // ----- camera -----
  framedDistance() {
    const vfov = THREE.MathUtils.degToRad(this.camera.fov);
    const hfov = 2 * Math.atan(Math.tan(vfov / 2) * this.camera.aspect);
    return (this.radius / Math.sin(Math.min(vfov, hfov) / 2)) * 0.95;
  }

  setView(azDeg, elDeg, distFactor) {
    const az = THREE.MathUtils.degToRad(azDeg);
    const el = THREE.MathUtils.degToRad(Math.max(-89.9, Math.min(89.9, elDeg)));
    const d = this.framedDistance() * (distFactor > 0 ? distFactor : 1);
    const dir = new THREE.Vector3()
      .addScaledVector(this.e1, Math.cos(el) * Math.cos(az))
      .addScaledVector(this.e2, Math.cos(el) * Math.sin(az))
      .addScaledVector(this.up, Math.sin(el));
    this.controls.target.copy(this.centre);
    this.camera.position.copy(this.centre).addScaledVector(dir, d);
    this.camera.lookAt(this.centre);
    this.controls.update();
  }

  resize() {
    const view = $('view');
    const w = Math.max(1, view.clientWidth);
    const h = Math.max(1, view.clientHeight);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    for (const m of this.lineMaterials) m.resolution.set(w, h);
  }

  // ----- step -----
  showStep(s) {
    const S = this.model.S;
    s = Math.max(0, Math.min(S - 1, Math.round(Number(s)) || 0));
    this.step = s;
    this.rebuild();
    this.updatePanel();
  }

  rebuild() {
    const m = this.model;
    const s = this.step;
    if (this.builtStep !== s) {
      m.build(s);
      this.builtStep = s;
      this.fillMesh();
      this.fillLines();
    } else {
      this.fillColors();
    }
    this.applyVisibility();
  }

  fillMesh() {
    const m = this.model;
    const n = m.nAlive;
    const P = m.pos, N = m.vnormal, FN = m.fnormal, faces = m.faces, alive = m.alive;
    const pos = this.meshGeo.attributes.position;
    const nrm = this.meshGeo.attributes.normal;
    const pa = pos.array, na = nrm.array;
    let o = 0;
    for (let i = 0; i < n; i++) {
      const f = alive[i];
      for (let k = 0; k < 3; k++) {
        const v = faces[3 * f + k];
        pa[o] = P[3 * v]; pa[o + 1] = P[3 * v + 1]; pa[o + 2] = P[3 * v + 2];
        let x = N[3 * v], y = N[3 * v + 1], z = N[3 * v + 2];
        const len = Math.hypot(x, y, z);
        if (len > 0) { x /= len; y /= len; z /= len; } else { x = FN[3 * i]; y = FN[3 * i + 1]; z = FN[3 * i + 2]; }
        na[o] = x; na[o + 1] = y; na[o + 2] = z;
        o += 3;
      }
    }
    for (const a of [pos, nrm]) {
      a.clearUpdateRanges();
      a.addUpdateRange(0, Math.max(o, 3));
      a.needsUpdate = true;
    }
    this.meshGeo.setDrawRange(0, 3 * n);
    this.fillColors();

    // Wireframe.
    if (this.wirePosVersion !== m.posVersion) {
      this.wirePos.needsUpdate = true;
      this.wirePosVersion = m.posVersion;
    }
    this.wireIndex.clearUpdateRanges();
    this.wireIndex.addUpdateRange(0, Math.max(2 * m.nEdges, 2));
    this.wireIndex.needsUpdate = true;
    this.wire.geometry.setDrawRange(0, 2 * m.nEdges);
  }

  fillColors() {
    const m = this.model;
    const n = m.nAlive, alive = m.alive, s = this.step;
    const col = this.meshGeo.attributes.color;
    const ca = col.array;
    const q = this.layers.quality ? m.faceColors(this.qualityMode) : null;
    const sr = this.surfaceRgb, ad = this.addedRgb;
    let o = 0;
    for (let i = 0; i < n; i++) {
      const f = alive[i];
      let r, g, b;
      if (q) { r = q[3 * f]; g = q[3 * f + 1]; b = q[3 * f + 2]; }
      else if (s > 0 && m.born[f] === s) { r = ad[0]; g = ad[1]; b = ad[2]; }
      else { r = sr[0]; g = sr[1]; b = sr[2]; }
      for (let k = 0; k < 3; k++) { ca[o] = r; ca[o + 1] = g; ca[o + 2] = b; o += 3; }
    }
    col.clearUpdateRanges();
    col.addUpdateRange(0, Math.max(o, 3));
    col.needsUpdate = true;
  }

  fillLines() {
    const m = this.model;
    const nb = m.nFront;
    if (nb > 0) {
      const P = m.pos, B = m.frontEdges;
      const arr = new Float32Array(6 * nb);
      for (let i = 0; i < nb; i++) {
        const a = B[2 * i], b = B[2 * i + 1];
        arr[6 * i] = P[3 * a]; arr[6 * i + 1] = P[3 * a + 1]; arr[6 * i + 2] = P[3 * a + 2];
        arr[6 * i + 3] = P[3 * b]; arr[6 * i + 4] = P[3 * b + 1]; arr[6 * i + 5] = P[3 * b + 2];
      }
      const g = new LineSegmentsGeometry();
      g.setPositions(arr);
      this.front.geometry.dispose();
      this.front.geometry = g;
    }
    const st = m.steps[this.step] || {};
    const fp = st.focus;
    this.hasFocus = Array.isArray(fp) && fp.length === 3 && fp.every(Number.isFinite);
    if (this.hasFocus) this.focus.position.set(fp[0], fp[1], fp[2]);
  }

  applyVisibility() {
    const L = this.layers;
    const m = this.model;
    this.meshFront.visible = this.meshBack.visible = L.skin && m.nAlive > 0;
    this.wire.visible = L.skin && m.nEdges > 0;
    this.front.visible = L.front && m.nFront > 0;
    this.focus.visible = L.front && this.hasFocus;
    this.critical.visible = L.critical;
    this.arcs.visible = L.arcs;
    this.spheres.visible = L.spheres;
  }

  // ----- rendering -----
  renderNow() {
    this.renderPending = false;
    this.updateWireOpacity();
    this.renderer.render(this.scene, this.camera);
  }

  // The thin edges fade out when they are denser than a few pixels on screen.
  updateWireOpacity() {
    const h = Math.max(1, $('canvas').clientHeight);
    const d = this.camera.position.distanceTo(this.controls.target);
    const worldPerPixel = (2 * d * Math.tan(THREE.MathUtils.degToRad(this.camera.fov) / 2)) / h;
    const px = worldPerPixel > 0 ? this.model.meanEdge / worldPerPixel : 0;
    const alpha = 0.3 * Math.min(1, Math.max(0, (px - 4) / 16));
    this.wire.material.opacity = alpha;
    this.wire.visible = this.layers.skin && this.model.nEdges > 0 && alpha > 0.005;
  }

  requestRender() {
    if (this.renderPending) return;
    this.renderPending = true;
    requestAnimationFrame(() => { if (this.renderPending) this.renderNow(); });
  }

  // ----- playing -----
  play() {
    const S = this.model.S;
    if (S < 2) return;
    if (this.step >= S - 1) this.showStep(0);
    this.playing = true;
    this.playStart = performance.now();
    this.playFrom = this.step;
    this.playRate = Math.max(6, (S - 1) / 20); // steps per second; a large trace takes ~20 s
    $('btn-play').classList.add('playing');
    $('btn-play').textContent = '\u275A\u275A pause';
    this.renderNow();
    const tick = (now) => {
      if (!this.playing) return;
      const target = Math.min(S - 1, this.playFrom + Math.floor(((now - this.playStart) / 1000) * this.playRate));
      if (target !== this.step) {
        this.showStep(target);
        this.renderNow();
      }
      if (target >= S - 1) this.pause();
      else requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }

  pause() {
    this.playing = false;
    $('btn-play').classList.remove('playing');
    $('btn-play').textContent = '\u25B6 play';
  }

  // ----- panel -----
  initPanel() {
    const t = this.trace;
    const m = this.model;
    const title = typeof t.title === 'string' && t.title ? t.title : (t.input || 'trace');
    $('title').textContent = title;
    document.title = title + ' \u2014 skinmesh trace';
    const bits = [];
    if (t.algorithm) bits.push(String(t.algorithm));
    if (Number.isFinite(t.atoms)) bits.push(fmt(t.atoms) + ' atoms');
    if (Number.isFinite(t.probe)) bits.push('probe ' + t.probe + ' \u00C5');
    else if (t.probe === null) bits.push('weighted points');
    if (Number.isFinite(t.operations)) bits.push(fmt(t.operations) + ' operations');
    if (Number.isFinite(t.every) && t.every > 1) bits.push('every ' + fmt(t.every));
    bits.push(fmt(m.S) + ' steps');
    if (t.version !== 1) bits.push('format version ' + t.version + ' (viewer reads 1)');
    $('subtitle').textContent = bits.join(' \u00B7 ');

    const slider = $('step-slider');
    slider.max = String(m.S - 1);
    slider.addEventListener('input', () => { this.pause(); this.userStep(slider.value); });
    $('btn-first').addEventListener('click', () => { this.pause(); this.userStep(0); });
    $('btn-prev').addEventListener('click', () => { this.pause(); this.userStep(this.step - 1); });
    $('btn-next').addEventListener('click', () => { this.pause(); this.userStep(this.step + 1); });
    $('btn-last').addEventListener('click', () => { this.pause(); this.userStep(m.S - 1); });
    $('btn-play').addEventListener('click', () => (this.playing ? this.pause() : this.play()));

    for (const box of document.querySelectorAll('input[data-layer]')) {
      box.addEventListener('change', () => this.setLayer(box.dataset.layer, box.checked));
    }
    const sel = $('quality-mode');
    sel.addEventListener('change', () => this.setQualityMode(sel.value));

    window.addEventListener('keydown', (e) => {
      const tg = e.target;
      const tag = tg && tg.tagName;
      if (tag === 'SELECT' || tag === 'TEXTAREA' || (tag === 'INPUT' && tg.type !== 'checkbox')) return;
      if (e.ctrlKey || e.metaKey || e.altKey) return;
      let s = null;
      const big = e.shiftKey ? 10 : 1;
      if (e.key === 'ArrowRight') s = this.step + big;
      else if (e.key === 'ArrowLeft') s = this.step - big;
      else if (e.key === 'PageDown') s = this.step + 10;
      else if (e.key === 'PageUp') s = this.step - 10;
      else if (e.key === 'Home') s = 0;
      else if (e.key === 'End') s = m.S - 1;
      else if (e.key === ' ' && tag !== 'BUTTON') {
        e.preventDefault();
        if (this.playing) this.pause(); else this.play();
        return;
      }
      if (s === null) return;
      e.preventDefault();
      this.pause();
      this.userStep(s);
    });

    this.syncLayerBoxes();
    this.updateLegend();
  }

  userStep(s) {
    this.showStep(s);
    this.renderNow();
  }

  syncLayerBoxes() {
    for (const box of document.querySelectorAll('input[data-layer]')) box.checked = !!this.layers[box.dataset.layer];
    $('quality-mode').value = this.qualityMode;
  }

  updateLegend() {
    const angle = this.qualityMode === 'min_angle';
    const stops = angle ? RAMPS.angle : RAMPS.ratio;
    $('ramp').style.background = 'linear-gradient(to right, ' + stops.map(([t, c]) => c + ' ' + (100 * t) + '%').join(', ') + ')';
    const bound = num(this.trace.min_angle_bound, 20);
    if (angle) {
      $('ramp-title').textContent = 'quality: smallest angle of the face';
      $('ramp-lo').textContent = '\u2264 ' + bound.toFixed(1) + '\u00B0';
      $('ramp-mid').textContent = ((bound + 60) / 2).toFixed(1) + '\u00B0';
      $('ramp-hi').textContent = '60\u00B0';
    } else {
      $('ramp-title').textContent = 'quality: ' + this.qualityMode + ' ratio (log scale; > 1 holds)';
      $('ramp-lo').textContent = '\u2264 1';
      $('ramp-mid').textContent = '1.41';
      $('ramp-hi').textContent = '\u2265 2';
    }
    $('ramp-box').style.opacity = this.layers.quality ? '1' : '0.45';
  }

  updatePanel() {
    const m = this.model;
    const s = this.step;
    const st = m.steps[s] || {};
    $('step-slider').value = String(s);
    $('step-label').textContent = 'step ' + s + ' / ' + (m.S - 1);
    const badge = $('stage-badge');
    badge.textContent = st.stage || '\u2013';
    badge.className = 'badge ' + (typeof st.stage === 'string' ? st.stage.replace(/[^a-z]/g, '') : '');
    $('op').textContent = st.op || '';
    $('text').textContent = st.text || '';
    const ops = st.ops && typeof st.ops === 'object' ? Object.entries(st.ops) : [];
    const opsText = ops.map(([k, v]) => k + ' \u00D7' + fmt(v)).join(', ');
    $('ops').textContent = (opsText ? 'merged: ' + opsText : '') +
      (Number.isInteger(st.critical) && st.critical >= 0 ? (opsText ? ' \u00B7 ' : '') + 'critical point ' + st.critical : '');

    const body = $('counter-table').tBodies[0];
    const rows = [];
    const counters = st.counters && typeof st.counters === 'object' ? Object.entries(st.counters) : [];
    for (const [k, v] of counters) rows.push([k, fmt(v), '']);
    rows.push(['triangles drawn', fmt(m.nAlive), 'drawn']);
    rows.push(['front edges', fmt(m.nFront), 'drawn']);
    rows.push(['vertices in mesh', fmt(m.nVerts), 'drawn']);
    body.replaceChildren(...rows.map(([k, v, cls]) => {
      const tr = document.createElement('tr');
      if (cls) tr.className = cls;
      const a = document.createElement('td');
      a.textContent = k.replace(/_/g, ' ');
      const b = document.createElement('td');
      b.textContent = v;
      tr.append(a, b);
      return tr;
    }));
  }

  // ----- API used by the panel, the hash and the automation API -----
  setLayer(name, on) {
    if (!LAYERS.includes(name)) throw new Error('unknown layer: ' + name + ' (layers: ' + LAYERS.join(', ') + ')');
    this.layers[name] = !!on;
    this.syncLayerBoxes();
    if (name === 'quality') { this.fillColors(); this.updateLegend(); }
    this.applyVisibility();
    this.renderNow();
  }

  setQualityMode(mode) {
    if (!QUALITY_MODES.includes(mode)) throw new Error('unknown quality mode: ' + mode + ' (modes: ' + QUALITY_MODES.join(', ') + ')');
    this.qualityMode = mode;
    this.syncLayerBoxes();
    this.updateLegend();
    this.fillColors();
    this.renderNow();
  }

  // #step=N&layers=a,b&quality=min_angle|L|U|off&view=az,el,dist&ui=0
  applyHash() {
    const p = new URLSearchParams(location.hash.replace(/^#/, ''));
    const S = this.model.S;
    if (p.has('ui')) document.body.classList.toggle('noui', p.get('ui') === '0');
    if (p.has('layers')) {
      const want = p.get('layers').split(',').map((x) => x.trim()).filter(Boolean);
      for (const l of LAYERS) this.layers[l] = want.includes(l);
    }
    if (p.has('quality')) {
      const q = p.get('quality');
      if (QUALITY_MODES.includes(q)) { this.qualityMode = q; this.layers.quality = true; }
      else if (q === 'off' || q === 'none' || q === '0') this.layers.quality = false;
    }
    this.syncLayerBoxes();
    this.updateLegend();
    this.resize();
    let view = [30, 20, 1];
    if (p.has('view')) {
      const v = p.get('view').split(',').map(Number);
      view = view.map((d, i) => (Number.isFinite(v[i]) ? v[i] : d));
    }
    if (p.has('view') || !this.viewSet) {
      this.setView(view[0], view[1], view[2]);
      this.viewSet = true;
    }
    let s = this.step;
    if (p.has('step')) {
      const n = parseInt(p.get('step'), 10);
      if (Number.isFinite(n)) s = n < 0 ? S + n : n;
    }
    this.showStep(s);
    this.renderNow();
  }

  stats() {
    const m = this.model;
    return { step: this.step, triangles: m.nAlive, frontEdges: m.nFront, vertices: m.nVerts, edges: m.nEdges };
  }
}

function main() {
  const loaded = loadTrace();
  if (loaded.error) {
    showMessage(loaded.error);
    window.skinmeshViewer = { ready: false, error: loaded.error };
    return;
  }
  let v;
  try {
    v = new Viewer(loaded.trace);
    v.applyHash();
  } catch (e) {
    showMessage('The viewer failed: ' + (e && e.message ? e.message : e));
    window.skinmeshViewer = { ready: false, error: String(e && e.message ? e.message : e) };
    console.error(e);
    return;
  }
  new ResizeObserver(() => { v.resize(); v.renderNow(); }).observe($('view'));
  window.addEventListener('hashchange', () => v.applyHash());

  const api = {
    ready: false,
    stepCount: v.model.S,
    layerNames: LAYERS.slice(),
    setStep(n) {
      v.pause();
      n = Number(n);
      v.showStep(n < 0 ? v.model.S + n : n);
      v.renderNow();
      return v.step;
    },
    getStep() { return v.step; },
    setLayer(name, on) { v.setLayer(name, on); return v.layers[name]; },
    getLayers() { return Object.assign({}, v.layers); },
    setQualityMode(mode) { v.setQualityMode(mode); return v.qualityMode; },
    setView(az, el, dist) { v.setView(az, el, dist === undefined ? 1 : dist); v.renderNow(); },
    stats() { return v.stats(); },
    render() { v.renderNow(); },
    play() { v.play(); },
    pause() { v.pause(); },
  };
  window.skinmeshViewer = api;
  v.renderNow();
  api.ready = true;
}

if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', main);
else main();
