// How each capability's cost grows with its input (docs/performance.md):
// the default size and 10×, 100×, 1000× it. One call per point (the
// fastest of 3 below 1 s). A point is not run when the growth seen so far
// predicts more than 30 s; the line says so and gives the prediction.
//   node bench/node/run.mjs scaling
import { performance } from 'node:perf_hooks';
import { wasm } from './harness.mjs';
import { createPool, monteCarloNc5 } from '../../www/lib/pool.js';
import { nodeSpawn } from '../../tests/node/pool-spawn.mjs';

const LIMIT_MS = 30_000;
async function time(fn) {
  let t0 = performance.now();
  await fn();
  let best = performance.now() - t0;
  if (best < 1000) {
    for (let i = 0; i < 2; i++) {
      t0 = performance.now();
      await fn();
      best = Math.min(best, performance.now() - t0);
    }
  }
  return best;
}

/** Times `make(n)` for n = base·{1, 10, 100, 1000}; prints one line. */
async function series(name, unit, base, make) {
  const points = [];
  for (const k of [1, 10, 100, 1000]) {
    const n = base * k;
    if (points.length >= 2) {
      const [a, b] = points.slice(-2);
      const slope = Math.log(b.ms / a.ms) / Math.log(b.n / a.n);
      const predicted = b.ms * (n / b.n) ** Math.max(slope, 1);
      if (predicted > LIMIT_MS) {
        points.push({ n, skipped: `not run (predicted ≈ ${(predicted / 1000).toFixed(0)} s > 30 s)` });
        break;
      }
    }
    let fn;
    try {
      fn = await make(n);
      points.push({ n, ms: await time(fn) });
    } catch (e) {
      points.push({ n, skipped: `failed: ${String(e.message || e).slice(0, 80)}` });
      break;
    }
  }
  const text = points.map((p) => `${p.n.toLocaleString('en')} ${unit}: ${p.skipped ?? `${p.ms.toFixed(p.ms < 10 ? 2 : 0)} ms`}`).join(' | ');
  const run = points.filter((p) => p.ms);
  const slope = run.length >= 2 ? Math.log(run.at(-1).ms / run.at(-2).ms) / Math.log(run.at(-1).n / run.at(-2).n) : NaN;
  console.log(`${name}: ${text}  (last growth exponent ${slope.toFixed(2)})`);
}

const m = wasm.machinePreset('nmv5000');
const axis = { ...m.axes.c, j1: 1.7 };

// Servo: samples of one axis (default 2 s at 0.1 ms = 20,000 samples).
await series('simulateAxis', 'samples', 20_000, (n) => {
  const position = new Float64Array(n).map((_, i) => Math.min(i * 1e-4, 1) * 4 * Math.PI);
  return () => wasm.simulateAxis(axis, { dt: 1e-4, position });
});
// Feed-vector test: trace length in s at 0.1 ms (default 2 s).
await series('feedVectorTest', 's of trace', 2, (d) => () => wasm.feedVectorTest(m, { rc: 5, rw: 8, omega: Math.PI, accelTime: 0.064, j1: 1.7, duration: d, dt: 1e-4 }));

// Tool path: segments of a wavy program of 1–3 mm chords, every fifth an arc (default 100).
function program(segments) {
  const lines = ['G90 G17 G21', 'G0 X0 Y0', 'G1 X1 Y0 F3000'];
  let x = 1, y = 0;
  for (let i = 0; i < segments - 1; i++) {
    const len = 1 + (i % 3);
    const ang = Math.sin(i * 0.05) * 0.6;
    const nx = x + len * Math.cos(ang), ny = y + len * Math.sin(ang);
    lines.push(i % 5 === 4 ? `G3 X${nx.toFixed(4)} Y${ny.toFixed(4)} R${(5 * len).toFixed(4)}` : `G1 X${nx.toFixed(4)} Y${ny.toFixed(4)}`);
    x = nx; y = ny;
  }
  return lines.join('\n');
}
const cfg = { tA: 0.04, T: 0.015, dt: 0.001 };
await series('parseNc', 'segments', 100, (n) => { const p = program(n); return () => wasm.parseNc(p); });
await series('simulateToolPath', 'segments', 100, (n) => { const p = program(n); return () => wasm.simulateToolPath(p, cfg); });
await series('reverseCompensate', 'segments', 100, (n) => { const p = program(n); return () => wasm.reverseCompensate(p, cfg); });

// Ball bar: trace length (default 720 points, 0.5°).
await series('parseBallbarTrace + circularTest', 'points', 720, (n) => {
  const text = 'angle_deg,deviation_um\n' + Array.from({ length: n }, (_, i) => `${((360 * i) / n).toFixed(6)},${(3 * Math.cos((4 * Math.PI * i) / n)).toFixed(4)}`).join('\n');
  return () => wasm.circularTest(wasm.parseBallbarTrace(text));
});
await series('travelRangeSweep', 'samples per range', 1000, (n) => () => wasm.travelRangeSweep({ offset: { z: 0.01, x: 0 }, harmonics: [{ order: 2, amplitude: 0.005, phase: 0 }], ranges: [90, 180, 270, 360], radius: 100, samples: n }));
await series('travelRangeSweep', 'ranges', 10, (n) => () => wasm.travelRangeSweep({ offset: { z: 0.01, x: 0 }, harmonics: [{ order: 2, amplitude: 0.005, phase: 0 }], ranges: Array.from({ length: n }, (_, i) => 10 + (350 * i) / n), radius: 100, samples: 1000 }));

// 5-axis: cone-frustum points (default 360), Monte-Carlo runs of the S-shape compensation (default 1).
await series('coneFrustumTest', 'points', 360, (n) => () => wasm.coneFrustumTest({ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, feed: 1000, points: n }));
const s = wasm.sShapeTestPiece({ machine: 'pocketnc-v2-10' });
const pool = createPool({ size: 1, spawn: nodeSpawn });
await series('Monte-Carlo S-shape (pool, 1 worker)', 'runs', 1, (n) => () => monteCarloNc5(pool, s.nc, { machine: 'pocketnc-v2-10', monteCarlo: { sigmaMm: 0.01, sigmaRad: 1e-4 } }, Array.from({ length: n }, (_, i) => i + 1)));
pool.close();
