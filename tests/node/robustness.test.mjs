// Bad input never crashes the core, and no output holds NaN or Infinity.
//
// - Coverage: every function pkg/mtmotion.d.ts exports has a good call
//   and bad-input calls here; a new export without them fails the test.
// - Bad input: each listed bad call must throw a JS Error (returning is a
//   failure) whose message is short, names something, and is not a trap
//   ("unreachable", "memory access out of bounds", a panic). Generic
//   garbage (undefined, null, {}, [], 'x', NaN, -1, 1e300 in every
//   argument) may be accepted by a tolerant export; then its result must be
//   free of NaN/Infinity.
// - Good calls: every export on the paper's examples and presets returns a
//   result whose every number is finite.
// - Hostile numbers: every number of each good call's arguments (a typed or
//   number array's first and last element) replaced in turn by NaN, ±∞,
//   ±1e308, a subnormal, 2⁵³ or −1 must give an Error in words or a finite
//   result, never a trap.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as mtModule from '../../pkg/mtmotion.js';

// While `recording` is an array, every export call through `mt` appends
// [name, arguments] to it: the good calls' own arguments seed the
// hostile-numbers test below.
let recording = null;
const mt = new Proxy(mtModule, {
  get(target, name) {
    const f = target[name];
    if (typeof f !== 'function' || name === 'initSync') return f;
    return (...args) => {
      if (recording) recording.push([name, args]);
      return f(...args);
    };
  },
});

mtModule.initSync({ module: readFileSync(new URL('../../pkg/mtmotion_bg.wasm', import.meta.url)) });

const f64 = (...v) => new Float64Array(v);
const axis = () => mt.machinePreset('nmv5000').axes.c;
const GARBAGE = [undefined, null, {}, [], 'x', NaN, -1, 1e300];
const COND = { rc: 5, rw: 8, omega: 3, accelTime: 0.064, j1: 1.7 };
const arcs = mt.toolpathExample('arcs');
const TP = { tA: 0.04, T: 0.015, dt: 0.001 };
const ramp = Float64Array.from({ length: 300 }, (_, i) => Math.max(0, i * 1e-3 - 0.05) * 0.2);
const angles = Float64Array.from({ length: 720 }, (_, i) => (i * Math.PI) / 180);
const sections = [0, 100].map((y) => ({
  y,
  angleDeg: Float64Array.from({ length: 121 }, (_, i) => i - 60),
  deviation: Float64Array.from({ length: 121 }, (_, i) => 0.01 * Math.cos(((i - 60) * Math.PI) / 180) + y * 1e-5),
}));
const servoTrace = 'time [ms],X [mm],Y [mm],C [deg]\n' + Array.from({ length: 50 }, (_, i) => `${i},${Math.cos(i / 8)},${Math.sin(i / 8)},${i / 10}`).join('\n');
const ballbarText = 'angle [deg],deviation [um]\n' + Array.from({ length: 37 }, (_, i) => `${i * 10},${Math.sin(i)}`).join('\n');
const sshape = () => mt.sShapeTestPiece({ machine: 'pocketnc-v2-10', scale: 0.1 });

