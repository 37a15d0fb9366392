// Flat heap: each main action of the page, called through the built pkg/
// as the panel calls it, runs 20 times after a warm-up; neither the wasm
// linear memory, nor wasm-bindgen's table of JS values held by Rust, nor the
// JS heap (after a full garbage collection) may grow beyond a stated bound.
// A leak of one result per run (the smallest result below is a few hundred
// bytes, most are kilobytes to megabytes) would cross the bounds; the
// control test proves the probes see growth.
//
// Bounds:
// - wasm memory (memory.buffer.byteLength): 0 bytes of growth after the
//   warm-up. Linear memory never shrinks; a run that frees what it
//   allocates reuses the same pages.
// - externref table (__wbindgen_externrefs.length): 0 growth (every JS value
//   handed to Rust is released).
// - JS heap (process.memoryUsage() heapUsed + arrayBuffers after gc(), so
//   that leaked typed arrays count too): at most 256 KiB
//   over the 20 runs (V8's own bookkeeping, e.g. inline caches and
//   compiled code, moves by tens of KiB between collections).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, readFileSync } from 'node:fs';
import { setFlagsFromString } from 'node:v8';
import { runInNewContext } from 'node:vm';

const root = new URL('../../', import.meta.url);
const built = existsSync(new URL('pkg/mtmotion_bg.wasm', root));
const WARMUP = 5;
const RUNS = 20;
const HEAP_BOUND = 256 * 1024;

setFlagsFromString('--expose-gc');
const gc = runInNewContext('gc');

let mt;
let wasm;
if (built) {
  mt = await import(new URL('pkg/mtmotion.js', root));
  wasm = mt.initSync({ module: readFileSync(new URL('pkg/mtmotion_bg.wasm', root)) });
}

function probe() {
  gc();
  gc();
  return {
    wasm: wasm.memory.buffer.byteLength,
    table: wasm.__wbindgen_externrefs?.length ?? 0,
    // Typed arrays (most results' series) live outside V8's heap, in
    // arrayBuffers; a leaked result is mostly there.
    heap: process.memoryUsage().heapUsed + process.memoryUsage().arrayBuffers,
  };
}

/** Growth of each probe over RUNS calls of `action`, after WARMUP calls.
 * wasm memory and the externref table over two batches of RUNS; the JS
 * heap as the smaller growth of the two batches: a leak grows in both, a
 * one-off allocation of V8's own (code, feedback, a heap page) in only one
 * (it made the bound fail on a quiet instance, 275 KiB once in three runs). */
function growth(action) {
  for (let i = 0; i < WARMUP; i++) action();
  const before = probe();
  for (let i = 0; i < RUNS; i++) action();
  const mid = probe();
  for (let i = 0; i < RUNS; i++) action();
  const after = probe();
  const heap = Math.min(mid.heap - before.heap, after.heap - mid.heap);
  return { wasm: after.wasm - before.wasm, table: after.table - before.table, heap };
}

