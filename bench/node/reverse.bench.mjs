// Node benchmarks of reverseCompensate on the repository's corpus of real
// programs (the shared corpus, tests/support/corpus.mjs; wasm build in pkg/), and of parse + simulate
// of large programs at dt = 1 ms: the corpus's 40,306-line CNCjs pocket
// and a GENERATED 35,000-line raster (zig-zag of G1 moves, made here for
// the benchmark only — not a real program).
// The 40,306-line pocket is measured on its own below: since the rounds
// simulate only around the places they correct, it is compensated, not
// refused (2.4 s natively at dt 2 ms; see docs/toolpath.md).
// Targets: reverse compensation < 5 s per program; parse + simulate of
// 35,000 lines < 1 s.
import { wasm, bench } from './harness.mjs';
import { corpusMissing, readCorpus } from '../../tests/support/corpus.mjs';

if (corpusMissing) throw new Error(`these benchmarks need the NC corpus: ${corpusMissing}`);
const read = readCorpus;
const cfg = { tA: 0.04, T: 0.015, dt: 0.001 };

// Rows of 20 chords of 1.5 mm at F4000 along X, 0.2 mm apart (a CAM
// finishing raster's shape): 35,000 lines, about 800 s of motion.
const lines = ['G21 G90 G17', 'G0 X0 Y0 Z1', 'G1 Z-1 F4000'];
for (let i = 0; lines.length < 35000; i++) {
  const row = Math.floor(i / 21), k = i % 21;
  if (k === 20) { lines.push(`G1 Y${(0.2 * (row + 1)).toFixed(1)}`); continue; }
  const x = row % 2 ? 30 - 1.5 * (k + 1) : 1.5 * (k + 1);
  lines.push(`G1 X${x.toFixed(1)}`);
}
const raster = lines.join('\n');
bench('parseNc + simulateToolPath generated raster, 35,000 lines', () => wasm.simulateToolPath(raster, cfg), { runs: 3, warmup: 1, target: 1000 });
// At dt = 1 ms the pocket needs 5.2 M samples (the CAMotics pocket 5.7 M):
// both simulate, their series thinned to at most 1 M samples (the numbers
// use all); the pocket's reverse compensation is measured at dt = 3 ms
// (its correction windows have their own budget, src/budget.rs; a cut
// shows in budgetNote).
const pocket = read('cncjs_tball-pocket.gcode');
bench('parseNc + simulateToolPath cncjs_tball-pocket (40,306 lines) at dt 1 ms', () => wasm.simulateToolPath(pocket, cfg), { runs: 3, warmup: 0, target: 1000 });
const botomata = read('camotics_botomata_bottom.nc');
bench('parseNc + simulateToolPath camotics_botomata_bottom (6,216 lines, 5.7 M samples) at dt 1 ms', () => wasm.simulateToolPath(botomata, cfg), { runs: 3, warmup: 0 });
const coarse = { ...cfg, dt: 0.003 };
bench('parseNc + simulateToolPath cncjs_tball-pocket (40,306 lines) at dt 3 ms', () => wasm.simulateToolPath(pocket, coarse), { runs: 1, warmup: 0, target: 1000 });
let rp;
bench('reverseCompensate cncjs_tball-pocket at dt 3 ms (work budget)', () => { rp = wasm.reverseCompensate(pocket, coarse); }, { runs: 1, warmup: 0, target: 5000 });
console.log(`  pocket: ${rp.before.maxErrorUm.toFixed(1)} → ${rp.after.maxErrorUm.toFixed(1)} µm; ${rp.budgetNote ?? 'not cut'}`);

const ratios = [];
for (const f of ['cncjs_arc-xz-plane.gcode', 'cncjs_arc-yz-plane.gcode', 'cncjs_circle-inch.gcode', 'cncjs_helical-thread-milling.gcode', 'linuxcnc_comp.ngc', 'linuxcnc_arcspiral.ngc', 'linuxcnc_cds.ngc', 'linuxcnc_tort.ngc']) {
  const text = read(f);
  let r;
  bench(`reverseCompensate ${f}`, () => { r = wasm.reverseCompensate(text, cfg); }, { runs: 1, warmup: 0, target: 5000 });
  ratios.push(r.after.maxErrorUm / r.before.maxErrorUm);
  console.log(`  ${f}: ${r.before.maxErrorUm.toFixed(1)} → ${r.after.maxErrorUm.toFixed(1)} µm (×${(r.after.maxErrorUm / r.before.maxErrorUm).toFixed(3)}), time ${r.before.motionTime.toFixed(3)} → ${r.after.motionTime.toFixed(3)} s`);
}
ratios.sort((a, b) => a - b);
const m = ratios.length;
console.log(`  median after/before max error: ${(m % 2 ? ratios[(m - 1) / 2] : 0.5 * (ratios[m / 2 - 1] + ratios[m / 2])).toFixed(3)}`);
