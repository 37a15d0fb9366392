// One process of compare.mjs: the fastest of several runs of each call (CPU
// time, ms), as JSON.
import { readFileSync } from 'node:fs';
import { resolve } from 'node:path';
import { pathToFileURL, fileURLToPath } from 'node:url';

const dir = pathToFileURL(resolve(process.env.MTMOTION_PKG) + '/');
const js = (await import('node:fs')).readdirSync(fileURLToPath(dir)).find((f) => /^mtmotion(_embed)?\.js$/.test(f));
const wasm = await import(new URL(js, dir));
wasm.initSync({ module: readFileSync(fileURLToPath(new URL(js.replace('.js', '_bg.wasm'), dir))) });

// CPU time of this process (user + system), not wall time: on the shared
// machine a call often waits for a core, which wall time would count.
const cpu = () => { const u = process.cpuUsage(); return (u.user + u.system) / 1000; };
const fastest = (fn, runs = 12, warmup = 4) => {
  for (let i = 0; i < warmup; i++) fn();
  let best = Infinity;
  for (let i = 0; i < runs; i++) {
    const t0 = cpu();
    fn();
    best = Math.min(best, cpu() - t0);
  }
  return best;
};
const out = {};
const m = wasm.machinePreset('nmv5000');
const axis = { ...m.axes.c, j1: 1.7 };
const n = 100_000, dt = 1e-4, omega = 4 * Math.PI, ta = 0.064;
const position = new Float64Array(n).map((_, i) => (i * dt < ta ? (omega * (i * dt) ** 2) / (2 * ta) : omega * (i * dt - ta / 2)));
if (wasm.simulateAxis) {
  out['simulateAxis 1e5 steps'] = fastest(() => wasm.simulateAxis(axis, { dt, position }));
  out['feedVectorTest 2 s'] = fastest(() => wasm.feedVectorTest(m, { rc: 5, rw: 8, omega: Math.PI, accelTime: 0.064, j1: 1.7, duration: 2, dt: 1e-4 }));
  const arcs = wasm.toolpathExample('arcs');
  out['simulateToolPath arcs 1 ms'] = fastest(() => wasm.simulateToolPath(arcs, { tA: 0.04, T: 0.015, dt: 0.001 }), 20, 20);
  out['reverseCompensate arcs'] = fastest(() => wasm.reverseCompensate(arcs, { tA: 0.04, T: 0.015, dt: 0.001 }), 3, 1);
}
const trace = 'angle_deg,deviation_um\n' + Array.from({ length: 720 }, (_, i) => `${i / 2},${(Math.sin((i / 2) * Math.PI / 90) * 3).toFixed(4)}`).join('\n');
out['circularTest 720 points'] = fastest(() => wasm.circularTest(wasm.parseBallbarTrace(trace)), 30, 10);
out['travelRangeSweep 1000 samples'] = fastest(() => wasm.travelRangeSweep({ offset: { z: 0, x: 0 }, harmonics: [{ order: 2, amplitude: 0.005, phase: 0 }], ranges: [180], radius: 100, samples: 1000 }), 30, 10);
process.stdout.write(JSON.stringify(out));
