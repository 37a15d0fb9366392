// Bundles the page's npm libraries that are not single files (CodeMirror 6,
// three.js + OrbitControls) into dist/vendor/ with esbuild, one ES module
// each, so the served page imports them as ../vendor/<name>.js like uPlot.
// Run by scripts/bundle.mjs (before the single-file page is bundled).
import { mkdirSync } from 'node:fs';
import { build } from 'esbuild';

const entries = { codemirror: 'vendor/codemirror.mjs', three: 'vendor/three.mjs' };

/** Writes dist/vendor/<name>.js for each entry. */
export async function bundleVendor(dist) {
  mkdirSync(new URL('vendor/', dist), { recursive: true });
  for (const [name, entry] of Object.entries(entries)) {
    await build({
      entryPoints: [new URL(entry, import.meta.url).pathname],
      outfile: new URL(`vendor/${name}.js`, dist).pathname,
      bundle: true,
      format: 'esm',
      minify: true,
      logLevel: 'error',
      target: 'es2022',
      legalComments: 'eof',
    });
  }
}