// name → { good: () => result, bad: [argument lists that must throw] }
const CASES = {
  start: { good: () => mt.start(), bad: [] },
  version: { good: () => mt.version(), bad: [] },
  machines: { good: () => mt.machines(), bad: [] },
  checkFileSize: { good: () => mt.checkFileSize('part.nc', 8 * 2 ** 20), bad: [['huge.csv', 100 * 2 ** 20], ['a.nc', -1], ['a.nc', 1.5], ['a.nc', NaN], ['a.nc', Infinity], [42, 10], [undefined, 10]] },
  machinePreset: { good: () => mt.machinePreset('nmv5000', 'inertiaAtLoad'), bad: [[''], ['\u0000'], [null], [{ name: 'nmv5000' }], ['nmv5000', 'nope'], ['nmv5000', 3], ['trunnion-ac', 'table']] },
  ncMainFile: { good: () => mt.ncMainFile(['O100\nG1 X1 F100\nM99\n', 'G1 X1 F100\nM98 P100\nM30\n']), bad: [[42], [[1, 2]], [{ length: -1 }]] },
  frequencyResponse: {
    good: () => mt.frequencyResponse(axis(), f64(1, 10, 100, 1000)),
    bad: [[{}, f64(1)], [{ ...axis(), kpp: NaN }, f64(1)], [axis(), f64(NaN, -1, Infinity)], [{ ...axis(), j: 0 }, f64(1)],
      [{ ...axis(), ts: 1e300 }, f64(1)], [axis(), '100'], [axis(), { length: -1 }], [[axis()], f64(1)]],
  },
  simulateAxis: {
    good: () => mt.simulateAxis(axis(), { dt: 1e-3, position: ramp }),
    bad: [[axis(), {}], [axis(), { dt: 0, position: f64(0, 1) }], [axis(), { dt: NaN, position: f64(0) }], [axis(), { dt: 1e-3, position: f64(NaN, 1) }],
      [axis(), { dt: 1e-3, position: f64() }], [{ ...axis(), torqueMax: -5 }, { dt: 1e-3, position: f64(0, 1) }],
      [{ ...axis(), ta: 1e6 }, { dt: 1e-3, position: ramp }], [{ ...axis(), tp: 2 ** 31 }, { dt: 1e-3, position: ramp }],
      [axis(), { dt: 1e-320, position: ramp }], [{ ...axis(), lead: 1e-320 }, { dt: 1e-3, position: ramp }],
      [{ ...axis(), pitchError: Array.from({ length: 1000 }, () => ({ n: 1, w: 1e-5, phi: 0 })) }, { dt: 1e-3, position: ramp }]],
  },
  feedVectorTest: {
    good: () => mt.feedVectorTest('nmv5000', { ...COND, duration: 1 }),
    bad: [['nmv5000', {}], ['nmv5000', { ...COND, omega: NaN }], ['nmv5000', { ...COND, duration: 1e9, dt: 1e-9 }], ['nope', { rc: 5 }],
      ['nmv5000', { ...COND, omega: 1e18 }], ['nmv5000', { ...COND, kffp: { x: 1e308, y: 0, c: 0 } }], ['nmv5000', { ...COND, duration: 3999 }],
      ['nmv5000', [5, 8, 3, 0.064, 1.7]]],
  },
  analyzeFeedVectorTrace: {
    good: () => mt.analyzeFeedVectorTrace(servoTrace, COND, { time: 'time', timeScale: 1e-3, steadyFrom: 0 }),
    bad: [['', {}], ['time,x\n0,abc\n', COND], ['a,b,c,d\n1,2,3,4\n', COND, { x: 'zz' }], [servoTrace, COND, { timeScale: 1e300 }],
      [servoTrace, COND, { motionStart: NaN }], ['x'.repeat(9 << 20), COND]],
  },
  bestKffp: {
    good: () => mt.bestKffp('nmv5000', { ...COND, duration: 1 }, { method: 'analytic' }),
    bad: [['nmv5000', {}], ['nmv5000', { ...COND, rc: 0 }], ['nmv5000', { ...COND, omega: 1e6 }, { method: 'magic' }]],
  },
  bestKffpFromTrace: {
    good: () => mt.bestKffpFromTrace('nmv5000', { ...COND, duration: 1, kffp: { x: 60, y: 60, c: 60 } }, servoTrace, { time: 'time', timeScale: 1e-3, steadyFrom: 0 }, { method: 'analytic' }),
    bad: [['nmv5000', { ...COND, duration: 1 }, servoTrace, { time: 'time', timeScale: 1e-3, steadyFrom: 0 }],
      ['nmv5000', { ...COND, kffp: { x: 60, y: 60, c: 60 } }, 'time,x\n0,abc\n'], ['nmv5000', { ...COND, kffp: { x: 60, y: 60, c: 60 } }, servoTrace, { timeScale: 1e300 }],
      ['nmv5000', { ...COND, kffp: { x: 60, y: 60, c: 60 } }, servoTrace, { time: 'time', timeScale: 1e-3, steadyFrom: 0 }, { kMin: 5, kMax: 1 }],
      ['nope', { ...COND, kffp: { x: 60, y: 60, c: 60 } }, servoTrace], ['nmv5000', { ...COND, kffp: { x: 60, y: 60, c: 60 } }, 'x'.repeat(9 << 20)]],
  },
  torqueSaturation: {
    good: () => mt.torqueSaturation('nmv5000', { j1: [1.7], torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200 }),
    bad: [['nmv5000', {}], ['nmv5000', { j1: [-10], torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200 }],
      ['nmv5000', { j1: [1.7], torqueMax: 0, accelTime: 0, feedAtCuttingPoint: -1 }],
      ['nmv5000', { j1: [1.7], torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200, dt: 1e-320 }]],
  },
  axisInertia: {
    good: () => mt.axisInertia('nmv5000', 'c'),
    bad: [['nmv5000', 'q'], ['nope', 'c'], ['nmv5000', 3], [{}, 'c'], [42, 'c'], ['nmv5000', 'x'.repeat(9 << 20)]],
  },
  identifyPitchError: {
    good: () => mt.identifyPitchError(angles, angles.map((a) => 1e-5 * Math.sin(4 * a)), { maxOrder: 8 }),
    bad: [[f64(), f64()], [f64(0, 1), f64(0)], [angles, angles.map(() => NaN)], ['100', '100'], [angles, angles, { maxOrder: -1 }]],
  },
  identifyAxis: {
    good: () => mt.identifyAxis(mt.machinePreset('nmv5000').axes.x, { dt: 1e-3, command: Array.from(ramp), position: Array.from(mt.simulateAxis(mt.machinePreset('nmv5000').axes.x, { dt: 1e-3, position: ramp }).position) }),
    bad: [[axis(), {}], [axis(), { dt: 1e-3, command: [0, 1], position: [0] }], [axis(), { dt: NaN, command: [0, 1], position: [0, 1] }]],
  },
  traceLayout: { good: () => mt.traceLayout(servoTrace, { ratedTorque: 10 }), bad: [[''], ['\u0089PNG\r\n\u001a\n\0\0\0'], [42], ['<?xml version="1.0"?>\n<a/>\n'], [servoTrace, { samplePeriod: -1 }], [servoTrace, { rated: 1 }], [servoTrace, {}, 'servo'], [new Uint8Array(9 << 20)], ['x'.repeat(9 << 20)]] },
  traceColumns: { good: () => mt.traceColumns(servoTrace), bad: [[''], ['\u0089PNG\r\n\u001a\n\0\0\0'], [42], ['t,x\n0,1\u0007\n'], ['x'.repeat(9 << 20)]] },
  parseNc: {
    good: () => mt.parseNc(arcs),
    bad: [['G2 X10 Y0 F100'], ['G1 X1e999 F100'], ['G2 X10 Y0 R1 F100'], ['G1 X1'], ['G4 P-1'], ['(unclosed'], ['\u0000\u0001'], ['G1 X1 F0'],
      ['G1 X1 F100', { bogus: 1 }], ['G1 X1 F100\n' + '\n'.repeat(4_000_000)], [`G1 X1 F${'9'.repeat(309)}`]],
  },
  checkNc: { good: () => mt.checkNc(arcs), bad: [[42], ['G1 X1 F100', { dwellP: 'weeks' }], ['G1 X1 F100', []],
    ['G1 X1 F100', { toolRadii: { D1: -1 } }], ['G1 X1 F100', { toolRadii: 'D1=NaN' }], ['G1 X1 F100', { toolRadii: 3 }], ['G1 X1 F100', { toolRadii: { X1: 1 } }]] },
  simulateToolPath: {
    good: () => mt.simulateToolPath(arcs, TP),
    bad: [['G1 X10 F1000', { dt: 0 }], ['G1 X10 F1000', { ...TP, tA: -1 }], ['G1 X10 F1000', { ...TP, dt: 0 }], ['G1 X1e9 F1', { ...TP, dt: 1e-6 }],
      ['G1 X10 F1000', { ...TP, T: { x: NaN } }], ['G1 X199000 F1000', { ...TP, dt: 6e-5 }], ['G1 X10 F1000', [0.04, 0.015, 0.001]],
      ['G0 X0 Y0\nG41 D1 G1 X10 F100\nG3 X10 Y0 I-10 J0\nG40 G1 X0', { ...TP, toolRadii: 'D1=20' }], ['G1 X10 F1000', { ...TP, toolRadii: { D1: Infinity } }]],
  },
  // the same bad arguments as simulateToolPath (below CASES)
  simulateToolPathColumns: { good: () => mt.simulateToolPathColumns(arcs, TP), bad: [] },
  radiusReduction: {
    good: () => mt.radiusReduction({ feed: 2000, radius: 10, tA: 0.04, T: 0.015 }),
    bad: [[{}], [{ feed: 0, radius: 1, tA: 0.04, T: 0.01 }], [{ feed: 1000, radius: -1, tA: 0.04, T: 0.01 }], [{ feed: 1000, radius: 1e-320, tA: 0.04, T: 0.01 }],
      [{ feed: 1000, radius: '200', tA: 0.04, T: 0.01 }], [[2000, 10, 0.04, 0.015]]],
  },
  identifyAccDec: {
    good: () => mt.identifyAccDec([[2000, 3], [4000, 5], [6000, 4], [1000, 10]].map(([feed, radius]) => ({ feed, radius, radiusLoss: mt.radiusReduction({ feed, radius, tA: 0.05, T: 0.02 }) }))),
    bad: [[[]], [[{ feed: 1000, radius: 10, radiusLoss: NaN }]], [[{ feed: 1000, radius: 10, radiusLoss: 0.01 }, { feed: 1000, radius: 10, radiusLoss: 0.01 }]]],
  },
  reverseCompensate: {
    good: () => mt.reverseCompensate(arcs, { ...TP, iterations: 2 }),
    bad: [['G1 X10 F1000', { iterations: -1 }], ['', TP], ['G1 X10 F1000', { ...TP, iterations: 1e9 }], ['G1 X10 F1000', { ...TP, timeBudget: -1 }],
      ['M98 P100\nM30\n', { ...TP, files: [{ name: 'sub.nc', text: 'O100\nG1 X1 F100\nM99\n' }] }]],
  },
  toolpathExample: { good: () => mt.toolpathExample('lines'), bad: [['nope'], [null]] },
  fitCircle: {
    good: () => mt.fitCircle(angles.map((a) => 1 + 50 * Math.cos(a)), angles.map((a) => 2 + 50 * Math.sin(a))),
    bad: [[f64(), f64()], [f64(1, 2), f64(1, 2)], [f64(0, 1, 2), f64(0, 1, 2)], [f64(0, 1, NaN), f64(1, 0, 0)], [f64(1, 2, 3), f64(1)],
      [{ length: -1 }, { length: -1 }], [{ length: 2 ** 40 }, f64(1)], ['100', '100'], [[1, '2', 3], [1, 2, 3]]],
  },
  harmonics: {
    good: () => mt.harmonics(angles, angles.map((a) => 0.005 * Math.sin(2 * a)), 4),
    bad: [[f64(), f64(), 3], [f64(0, 1), f64(0, 1), 50], [f64(0, 0.1, 0.2), f64(1, NaN, 1), 1], [f64(0, 1), f64(0, 1), 1e9], [angles, angles, 2 ** 32 + 1], [angles, angles, 1.5]],
  },
  travelRangeSweep: {
    good: () => mt.travelRangeSweep({ offset: { z: 0.01, x: -0.02 }, ranges: [90, 180, 360], samples: 1000 }),
    bad: [[{}], [{ ranges: [0, -5, 720] }], [{ ranges: [180], samples: 2 }], [{ ranges: [180], samples: 1e12 }], [{ ranges: [180], radius: NaN }],
      [{ ranges: Array.from({ length: 1000 }, () => 180), samples: 1e7 }], [[180]]],
  },
  estimateAlignment: {
    good: () => mt.estimateAlignment({ sections }),
    bad: [[{}], [{ sections: [] }], [{ sections: [{ y: 0, angleDeg: f64(0, 1), deviation: f64(0) }] }], [{ sections: 'x' }], [{ sections, radius: '200' }], [[sections]]],
  },
  estimateAlignmentBand: {
    good: () => mt.estimateAlignmentBand({ sections }),
    bad: [[{}], [{ sections, maxOrder: 2 ** 32 + 1 }], [{ sections, travelRangeDeg: 'all' }], [{ sections, travelRangeDeg: 180 }], [{ sections, radius: -1 }],
      [{ sections, maxOrder: 0 }], [{ sections: [{ y: 0, text: 'x,y\n1,2\n' }] }], [{ sections: [{ y: 0, text: 42 }] }], [{ sections: [{ y: 0, text: 'x,y\n' + Array.from({ length: 20 }, (_, i) => `${Math.cos(i / 10)},${Math.sin(i / 10)}`).join('\n') }] }],
      [{ sections: [{ y: 0, text: 'angle,dev\n' + Array.from({ length: 20 }, (_, i) => `${i},0`).join('\n'), run: 3 }] }], [{ sections: [{ y: 0, text: 'angle,dev\n0,0\n' }], centre: { x: 'a', y: 0 } }]],
  },
  angleSweep: {
    good: () => mt.angleSweep({ sections: [{ y: 0, offset: { z: 0, x: 0.01 } }, { y: 100, offset: { z: 0.01, x: 0 } }], ranges: [90, 180] }),
    bad: [[{}], [{ sections: [{ y: 0, offset: { z: 0, x: 0 } }], ranges: [90] }], [{ sections: [{ y: 0, offset: { z: 0, x: 0 } }, { y: 0, offset: { z: 0, x: 0 } }], ranges: [90] }]],
  },
  parseBallbarTrace: {
    good: () => mt.parseBallbarTrace(ballbarText),
    bad: [[''], ['angle,deviation\n'], ['angle,deviation\n0,abc\n'], ['x,y\n0,0\n1,1\n'], ['angle,deviation\n0,1\n', { nominalRadius: -1 }], ['angle,deviation\n0,1\n1,\u00082\n'],
      [new TextEncoder().encode('MATLAB 5.0 MAT-file')], [new Uint8Array(9 << 20)], [42]],
  },
  readB5r: {
    good: () => mt.readB5r('<TEST_DOCUMENT><ANALYSIS NAME="RENISHAW_DIAGNOSTICS"><FEATURE NAME="AF_SQUARENESS" DT="UT_SQUARENESS">12</FEATURE></ANALYSIS></TEST_DOCUMENT>'),
    bad: [[''], [42], ['<trace/>'], ['<TEST_DOCUMENT><ANALYSIS><FEATURE NAME="X">abc</FEATURE></ANALYSIS></TEST_DOCUMENT>'], ['<!DOCTYPE x><TEST_DOCUMENT/>'], ['x'.repeat(9 << 20)]],
  },
  b5rBeside: {
    good: () => mt.b5rBeside('<TEST_DOCUMENT><ANALYSIS NAME="A"><FEATURE NAME="AF_SQUARENESS" DT="UT_SQUARENESS">12</FEATURE></ANALYSIS></TEST_DOCUMENT>', mt.syntheticBallbarTrace({ backlashX: 0.004 })),
    bad: [['<TEST_DOCUMENT/>', {}], ['<trace/>', mt.syntheticBallbarTrace({})], [42, mt.syntheticBallbarTrace({})], ['<TEST_DOCUMENT/>', { nominalRadius: 100, feed: null, runs: [] }]],
  },
  circularTest: {
    good: () => mt.circularTest(mt.syntheticBallbarTrace({ backlashX: 0.004 })),
    bad: [[{}], [{ nominalRadius: 100, feed: null, runs: [] }], [{ nominalRadius: 100, feed: null, runs: [{ direction: 'ccw', angleRad: f64(0), deviation: f64(0) }] }],
      [{ nominalRadius: 100, feed: null, runs: [{ direction: 'up', angleRad: f64(0, 1, 2), deviation: f64(0, 0, 0) }] }], [{ nominalRadius: 100, feed: '1000', runs: [] }],
      [{ nominalRadius: 100, feed: null, runs: Array.from({ length: 100 }, () => ({ direction: 'ccw', angleRad: f64(0, 1, 2), deviation: f64(0, 0, 0) })) }]],
  },
  circularDeviation: {
    good: () => mt.circularDeviation(mt.syntheticBallbarTrace({ backlashX: 0.004, bothDirections: true })),
    bad: [[{}], [{ nominalRadius: 100, feed: null, runs: [] }], [{ nominalRadius: 100, feed: null, runs: [{ direction: 'ccw', angleRad: f64(0), deviation: f64(0) }] }],
      [{ nominalRadius: 100, feed: null, runs: [{ direction: 'up', angleRad: f64(0, 1, 2), deviation: f64(0, 0, 0) }] }], [{ nominalRadius: 100, feed: '1000', runs: [] }]],
  },
  syntheticBallbarTrace: {
    good: () => mt.syntheticBallbarTrace({ offsetX: 0.003, noise: 0.001 }),
    bad: [[{ samples: 1e12 }], [{ radius: -1 }], [{ rangeDeg: 0 }], [{ noise: NaN }], [{ radius: 1e-320 }], [[]], [{ scaleX: 1e308 }]],
  },
  ballbarExample: { good: () => mt.ballbarExample('fig7'), bad: [['nope'], ['fig7', -1], ['fig7', '200']] },
  forwardKinematics: {
    good: () => mt.forwardKinematics('pocketnc-v2-10', { x: 10, y: -5, z: 3, a: 20, b: 45 }),
    bad: [['nope', {}], ['pocketnc-v2-10', { x: NaN, y: 0, z: 0, a: 0, b: 0 }], ['pocketnc-v2-10', { x: 0 }, { location: { bogus: 1 } }], ['pocketnc-v2-10', { x: 0 }, undefined, 'long']],
  },
  forwardKinematicsBulk: {
    good: () => mt.forwardKinematicsBulk('pocketnc-v2-10', f64(10, -5, 3, 20, 45, 0, 0, 0, 0, 0, 0, 0)),
    bad: [['pocketnc-v2-10', f64(1, 2, 3)], ['nope', f64(0, 0, 0, 0, 0, 0)], ['pocketnc-v2-10', f64(0, 0, 0, 0, NaN, 0)], ['pocketnc-v2-10', { length: -6 }]],
  },
  errorSymbols: { good: () => mt.errorSymbols('trunnion-ac'), bad: [['nope'], [{}], [{ name: 'trunnion-ac' }]] },
  inverseKinematics: {
    good: () => mt.inverseKinematics('table-on-table-bc', { position: [10, 0, 5], orientation: [0, 0, 1] }),
    bad: [['pocketnc-v2-10', {}], ['pocketnc-v2-10', { position: [NaN, 0, 0], orientation: [0, 0, 1] }], ['pocketnc-v2-10', { position: [0, 0, 0], orientation: [0, 0, 0] }]],
  },
  coneFrustumTest: {
    good: () => mt.coneFrustumTest({ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, feed: 1000, points: 200 }),
    bad: [[{}], [{ machine: 'trunnion-ac', halfApexDeg: 90, inclinationDeg: 10, feed: 1000 }], [{ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, method: 'sideways', feed: 1000 }],
      [{ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, barLength: -1, feed: 0 }], [{ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, feed: 1e308 }],
      [{ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, feed: 5e-324 }]],
  },
  compensateNc5: {
    good: () => mt.compensateNc5(sshape().nc, { machine: 'pocketnc-v2-10', errors: mt.machinePreset('pocketnc-v2-10').exampleErrors }),
    bad: [['', {}], ['G1 X1 Y1 Z1 A0 B0 F100', { machine: 'nope' }], ['G2 X1 Y1 I1 J0 F100', { machine: 'pocketnc-v2-10' }], ['G1 X1e9 F100', { machine: 'pocketnc-v2-10' }]],
  },
  sShapeTestPiece: {
    good: sshape,
    bad: [[{ scale: -1 }], [{ scale: NaN }], [{ machine: 'pocketnc-v2-10', feed: 1e-300 }], [{ machine: 'pocketnc-v2-10', feed: 1e308 }], [[]]],
  },
};
CASES.simulateToolPathColumns.bad = CASES.simulateToolPath.bad;

