// node test/browser_test.mjs TRACE.html [more.html ...]
// Opens each trace page (written by `skinmesh trace`) in headless Chromium with every
// request other than file:, data:, blob: refused, and checks it against the trace it embeds:
// loads without console errors, becomes ready, draws the right number of triangles and front
// edges (computed here, independently of the viewer), renders non-blank pictures that change
// with the step and with every layer. Prints "ok - ..." / "not ok - ..." per check;
// exit 0 if all pass, 1 if any fails, 77 if Chromium is missing.
import { resolve } from 'node:path';
import { existsSync } from 'node:fs';
import { pathToFileURL } from 'node:url';
import { launch, requireChromium, isLocalUrl } from './launch.mjs';
import { decodePng } from './png.mjs';

const files = process.argv.slice(2);
if (!files.length) {
  console.error('usage: node test/browser_test.mjs TRACE.html [more.html ...]');
  process.exit(2);
}
requireChromium();

const LAYERS = ['skin', 'front', 'critical', 'arcs', 'spheres', 'quality'];
const DEFAULTS = { skin: true, front: true, critical: true, arcs: true, spheres: false, quality: false };
// Driver chatter that SwiftShader may print as a console warning; not the page's doing.
const DRIVER_NOTE = /GL Driver Message|GPU stall due to ReadPixels/;

let passed = 0;
let failed = 0;
function check(ok, what, detail) {
  if (ok) passed++;
  else failed++;
  console.log((ok ? 'ok' : 'not ok') + ' - ' + what + (detail ? ' (' + detail + ')' : ''));
  return ok;
}
function skip(what, why) {
  passed++;
  console.log('ok - ' + what + ' # SKIP ' + why);
}

// ----- the mesh at a step, computed from the trace alone -----
function aliveFaces(t, s) {
  const fs = t.face_steps;
  const out = [];
  for (let f = 0; 2 * f + 1 < fs.length && 3 * f + 2 < t.faces.length; f++) {
    const born = fs[2 * f], died = fs[2 * f + 1];
    if (born <= s && (died === -1 || s < died)) out.push(f);
  }
  return out;
}
function boundaryEdges(t, s) {
  const count = new Map();
  const nV = t.vertices.length / 3;
  for (const f of aliveFaces(t, s)) {
    const v = [t.faces[3 * f], t.faces[3 * f + 1], t.faces[3 * f + 2]];
    for (let k = 0; k < 3; k++) {
      const a = v[k], b = v[(k + 1) % 3];
      const key = a < b ? a * nV + b : b * nV + a;
      count.set(key, (count.get(key) || 0) + 1);
    }
  }
  let n = 0;
  for (const c of count.values()) if (c === 1) n++;
  return n;
}

// ----- pictures -----
function pixelStats(img) {
  const { rgba } = img;
  const n = rgba.length / 4;
  const freq = new Map();
  for (let i = 0; i < n; i++) {
    const c = (rgba[4 * i] << 16) | (rgba[4 * i + 1] << 8) | rgba[4 * i + 2];
    freq.set(c, (freq.get(c) || 0) + 1);
  }
  let bg = 0, best = -1;
  for (const [c, k] of freq) if (k > best) { best = k; bg = c; }
  const br = bg >> 16, bgG = (bg >> 8) & 255, bb = bg & 255;
  let fg = 0;
  for (let i = 0; i < n; i++) {
    const d = Math.max(Math.abs(rgba[4 * i] - br), Math.abs(rgba[4 * i + 1] - bgG), Math.abs(rgba[4 * i + 2] - bb));
    if (d > 10) fg++;
  }
  return { colours: freq.size, foreground: fg / n };
}
function pixelDiff(a, b, threshold = 0) {
  if (a.width !== b.width || a.height !== b.height) return { count: Infinity, fraction: 1 };
  let count = 0;
  const n = a.rgba.length / 4;
  for (let i = 0; i < n; i++) {
    const d = Math.max(Math.abs(a.rgba[4 * i] - b.rgba[4 * i]), Math.abs(a.rgba[4 * i + 1] - b.rgba[4 * i + 1]),
      Math.abs(a.rgba[4 * i + 2] - b.rgba[4 * i + 2]));
    if (d > threshold) count++;
  }
  return { count, fraction: count / n };
}
const pct = (x) => (100 * x).toFixed(2) + '%';

