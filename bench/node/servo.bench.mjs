// Node benchmarks of the servo bindings (wasm build): the issue-3 targets.
//   simulateAxis with saturation and Pre-Control ≤ 40 ns/step;
//   feedVectorTest, 3 axes, 2 s at 0.1 ms < 10 ms;
//   bestKffp in simulated mode < 300 ms.
import { wasm, bench } from './harness.mjs';

const m = wasm.machinePreset('nmv5000');
const axis = { ...m.axes.c, j1: 1.7 };
const dt = 1e-4;
const n = 100_000;
const omega = 4 * Math.PI;
const ta = 0.064;
const position = new Float64Array(n);
for (let i = 0; i < n; i++) {
  const t = i * dt;
  position[i] = t < ta ? (omega * t * t) / (2 * ta) : omega * (t - ta / 2);
}
const check = wasm.simulateAxis(axis, { dt, position });
if (!check.saturated) throw new Error('the benchmark case must saturate');
bench('simulateAxis (saturating, Pre-Control) 1e5 steps', () => wasm.simulateAxis(axis, { dt, position }), {
  perItem: n,
  unit: 'step',
  target: (40 * n) / 1e6,
});

const cond = { rc: 5, rw: 8, omega: Math.PI, accelTime: 0.064, j1: 1.7, duration: 2, dt: 1e-4 };
bench('feedVectorTest 3 axes 2 s at 0.1 ms', () => wasm.feedVectorTest(m, cond), { target: 10 });

const sat = { rc: 5, rw: 8, omega: 3.2 * Math.PI, accelTime: 0.064, j1: 1.7 };
const r = wasm.bestKffp(m, sat, { method: 'simulated' });
if (r.method !== 'simulated') throw new Error('expected simulated mode');
bench('bestKffp simulated (ω = 3.2π, saturating)', () => wasm.bestKffp(m, sat, { method: 'simulated' }), {
  runs: 7,
  target: 300,
});

const omegas = new Float64Array(1000).map((_, i) => 0.1 * 1.01 ** i);
bench('frequencyResponse 1000 points', () => wasm.frequencyResponse(axis, omegas), { perItem: 1000, unit: 'point' });