/** Paths of every non-finite number in `v` (typed arrays included). */
function nonFinite(v, path = 'result', out = []) {
  if (typeof v === 'number') {
    if (!Number.isFinite(v)) out.push(`${path} = ${v}`);
  } else if (ArrayBuffer.isView(v)) {
    const i = Array.prototype.findIndex.call(v, (x) => !Number.isFinite(x));
    if (i >= 0) out.push(`${path}[${i}] = ${v[i]}`);
  } else if (v && typeof v === 'object') {
    for (const [k, u] of Object.entries(v)) nonFinite(u, `${path}.${k}`, out);
  }
  return out.slice(0, 5);
}

const TRAP = /unreachable|memory access out of bounds|panicked|RuntimeError|index out of bounds/i;
const show = (args) => JSON.stringify(args, (k, v) => (typeof v === 'string' && v.length > 40 ? `${v.slice(0, 40)}…(${v.length})` : ArrayBuffer.isView(v) ? `Float64Array(${v.length})` : v));

test('every export of pkg/mtmotion.d.ts has a good call and bad-input calls here', () => {
  const dts = readFileSync(new URL('../../pkg/mtmotion.d.ts', import.meta.url), 'utf8');
  const exported = [...dts.matchAll(/^export function (\w+)\(/gm)].map((m) => m[1]).filter((n) => n !== 'initSync');
  assert.ok(exported.length >= 30, `parsed only ${exported.length} exports from the .d.ts`);
  const missing = exported.filter((n) => !(n in CASES));
  assert.deepEqual(missing, [], 'exports without a robustness case');
  for (const n of exported) {
    const takesArgs = !new RegExp(`^export function ${n}\\(\\)`, 'm').test(dts);
    if (takesArgs) assert.ok(CASES[n].bad.length > 0, `${n} takes arguments but has no bad-input call`);
  }
  const stale = Object.keys(CASES).filter((n) => !exported.includes(n));
  assert.deepEqual(stale, [], 'cases for functions that are no longer exported');
});

/** What is wrong with one call that should throw (null when it threw well). */
function badOutcome(name, args) {
  let result;
  try {
    result = mt[name](...args);
  } catch (e) {
    if (!(e instanceof Error) || e instanceof WebAssembly.RuntimeError) return `${name}(${show(args)}) threw ${e}`;
    if (TRAP.test(e.message)) return `${name}(${show(args)}) trapped: ${e.message}`;
    if (e.message.length < 10 || e.message.length > 400) return `${name}(${show(args)}): message of ${e.message.length} chars: ${e.message.slice(0, 200)}`;
    return null;
  }
  return `${name}(${show(args)}) returned instead of throwing: ${show(result).slice(0, 200)}`;
}

/** What is wrong with a garbage call: a trap, or a non-finite result. */
function garbageOutcome(name, g) {
  let result;
  try {
    result = mt[name](g, g, g, g);
  } catch (e) {
    if (!(e instanceof Error) || e instanceof WebAssembly.RuntimeError || TRAP.test(e.message)) return `${name}(${show(g)} × 4) threw ${e}`;
    return null;
  }
  const bad = nonFinite(result);
  return bad.length ? `${name}(${show(g)} × 4) returned ${bad.join(', ')}` : null;
}

for (const [name, { good, bad }] of Object.entries(CASES)) {
  test(`${name}: bad input throws an Error in words; good and tolerated results are finite`, () => {
    assert.equal(typeof mt[name], 'function', `${name} is exported`);
    assert.deepEqual(nonFinite(good()), [], `${name} good call`);
    const problems = [
      ...bad.map((args) => badOutcome(name, args)),
      ...GARBAGE.map((g) => garbageOutcome(name, g)),
    ].filter(Boolean);
    assert.deepEqual(problems, []);
    // The instance still works.
    assert.deepEqual(nonFinite(good()), []);
    assert.equal(mt.machinePreset('nmv5000').axes.c.torqueMax, 725);
  });
}

test('the checks can fail: a returned bad call, a NaN result and a trap are each caught', () => {
  assert.match(badOutcome('machines', []), /returned instead of throwing/);
  assert.deepEqual(nonFinite({ a: [1, { b: new Float64Array([0, NaN]) }] }), ['result.a.1.b[1] = NaN']);
  assert.match(badOutcome('fitCircle', [f64(1, 2, 3), f64(1, 2, 3)]) ?? 'threw well', /threw well/);
});

test('checkFileSize: the core names the file, its size and the limit; at the limit it passes', () => {
  // 64 MiB: the NC program budget (budget::MAX_TEXT_BYTES); any dropped
  // file may be a program.
  assert.throws(() => mt.checkFileSize('huge-trace.csv', 100 * 2 ** 20), {
    message: 'huge-trace.csv: file size: 104857600 bytes, more than the limit of 67108864; split the file or remove what the calculation does not need',
  });
  assert.equal(mt.checkFileSize('part.nc', 64 * 2 ** 20), undefined);
  assert.throws(() => mt.checkFileSize('part.nc', 64 * 2 ** 20 + 1), /67108865 bytes/);
  assert.throws(() => mt.checkFileSize('x'.repeat(500), 1e9), (e) => e.message.length < 250);
});

/** Paths to every number of `v` (a number array's first and last element). */
function numberPaths(v, path = [], out = [], depth = 0) {
  if (typeof v === 'number') out.push(path);
  else if (ArrayBuffer.isView(v) || (Array.isArray(v) && v.length > 4 && v.every((x) => typeof x === 'number'))) {
    if (v.length) out.push([...path, 0], [...path, v.length - 1]);
  } else if (v && typeof v === 'object' && depth < 8) for (const [k, x] of Object.entries(v)) numberPaths(x, [...path, k], out, depth + 1);
  return out;
}

/** A deep copy of `args` with the number at `path` set to `value`. */
function withNumber(args, path, value) {
  const copy = structuredClone(args);
  let o = copy;
  for (const k of path.slice(0, -1)) o = o[k];
  o[path[path.length - 1]] = value;
  return copy;
}

const HOSTILE = [NaN, Infinity, -Infinity, 1e308, -1e308, 5e-324, 2 ** 53, -1];

for (const [name, { good }] of Object.entries(CASES)) {
  test(`${name}: each number of the good call made hostile gives an Error in words or a finite result`, () => {
    recording = [];
    const t0 = performance.now();
    good();
    const ms = performance.now() - t0;
    const own = recording.find(([n]) => n === name);
    recording = null;
    if (!own) return; // no arguments to vary (start, version, machines)
    let args;
    try {
      args = structuredClone(own[1]);
    } catch {
      return; // a function argument (progress callbacks) cannot be cloned
    }
    const paths = numberPaths(args);
    // at most about 3 s per export: the slow calls vary every k-th number
    const k = Math.max(1, Math.ceil((paths.length * HOSTILE.length * Math.max(ms, 0.05)) / 3000));
    const problems = [];
    for (const path of paths.filter((_, i) => i % k === 0)) {
      for (const h of HOSTILE) {
        const a = withNumber(args, path, h);
        let result;
        try {
          result = mtModule[name](...a);
        } catch (e) {
          if (!(e instanceof Error) || e instanceof WebAssembly.RuntimeError || TRAP.test(e.message)) problems.push(`${name} ${path.join('.')} = ${h}: threw ${e}`);
          continue;
        }
        const bad = nonFinite(result);
        if (bad.length) problems.push(`${name} ${path.join('.')} = ${h}: returned ${bad.join(', ')}`);
      }
    }
    assert.deepEqual(problems.slice(0, 10), []);
    assert.deepEqual(nonFinite(good()), [], 'the instance still works');
    // HOSTILE_COUNT=1 node --test … prints how much of each export was varied
    if (process.env.HOSTILE_COUNT) console.log(`${name}: ${paths.length} numbers, every ${k}th varied, good call ${ms.toFixed(1)} ms`);
  });
}

test('the hostile-numbers check can fail: it finds the number paths it varies', () => {
  assert.deepEqual(numberPaths([{ a: 1, b: [2, 3], c: new Float64Array(9) }, 'x']), [['0', 'a'], ['0', 'b', '0'], ['0', 'b', '1'], ['0', 'c', 0], ['0', 'c', 8]]);
  assert.deepEqual(withNumber([{ a: [1, 2] }], [0, 'a', 1], NaN), [{ a: [1, NaN] }]);
});

test('a misspelt config key is an Error naming it, not a default used in silence', () => {
  const a = mt.toolpathExample('arcs');
  const cone = { machine: 'trunnion-ac', halfApexDeg: 45, inclinationDeg: 10, method: 'perpendicular', barLength: 100, feed: 1000 };
  for (const [call, key] of [
    [() => mt.simulateToolPath(a, { tA: 0.04, Tx: 0.3 }), 'Tx'],
    [() => mt.reverseCompensate(a, { timebudget: 0.2 }), 'timebudget'],
    [() => mt.feedVectorTest('nmv5000', { ...COND, omgea: 4 }), 'omgea'],
    [() => mt.coneFrustumTest({ ...cone, pionts: 5 }), 'pionts'],
  ]) {
    assert.throws(call, (e) => e instanceof Error && e.message.includes(`unknown key '${key}'; expected one of`), key);
  }
  assert.throws(() => mt.reverseCompensate(a, { toolRadii: { D1: 3 } }), /config\.toolRadii: reverseCompensate corrects the programmed path/);
  // the right keys still work
  assert.ok(mt.reverseCompensate(a, { timeBudget: 0.05, tA: 0.04, dt: 0.002 }).after.maxErrorUm >= 0);
  assert.ok(mt.coneFrustumTest({ ...cone, points: 90 }).angle.length > 0);
});

test('a bulk input reads the same from a Float64Array, a plain array or another typed array, and runs no code of the caller', () => {
  const ax = axis();
  const position = Float64Array.from({ length: 2000 }, (_, i) => 0.5 * Math.sin(i / 300));
  const want = mt.simulateAxis(ax, { dt: 1e-3, position });
  for (const [what, p] of [
    ['an array', Array.from(position)],
    ['a Float32Array (converted)', new Float32Array(position)],
  ]) {
    const got = mt.simulateAxis(ax, { dt: 1e-3, position: p });
    const exp = what.startsWith('a Float32') ? mt.simulateAxis(ax, { dt: 1e-3, position: Float64Array.from(new Float32Array(position)) }) : want;
    assert.deepEqual(got.position, exp.position, what);
    assert.deepEqual(got.torque, exp.torque, what);
  }
  // The snapshot copies a typed array through its internal slots: an own
  // `length` or `buffer` getter, or a subclass's, is never called.
  let called = 0;
  class Sly extends Float64Array {
    get length() {
      called++;
      return 1e9;
    }
  }
  const sly = Sly.from(position);
  Object.defineProperty(sly, 'buffer', { get: () => (called++, new ArrayBuffer(8)) });
  const own = Float64Array.from(position);
  Object.defineProperty(own, 'length', { get: () => (called++, 3) });
  for (const p of [sly, own]) assert.deepEqual(mt.simulateAxis(ax, { dt: 1e-3, position: p }).position, want.position);
  assert.equal(called, 0, 'a getter of the caller ran');
});
