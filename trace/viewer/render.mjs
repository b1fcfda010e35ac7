// node render.mjs TRACE.html OUT.png [--step N] [--layers a,b] [--quality min_angle|L|U]
//                 [--view az,el,dist] [--size WxH] [--scale F]
// Renders one figure of a trace page headlessly: the page is opened with the hash
// parameters and ui=0 (no panel, the canvas fills the window) and the canvas is saved as PNG.
import { resolve } from 'node:path';
import { existsSync, writeFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';
import { launch, isLocalUrl } from './test/launch.mjs';

const USAGE = 'usage: node render.mjs TRACE.html OUT.png [--step N] [--layers a,b] [--quality min_angle|L|U] ' +
  '[--view az,el,dist] [--size WxH] [--scale F]';

function fail(msg, code = 1) {
  console.error('render.mjs: ' + msg);
  process.exit(code);
}

const positional = [];
const opts = {};
const argv = process.argv.slice(2);
for (let i = 0; i < argv.length; i++) {
  const a = argv[i];
  if (a.startsWith('--')) {
    const [k, inline] = a.slice(2).split('=', 2);
    if (!['step', 'layers', 'quality', 'view', 'size', 'scale'].includes(k)) fail('unknown option ' + a + '\n' + USAGE, 2);
    const v = inline !== undefined ? inline : argv[++i];
    if (v === undefined) fail('option ' + a + ' needs a value\n' + USAGE, 2);
    opts[k] = v;
  } else positional.push(a);
}
if (positional.length !== 2) fail(USAGE, 2);
const [input, output] = positional;
if (!existsSync(input)) fail('no such file: ' + input);

const size = /^(\d+)x(\d+)$/.exec(opts.size || '900x700');
if (!size) fail('--size must be WIDTHxHEIGHT, e.g. 900x700', 2);
const width = Number(size[1]);
const height = Number(size[2]);
const scale = opts.scale !== undefined ? Number(opts.scale) : 1;
if (!(scale > 0 && scale <= 4)) fail('--scale must be in (0, 4]', 2);
if (opts.step !== undefined && !/^-?\d+$/.test(opts.step)) fail('--step must be an integer (negative: from the end)', 2);
if (opts.quality !== undefined && !['min_angle', 'L', 'U', 'off'].includes(opts.quality)) fail('--quality must be min_angle, L, U or off', 2);
if (opts.view !== undefined && !/^-?[\d.]+(,-?[\d.]+){0,2}$/.test(opts.view)) fail('--view must be az,el[,dist] (degrees, degrees, factor)', 2);

const hash = new URLSearchParams();
for (const k of ['step', 'layers', 'quality', 'view']) if (opts[k] !== undefined) hash.set(k, opts[k]);
hash.set('ui', '0');
const url = pathToFileURL(resolve(input)).href + '#' + hash.toString().replace(/%2C/gi, ',');

const browser = await launch({ width, height, scale });
const problems = [];
try {
  await browser.context.route('**/*', (route) => (isLocalUrl(route.request().url()) ? route.continue() : route.abort()));
  const page = await browser.context.newPage();
  page.on('console', (m) => { if (m.type() === 'error') problems.push(m.text()); });
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(url, { waitUntil: 'load', timeout: 60000 });
  await page.waitForFunction(() => window.skinmeshViewer && (window.skinmeshViewer.ready || window.skinmeshViewer.error),
    null, { timeout: 60000, polling: 100 });
  const state = await page.evaluate(() => ({ error: window.skinmeshViewer.error || null, stats: window.skinmeshViewer.ready ? window.skinmeshViewer.stats() : null }));
  if (state.error) throw new Error(state.error);
  await page.evaluate(() => window.skinmeshViewer.render());
  const png = await page.locator('#canvas').screenshot({ type: 'png' });
  writeFileSync(output, png);
  const s = state.stats;
  console.log(`render.mjs: wrote ${output} (${width}x${height}${scale !== 1 ? ' @' + scale + 'x' : ''}, step ${s.step}, ` +
    `${s.triangles} triangles, ${s.frontEdges} front edges)`);
} catch (e) {
  problems.push(e.message);
} finally {
  await browser.close();
}
if (problems.length) fail(problems.join('\n'));
