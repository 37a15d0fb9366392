// A revoked Proxy — or a Proxy whose every trap throws — in any argument
// position of any export gives a named Error and leaks nothing. The
// exports are enumerated from the pkg module itself (every function but
// initSync and the default init; a class's constructor and methods, as
// functions); each has a good argument list here (a new export without
// one fails the first test), and each position in turn
// gets the hostile value while the others stay good, so the position is
// really read. 10,000 calls in all; then the wasm stack pointer must be
// where it was (a JS exception unwinding through wasm frames skips its
// restore: the leak that used to kill the instance after 800-5,500 calls),
// and normal calls must still give the right answers.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as mt from '../../pkg/mtmotion.js';
import { exportedFunctions, testClassesListed } from './fixtures/exports.mjs';

const wasm = mt.initSync({ module: readFileSync(new URL('../../pkg/mtmotion_bg.wasm', import.meta.url)) });

const TOTAL_CALLS = 10_000;

const revokedProxy = () => {
  const { proxy, revoke } = Proxy.revocable({}, {});
  revoke();
  return proxy;
};
const boom = () => { throw new Error('trap boom'); };
const throwingProxy = new Proxy({}, {
  get: boom, has: boom, ownKeys: boom, getOwnPropertyDescriptor: boom, getPrototypeOf: boom,
});

const f64 = (...v) => new Float64Array(v);
const COND = { rc: 5, rw: 8, omega: 3, accelTime: 0.064, j1: 1.7 };
const TP = { tA: 0.04, T: 0.015, dt: 0.001 };
const arcs = mt.toolpathExample('arcs');
const axisC = mt.machinePreset('nmv5000').axes.c;
const axisX = mt.machinePreset('nmv5000').axes.x;
const ramp = Float64Array.from({ length: 300 }, (_, i) => Math.max(0, i * 1e-3 - 0.05) * 0.2);
const angles = Float64Array.from({ length: 360 }, (_, i) => (i * Math.PI) / 180);
const twoTurns = Float64Array.from({ length: 720 }, (_, i) => (i * Math.PI) / 180);
const sections = [0, 100].map((y) => ({
  y,
  angleDeg: Float64Array.from({ length: 121 }, (_, i) => i - 60),
  deviation: Float64Array.from({ length: 121 }, (_, i) => 0.01 * Math.cos(((i - 60) * Math.PI) / 180) + y * 1e-5),
}));
const servoTrace = 'time [ms],X [mm],Y [mm],C [deg]\n' + Array.from({ length: 50 }, (_, i) => `${i},${Math.cos(i / 8)},${Math.sin(i / 8)},${i / 10}`).join('\n');
const ballbarText = 'angle [deg],deviation [um]\n' + Array.from({ length: 37 }, (_, i) => `${i * 10},${Math.sin(i)}`).join('\n');
const b5rText = '<TEST_DOCUMENT><ANALYSIS NAME="RENISHAW_DIAGNOSTICS"><FEATURE NAME="AF_SQUARENESS" DT="UT_SQUARENESS">12</FEATURE></ANALYSIS></TEST_DOCUMENT>';
const trace = mt.syntheticBallbarTrace({ backlashX: 0.004, bothDirections: true });
const sshape = mt.sShapeTestPiece({ machine: 'pocketnc-v2-10', scale: 0.1 });
const x = angles.map((a) => 1 + 50 * Math.cos(a));
const y = angles.map((a) => 2 + 50 * Math.sin(a));
const ok = () => true;

