// Node benchmark harness for the wasm build (pkg/, built by ./scripts/build).
// Usage in a bench file:
//   import { wasm, bench } from './harness.mjs';
//   bench('simulateAxis 1e5 steps', () => wasm.simulateAxis(axis, cfg), { perItem: 1e5, unit: 'step' });
import { readFileSync } from 'node:fs';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { performance } from 'node:perf_hooks';
import { resolve } from 'node:path';

// MTMOTION_PKG=<dir> benchmarks another build of the package (e.g. a size
// variant); the default is the repository's pkg/.
const pkgDir = process.env.MTMOTION_PKG ? pathToFileURL(resolve(process.env.MTMOTION_PKG) + '/') : new URL('../../pkg/', import.meta.url);
const wasm = await import(new URL('mtmotion.js', pkgDir));
const bytes = readFileSync(fileURLToPath(new URL('mtmotion_bg.wasm', pkgDir)));
wasm.initSync({ module: bytes });
export { wasm };

/** Times `fn` (after warm-up) and prints the median; returns the median in ms. */
export function bench(name, fn, { perItem = 1, unit = 'call', runs = 15, warmup = 3, target } = {}) {
  for (let i = 0; i < warmup; i++) fn();
  const times = [];
  for (let i = 0; i < runs; i++) {
    const t0 = performance.now();
    fn();
    times.push(performance.now() - t0);
  }
  times.sort((a, b) => a - b);
  const med = times[Math.floor(times.length / 2)];
  const per = (med * 1e6) / perItem;
  const rate = perItem / (med / 1e3);
  const verdict = target === undefined ? '' : med <= target ? `  ✓ target ${target} ms` : `  ✗ target ${target} ms`;
  console.log(`${name}: median ${med.toFixed(3)} ms (min ${times[0].toFixed(3)}) — ${per.toFixed(1)} ns/${unit}, ${(rate / 1e6).toFixed(2)} M ${unit}/s${verdict}`);
  return med;
}
