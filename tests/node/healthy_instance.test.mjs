// A failure leaves the instance healthy. Hostile arguments — throwing
// getters, Proxies whose traps throw, configs nested 10,000 deep,
// array-likes with a negative, huge or changing `length`, numbers that
// used to trap the core — are fed 10,000 times, alternating with good
// calls. Every bad call must throw a JS Error (never a WebAssembly trap),
// the good calls must keep returning bit-identical results, and wasm
// memory must not grow by more than GROWTH_BOUND after the warm-up: a JS
// exception unwinding through wasm frames (which skips the restore of
// wasm's stack pointer) or a trap (which skips every free) would leak on
// each call until the instance dies.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as mt from '../../pkg/mtmotion.js';

const wasm = mt.initSync({ module: readFileSync(new URL('../../pkg/mtmotion_bg.wasm', import.meta.url)) });

// One 64 KiB wasm page: the allocator may round a request up to a page once,
// but a leak of even 100 bytes per call would be 1 MB over 10,000 calls.
const GROWTH_BOUND = 65536;
const ROUNDS = 10_000; // bad + good = 20,000 calls

const deep = (n) => {
  let o = {};
  for (let i = 0; i < n; i++) o = { nested: o };
  return o;
};
const DEEP = deep(10_000);
const throwingGetter = { get x() { throw new Error('getter boom'); } };
const throwingProxy = new Proxy({}, { ownKeys() { throw new Error('trap boom'); } });
const protoProxy = new Proxy({}, { getPrototypeOf() { throw 42; } });
let grow = 0;
const changingLength = { get length() { grow += 1000; return grow; }, 0: 1, 1: 2, 2: 3 };
const axis = mt.machinePreset('nmv5000').axes.c;

const BAD = [
  () => mt.forwardKinematics('pocketnc-v2-10', throwingGetter),
  () => mt.forwardKinematics('pocketnc-v2-10', { x: 0 }, throwingProxy),
  () => mt.coneFrustumTest(throwingProxy),
  () => mt.coneFrustumTest(protoProxy),
  () => mt.torqueSaturation('nmv5000', DEEP),
  () => mt.syntheticBallbarTrace(DEEP),
  () => mt.simulateAxis(axis, { dt: 1e-3, position: DEEP }),
  () => mt.fitCircle({ length: -1 }, { length: -1 }),
  () => mt.fitCircle({ length: 2 ** 40 }, [1, 2, 3]),
  () => mt.fitCircle(changingLength, changingLength),
  () => mt.fitCircle(new Proxy([1, 2, 3], { get() { throw new Error('index boom'); } }), [1, 2, 3]),
  () => mt.harmonics([0, 1, 2], [0, 1, 2], 2 ** 32 + 1),
  () => mt.forwardKinematicsBulk('pocketnc-v2-10', { length: -5 }),
  () => mt.estimateAlignment({ sections: throwingProxy }),
  () => mt.circularTest({ nominalRadius: 100, get runs() { throw new Error('runs boom'); } }),
  () => mt.torqueSaturation('nmv5000', { j1: [1.7], torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200, dt: 1e-320 }),
  () => mt.coneFrustumTest({ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, feed: 1e308 }),
  () => mt.coneFrustumTest({ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, feed: 5e-324 }),
  () => mt.simulateAxis({ ...axis, ta: 1e6 }, { dt: 1e-3, position: new Float64Array(10) }),
  () => mt.feedVectorTest('nmv5000', { rc: 5, rw: 8, omega: 1e18, accelTime: 0.064, j1: 1.7 }),
  () => mt.parseNc({ toString() { throw new Error('no'); } }),
  () => mt.radiusReduction([1000, 10, 0.04, 0.01]),
];

const x = new Float64Array(64);
const y = new Float64Array(64);
for (let i = 0; i < 64; i++) {
  x[i] = 3 + 50 * Math.cos(i / 10);
  y[i] = -2 + 50 * Math.sin(i / 10) + 1e-3 * Math.sin(7 * i);
}
const GOOD = [
  () => mt.fitCircle(x, y),
  () => mt.forwardKinematics('pocketnc-v2-10', { x: 10, y: -5, z: 3, a: 20, b: 45 }),
];

/** Every number of a result, as its IEEE-754 bit pattern. */
const bits = (v) => {
  const out = [];
  const walk = (u) => {
    if (typeof u === 'number') out.push(new BigUint64Array(new Float64Array([u]).buffer)[0]);
    else if (u && typeof u === 'object') for (const k of Object.keys(u).sort()) walk(u[k]);
  };
  walk(v);
  return out;
};

function badCall(k) {
  try {
    BAD[k % BAD.length]();
  } catch (e) {
    assert.ok(!(e instanceof WebAssembly.RuntimeError), `bad call ${k % BAD.length} trapped: ${e}`);
    assert.ok(e instanceof Error, `bad call ${k % BAD.length} threw a non-Error: ${e}`);
    assert.ok(e.message.length < 400, `bad call ${k % BAD.length}: message of ${e.message.length} chars`);
    return;
  }
  assert.fail(`bad call ${k % BAD.length} returned instead of throwing`);
}

test('20,000 alternating bad and good calls leave the instance healthy', () => {
  const reference = GOOD.map((g) => bits(g()));
  for (let k = 0; k < 2 * BAD.length; k++) {
    badCall(k);
    GOOD[k % GOOD.length]();
  }
  const before = wasm.memory.buffer.byteLength;
  for (let k = 0; k < ROUNDS; k++) {
    badCall(k);
    const g = k % GOOD.length;
    if (k % 97 === 0) assert.deepEqual(bits(GOOD[g]()), reference[g], `good call ${g} changed after ${k} rounds`);
    else GOOD[g]();
  }
  const growth = wasm.memory.buffer.byteLength - before;
  GOOD.forEach((g, i) => assert.deepEqual(bits(g()), reference[i], `good call ${i} changed`));
  console.log(`wasm memory: ${before} bytes before, growth ${growth} bytes over ${ROUNDS} rounds`);
  assert.ok(growth <= GROWTH_BOUND, `wasm memory grew by ${growth} bytes over ${ROUNDS} bad calls`);
});

test('each hostile argument gets an Error that names what to fix', () => {
  const message = (f) => {
    try {
      f();
    } catch (e) {
      return e.message;
    }
    return 'returned';
  };
  assert.match(message(BAD[0]), /^q\.x: is a getter or setter; pass plain data$/);
  assert.match(message(BAD[1]), /^errors: reading the argument threw \(trap boom\)/);
  assert.match(message(BAD[4]), /^query\.nested[.a-z]*\.\.\.: nested deeper than 32 levels$/);
  assert.match(message(BAD[7]), /^x: expected a Float64Array or an array of numbers, got an object$/);
  assert.match(message(BAD[11]), /^maxOrder: expected a whole number from 0 to \d+, got 4\.29497e\+?9$/);
  assert.match(message(BAD[21]), /^radiusReduction: expected an object \{ … \}, got an array$/);
});
