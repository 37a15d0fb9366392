// The shipped wasm is optimised by wasm-opt (npm binaryen, scripts/build):
// it must still load through initSync (Debian's binaryen 108 broke the
// externref table there) and give bit-identical results to the unoptimised
// wasm that scripts/build keeps in target/unopt/. The embed module
// (cargo --no-default-features, pkg-embed/; not run through wasm-opt) must
// give the same values as the full module for the functions the calculators
// call.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, readFileSync } from 'node:fs';

const root = new URL('../../', import.meta.url);
/** A fresh instance of a glue module (the query makes a separate module instance). */
async function load(glue, wasm, tag) {
  const m = await import(new URL(`${glue}?${tag}`, root));
  m.initSync({ module: readFileSync(new URL(wasm, root)) });
  return m;
}

// A deterministic set of calls over every area; results as plain data.
function calls(mt, { full = true } = {}) {
  const m = mt.machinePreset('nmv5000');
  const trace = 'angle_deg,deviation_um\n' + Array.from({ length: 360 }, (_, i) => `${i},${(3 * Math.cos((2 * i * Math.PI) / 180) + 0.5 * Math.sin((3 * i * Math.PI) / 180)).toFixed(4)}`).join('\n');
  const out = {
    machine: m,
    torque: mt.torqueSaturation(m, { j1: [1.7], torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200 }),
    radius: mt.radiusReduction({ feed: 2000, radius: 10, tA: 0.064, T: 0.03 }),
    circular: mt.circularTest(mt.parseBallbarTrace(trace)),
    sweep: mt.travelRangeSweep({ offset: { z: 0.01, x: -0.02 }, harmonics: [{ order: 2, amplitude: 0.005, phase: 0.3 }], ranges: [90, 180, 360], radius: 100, samples: 1000 }),
  };
  if (!full) return out;
  const axis = { ...m.axes.c, j1: 1.7 };
  const position = new Float64Array(20000).map((_, i) => Math.min(i * 1e-4, 0.5) * 4 * Math.PI);
  const arcs = mt.toolpathExample('arcs');
  const cfg = { tA: 0.04, T: 0.015, dt: 0.001 };
  return {
    ...out,
    simulate: mt.simulateAxis(axis, { dt: 1e-4, position }),
    feedVector: mt.feedVectorTest(m, { rc: 5, rw: 8, omega: Math.PI, accelTime: 0.064, j1: 1.7, duration: 1, dt: 1e-4 }).summary,
    bestKffp: mt.bestKffp(m, { rc: 5, rw: 8, omega: 3.2 * Math.PI, accelTime: 0.064, j1: 1.7 }, { method: 'simulated' }),
    toolpath: mt.simulateToolPath(arcs, cfg),
    reverse: mt.reverseCompensate(arcs, cfg).after,
    cone: mt.coneFrustumTest({ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, feed: 1000, points: 200 }).maxDeviation,
  };
}

const have = (p) => existsSync(new URL(p, root));

test('the optimised full wasm loads with initSync and equals the unoptimised one bit for bit', { skip: !have('target/unopt/mtmotion_bg.wasm') && 'run ./scripts/build first' }, async () => {
  const opt = await load('pkg/mtmotion.js', 'pkg/mtmotion_bg.wasm', 'opt');
  const raw = await load('pkg/mtmotion.js', 'target/unopt/mtmotion_bg.wasm', 'raw');
  assert.notDeepEqual(readFileSync(new URL('pkg/mtmotion_bg.wasm', root)), readFileSync(new URL('target/unopt/mtmotion_bg.wasm', root)), 'wasm-opt ran');
  assert.deepEqual(calls(opt), calls(raw));
});

test('the embed module exports only the calculators\' functions and gives the full module\'s values', async () => {
  const embed = await load('pkg-embed/mtmotion_embed.js', 'pkg-embed/mtmotion_embed_bg.wasm', 'embed');
  const full = await load('pkg/mtmotion.js', 'pkg/mtmotion_bg.wasm', 'full');
  assert.equal(embed.simulateAxis, undefined);
  assert.equal(embed.coneFrustumTest, undefined);
  const e = calls(embed, { full: false });
  const f = calls(full, { full: false });
  // Different opt-levels may round differently in the last bits: compare to 1e-12 relative.
  const close = (a, b, path) => {
    if (typeof a === 'number') return assert.ok(Math.abs(a - b) <= 1e-12 * Math.max(1, Math.abs(b)) || (Number.isNaN(a) && Number.isNaN(b)), `${path}: ${a} vs ${b}`);
    if (a && typeof a === 'object') {
      assert.deepEqual(Object.keys(a).sort(), Object.keys(b).sort(), path);
      for (const k of Object.keys(a)) close(a[k], b[k], `${path}.${k}`);
      return;
    }
    assert.equal(a, b, path);
  };
  close(e, f, 'embed');
});
