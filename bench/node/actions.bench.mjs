// Node benchmarks of the core calls behind the page's main actions, with
// the panels' own arguments (docs/performance.md §5): the wasm time of a
// click, without the worker's messages or the drawing.
// - kinematics "cone frustum (4 runs)": four coneFrustumTest calls (15°/45°
//   × perpendicular/parallel, 1440 points, servo models), as runCone in
//   www/panels/kinematics.js;
// - toolpath "Simulate": simulateToolPath of the arc example at the
//   panel's defaults (www/panels/toolpath.js);
// - servo "Simulate" and "Best K_FFP" (www/panels/servo.js run()).
import { wasm, bench } from './harness.mjs';

const opts = { runs: 9, warmup: 3 };

const combos = [[15, 'perpendicular'], [15, 'parallel'], [45, 'perpendicular'], [45, 'parallel']];
const cone = (theta, method) => ({
  machine: 'trunnion-ac', halfApexDeg: theta, inclinationDeg: 10, method,
  barLength: 100, feed: 1000, centre: [60, 40, 20],
  errors: { location: {} }, drives: { backlash: {} }, idealServo: false, points: 1440,
});
for (const [theta, method] of combos) bench(`coneFrustumTest ${theta}° ${method}`, () => wasm.coneFrustumTest(cone(theta, method)), opts);
bench('cone frustum, the 4 runs in sequence', () => combos.map(([t, m]) => wasm.coneFrustumTest(cone(t, m))), { ...opts, target: 100 });

const arcs = wasm.toolpathExample('arcs');
const tp = { tA: 0.04, T: [0.015, 0.015, 0.015], dt: 0.001, feedOverride: 1 };
const n = wasm.simulateToolPath(arcs, tp).t.length;
bench(`toolpath Simulate: simulateToolPath arc example (${n} samples)`, () => wasm.simulateToolPath(arcs, tp), { ...opts, warmup: 20, target: 100 });

const m = wasm.machinePreset('nmv5000');
const p = m.paperSweep;
const cond = { rc: p.rc, rw: p.rw, omega: Number(Math.PI.toFixed(6)), accelTime: p.accelTime, j1: p.j1[0], dt: 0.001 };
bench('servo Simulate: feedVectorTest', () => wasm.feedVectorTest(m, cond), { ...opts, target: 100 });
bench('servo Best K_FFP: bestKffp alone', () => wasm.bestKffp(m, cond), opts);
bench('servo Best K_FFP: the panel\'s calls (feedVectorTest, bestKffp, feedVectorTest)', () => {
  wasm.feedVectorTest(m, cond);
  const best = wasm.bestKffp(m, cond);
  wasm.feedVectorTest(m, { ...cond, kffp: best.kffp });
}, { ...opts, target: 100 });
