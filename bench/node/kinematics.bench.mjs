// Node benchmarks of the kinematics bindings (wasm build in pkg/).
// Targets: forward kinematics ≥ 5 M evaluations/s (bulk entry
// point, so the model is measured, not the per-call boundary); a 3600-point
// cone-frustum test with servo models < 50 ms.
import { wasm, bench } from './harness.mjs';

const n = 100_000;
const q = new Float64Array(n * 6);
for (let i = 0; i < n; i++) {
  q[6 * i] = -100 + (i % 200);
  q[6 * i + 1] = 50 - (i % 100);
  q[6 * i + 2] = 10 + (i % 50);
  q[6 * i + 3] = (i % 120) - 20; // A, degrees
  q[6 * i + 5] = (i % 720) - 360; // C, degrees
}
const errors = { location: { EX0C: 0.01, EY0C: -0.005, EA0C: 2e-5, EB0C: -1e-5, EY0A: 0.02, EC0Y: 1e-5 } };

const nominalMs = bench('forwardKinematicsBulk trunnion-ac, nominal, 1e5 points', () =>
  wasm.forwardKinematicsBulk('trunnion-ac', q, undefined, 50), { perItem: n, unit: 'FK' });
const errMs = bench('forwardKinematicsBulk trunnion-ac, 6 location errors, 1e5 points', () =>
  wasm.forwardKinematicsBulk('trunnion-ac', q, errors, 50), { perItem: n, unit: 'FK' });
const single = [10, 20, 30, 15, 0, 40];
const calls = 2000;
const perCallMs = bench(`forwardKinematics per call (${calls} calls, preset by name)`, () => {
  for (let i = 0; i < calls; i++) wasm.forwardKinematics('trunnion-ac', single, undefined, 50);
}, { perItem: calls, unit: 'call' });
const preset = wasm.machinePreset('trunnion-ac');
bench(`forwardKinematics per call (${calls} calls, preset object)`, () => {
  for (let i = 0; i < calls; i++) wasm.forwardKinematics(preset, single, undefined, 50);
}, { perItem: calls, unit: 'call' });

const cone = {
  machine: 'trunnion-ac', halfApexDeg: 45, inclinationDeg: 10, method: 'perpendicular',
  barLength: 100, feed: 1000, centre: [60, 40, 20], points: 3600, leadInDeg: 0,
  errors: { backlash: { c: 1.745e-4 } },
};
bench('coneFrustumTest 3600 points, servo models (5 axes)', () => wasm.coneFrustumTest(cone), { target: 50, runs: 7, warmup: 1 });
bench('coneFrustumTest 3600 points, ideal servos', () => wasm.coneFrustumTest({ ...cone, idealServo: true }), { target: 50, runs: 7, warmup: 1 });
const rate = (ms) => (n / (ms / 1e3) / 1e6).toFixed(2);
console.log(`FK rate: nominal ${rate(nominalMs)} M/s, with errors ${rate(errMs)} M/s (target ≥ 5 M/s); per call ${(perCallMs * 1e3 / calls).toFixed(2)} µs`);
