// Synthetic trace for developing the viewer without the C++ side:
//   node test/make_sample_trace.mjs TEMPLATE.html OUT.html [--level N] [--sweep-steps K] [--json OUT.json]
// An icosphere (subdivision level N, default 2) is grown bottom to top over K sweep steps, then a
// few edge flips and vertex insertions (refine), a step of vertex moves (angles) and the final
// mesh; four live critical points with arcs and protecting spheres plus one non-live pair.
// The document follows trace/FORMAT.md; it is written into the template in place of the
// placeholder, with every "</" escaped.
import { readFileSync, writeFileSync } from 'node:fs';

const args = process.argv.slice(2);
const opt = (name, dflt) => {
  const i = args.indexOf(name);
  if (i < 0) return dflt;
  const v = args[i + 1];
  args.splice(i, 2);
  return v;
};
const level = Number(opt('--level', 2));
const sweepSteps = Number(opt('--sweep-steps', 52));
const jsonOut = opt('--json', null);
if (args.length !== 2) {
  console.error('usage: node test/make_sample_trace.mjs TEMPLATE.html OUT.html [--level N] [--sweep-steps K] [--json OUT.json]');
  process.exit(2);
}
const [templatePath, outPath] = args;
const R = 10;

// ----- icosphere -----
const t = (1 + Math.sqrt(5)) / 2;
let verts = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
  [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]];
let tris = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6],
  [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]];
const norm = (p) => { const l = Math.hypot(...p); return p.map((x) => (x / l) * R); };
verts = verts.map(norm);
for (let l = 0; l < level; l++) {
  const mid = new Map();
  const midpoint = (a, b) => {
    const k = a < b ? a + ',' + b : b + ',' + a;
    if (!mid.has(k)) {
      verts.push(norm(verts[a].map((x, i) => (x + verts[b][i]) / 2)));
      mid.set(k, verts.length - 1);
    }
    return mid.get(k);
  };
  const next = [];
  for (const [a, b, c] of tris) {
    const ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    next.push([a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]);
  }
  tris = next;
}
// A little shape so it is not a perfect ball: squash along y, bulge at the top.
verts = verts.map(([x, y, z]) => [x, y * 0.8, z * (z > 0 ? 1.15 : 1)]);

// ----- recording -----
const r4 = (x) => Math.round(x * 1e4) / 1e4;
const V = verts.map((p) => p.map(r4));
const vertexStep = new Array(V.length).fill(-1);
const faces = []; // {v: [a,b,c], born, died}
const steps = [];
const counters = { triangles: 0, creations: 0, creeps: 0, wings: 0, bridges: 0, seals: 0, flips: 0, insertions: 0, moves: 0 };
const moves = [];
let operations = 0;

const addStep = (stage, op, text, ops, focus, critical) => {
  steps.push({ stage, op, text, ops, focus: focus ? focus.map(r4) : null, critical, counters: Object.assign({}, counters) });
  operations += Object.values(ops).reduce((a, b) => a + b, 0) || 0;
};
const newFace = (v, s) => {
  for (const x of v) if (vertexStep[x] < 0) vertexStep[x] = s;
  faces.push({ v, born: s, died: -1 });
  counters.triangles++;
  return faces.length - 1;
};
const killFace = (f, s) => { faces[f].died = s; counters.triangles--; };
const centroid = (v) => [0, 1, 2].map((i) => (V[v[0]][i] + V[v[1]][i] + V[v[2]][i]) / 3);

// Critical points and arcs (height function along z).
const critical = [
  { p: [0, 0, -R], index: 0, live: true, sphere: 1.6 },
  { p: [R, 0, 0], index: 1, live: true, sphere: 1.2 },
  { p: [-R, 0, 0], index: 1, live: true, sphere: 1.2 },
  { p: [0, 0, R * 1.15], index: 2, live: true, sphere: 1.6 },
  { p: [0, R * 0.8, 0.5], index: 1, live: false, sphere: 0 },
  { p: [0, -R * 0.8, 0.5], index: 2, live: false, sphere: 0 },
].map((c) => Object.assign(c, { p: c.p.map(r4) }));
const arc = (from, to, n = 24) => {
  const pts = [];
  for (let i = 0; i <= n; i++) {
    const u = i / n;
    const q = norm(from.map((x, k) => x * (1 - u) + to[k] * u));
    pts.push(r4(q[0]), r4(q[1] * 0.8), r4(q[2] * (q[2] > 0 ? 1.15 : 1)));
  }
  return pts;
};
const lines = [];
for (const ci of [1, 2, 4, 5]) {
  const live = critical[ci].live;
  const p = critical[ci].p.slice();
  p[1] /= 0.8; // back to the ball
  lines.push({ points: arc(p, [0, 0, -R]), critical: ci, live });
  lines.push({ points: arc(p, [0, 0, R]), critical: ci, live });
}

