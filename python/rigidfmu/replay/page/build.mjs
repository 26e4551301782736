// Builds dist/replay.html: the page template (src/page.html) with the bundled three.js
// replay (src/main.js and what it imports, minified by esbuild) inlined, so that the
// page needs no network and no other file. rigidfmu.replay (../__init__.py) fills in
// the run's data where the template says <!-- replay-data -->.
import { build } from 'esbuild';
import { mkdirSync, readFileSync, renameSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const result = await build({
  entryPoints: [join(here, 'src', 'main.js')],
  bundle: true,
  minify: true,
  format: 'iife',
  target: 'es2020',
  legalComments: 'inline',  // three.js's MIT licence notice stays in the page
  write: false,
  logLevel: 'warning',
});
let js = result.outputFiles[0].text;
// "</script" inside the code would end the inline script early
js = js.replaceAll('</script', '<\\/script');
const page = readFileSync(join(here, 'src', 'page.html'), 'utf8');
const marker = '<!-- replay-bundle -->';
if (!page.includes(marker)) throw new Error(`src/page.html has no ${marker}`);
const html = page.replace(marker, () => `<script>${js}</script>`);
const out = join(here, 'dist', 'replay.html');
mkdirSync(dirname(out), { recursive: true });
// written aside and renamed, so that a reader never sees half a page
writeFileSync(`${out}.tmp`, html);
renameSync(`${out}.tmp`, out);
console.log(`replay: built ${out} (${(html.length / 1024).toFixed(0)} KiB)`);
