// Node benchmarks of the tool-path bindings (wasm build in pkg/).
// Targets: simulateToolPath ≥ 5 M samples/s; a 10,000-segment
// program at dt = 1 ms in < 1 s; reverseCompensate of the example < 500 ms.
import { wasm, bench } from './harness.mjs';

const arcs = wasm.toolpathExample('arcs');
const cfg = { tA: 0.04, T: 0.015, dt: 0.001 };

// V8 runs wasm first in its baseline compiler (Liftoff) and swaps in the
// optimised code (TurboFan) after a budget of calls; on this 2-ms call that
// takes about a dozen calls, so warm up with 20 for the steady-state rate.
const n1 = wasm.simulateToolPath(arcs, cfg).t.length;
bench(`simulateToolPath arc example dt=1 ms (${n1} samples)`, () => wasm.simulateToolPath(arcs, cfg), { perItem: n1, unit: 'sample', warmup: 20 });
const fine = { ...cfg, dt: 0.0001 };
const n2 = wasm.simulateToolPath(arcs, fine).t.length;
bench(`simulateToolPath arc example dt=0.1 ms (${n2} samples)`, () => wasm.simulateToolPath(arcs, fine), { perItem: n2, unit: 'sample', runs: 7 });

// 10,000 segments: a wavy line of 1–3 mm chords, every fifth an arc, F3000
// (the same program as benches/toolpath.rs).
const lines = ['G90 G17 G21', 'G0 X0 Y0', 'G1 X1 Y0 F3000'];
let x = 1, y = 0;
for (let i = 0; i < 9999; i++) {
  const len = 1 + (i % 3);
  const ang = Math.sin(i * 0.05) * 0.6;
  const nx = x + len * Math.cos(ang), ny = y + len * Math.sin(ang);
  lines.push(i % 5 === 4 ? `G3 X${nx.toFixed(4)} Y${ny.toFixed(4)} R${(5 * len).toFixed(4)}` : `G1 X${nx.toFixed(4)} Y${ny.toFixed(4)}`);
  x = nx; y = ny;
}
const long = lines.join('\n');
const n3 = wasm.simulateToolPath(long, cfg).t.length;
bench(`simulateToolPath 10,000 segments dt=1 ms (${n3} samples)`, () => wasm.simulateToolPath(long, cfg), { perItem: n3, unit: 'sample', runs: 5, warmup: 1, target: 1000 });

bench('reverseCompensate arc example', () => wasm.reverseCompensate(arcs, cfg), { runs: 5, warmup: 1, target: 500 });
const r = wasm.reverseCompensate(arcs, cfg);
console.log(`  arc example: ${r.before.maxErrorUm.toFixed(1)} µm → ${r.after.maxErrorUm.toFixed(1)} µm, motion time ${r.before.motionTime.toFixed(3)} s → ${r.after.motionTime.toFixed(3)} s`);