// Step 0: the Morse-Smale complex.
addStep('morse', 'morse-smale complex', 'Morse–Smale complex: 4 live critical points, 8 arcs (4 live)', {}, null, -1);

// Sweep: faces in order of height, in sweepSteps groups.
const order = tris.map((v, i) => i).sort((i, j) => centroid(tris[i])[2] - centroid(tris[j])[2]);
const per = Math.ceil(order.length / sweepSteps);
for (let k = 0, s = 1; k < order.length; k += per, s++) {
  const group = order.slice(k, k + per);
  const first = k === 0;
  const last = k + per >= order.length;
  let op, text, ops, crit = -1, focus;
  if (first) {
    counters.creations++;
    op = 'creation'; crit = 0; focus = critical[0].p;
    text = `creation at minimum 0 (bowl of ${group.length} triangles)`;
    ops = { creation: 1 };
  } else if (last) {
    counters.seals++;
    op = 'seal'; crit = 3; focus = critical[3].p;
    text = `seal at maximum 3 (${group.length} triangles close the front)`;
    ops = { creep: group.length - 1, seal: 1 };
    counters.creeps += group.length - 1;
  } else if (s === Math.round(sweepSteps / 2)) {
    counters.bridges++;
    op = 'bridge'; crit = 1; focus = critical[1].p;
    text = 'bridge at saddle 1';
    ops = { creep: group.length - 1, bridge: 1 };
    counters.creeps += group.length - 1;
  } else {
    const w = Math.floor(group.length / 3);
    counters.creeps += group.length - w;
    counters.wings += w;
    op = w ? 'wings' : 'creep';
    focus = centroid(tris[group[0]]);
    text = `${group.length - w} creeps and ${w} wings around the front`;
    ops = w ? { creep: group.length - w, wings: w } : { creep: group.length };
  }
  for (const f of group) newFace(tris[f], s);
  addStep('sweep', op, text, ops, focus, crit);
}

// Refine: flips and insertions on the closed mesh.
const aliveFaces = () => faces.map((f, i) => i).filter((i) => faces[i].died === -1);
const edgeMap = () => {
  const m = new Map();
  for (const i of aliveFaces()) {
    const v = faces[i].v;
    for (let k = 0; k < 3; k++) m.set(v[k] + '>' + v[(k + 1) % 3], i);
  }
  return m;
};
const touched = new Set();
let s;
for (let flip = 0; flip < 5; flip++) {
  s = steps.length;
  const m = edgeMap();
  const candidates = aliveFaces().filter((i) => !touched.has(i));
  const f1 = candidates[Math.floor(((flip * 0.37 + 0.11) % 1) * candidates.length)];
  const [a, b, c] = faces[f1].v;
  const f2 = m.get(b + '>' + a);
  const d = faces[f2].v.find((x) => x !== a && x !== b);
  if (m.has(c + '>' + d) || m.has(d + '>' + c)) continue;
  killFace(f1, s);
  killFace(f2, s);
  touched.add(newFace([a, d, c], s));
  touched.add(newFace([d, b, c], s));
  counters.flips++;
  addStep('refine', 'flip', `flip of edge ${a}–${b} (Delaunay)`, { flip: 1 }, centroid([a, b, c]), -1);
}
for (let ins = 0; ins < 2; ins++) {
  s = steps.length;
  const candidates = aliveFaces().filter((i) => !touched.has(i));
  const f = candidates[Math.floor(((ins * 0.53 + 0.29) % 1) * candidates.length)];
  const [a, b, c] = faces[f].v;
  const cpos = centroid([a, b, c]);
  V.push(cpos.map(r4));
  vertexStep.push(s);
  const p = V.length - 1;
  killFace(f, s);
  for (const g of [[a, b, p], [b, c, p], [c, a, p]]) touched.add(newFace(g, s));
  counters.insertions++;
  addStep('refine', 'insertion', `insertion of vertex ${p} ([U] violated)`, { insertion: 1 }, cpos, -1);
}

