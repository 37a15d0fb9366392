// Compares builds of the package on a few representative calls, for the
// size/speed table of docs/performance.md:
//   node bench/node/compare.mjs <pkg dir> [<pkg dir> …]
// All builds are loaded in this one process and their calls interleaved
// (A, B, C, A, B, C, …), so every build sees the same machine load; each
// call's CPU time (user + system of this process: time spent waiting for a
// core is not counted) is recorded, and the lower quartile is printed.
// The package directories may hold mtmotion.js or mtmotion_embed.js.
import { readFileSync, readdirSync } from 'node:fs';
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const dirs = process.argv.slice(2);
const rounds = Number(process.env.ROUNDS || 60);
const mods = [];
for (const [k, d] of dirs.entries()) {
  const js = readdirSync(d).find((f) => /^mtmotion(_embed)?\.js$/.test(f));
  const m = await import(`${pathToFileURL(resolve(d, js))}?${k}`);
  m.initSync({ module: readFileSync(resolve(d, js.replace('.js', '_bg.wasm'))) });
  mods.push(m);
}
const cpu = () => {
  const u = process.cpuUsage();
  return (u.user + u.system) / 1000;
};

const full = mods.every((m) => m.simulateAxis);
// The embed module has no machinePreset; only the full calls need it.
const m0 = full ? mods[0].machinePreset('nmv5000') : null;
const axis = full ? { ...m0.axes.c, j1: 1.7 } : null;
const n = 100_000, dt = 1e-4, omega = 4 * Math.PI, ta = 0.064;
const position = new Float64Array(n).map((_, i) => (i * dt < ta ? (omega * (i * dt) ** 2) / (2 * ta) : omega * (i * dt - ta / 2)));
const trace = 'angle_deg,deviation_um\n' + Array.from({ length: 720 }, (_, i) => `${i / 2},${(Math.sin(((i / 2) * Math.PI) / 90) * 3).toFixed(4)}`).join('\n');
const calls = {
  'circularDeviation 720 points': [(w) => w.circularDeviation(w.parseBallbarTrace(trace)), 1],
  'travelRangeSweep 1000 samples': [(w) => w.travelRangeSweep({ offset: { z: 0, x: 0 }, harmonics: [{ order: 2, amplitude: 0.005, phase: 0 }], ranges: [180], radius: 100, samples: 1000 }), 1],
};
if (full) {
  const arcs = mods[0].toolpathExample('arcs');
  Object.assign(calls, {
    'simulateAxis 1e5 steps': [(w) => w.simulateAxis(axis, { dt, position }), 1],
    'feedVectorTest 2 s': [(w) => w.feedVectorTest(m0, { rc: 5, rw: 8, omega: Math.PI, accelTime: 0.064, j1: 1.7, duration: 2, dt: 1e-4 }), 1],
    'simulateToolPath arcs 1 ms': [(w) => w.simulateToolPath(arcs, { tA: 0.04, T: 0.015, dt: 0.001 }), 1],
    'reverseCompensate arcs': [(w) => w.reverseCompensate(arcs, { tA: 0.04, T: 0.015, dt: 0.001 }), 6],
  });
}
console.log(['call', ...dirs].join(' | '));
for (const [name, [fn, slow]] of Object.entries(calls)) {
  const times = mods.map(() => []);
  for (let r = 0; r < 5; r++) mods.forEach((w) => fn(w)); // warm-up (Liftoff → TurboFan)
  for (let r = 0; r < Math.ceil(rounds / slow); r++) {
    mods.forEach((w, k) => {
      const t0 = cpu();
      fn(w);
      times[k].push(cpu() - t0);
    });
  }
  const q1 = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 4)];
  console.log([name, ...times.map((t) => `${q1(t).toFixed(3)} ms`)].join(' | '));
}
