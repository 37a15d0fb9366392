// Bad input never crashes the core: every exported function, fed malformed,
// missing, non-finite, out-of-range and oversized arguments, either returns
// or throws a JS Error with a message — never a wasm trap (RuntimeError,
// "unreachable", a panic), and the instance keeps working afterwards.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as mt from '../../pkg/mtmotion.js';

mt.initSync({ module: readFileSync(new URL('../../pkg/mtmotion_bg.wasm', import.meta.url)) });

const f64 = (...v) => new Float64Array(v);
const axis = () => mt.machinePreset('nmv5000').axes.c;
const GARBAGE = [undefined, null, {}, [], 'x', NaN, -1, 1e300];

// [function name, list of argument lists]
const CASES = [
  ['machinePreset', [[''], ['\u0000'], [null], ['nmv5000', 'nope'], ['nmv5000', null], ['nmv5000', 3], ['trunnion-ac', 'table']]],
  ['frequencyResponse', [[{}, f64(1)], [{ ...axis(), kpp: NaN }, f64(1)], [axis(), f64(NaN, -1, Infinity)], [{ ...axis(), j: 0 }, f64(1)]]],
  ['simulateAxis', [[axis(), {}], [axis(), { dt: 0, position: f64(0, 1) }], [axis(), { dt: NaN, position: f64(0) }], [axis(), { dt: 1e-3, position: f64(NaN, 1) }], [axis(), { dt: 1e-3, position: f64() }], [{ ...axis(), torqueMax: -5 }, { dt: 1e-3, position: f64(0, 1) }]]],
  ['feedVectorTest', [['nmv5000', {}], ['nmv5000', { rc: 5, rw: 8, omega: NaN, accelTime: 0.064, j1: 1.7 }], ['nmv5000', { rc: 5, rw: 8, omega: 3, accelTime: 0.064, j1: 1.7, duration: 1e9, dt: 1e-9 }], ['nope', { rc: 5 }]]],
  ['analyzeFeedVectorTrace', [['', {}], ['time,x\n0,abc\n', { rc: 5, rw: 8, omega: 3, accelTime: 0.064, j1: 1.7 }], ['a,b,c,d\n1,2,3,4\n', { rc: 5, rw: 8, omega: 3, accelTime: 0.064, j1: 1.7 }, { x: 'zz' }]]],
  ['bestKffp', [['nmv5000', {}], ['nmv5000', { rc: 0, rw: 8, omega: 3, accelTime: 0.064, j1: 1.7 }], ['nmv5000', { rc: 5, rw: 8, omega: 1e6, accelTime: 0.064, j1: 1.7 }, { method: 'magic' }]]],
  ['torqueSaturation', [['nmv5000', {}], ['nmv5000', { j1: [-10], torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200 }], ['nmv5000', { j1: [1.7], torqueMax: 0, accelTime: 0, feedAtCuttingPoint: -1 }]]],
  ['parseNc', [['G2 X10 Y0 F100'], ['G1 X1e999 F100'], ['G2 X10 Y0 R1 F100'], ['G1 X1'], ['G4 P-1'], ['(unclosed'], ['\u0000\u0001'], ['G1 X1 F0']]],
  ['simulateToolPath', [['G1 X10 F1000', {}], ['G1 X10 F1000', { tA: -1, T: 0.01, dt: 0.001 }], ['G1 X10 F1000', { tA: 0.04, T: 0.01, dt: 0 }], ['G1 X1e9 F1', { tA: 0.04, T: 0.01, dt: 1e-6 }], ['G1 X10 F1000', { tA: 0.04, T: { x: NaN }, dt: 0.001 }]]],
  ['radiusReduction', [[{}], [{ feed: 0, radius: 1, tA: 0.04, T: 0.01 }], [{ feed: 1000, radius: -1, tA: 0.04, T: 0.01 }]]],
  ['identifyAccDec', [[[]], [[{ feed: 1000, radius: 10, radiusLoss: NaN }]], [[{ feed: 1000, radius: 10, radiusLoss: 0.01 }, { feed: 1000, radius: 10, radiusLoss: 0.01 }]]]],
  ['reverseCompensate', [['G1 X10 F1000', {}], ['', { tA: 0.04, T: 0.015, dt: 0.001 }], ['G1 X10 F1000', { tA: 0.04, T: 0.015, dt: 0.001, iterations: 1e9 }]]],
  ['toolpathExample', [['nope']]],
  ['fitCircle', [[f64(), f64()], [f64(1, 2), f64(1, 2)], [f64(0, 1, 2), f64(0, 1, 2)], [f64(0, 1, NaN), f64(1, 0, 0)], [f64(1, 2, 3), f64(1)]]],
  ['harmonics', [[f64(), f64(), 3], [f64(0, 1), f64(0, 1), 50], [f64(0, 0.1, 0.2), f64(1, NaN, 1), 1], [f64(0, 1), f64(0, 1), 1e9]]],
  ['travelRangeSweep', [[{}], [{ ranges: [0, -5, 720] }], [{ ranges: [180], samples: 2 }], [{ ranges: [180], samples: 1e12 }], [{ ranges: [180], radius: NaN }]]],
  ['estimateAlignment', [[{}], [{ sections: [] }], [{ sections: [{ y: 0, angleDeg: f64(0, 1), deviation: f64(0) }] }], [{ sections: 'x' }]]],
  ['angleSweep', [[{}], [{ sections: [{ y: 0, offset: { z: 0, x: 0 } }], ranges: [90] }], [{ sections: [{ y: 0, offset: { z: 0, x: 0 } }, { y: 0, offset: { z: 0, x: 0 } }], ranges: [90] }]]],
  ['parseBallbarTrace', [[''], ['angle,deviation\n'], ['angle,deviation\n0,abc\n'], ['x,y\n0,0\n1,1\n'], ['angle,deviation\n0,1\n', { nominalRadius: -1 }]]],
  ['circularTest', [[{}], [{ nominalRadius: 100, feed: null, runs: [] }], [{ nominalRadius: 100, feed: null, runs: [{ direction: 'ccw', angleRad: f64(0), deviation: f64(0) }] }], [{ nominalRadius: 100, feed: null, runs: [{ direction: 'up', angleRad: f64(0, 1, 2), deviation: f64(0, 0, 0) }] }]]],
  ['syntheticBallbarTrace', [[{ samples: 1e12 }], [{ radius: -1 }], [{ rangeDeg: 0 }], [{ noise: NaN }]]],
  ['ballbarExample', [['nope'], ['fig7', -1]]],
  ['forwardKinematics', [['nope', {}], ['pocketnc-v2-10', {}], ['pocketnc-v2-10', { x: NaN, y: 0, z: 0, a: 0, b: 0 }], ['pocketnc-v2-10', { x: 0 }, { location: { bogus: 1 } }]]],
  ['forwardKinematicsBulk', [['pocketnc-v2-10', f64(1, 2, 3)], ['pocketnc-v2-10', f64()], ['nope', f64(0, 0, 0, 0, 0)]]],
  ['errorSymbols', [['nope'], [{}], [{ name: 'trunnion-ac' }]]],
  ['inverseKinematics', [['pocketnc-v2-10', {}], ['pocketnc-v2-10', { position: [NaN, 0, 0], orientation: [0, 0, 1] }], ['pocketnc-v2-10', { position: [0, 0, 0], orientation: [0, 0, 0] }], ['pocketnc-v2-10', { position: [1e9, 0, 0], orientation: [0, 0, 1] }]]],
  ['coneFrustumTest', [[{}], [{ machine: 'trunnion-ac', halfApexDeg: 90, inclinationDeg: 10, method: 'perpendicular', barLength: 100, feed: 1000 }], [{ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, method: 'sideways', barLength: 100, feed: 1000 }], [{ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, method: 'parallel', barLength: -1, feed: 0 }]]],
  ['compensateNc5', [['', {}], ['G1 X1 Y1 Z1 A0 B0 F100', { machine: 'nope' }], ['G2 X1 Y1 I1 J0 F100', { machine: 'pocketnc-v2-10' }], ['G1 X1e9 F100', { machine: 'pocketnc-v2-10' }]]],
  ['sShapeTestPiece', [[{ scale: -1 }], [{ scale: NaN }], [{ points: 1e12 }]]],
];

for (const [name, argLists] of CASES) {
  test(`${name}: malformed input gives an Error, never a trap`, () => {
    assert.equal(typeof mt[name], 'function', `${name} is exported`);
    const lists = [...argLists, ...GARBAGE.map((g) => [g, g, g])];
    for (const args of lists) {
      let outcome;
      try {
        mt[name](...args);
        outcome = 'returned';
      } catch (e) {
        assert.ok(!(e instanceof WebAssembly.RuntimeError), `${name}(${JSON.stringify(args)}) trapped: ${e}`);
        assert.ok(e instanceof Error, `${name} threw a non-Error: ${e}`);
        assert.ok(e.message.length > 0 && !/unreachable|panicked/i.test(e.message), `${name} threw an unhelpful error: ${e.message}`);
        outcome = 'threw';
      }
      assert.ok(outcome);
    }
    // The instance still works after all that.
    assert.equal(mt.machinePreset('nmv5000').axes.c.torqueMax, 725);
  });
}