// Angles: a few vertices move along the surface.
s = steps.length;
const movedPos = V.map((p) => p.slice());
const movedList = [];
for (let i = 0; i < Math.min(12, V.length); i++) {
  const v = (i * 7919) % V.length;
  if (movedList.includes(v)) continue;
  movedList.push(v);
  movedPos[v] = movedPos[v].map((x, k) => r4(x + [0.35, -0.25, 0.2][k]));
  moves.push(v, s, ...movedPos[v]);
  counters.moves++;
}
addStep('angles', 'vertex moves', `${movedList.length} vertices moved to raise the smallest angle`, { move: movedList.length }, movedPos[movedList[0]], -1);
s++;
// A second move of the first vertex on the final step, to exercise "latest position".
{
  const v = movedList[0];
  const q = movedPos[v].map((x, k) => r4(x + [-0.1, 0.1, 0.05][k]));
  movedPos[v] = q;
  moves.push(v, s, ...q);
  counters.moves++;
}
addStep('final', 'final mesh', `final mesh: ${counters.triangles} triangles`, {}, null, -1);

// ----- quality of the final faces -----
const angleDeg = (p, q, r) => {
  const u = [0, 1, 2].map((i) => q[i] - p[i]);
  const w = [0, 1, 2].map((i) => r[i] - p[i]);
  const dot = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
  return (Math.acos(Math.max(-1, Math.min(1, dot / (Math.hypot(...u) * Math.hypot(...w))))) * 180) / Math.PI;
};
const dist = (p, q) => Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
const quality = { min_angle: [], L: [], U: [] };
const finalFaces = faces.filter((f) => f.died === -1);
const meanEdge = finalFaces.reduce((acc, f) => acc + dist(movedPos[f.v[0]], movedPos[f.v[1]]), 0) / finalFaces.length;
for (const f of faces) {
  if (f.died !== -1) { quality.min_angle.push(0); quality.L.push(0); quality.U.push(0); continue; }
  const [p, q, r] = f.v.map((x) => movedPos[x]);
  const ang = Math.min(angleDeg(p, q, r), angleDeg(q, r, p), angleDeg(r, p, q));
  quality.min_angle.push(Math.round(ang * 100) / 100);
  const emin = Math.min(dist(p, q), dist(q, r), dist(r, p));
  const emax = Math.max(dist(p, q), dist(q, r), dist(r, p));
  quality.L.push(Math.round((emin / meanEdge) * 1.7 * 1000) / 1000);
  quality.U.push(Math.round((meanEdge / emax) * 2.1 * 1000) / 1000);
}

// ----- document -----
const all = V.concat(movedPos);
const bmin = [0, 1, 2].map((i) => all.reduce((m, p) => Math.min(m, p[i]), Infinity));
const bmax = [0, 1, 2].map((i) => all.reduce((m, p) => Math.max(m, p[i]), -Infinity));
const doc = {
  format: 'skinmesh-trace',
  version: 1,
  title: `synthetic icosphere (level ${level}), sweep </script> test`,
  input: 'synthetic',
  algorithm: 'sweep',
  probe: 1.4,
  atoms: 1,
  frame_centre: [0, 0, 0],
  bounds: { min: bmin, max: bmax },
  height_direction: [0, 0, 1],
  every: 1,
  operations,
  min_angle_bound: 21.55,
  critical,
  lines,
  vertices: V.flat(),
  vertex_step: vertexStep,
  moves,
  faces: faces.flatMap((f) => f.v),
  face_steps: faces.flatMap((f) => [f.born, f.died]),
  quality,
  steps,
};
const json = JSON.stringify(doc);
if (jsonOut) writeFileSync(jsonOut, json);
const template = readFileSync(templatePath, 'utf8');
const PLACEHOLDER = '__SKINMESH_TRACE_JSON__';
if (template.split(PLACEHOLDER).length !== 2) {
  console.error('make_sample_trace: the template must contain ' + PLACEHOLDER + ' exactly once');
  process.exit(1);
}
const i = template.indexOf(PLACEHOLDER);
writeFileSync(outPath, template.slice(0, i) + json.replace(/</g, '\\u003c') + template.slice(i + PLACEHOLDER.length));
console.log(`make_sample_trace: ${steps.length} steps, ${faces.length} face records, ${V.length} vertices, ` +
  `${finalFaces.length} final triangles -> ${outPath}`);
