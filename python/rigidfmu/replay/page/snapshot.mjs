// node snapshot.mjs PAGE.html OUT_DIR [FRAME ...]
// Opens a replay page in headless Debian chromium (playwright-core, no browser download)
// and, for each FRAME (a slider position; "last" for the end; default: 0 and last),
// moves the time slider there as a user would (value + input event) and takes a
// screenshot of the 3D view, OUT_DIR/frame-<FRAME>.png, with the legend greyed out
// (its colour swatches are not bodies). Prints one JSON line: {"errors": [console
// errors and page errors], "screenshots": [paths], "frames": [slider values]}.
import { chromium } from 'playwright-core';
import { mkdirSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const [page_, outDir, ...wanted] = process.argv.slice(2);
if (!page_ || !outDir) {
  console.error('usage: node snapshot.mjs PAGE.html OUT_DIR [FRAME ...]');
  process.exit(2);
}
const frames = wanted.length ? wanted : ['0', 'last'];
mkdirSync(outDir, { recursive: true });
const profile = mkdtempSync(join(tmpdir(), 'replay-chromium-'));
// a persistent context is playwright's way to give chromium a --user-data-dir: a fresh
// one each time, so that no earlier profile changes what is seen
const context = await chromium.launchPersistentContext(profile, {
  headless: true,
  viewport: { width: 1000, height: 700 },
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  args: [
    '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    // this machine's network is closed: no background connections, no updates, no sync
    '--disable-background-networking', '--disable-component-update', '--disable-sync',
    // WebGL without a GPU: chromium's software renderer, which it no longer picks by itself
    '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
  ],
});
const errors = [];
try {
  const page = context.pages()[0] ?? await context.newPage();
  page.on('console', m => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
  page.on('pageerror', e => errors.push(`page: ${e.message}`));
  // a self-contained page asks for nothing: any request but the file itself is an error
  page.on('request', r => { if (!r.url().startsWith('file:')) errors.push(`request: ${r.url()}`); });
  await page.goto(pathToFileURL(resolve(page_)).href, { waitUntil: 'load' });
  await page.waitForSelector('#view canvas', { timeout: 10000 });
  const screenshots = [], values = [];
  for (const frame of frames) {
    const value = await page.$eval('#time', (slider, frame) => {
      slider.value = frame === 'last' ? slider.max : frame;
      slider.dispatchEvent(new Event('input', { bubbles: true }));
      return Number(slider.value);
    }, frame);
    // two animation frames, so that the drawn canvas has reached the screen
    await page.evaluate(() => new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r))));
    const path = join(outDir, `frame-${frame}.png`);
    await page.locator('#view canvas').screenshot({
      path, mask: [page.locator('#legend')], maskColor: '#808080' });
    screenshots.push(path);
    values.push(value);
  }
  console.log(JSON.stringify({ errors, screenshots, frames: values }));
} finally {
  await context.close();
  rmSync(profile, { recursive: true, force: true });
}