// name → a good argument list, one value for every parameter
const GOOD = {
  analyzeFeedVectorTrace: [servoTrace, COND, { time: 'time', timeScale: 1e-3, steadyFrom: 0 }],
  angleSweep: [{ sections: [{ y: 0, offset: { z: 0, x: 0.01 } }, { y: 100, offset: { z: 0.01, x: 0 } }], ranges: [90, 180] }],
  axisInertia: ['nmv5000', 'c'],
  b5rBeside: [b5rText, trace],
  ballbarExample: ['fig7', 100],
  bestKffp: ['nmv5000', { ...COND, duration: 1 }, { method: 'analytic' }],
  bestKffpFromTrace: ['nmv5000', { ...COND, duration: 1, kffp: { x: 60, y: 60, c: 60 } }, servoTrace, { time: 'time', timeScale: 1e-3, steadyFrom: 0 }, { method: 'analytic' }],
  checkFileSize: ['part.nc', 1000],
  checkNc: [arcs, {}],
  'new NcStream': [1000],
  'NcStream.push': [new TextEncoder().encode(arcs)],
  'NcStream.checkNc': [{}],
  'NcStream.simulateToolPathColumns': [TP, ok],
  circularDeviation: [trace],
  circularTest: [trace],
  compensateNc5: [sshape.nc, { machine: 'pocketnc-v2-10' }],
  coneFrustumTest: [{ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, feed: 1000, points: 200 }, ok],
  errorSymbols: ['trunnion-ac'],
  estimateAlignment: [{ sections }],
  estimateAlignmentBand: [{ sections }],
  feedVectorTest: ['nmv5000', { ...COND, duration: 0.2 }],
  fitCircle: [x, y],
  forwardKinematics: ['pocketnc-v2-10', { x: 10, y: -5, z: 3, a: 20, b: 45 }, {}, 0],
  forwardKinematicsBulk: ['pocketnc-v2-10', f64(10, -5, 3, 20, 45, 0), {}, 0],
  frequencyResponse: [axisC, f64(1, 10, 100)],
  harmonics: [angles, angles.map((a) => 0.005 * Math.sin(2 * a)), 4],
  identifyAccDec: [[[2000, 3], [4000, 5], [6000, 4], [1000, 10]].map(([feed, radius]) => ({ feed, radius, radiusLoss: mt.radiusReduction({ feed, radius, tA: 0.05, T: 0.02 }) }))],
  identifyAxis: [axisX, { dt: 1e-3, command: Array.from(ramp), position: Array.from(mt.simulateAxis(axisX, { dt: 1e-3, position: ramp }).position) }],
  identifyPitchError: [twoTurns, twoTurns.map((a) => 1e-5 * Math.sin(4 * a)), { maxOrder: 8 }],
  inverseKinematics: ['table-on-table-bc', { position: [10, 0, 5], orientation: [0, 0, 1] }, 0],
  machinePreset: ['nmv5000', 'inertiaAtLoad'],
  machines: [],
  ncMainFile: [['O100\nG1 X1 F100\nM99\n', 'G1 X1 F100\nM98 P100\nM30\n']],
  parseBallbarTrace: [ballbarText, {}],
  parseNc: [arcs, {}],
  radiusReduction: [{ feed: 2000, radius: 10, tA: 0.04, T: 0.015 }],
  readB5r: [b5rText],
  reverseCompensate: [arcs, { ...TP, iterations: 1 }, ok],
  sShapeTestPiece: [{ machine: 'pocketnc-v2-10', scale: 0.1 }],
  simulateAxis: [axisC, { dt: 1e-3, position: ramp }],
  simulateToolPath: [arcs, TP, ok],
  simulateToolPathColumns: [arcs, TP, ok],
  start: [],
  syntheticBallbarTrace: [{ offsetX: 0.003 }],
  toolpathExample: ['lines'],
  torqueSaturation: ['nmv5000', { j1: [1.7], torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200 }],
  traceLayout: [servoTrace, { ratedTorque: 10 }, 'feedVector'],
  traceColumns: [servoTrace],
  travelRangeSweep: [{ offset: { z: 0.01, x: -0.02 }, ranges: [90, 180], samples: 200 }],
  version: [],
};

const exported = exportedFunctions(mt, arcs);
testClassesListed(mt, exported);

// every (export, argument position)
const positions = exported.flatMap(({ name, f }) => Array.from({ length: f.length }, (_, i) => ({ name, f, i })));

/** The wasm stack pointer (moving it by 0 returns it). */
const stackPointer = () => wasm.__wbindgen_add_to_stack_pointer(0);

