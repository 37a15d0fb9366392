// reverseCompensate on every program of the shared NC corpus in the wasm
// build (issue 27's must-shows): tA 40 ms, T 15 ms, dt 2 ms, one run each.
// Per program: lines, before → after maximum error and their ratio, the
// motion-time growth, wall and CPU time of the call (process.cpuUsage),
// the CPU time against the target (5 s up to 20,000 lines, 30 s above:
// the 35k-line CAMotics cameo raster; on a shared machine the wall time
// depends on its load, printed with os.loadavg); then the median ratio, the
// unchanged and refused ones. Programs that do not parse are out of scope
// (as examples/reverse_corpus.rs, which prints the same numbers natively).
//   node bench/node/run.mjs reverse-corpus
//   node bench/node/reverse-corpus.bench.mjs [name-part…]
import { readdirSync } from 'node:fs';
import { loadavg } from 'node:os';
import { performance } from 'node:perf_hooks';
import { wasm } from './harness.mjs';
import { corpusDir, corpusMissing, readCorpus } from '../../tests/support/corpus.mjs';

if (corpusMissing) throw new Error(`this benchmark needs the NC corpus: ${corpusMissing}`);
const only = process.argv.slice(2).filter((a) => !a.startsWith('reverse-corpus'));
const cfg = { tA: 0.04, T: 0.015, dt: 0.002 };
const names = readdirSync(corpusDir)
  .filter((n) => n !== 'SOURCES.md' && !n.startsWith('.'))
  .filter((n) => !only.length || only.some((o) => n.includes(o)))
  .sort();
console.log(`load average at start: ${loadavg().map((x) => x.toFixed(2)).join(' ')}`);
const ratios = [];
let unchanged = 0, refused = 0, over = 0, cpuTotal = 0;
for (const name of names) {
  const text = readCorpus(name);
  try {
    wasm.parseNc(text);
  } catch {
    console.log(`${name.padEnd(50)} does not parse (out of scope)`);
    continue;
  }
  const lines = text.split('\n').length;
  const target = lines <= 20000 ? 5000 : 30000;
  const c0 = process.cpuUsage();
  const t0 = performance.now();
  let r;
  try {
    r = wasm.reverseCompensate(text, cfg);
  } catch (e) {
    refused++;
    console.log(`${name.padEnd(50)} refused: ${e.message ?? e}`);
    continue;
  }
  const wall = performance.now() - t0;
  const c = process.cpuUsage(c0);
  const cpu = (c.user + c.system) / 1e3;
  cpuTotal += cpu;
  const ratio = r.after.maxErrorUm / r.before.maxErrorUm;
  ratios.push(ratio);
  if (r.unchanged) unchanged++;
  const ok = cpu <= target;
  if (!ok) over++;
  const time = 100 * (r.after.motionTime / r.before.motionTime - 1);
  console.log(
    `${name.padEnd(50)} ${String(lines).padStart(6)} lines ${r.before.maxErrorUm.toFixed(1).padStart(8)} → ${r.after.maxErrorUm.toFixed(1).padStart(7)} µm ×${ratio.toFixed(3)}  time ${time >= 0 ? '+' : ''}${time.toFixed(2)} %  wall ${(wall / 1e3).toFixed(2)} s  CPU ${(cpu / 1e3).toFixed(2)} s  ${ok ? '✓' : '✗'} CPU ${target / 1e3} s${r.unchanged ? '  unchanged' : ''}${r.budgetNote ? '  (budget cut)' : ''}`,
  );
}
ratios.sort((a, b) => a - b);
const m = ratios.length;
if (m) {
  const median = m % 2 ? ratios[(m - 1) / 2] : 0.5 * (ratios[m / 2 - 1] + ratios[m / 2]);
  console.log(`${m} compensated, median after/before ×${median.toFixed(3)}, ${unchanged} unchanged, ${refused} refused, ${over} over their CPU time target; CPU ${(cpuTotal / 1e3).toFixed(1)} s in all; load average at end: ${loadavg().map((x) => x.toFixed(2)).join(' ')}`);
}