// The panels' main actions with their default inputs (www/panels/*.js).
function actions() {
  const m = mt.machinePreset('nmv5000');
  const cond = { rc: 5, rw: 8, omega: Math.PI, accelTime: 0.064, j1: 1.7, duration: 1, dt: 1e-3 };
  const arcs = mt.toolpathExample('arcs');
  const cfg = { tA: 0.04, T: 0.015, dt: 0.001 };
  const ws = Float64Array.from({ length: 200 }, (_, i) => 10 ** (-1 + (4 * i) / 199));
  const trace = 'angle_deg,deviation_um\n' + Array.from({ length: 360 }, (_, i) => `${i},${(3 * Math.cos((2 * i * Math.PI) / 180)).toFixed(4)}`).join('\n');
  const synth = { radius: 100, rangeDeg: 360, feed: 1000, offsetX: 0.002, offsetY: -0.001, harmonics: [{ order: 2, amplitude: 0.003, phase: 0.2 }], backlashX: 0.001 };
  return {
    'servo: feedVectorTest + bestKffp': () => {
      mt.feedVectorTest(m, cond);
      const best = mt.bestKffp(m, cond);
      mt.feedVectorTest(m, { ...cond, kffp: best.kffp });
    },
    'servo: frequencyResponse (Bode)': () => mt.frequencyResponse({ ...m.axes.c, j1: 1.7 }, ws),
    'servo: torqueSaturation': () => mt.torqueSaturation(m, { j1: [1.7, 3.2], torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200, dt: 1e-3 }),
    'tool path: checkNc': () => mt.checkNc(arcs),
    'tool path: simulateToolPath': () => mt.simulateToolPath(arcs, cfg),
    'tool path: reverseCompensate': () => mt.reverseCompensate(arcs, cfg),
    'ball bar: synthetic trace, fit, harmonics, ISO 230-4, sweep': () => {
      const t = mt.syntheticBallbarTrace(synth);
      const run = t.runs[0];
      const x = run.angleRad.map((a, i) => (t.nominalRadius + run.deviation[i]) * Math.cos(a));
      const y = run.angleRad.map((a, i) => (t.nominalRadius + run.deviation[i]) * Math.sin(a));
      const fit = mt.fitCircle(x, y);
      mt.harmonics(run.angleRad, run.deviation, 10);
      mt.circularTest(t);
      mt.travelRangeSweep({ offset: { z: fit.cx, x: fit.cy }, ranges: [90, 180, 270, 360], radius: 100, samples: 1000 });
    },
    'ball bar: parseBallbarTrace': () => mt.parseBallbarTrace(trace, { nominalRadius: 100 }),
    'kinematics: coneFrustumTest': () => mt.coneFrustumTest({ machine: 'trunnion-ac', halfApexDeg: 45, inclinationDeg: 10, feed: 1000, centre: [0, 50, 0], points: 360 }),
    'kinematics: compensateNc5': () => {
      const s = mt.sShapeTestPiece({ machine: 'pocketnc-v2-10' });
      mt.compensateNc5(s.nc, { machine: 'pocketnc-v2-10', monteCarlo: { seed: 1, sigmaMm: 0.01, sigmaRad: 1e-4 } });
    },
  };
}

test('every main action of the page leaves wasm memory, the externref table and the JS heap flat over 20 runs', { skip: !built && 'run ./scripts/build first' }, () => {
  const rows = [];
  for (const [name, action] of Object.entries(actions())) {
    const g = growth(action);
    rows.push(`${name}: wasm ${g.wasm} B, table ${g.table}, JS heap ${(g.heap / 1024).toFixed(1)} KiB`);
    assert.equal(g.wasm, 0, `${name}: wasm memory grew by ${g.wasm} bytes over ${RUNS} runs`);
    assert.equal(g.table, 0, `${name}: ${g.table} JS values left in the externref table over ${RUNS} runs`);
    assert.ok(g.heap <= HEAP_BOUND, `${name}: JS heap grew by ${(g.heap / 1024).toFixed(1)} KiB over ${RUNS} runs (bound ${HEAP_BOUND / 1024} KiB)`);
  }
  console.log(rows.join('\n'));
});

test('control: the probes see a result kept per run and wasm memory that must grow', { skip: !built && 'run ./scripts/build first' }, () => {
  const kept = [];
  const arcs = mt.toolpathExample('arcs');
  const heap = growth(() => kept.push(mt.simulateToolPath(arcs, { tA: 0.04, T: 0.015, dt: 0.001 })));
  assert.ok(heap.heap > HEAP_BOUND, `keeping ${RUNS} simulations should grow the JS heap past the bound, grew ${heap.heap} B`);
  // Inputs that grow by 2 MiB a run must be copied into ever more wasm memory.
  const max = (WARMUP + RUNS) << 17;
  const cx = Float64Array.from({ length: max }, (_, i) => Math.cos(i));
  const cy = Float64Array.from({ length: max }, (_, i) => Math.sin(i));
  let n = 0;
  const bigger = growth(() => {
    n += 1 << 17;
    mt.fitCircle(cx.subarray(0, n), cy.subarray(0, n));
  });
  assert.ok(bigger.wasm >= RUNS << 20, `growing inputs should grow the wasm memory, grew ${bigger.wasm} B`);
});
