// Speed-up of the study pool (www/lib/pool.js) from 1 to 2 workers (this
// machine has 2 cores; worker_threads stand in for Web Workers). The
// results are identical for any count (tests/node/pool.test.mjs).
import { performance } from 'node:perf_hooks';
import { wasm } from './harness.mjs';
import { createPool, kffpSweep, travelRangeSweep, monteCarloNc5 } from '../../www/lib/pool.js';
import { nodeSpawn } from '../../tests/node/pool-spawn.mjs';

const m = wasm.machinePreset('nmv5000');
// The servo panel's paper sweep (suzuki-best-kffp): 3 loads × 6 speeds.
const conditions = [1.7, 3.24, 4.77].flatMap((j1) => [0.5, 1, 1.5, 2, 3, 4].map((k) => ({ rc: 5, rw: 8, omega: k * Math.PI, accelTime: 0.064, j1 })));
const sweep = { offset: { z: 0.01, x: -0.02 }, harmonics: [{ order: 2, amplitude: 0.005, phase: 0.3 }], ranges: Array.from({ length: 360 }, (_, i) => i + 1), radius: 100, samples: 1000 };
const s = wasm.sShapeTestPiece({ machine: 'pocketnc-v2-10' });
const seeds = Array.from({ length: 16 }, (_, i) => i + 1);
const studies = {
  'K_FFP sweep (18 bestKffp)': (p) => kffpSweep(p, m, conditions),
  'travel-range sweep (360 ranges)': (p) => travelRangeSweep(p, sweep),
  'Monte-Carlo S-shape (16 seeds)': (p) => monteCarloNc5(p, s.nc, { machine: 'pocketnc-v2-10', monteCarlo: { sigmaMm: 0.01, sigmaRad: 1e-4 } }, seeds),
};
for (const [name, study] of Object.entries(studies)) {
  const med = {};
  for (const size of [1, 2]) {
    const pool = createPool({ size, spawn: nodeSpawn });
    await study(pool); // start the workers and warm up
    const times = [];
    for (let i = 0; i < 5; i++) {
      const t0 = performance.now();
      await study(pool);
      times.push(performance.now() - t0);
    }
    pool.close();
    med[size] = times.sort((a, b) => a - b)[2];
  }
  console.log(`${name}: 1 worker ${med[1].toFixed(0)} ms, 2 workers ${med[2].toFixed(0)} ms → speed-up ${(med[1] / med[2]).toFixed(2)}×`);
}
