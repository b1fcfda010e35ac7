// Headless Chromium for the browser test and render.mjs (playwright-core, the system's
// Chromium; nothing is downloaded). WebGL runs on SwiftShader (software): the GPU process
// is kept (no --disable-gpu), which spares the canvas a read-back on every frame and the
// "GPU stall due to ReadPixels" driver warnings that come with it.
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

export const CHROMIUM_ARGS = [
  '--headless',
  '--no-sandbox',
  '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--disable-default-apps',
  '--disable-extensions',
];

export function chromiumPath() {
  return process.env.CHROMIUM || '/usr/bin/chromium';
}

// Exits with 77 (the "skipped" code of ctest and automake) when there is no Chromium.
export function requireChromium() {
  const exe = chromiumPath();
  if (!existsSync(exe)) {
    console.log('SKIP: chromium not found at ' + exe + ' (set CHROMIUM to its path)');
    process.exit(77);
  }
  return exe;
}

// A persistent context over a fresh temporary profile, removed by close().
export async function launch({ width = 1000, height = 700, scale = 1 } = {}) {
  const exe = requireChromium();
  const profile = mkdtempSync(join(tmpdir(), 'skinmesh-viewer-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: exe,
    headless: true,
    args: CHROMIUM_ARGS,
    viewport: { width, height },
    deviceScaleFactor: scale,
    offline: false,
  });
  return {
    context,
    async close() {
      await context.close().catch(() => {});
      rmSync(profile, { recursive: true, force: true });
    },
  };
}

// Is this URL allowed for an offline page? (the page itself, inline data)
export function isLocalUrl(url) {
  return /^(file|data|blob|about):/i.test(url);
}
