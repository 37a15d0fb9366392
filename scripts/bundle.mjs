// Bundles for delivery, run by scripts/build after dist/ is assembled:
// - dist/vendor/codemirror.js and three.js (scripts/vendor.mjs);
// - dist/mtmotion-standalone.html: one file with the page, its CSS, the
//   bundled JS (panels, uPlot, wasm-bindgen glue), the worker's code and the
//   wasm inlined as base64 — it opens from file:// with no other file;
// - dist/mtmotion-embed.js: the documentation calculators (custom elements)
//   in one module that loads the small embed module
//   pkg/mtmotion_embed_bg.wasm beside it.
import { readFileSync, writeFileSync } from 'node:fs';
import { gzipSync } from 'node:zlib';
import { build } from 'esbuild';
import { bundleVendor } from './vendor.mjs';

const dist = new URL('../dist/', import.meta.url);
const read = (p) => readFileSync(new URL(p, dist), 'utf8');
// The vendor bundles first: the served page imports them, and the
// single-file page bundles them in.
await bundleVendor(dist);

async function bundle(entry, define = {}, format = 'esm') {
  const out = await build({
    entryPoints: [new URL(entry, dist).pathname],
    bundle: true,
    format,
    minify: true,
    write: false,
    define,
    logLevel: 'error',
    target: 'es2022',
  });
  return out.outputFiles[0].text;
}

// A classic (IIFE) worker: Chromium refuses module workers from blob URLs of
// a file:// page, but accepts classic ones.
const workerSource = await bundle('standalone-worker.js', {}, 'iife');
const wasmBase64 = readFileSync(new URL('pkg/mtmotion_bg.wasm', dist)).toString('base64');
const pageJs = await bundle('standalone.js', {
  __MTMOTION_WASM_BASE64__: JSON.stringify(wasmBase64),
  __MTMOTION_WORKER_SOURCE__: JSON.stringify(workerSource),
});

// Nothing inlined may close the <script> or <style> element early.
const safe = (s) => s.replace(/<\/(script|style)/gi, '<\\/$1');
const css = safe(read('vendor/uPlot.min.css') + '\n' + read('style.css'));
let html = read('index.html');
const swaps = [
  [/<link rel="stylesheet" href="vendor\/uPlot\.min\.css">\s*<link rel="stylesheet" href="style\.css">/, `<style>\n${css}\n</style>`],
  [/<script type="module" src="main\.js"><\/script>/, `<script type="module">\n${safe(pageJs)}\n</script>`],
];
for (const [re, rep] of swaps) {
  if (!re.test(html)) throw new Error(`bundle: index.html no longer matches ${re}`);
  html = html.replace(re, () => rep);
}
writeFileSync(new URL('mtmotion-standalone.html', dist), html);
const embed = await bundle('embed.js');
writeFileSync(new URL('mtmotion-embed.js', dist), embed);

const kb = (n) => `${(n / 1024).toFixed(0)} KiB`;
const gz = (s) => kb(gzipSync(s, { level: 9 }).length);
console.log(
  `bundle: mtmotion-embed.js ${kb(embed.length)} (gzip ${gz(embed)}); mtmotion-standalone.html ${kb(html.length)} (gzip ${gz(html)}; wasm as base64 ${kb(wasmBase64.length)}, page JS ${kb(pageJs.length - wasmBase64.length - workerSource.length)}, worker JS ${kb(workerSource.length)}, CSS ${kb(css.length)})`,
);