/** What is wrong with a call that must throw a named Error (null: none). */
function outcome({ name, f, i }, hostile, named) {
  const args = GOOD[name].slice();
  args[i] = hostile;
  try {
    f(...args);
  } catch (e) {
    const m = e instanceof Error ? e.message : String(e);
    if (!(e instanceof Error) || e instanceof WebAssembly.RuntimeError) return `${name} #${i}: threw ${e}`;
    if (!named.test(m) || m.length > 400) return `${name} #${i}: ${e.constructor.name}: ${m.slice(0, 200)}`;
    return null;
  }
  return `${name} #${i}: returned instead of throwing`;
}

test('every export has a good argument list, and it works', () => {
  assert.ok(exported.length >= 30, `only ${exported.length} exports found`);
  assert.deepEqual(exported.filter(({ name }) => !(name in GOOD)).map(({ name }) => name), [], 'exports without a good argument list');
  for (const { name, f } of exported) {
    assert.equal(GOOD[name].length, f.length, `${name}: ${f.length} parameters`);
    f(...GOOD[name]);
  }
  assert.ok(positions.length >= 50, `only ${positions.length} argument positions`);
});

test('a revoked or throwing Proxy in each of the argument positions, 10,000 calls, gives named Errors and leaks nothing', () => {
  const sp = stackPointer();
  assert.equal(typeof sp, 'number', 'the wasm module exports its stack-pointer helper');
  const problems = new Set();
  let calls = 0;
  while (calls < TOTAL_CALLS) {
    for (const p of positions) {
      // the argument's name and "revoked Proxy", e.g. "text: expected a
      // string, got a revoked Proxy", "radiusReduction: is a revoked Proxy"
      const revoked = outcome(p, revokedProxy(), /^[\w.[\]]+: .*revoked Proxy/);
      if (revoked) problems.add(revoked);
      calls += 1;
      if (calls % 4 === 0) {
        // the thrown message, or what the argument should have been
        const thrown = outcome(p, throwingProxy, /^[\w.[\]]+: .*(trap boom|expected)/);
        if (thrown) problems.add(thrown);
        calls += 1;
      }
    }
  }
  assert.deepEqual([...problems], []);
  assert.equal(stackPointer(), sp, `the wasm stack pointer moved over ${calls} hostile calls`);
  // the instance still answers, and right: Eq. 3 and a parsed move
  const [feed, radius, tA, T] = [2000, 10, 0.04, 0.015];
  const w = feed / 60 / radius;
  const eq3 = (1 - (Math.sin((tA * w) / 2) / ((tA * w) / 2)) / Math.sqrt(T * T * w * w + 1)) * radius;
  assert.ok(Math.abs(mt.radiusReduction({ feed, radius, tA, T }) - eq3) < 1e-12);
  assert.equal(mt.parseNc('#1=[2+3]*2\nG1 X#1 Y-7 F600').segments[0].end.x, 10);
  assert.equal(mt.machinePreset('nmv5000').axes.c.torqueMax, 725);
});

test('the messages name the argument and say what is wrong', () => {
  const message = (f) => {
    try {
      f();
    } catch (e) {
      return e.message;
    }
    return 'returned';
  };
  const r = revokedProxy();
  assert.match(message(() => mt.radiusReduction(r)), /^radiusReduction: is a revoked Proxy; pass plain data/);
  assert.match(message(() => mt.parseNc(r)), /^text: expected a string, got a revoked Proxy$/);
  assert.match(message(() => mt.harmonics(angles, angles, r)), /^maxOrder: expected a number, got a revoked Proxy$/);
  assert.match(message(() => mt.simulateToolPath(arcs, TP, r)), /^onProgress: expected a function, got a revoked Proxy$/);
  assert.match(message(() => mt.estimateAlignment({ sections: [r] })), /^input\.sections\[0\]: is a revoked Proxy/);
  assert.match(message(() => mt.circularTest(throwingProxy)), /^trace: reading the argument threw \(trap boom\)/);
  // a progress callback must be a function; a working one is still called
  assert.match(message(() => mt.simulateToolPath(arcs, TP, {})), /^onProgress: expected a function, got object$/);
  let seen = 0;
  mt.coneFrustumTest(GOOD.coneFrustumTest[0], () => { seen += 1; });
  assert.equal(seen, 2);
});