async function testFile(context, file) {
  const path = resolve(file);
  console.log('# ' + file);
  if (!check(existsSync(path), 'file exists', path)) return;

  const page = await context.newPage();
  const errors = [];
  const warnings = [];
  const notes = [];
  page.on('console', (m) => {
    const text = m.text();
    if (m.type() === 'error') errors.push('console error: ' + text);
    else if (m.type() === 'warning') (DRIVER_NOTE.test(text) ? notes : warnings).push('console warning: ' + text);
  });
  page.on('pageerror', (e) => errors.push('page error: ' + e.message));

  await page.goto(pathToFileURL(path).href, { waitUntil: 'load', timeout: 60000 });
  let ready = true;
  try {
    await page.waitForFunction(() => window.skinmeshViewer && (window.skinmeshViewer.ready || window.skinmeshViewer.error),
      null, { timeout: 30000, polling: 100 });
  } catch (e) {
    ready = false;
  }
  const state = await page.evaluate(() => window.skinmeshViewer
    ? { ready: !!window.skinmeshViewer.ready, error: window.skinmeshViewer.error || null } : { ready: false, error: 'no window.skinmeshViewer' });
  const loadProblems = errors.concat(warnings);
  check(loadProblems.length === 0, '(a) no console errors, warnings or page errors during load', loadProblems.slice(0, 3).join(' | '));
  for (const n of notes) console.log('# note: ' + n);
  if (!check(ready && state.ready, '(b) window.skinmeshViewer.ready within 30 s', state.error || (ready ? '' : 'timed out'))) {
    await page.close();
    return;
  }

  const text = await page.evaluate(() => document.getElementById('skinmesh-trace').textContent);
  let t;
  try {
    t = JSON.parse(text);
  } catch (e) {
    check(false, 'the embedded trace is JSON', e.message);
    await page.close();
    return;
  }
  check(t.format === 'skinmesh-trace' && t.version === 1, 'the embedded trace is skinmesh-trace version 1');
  const S = t.steps.length;
  const api = (fn, ...args) => page.evaluate(([f, a]) => window.skinmeshViewer[f](...a), [fn, args]);
  check((await page.evaluate(() => window.skinmeshViewer.stepCount)) === S, 'stepCount equals steps.length', 'steps ' + S);
  const layers0 = await api('getLayers');
  check(LAYERS.every((l) => layers0[l] === DEFAULTS[l]), 'default layers', JSON.stringify(layers0));

  // (c) triangles drawn at several steps, against the trace.
  const sample = S <= 150 ? [...Array(S).keys()]
    : [...new Set([0, 1, Math.floor(S / 6), Math.floor(S / 3), Math.floor(S / 2), Math.floor((2 * S) / 3), Math.floor((5 * S) / 6), S - 2, S - 1])];
  const expected = new Map(sample.map((s) => [s, aliveFaces(t, s).length]));
  const wrong = [];
  const seen = [];
  for (const s of sample) {
    await api('setStep', s);
    const st = await api('stats');
    seen.push(st.triangles);
    if (st.step !== s || st.triangles !== expected.get(s)) wrong.push(`step ${s}: drawn ${st.triangles}, trace ${expected.get(s)}`);
  }
  check(wrong.length === 0, `(c) triangles drawn = alive face records at ${sample.length} steps`,
    wrong.length ? wrong.slice(0, 4).join('; ') : 'steps ' + (sample.length > 10 ? 'all ' + S : sample.join(', ')));
  const third = [0, Math.floor(S / 3), Math.floor((2 * S) / 3), S - 1].map((s) => aliveFaces(t, s).length);
  const changes = new Set(third).size > 1;
  const seenChange = new Set(seen).size > 1;
  check(changes === seenChange && (changes || aliveFaces(t, S - 1).length === 0),
    '(c) the triangle count changes between steps as the trace says', 'at 0, 1/3, 2/3, last: ' + third.join(', '));

  // (d) front edges.
  const lastFront = boundaryEdges(t, S - 1);
  await api('setStep', S - 1);
  const lastStats = await api('stats');
  check(lastStats.frontEdges === lastFront, '(d) front edges at the last step = boundary edges of the final mesh',
    `drawn ${lastStats.frontEdges}, trace ${lastFront}${lastFront === 0 ? ', closed' : ', NOT closed'}`);
  if (aliveFaces(t, S - 1).length > 0) check(lastFront === 0, '(d) the final mesh is closed (0 front edges)', 'boundary edges ' + lastFront);
  const sweep = [];
  t.steps.forEach((st, i) => { if (st.stage === 'sweep') sweep.push(i); });
  let midSweep = -1;
  if (sweep.length) {
    const mid = sweep[Math.floor(sweep.length / 2)];
    const byDistance = sweep.slice().sort((a, b) => Math.abs(a - mid) - Math.abs(b - mid)).slice(0, 50);
    for (const s of byDistance) if (boundaryEdges(t, s) > 0) { midSweep = s; break; }
    if (midSweep < 0) midSweep = mid;
    const want = boundaryEdges(t, midSweep);
    await api('setStep', midSweep);
    const st = await api('stats');
    check(st.frontEdges === want && want > 0, `(d) front edges > 0 in the middle of the sweep (step ${midSweep})`,
      `drawn ${st.frontEdges}, trace ${want}`);
  } else {
    skip('(d) front edges in the middle of the sweep', 'no sweep stage in this trace');
  }

  // (e) pictures: non-blank, and different at two steps.
  const shot = async () => decodePng(await page.locator('#canvas').screenshot({ type: 'png' }));
  const stepA = midSweep >= 0 ? midSweep : Math.floor(S / 3);
  const stepB = S - 1;
  await api('setStep', stepA);
  const imgA = await shot();
  await api('setStep', stepB);
  const imgB = await shot();
  const drawable = (s) => aliveFaces(t, s).length > 0 || (Array.isArray(t.critical) && t.critical.length > 0);
  for (const [s, img] of stepA === stepB ? [[stepB, imgB]] : [[stepA, imgA], [stepB, imgB]]) {
    if (!drawable(s)) { skip(`(e) the picture at step ${s} is not blank`, 'nothing to draw at this step'); continue; }
    const ps = pixelStats(img);
    check(ps.colours > 50 && ps.foreground > 0.01, `(e) the picture at step ${s} is not blank`,
      `${img.width}x${img.height}, ${ps.colours} colours, ${pct(ps.foreground)} non-background`);
  }
  if (stepA !== stepB && aliveFaces(t, stepA).length !== aliveFaces(t, stepB).length) {
    const d = pixelDiff(imgA, imgB, 16);
    check(d.fraction > 0.002, `(e) the pictures at steps ${stepA} and ${stepB} differ`, pct(d.fraction) + ' of pixels');
  }

  // (f) every layer changes the picture where it has content.
  const finalFaces = t.face_steps.filter((x, i) => i % 2 === 1 && x === -1).length;
  const hasQuality = t.quality && Array.isArray(t.quality.min_angle) && t.quality.min_angle.length > 0;
  const crit = Array.isArray(t.critical) ? t.critical : [];
  const lines = (Array.isArray(t.lines) ? t.lines : []).filter((l) => Array.isArray(l.points) && l.points.length >= 6);
  const plan = [
    ['skin', S - 1, aliveFaces(t, S - 1).length > 0, 'no triangles at the last step'],
    ['front', midSweep, midSweep >= 0, 'no sweep stage'],
    ['critical', 0, crit.length > 0, 'no critical points'],
    ['arcs', 0, lines.length > 0, 'no integral lines'],
    ['spheres', 0, crit.some((c) => c.sphere > 0), 'no protecting spheres'],
    ['quality', S - 1, hasQuality && finalFaces > 0, 'no quality data'],
  ];
  for (const [layer, s, has, why] of plan) {
    if (!has) { skip(`(f) layer ${layer} changes the picture`, why); continue; }
    for (const l of LAYERS) await api('setLayer', l, DEFAULTS[l]);
    await api('setStep', s);
    // The default view first; if the layer's content is hidden there (e.g. behind the
    // surface), the opposite side and from below.
    let d, view;
    for (view of [[30, 20, 1], [210, 20, 1], [120, -60, 1]]) {
      await api('setView', ...view);
      const before = await shot();
      await api('setLayer', layer, !DEFAULTS[layer]);
      const after = await shot();
      await api('setLayer', layer, DEFAULTS[layer]);
      d = pixelDiff(before, after, 0);
      if (d.count > 0) break;
    }
    await api('setView', 30, 20, 1);
    check(d.count > 0, `(f) layer ${layer} ${DEFAULTS[layer] ? 'off' : 'on'} changes the picture at step ${s}`,
      `${d.count} pixels, ${pct(d.fraction)}, view ${view.join(',')}`);
  }

  // Hash parameters (as render.mjs uses them).
  await page.evaluate(() => { location.hash = 'step=-1&layers=skin,critical&quality=min_angle&view=60,30,1.2&ui=0'; });
  await page.waitForFunction(() => document.body.classList.contains('noui'), null, { timeout: 5000 }).catch(() => {});
  const h = await page.evaluate(() => ({
    step: window.skinmeshViewer.getStep(),
    layers: window.skinmeshViewer.getLayers(),
    panel: document.getElementById('panel').offsetWidth,
    canvas: document.getElementById('canvas').clientWidth,
    window: window.innerWidth,
  }));
  const wantLayers = { skin: true, front: false, critical: true, arcs: false, spheres: false, quality: true };
  check(h.step === S - 1 && LAYERS.every((l) => h.layers[l] === wantLayers[l]) && h.panel === 0 && h.canvas === h.window,
    'hash #step=-1&layers=skin,critical&quality=min_angle&view=…&ui=0 applied', JSON.stringify(h));

  const all = errors.concat(warnings);
  check(all.length === 0, 'no console errors or warnings during the whole test', all.slice(0, 3).join(' | '));
  await page.close();
}

const browser = await launch({ width: 1000, height: 700 });
const external = [];
await browser.context.route('**/*', (route) => {
  const url = route.request().url();
  if (isLocalUrl(url)) return route.continue();
  external.push(url);
  return route.abort();
});
browser.context.on('request', (r) => { if (!isLocalUrl(r.url())) external.push(r.url()); });
browser.context.on('websocket', (w) => external.push(w.url()));
try {
  for (const f of files) {
    const before = external.length;
    await testFile(browser.context, f);
    check(external.length === before, 'offline: no request other than file:, data:, blob:', [...new Set(external.slice(before))].slice(0, 3).join(' '));
  }
} catch (e) {
  check(false, 'the test ran to the end', e && e.stack ? e.stack.split('\n').slice(0, 3).join(' / ') : String(e));
} finally {
  await browser.close();
}
console.log(`# ${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
