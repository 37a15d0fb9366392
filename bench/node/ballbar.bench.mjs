// Ball-bar and alignment benchmarks of the wasm build (targets):
//   fitCircle on 1e6 points < 50 ms; travelRangeSweep, 10 ranges at 1000 samples < 10 ms.
// Run: node bench/node/run.mjs ballbar   (needs pkg/ from wasm-pack build --release)
import { wasm, bench } from './harness.mjs';

const n = 1_000_000;
const x = new Float64Array(n);
const y = new Float64Array(n);
let s = 1;
for (let i = 0; i < n; i++) {
  s = (s * 1103515245 + 12345) % 2147483648;
  const e = 0.001 * (s / 2147483648 - 0.5);
  const t = ((200 * i) / n) * (Math.PI / 180);
  x[i] = 3 + (100 + e) * Math.cos(t);
  y[i] = -1 + (100 + e) * Math.sin(t);
}
const fit = wasm.fitCircle(x, y);
if (Math.abs(fit.r - 100) > 1e-3 || Math.abs(fit.cx - 3) > 1e-3) throw new Error(`fitCircle wrong: ${JSON.stringify(fit)}`);
bench('fitCircle 1e6 points (200° arc)', () => wasm.fitCircle(x, y), { perItem: n, unit: 'point', target: 50 });

const sweep = {
  offset: { z: 0, x: 0.01 },
  harmonics: [
    { order: 2, amplitude: 0.005, phase: 0 },
    { order: 3, amplitude: 0.003, phase: 0 },
    { order: 5, amplitude: 0.0025, phase: 0 },
  ],
  ranges: [90, 120, 150, 180, 210, 240, 270, 300, 330, 360],
  radius: 100,
  samples: 1000,
};
bench('travelRangeSweep 10 ranges × 1000 samples', () => wasm.travelRangeSweep(sweep), { perItem: 10, unit: 'range', target: 10 });

const trace = wasm.syntheticBallbarTrace({ backlashX: 0.004, cyclicAmplitude: 0.001 });
bench('circularTest 2 × 3601 points with diagnostics', () => wasm.circularTest(trace), { perItem: 7202, unit: 'point' });
