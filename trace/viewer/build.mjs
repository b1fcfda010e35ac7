// node build.mjs OUT.html — bundles src/viewer.js (three.js included) and inlines it and
// src/style.css into src/page.html. OUT.html is the template read by `skinmesh trace`: it
// holds the placeholder __SKINMESH_TRACE_JSON__ exactly once, where the trace JSON goes.
import { build } from 'esbuild';
import { readFile, writeFile, mkdir } from 'node:fs/promises';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const PLACEHOLDER = '__SKINMESH_TRACE_JSON__';
const STYLE_MARK = '/*@INLINE_STYLE@*/';
const SCRIPT_MARK = '/*@INLINE_SCRIPT@*/';

function fail(msg) {
  console.error('build.mjs: ' + msg);
  process.exit(1);
}

function count(haystack, needle) {
  return haystack.split(needle).length - 1;
}

const out = process.argv[2];
if (!out || process.argv.length > 3) fail('usage: node build.mjs OUT.html');

let result;
try {
  result = await build({
    entryPoints: [resolve(here, 'src/viewer.js')],
    bundle: true,
    minify: true,
    format: 'iife',
    target: ['es2019'],
    platform: 'browser',
    legalComments: 'eof',
    charset: 'utf8',
    write: false,
    logLevel: 'silent',
  });
} catch (e) {
  fail('esbuild failed:\n' + (e.errors || []).map((x) => '  ' + x.text + (x.location ? ' (' + x.location.file + ':' + x.location.line + ')' : '')).join('\n'));
}
for (const w of result.warnings) console.error('build.mjs: esbuild warning: ' + w.text);

let js = result.outputFiles[0].text;
// Nothing inside the inline <script> may close it or open an HTML comment.
js = js.replace(/<\/(script)/gi, '<\\/$1').replace(/<!--/g, '<\\!--');
let css = await readFile(resolve(here, 'src/style.css'), 'utf8');
if (/<\/style/i.test(css)) fail('src/style.css contains "</style"');
let page = await readFile(resolve(here, 'src/page.html'), 'utf8');

if (count(page, STYLE_MARK) !== 1) fail('src/page.html must contain ' + STYLE_MARK + ' exactly once');
if (count(page, SCRIPT_MARK) !== 1) fail('src/page.html must contain ' + SCRIPT_MARK + ' exactly once');
if (count(js, PLACEHOLDER) || count(css, PLACEHOLDER)) fail('the bundle or the style sheet contains the placeholder ' + PLACEHOLDER);
// split/join: no special replacement patterns ($&, $1) are interpreted in the inserted text
page = page.split(STYLE_MARK).join(css.trim());
page = page.split(SCRIPT_MARK).join(js.trim());

const n = count(page, PLACEHOLDER);
if (n !== 1) fail('the page must contain the placeholder ' + PLACEHOLDER + ' exactly once, found ' + n);
const outPath = resolve(process.cwd(), out);
await mkdir(dirname(outPath), { recursive: true });
await writeFile(outPath, page);
console.log('build.mjs: wrote ' + out + ' (' + Buffer.byteLength(page) + ' bytes)');
