// Identical numbers everywhere: the wasm build in Node against the native
// build's results in tests/golden/golden.json (tests/golden.rs), one case
// per capability.
//
// Bit for bit where no libm function is in the loop: the servo simulation
// (exact discretisation computed once) and the forward kinematics. Where
// the result goes through many sin/cos/exp/atan2 calls, the builds use
// different libm code — glibc natively, the Rust `libm` port (musl) in
// wasm32 — which may differ by 1 ulp per call, and fits and simulations
// carry those differences on. There the bound is relative: every number
// within REL_BOUND × max(|native|, its array's largest magnitude) + ABS_FLOOR.
// The largest difference seen is printed.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as mt from '../../pkg/mtmotion.js';

mt.initSync({ module: readFileSync(new URL('../../pkg/mtmotion_bg.wasm', import.meta.url)) });
const golden = JSON.parse(readFileSync(new URL('../golden/golden.json', import.meta.url), 'utf8'));
const inp = golden.inputs;

/** FNV-1a (32 bit) over the little-endian bytes, as tests/golden.rs. */
function fnv(values) {
  const bytes = new Uint8Array(Float64Array.from(values).buffer);
  let h = 0x811c9dc5;
  for (const b of bytes) h = Math.imul(h ^ b, 16777619) >>> 0;
  return h;
}
/** As tests/golden.rs `arr`: length, hash, largest magnitude, 33 samples. */
function arr(v) {
  const m = Math.min(v.length, 33);
  const sample = Array.from({ length: m }, (_, k) => v[m > 1 ? Math.floor((k * (v.length - 1)) / (m - 1)) : 0]);
  return { len: v.length, fnv: fnv(v), maxAbs: v.reduce((a, x) => Math.max(a, Math.abs(x)), 0), sample };
}

// Relative bound where libm differs. Measured here (largest per case,
// printed by each test): feed vector 6.7e-14, tool path 1.2e-11, ball bar
// 1.0e-10 (the circular-test diagnostics, least-squares fits of µm-sized
// terms), cone frustum 3.6e-11, alignment 9.2e-13. 1e-9 leaves a margin
// for other inputs without hiding a real change, which moves results by
// far more.
const REL_BOUND = 1e-9;
const ABS_FLOOR = 1e-15;

/**
 * Walks `want` and compares every number: exactly when `exact`, else
 * within the bound. Returns { problems, worst } (worst relative difference).
 */
function diff(got, want, exact, path = '', out = { problems: [], worst: 0 }, scale = 0) {
  if (typeof want === 'number') {
    if (Object.is(got, want)) return out;
    const d = Math.abs(got - want);
    const s = Math.max(Math.abs(want), scale);
    out.worst = Math.max(out.worst, d / (s || 1));
    if (exact || !(d <= REL_BOUND * s + ABS_FLOOR)) out.problems.push(`${path}: wasm ${got}, native ${want}`);
  } else if (want === null || typeof want !== 'object') {
    if (got !== want) out.problems.push(`${path}: wasm ${JSON.stringify(got)}, native ${JSON.stringify(want)}`);
  } else if ('fnv' in want && 'sample' in want) {
    if (got?.len !== want.len) out.problems.push(`${path}.len: wasm ${got?.len}, native ${want.len}`);
    else if (got.fnv !== want.fnv) {
      if (exact) out.problems.push(`${path}: hash differs (not bit-identical)`);
      want.sample.forEach((w, i) => diff(got.sample[i], w, false, `${path}.sample[${i}]`, out, want.maxAbs));
    }
  } else {
    for (const k of Object.keys(want)) diff(got?.[k], want[k], exact, `${path}.${k}`, out, scale);
    if (got && typeof got === 'object' && !ArrayBuffer.isView(got)) {
      for (const k of Object.keys(got)) if (!(k in want)) out.problems.push(`${path}.${k}: only in wasm`);
    }
  }
  return out;
}

/** Cases that must be bit-identical (no libm call in their loops). */
const EXACT = new Set(['servo', 'kinematics']);

const CASES = {
  servo: () => {
    const r = mt.simulateAxis(mt.machinePreset('nmv5000').axes.x, { dt: 1e-3, position: Float64Array.from(inp.servoRamp) });
    return { position: arr(r.position), velocity: arr(r.velocity), torque: arr(r.torque) };
  },
  feedVector: () => {
    const r = mt.feedVectorTest('nmv5000', inp.feedVector);
    const s = r.series;
    return { summary: r.summary, x: arr(s.x), y: arr(s.y), c: arr(s.c), torqueC: arr(s.torqueC), shapeError: arr(s.shapeError), angleDiff: arr(s.angleDiff) };
  },
  toolpath: () => {
    const s = mt.simulateToolPath(mt.toolpathExample('arcs'), inp.toolpath);
    return { t: arr(s.t), simX: arr(s.simX), simY: arr(s.simY), nearX: arr(s.nearX), velSimX: arr(s.velSimX), motionTime: s.motionTime, maxErrorTime: s.maxErrorTime };
  },
  ballbar: () => {
    const t = mt.syntheticBallbarTrace(inp.synthetic);
    return {
      deviation: arr(t.runs[0].deviation),
      fitCircle: mt.fitCircle(Float64Array.from(inp.circleX), Float64Array.from(inp.circleY)),
      circularTest: mt.circularTest(t),
    };
  },
  kinematics: () => {
    const [x, y, z, a, b, c] = inp.forwardQ;
    return mt.forwardKinematics('pocketnc-v2-10', { x, y, z, a, b, c }, inp.forwardErrors, inp.toolLength);
  },
  cone: () => {
    const r = mt.coneFrustumTest(inp.cone);
    return { deviation: arr(r.deviation), time: arr(r.time), x: arr(r.path.x), z: arr(r.path.z), maxDeviation: r.maxDeviation, minDeviation: r.minDeviation };
  },
  alignment: () => mt.estimateAlignment({ sections: inp.sections }),
};

test('the fixture has one case per capability', () => {
  assert.deepEqual(Object.keys(golden).filter((k) => k !== 'inputs').sort(), Object.keys(CASES).sort());
});

for (const [name, run] of Object.entries(CASES)) {
  const exact = EXACT.has(name);
  test(`${name}: wasm in Node = native, ${exact ? 'bit for bit' : `within ${REL_BOUND} relative`}`, () => {
    const { problems, worst } = diff(run(), golden[name], exact, name);
    console.log(`golden ${name}: largest relative difference wasm vs native ${worst.toExponential(2)}`);
    assert.deepEqual(problems, []);
  });
}

test('the comparison can fail: one ulp off is seen where exact, 1e-8 off where bounded', () => {
  const want = golden.kinematics;
  const got = structuredClone(want);
  const f = new Float64Array([got.position[0]]);
  new BigUint64Array(f.buffer)[0] += 1n;
  got.position[0] = f[0];
  assert.equal(diff(got, want, true).problems.length, 1);
  const far = structuredClone(golden.alignment);
  far.sections[0].x *= 1 + 1e-8;
  assert.equal(diff(far, golden.alignment, false).problems.length, 1);
  const a = Float64Array.from(golden.inputs.circleX);
  const b = a.slice();
  new BigUint64Array(b.buffer)[100] += 1n;
  assert.notEqual(fnv(a), fnv(b));
});
