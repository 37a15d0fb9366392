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
  const trace = 'angle_deg,deviation_um\n' + Array.from({ length: 360 }, (_, i) => `${i},${(3 * Math.cos((2 * i * Math.PI) / 180) + 0.5 * Math.sin((3 * i * Math.PI) / 180)).toFixed(4)}`).join('\n');
  const out = {
    inertia: mt.axisInertia('nmv5000', 'c'),
    torque: mt.torqueSaturation('nmv5000', { j1: [1.7], torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200 }),
    radius: mt.radiusReduction({ feed: 2000, radius: 10, tA: 0.064, T: 0.03 }),
    circular: mt.circularDeviation(mt.parseBallbarTrace(trace)),
    sweep: mt.travelRangeSweep({ offset: { z: 0.01, x: -0.02 }, harmonics: [{ order: 2, amplitude: 0.005, phase: 0.3 }], ranges: [90, 180, 360], radius: 100, samples: 1000 }),
  };
  if (!full) return out;
  const m = mt.machinePreset('nmv5000');
  const axis = { ...m.axes.c, j1: 1.7 };
  const position = new Float64Array(20000).map((_, i) => Math.min(i * 1e-4, 0.5) * 4 * Math.PI);
  const arcs = mt.toolpathExample('arcs');
  const cfg = { tA: 0.04, T: 0.015, dt: 0.001 };
  return {
    ...out,
    machine: m,
    circularTest: mt.circularTest(mt.parseBallbarTrace(trace)),
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
  assert.equal(embed.circularTest, undefined); // the calculator shows no diagnostics: circularDeviation
  // Nor the preset registry: the torque calculator names its machine.
  assert.equal(embed.machinePreset, undefined);
  assert.equal(embed.machines, undefined);
  assert.equal(embed.estimateAlignmentBand, undefined);
  assert.equal(embed.checkFileSize, undefined);
  // A machine object, or a preset without a torque-saturation reading, is refused by name.
  assert.throws(() => embed.torqueSaturation({ name: 'x' }, { j1: [1], accelTime: 0.064, feedAtCuttingPoint: 200 }), /machine: expected a string/);
  assert.throws(() => embed.axisInertia('trunnion-ac', 'c'), /known presets: nmv5000/);
  assert.throws(() => embed.axisInertia('nmv5000', 'q'), /no axis 'q'; its axes: c, x, y/);
  assert.equal(full.axisInertia(full.machinePreset('nmv5000'), 'c'), full.machinePreset('nmv5000').axes.c.j);
  const e = calls(embed, { full: false });
  const f = calls(full, { full: false });
  // Different opt-levels may round differently in the last bits: compare to 1e-12 relative.
  const close = (a, b, path) => {
    if (typeof a === 'number') return assert.ok(Math.abs(a - b) <= 1e-12 * Math.max(1, Math.abs(b)) || (Number.isNaN(a) && Number.isNaN(b)), `${path}: ${a} vs ${b}`);
    if (a && typeof a === 'object') {
      // Same keys in the same order (the embed module builds its results by hand).
      assert.deepEqual(Object.keys(a), Object.keys(b), path);
      for (const k of Object.keys(a)) close(a[k], b[k], `${path}.${k}`);
      return;
    }
    assert.equal(a, b, path);
  };
  close(e, f, 'embed');
  // Both directions with backlash, reversal spikes and a cyclic error: every part of the result is filled in.
  const synthetic = full.syntheticBallbarTrace({ bothDirections: true, backlashX: 0.002, spike: 0.003, cyclicAmplitude: 0.001, cyclicPitch: 5, servoMismatch: 0.001 });
  const { diagnostics, ...c } = full.circularTest(synthetic);
  assert.ok(c.hUm !== null && c.runs.length === 2 && diagnostics !== null, 'the synthetic trace fills in H and the diagnostics');
  close(full.circularDeviation(synthetic), c, 'circularDeviation is circularTest without the diagnostics');
  close(embed.circularDeviation(synthetic), c, 'synthetic trace');
  // The example page's trace.
  const html = readFileSync(new URL('www/embed-example.html', root), 'utf8');
  const text = html.slice(html.indexOf('angle_deg,deviation_um'), html.indexOf('</mt-circularity>'));
  close(embed.circularDeviation(embed.parseBallbarTrace(text)), full.circularDeviation(full.parseBallbarTrace(text)), 'example trace');
  close(embed.parseBallbarTrace(text, { nominalRadius: 50, feed: 1000 }), full.parseBallbarTrace(text, { nominalRadius: 50, feed: 1000 }), 'options');
  close(embed.travelRangeSweep({ ranges: [120] }), full.travelRangeSweep({ ranges: [120] }), 'sweep defaults');
  close(embed.torqueSaturation('nmv5000', { j1: [0, 3], accelTime: 0.064, feedAtCuttingPoint: 200, reading: 'inertiaOnly' }), full.torqueSaturation('nmv5000', { j1: [0, 3], accelTime: 0.064, feedAtCuttingPoint: 200, reading: 'inertiaOnly' }), 'reading');
  // The embed module reads its configs by hand (src/wasm/args.rs): the
  // messages for what a calculator can pass are the full module's.
  const sweep = (h, more = {}) => ({ offset: { z: 0, x: 0 }, harmonics: [{ order: 2, amplitude: 0.005, phase: 0, ...h }], ranges: [180], radius: 100, samples: 1000, ...more });
  const sat = (q) => ({ j1: [1.7], torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200, ...q });
  const eq3 = (q) => ({ feed: 2000, radius: 10, tA: 0.064, T: 0.03, ...q });
  const bad = [
    ...[2.5, -1, NaN, 5e9, 1e20, Infinity].map((order) => ['travelRangeSweep', sweep({ order })]),
    ['travelRangeSweep', sweep({ amplitude: NaN })],
    ['travelRangeSweep', sweep({}, { ranges: [NaN] })],
    ['travelRangeSweep', sweep({}, { radius: -1 })],
    ['travelRangeSweep', sweep({}, { samples: 2.5 })],
    ['travelRangeSweep', { harmonics: [] }],
    ['radiusReduction', eq3({ feed: NaN })],
    ['radiusReduction', eq3({ radius: -5 })],
    ['radiusReduction', { feed: 1, radius: 1, tA: 0.1 }],
    ['torqueSaturation', 'nmv5000', sat({ j1: [NaN] })],
    ['torqueSaturation', 'nmv5000', sat({ j1: [] })],
    ['torqueSaturation', 'nmv5000', sat({ torqueMax: NaN })],
    ['torqueSaturation', 'nmv5000', sat({ accelTime: -1 })],
    ['torqueSaturation', 'nmv5000', sat({ feedAtCuttingPoint: 0 })],
    ['torqueSaturation', 'nmv5000', sat({ reading: 'bogus' })],
    ['torqueSaturation', 'nmv5000', { j1: [1] }],
    ['parseBallbarTrace', 'x,y\n1,2'],
    ['parseBallbarTrace', text, { nominalRadius: -1 }],
  ];
  const message = (mt, [fn, ...args]) => {
    try {
      return `returned ${JSON.stringify(mt[fn](...args))}`;
    } catch (err) {
      return err.message;
    }
  };
  for (const b of bad) assert.equal(message(embed, b), message(full, b), `${b[0]} ${JSON.stringify(b.slice(1))}`);
});
