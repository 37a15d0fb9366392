// Issue 29, items 1-12: inputs that used to give a silent wrong answer, a
// non-finite result, a huge message or a slow or fatal refusal. One
// regression case per item, then three properties over every export (each
// enumerated from the pkg module, as revoked_proxy.test.mjs does):
// - no argument position documented as a number (in pkg/mtmotion.d.ts)
//   accepts a string, a boolean, a one-element array or a BigInt;
// - no number inside a good call's configs, at any depth, accepts a
//   string, a boolean or a one-element array (the error names its key);
// - every config object, and every object nested in it, refuses a key it
//   does not name, and the message names the key.
// Calls that could kill or exhaust an instance run in their own process
// (runIsolated); afterwards the good calls must give the same bits.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import * as mt from '../../pkg/mtmotion.js';
import { exportedFunctions, testClassesListed } from './fixtures/exports.mjs';

const wasm = mt.initSync({ module: readFileSync(new URL('../../pkg/mtmotion_bg.wasm', import.meta.url)) });
const PKG = new URL('../../pkg/', import.meta.url).href;

const message = (f) => {
  try {
    f();
  } catch (e) {
    assert.ok(e instanceof Error && !(e instanceof WebAssembly.RuntimeError), `threw ${e}`);
    return e.message;
  }
  return 'returned';
};

/** Runs `body` (JS source using `mt`) in a fresh Node process with the pkg loaded; its stdout as JSON. */
function runIsolated(body, timeout = 60_000) {
  const src = `import * as mt from '${PKG}mtmotion.js';
import { readFileSync } from 'node:fs';
const wasm = mt.initSync({ module: readFileSync(new URL('mtmotion_bg.wasm', '${PKG}')) });
const out = await (async () => { ${body} })();
process.stdout.write(JSON.stringify(out));`;
  const r = spawnSync(process.execPath, ['--input-type=module', '-e', src], { encoding: 'utf8', timeout, maxBuffer: 1 << 24 });
  assert.equal(r.status, 0, `isolated run failed: ${r.stderr.slice(0, 500)}`);
  return JSON.parse(r.stdout);
}

const f64 = (...v) => new Float64Array(v);
const COND = { rc: 5, rw: 8, omega: 3, accelTime: 0.064, j1: 1.7 };
const TP = { tA: 0.04, T: 0.015, dt: 0.001 };
const arcs = mt.toolpathExample('arcs');
const axisC = mt.machinePreset('nmv5000').axes.c;
const axisX = mt.machinePreset('nmv5000').axes.x;
const ramp = Float64Array.from({ length: 300 }, (_, i) => Math.max(0, i * 1e-3 - 0.05) * 0.2);
const angles = Float64Array.from({ length: 360 }, (_, i) => (i * Math.PI) / 180);
const twoTurns = Float64Array.from({ length: 720 }, (_, i) => (i * Math.PI) / 180);
const sections = () => [0, 100].map((y) => ({
  y,
  angleDeg: Float64Array.from({ length: 121 }, (_, i) => i - 60),
  deviation: Float64Array.from({ length: 121 }, (_, i) => 0.01 * Math.cos(((i - 60) * Math.PI) / 180) + y * 1e-5),
}));
const servoTrace = 'time [ms],X [mm],Y [mm],C [deg]\n' + Array.from({ length: 50 }, (_, i) => `${i},${Math.cos(i / 8)},${Math.sin(i / 8)},${i / 10}`).join('\n');
const ballbarText = 'angle [deg],deviation [um]\n' + Array.from({ length: 37 }, (_, i) => `${i * 10},${Math.sin(i)}`).join('\n');
const b5rText = '<TEST_DOCUMENT><ANALYSIS NAME="RENISHAW_DIAGNOSTICS"><FEATURE NAME="AF_SQUARENESS" DT="UT_SQUARENESS">12</FEATURE></ANALYSIS></TEST_DOCUMENT>';
const trace = () => mt.syntheticBallbarTrace({ backlashX: 0.004, bothDirections: true });
const sshape = mt.sShapeTestPiece({ machine: 'pocketnc-v2-10', scale: 0.1 });
const pocket = mt.machinePreset('pocketnc-v2-10');
const x = angles.map((a) => 1 + 50 * Math.cos(a));
const y = angles.map((a) => 2 + 50 * Math.sin(a));

// name → () => a good argument list (fresh each time), one value per parameter
const GOOD = {
  analyzeFeedVectorTrace: () => [servoTrace, COND, { time: 'time', timeScale: 1e-3, steadyFrom: 0 }],
  angleSweep: () => [{ sections: [{ y: 0, offset: { z: 0, x: 0.01 } }, { y: 100, offset: { z: 0.01, x: 0 } }], ranges: [90, 180], harmonics: [{ order: 2, amplitude: 0.001, phase: 0 }] }],
  axisInertia: () => ['nmv5000', 'c'],
  b5rBeside: () => [b5rText, trace()],
  ballbarExample: () => ['fig7', 100],
  bestKffp: () => ['nmv5000', { ...COND, duration: 1 }, { method: 'analytic' }],
  bestKffpFromTrace: () => ['nmv5000', { ...COND, duration: 1, kffp: { x: 60, y: 60, c: 60 } }, servoTrace, { time: 'time', timeScale: 1e-3, steadyFrom: 0 }, { method: 'analytic', identify: false }],
  checkFileSize: () => ['part.nc', 1000],
  checkNc: () => [arcs, {}],
  'new NcStream': () => [1000],
  'NcStream.push': () => [new TextEncoder().encode(arcs)],
  'NcStream.checkNc': () => [{}],
  'NcStream.simulateToolPathColumns': () => [TP, () => true],
  circularDeviation: () => [trace()],
  circularTest: () => [trace()],
  compensateNc5: () => [sshape.nc, { machine: 'pocketnc-v2-10', errors: pocket.exampleErrors }],
  coneFrustumTest: () => [{ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, feed: 1000, points: 200 }, () => true],
  errorSymbols: () => ['trunnion-ac'],
  estimateAlignment: () => [{ sections: sections() }],
  estimateAlignmentBand: () => [{ sections: sections() }],
  feedVectorTest: () => ['nmv5000', { ...COND, duration: 0.2 }],
  fitCircle: () => [x, y],
  forwardKinematics: () => ['pocketnc-v2-10', { x: 10, y: -5, z: 3, a: 20, b: 45 }, {}, 0],
  forwardKinematicsBulk: () => ['pocketnc-v2-10', f64(10, -5, 3, 20, 45, 0), {}, 0],
  frequencyResponse: () => [axisC, f64(1, 10, 100)],
  harmonics: () => [angles, angles.map((a) => 0.005 * Math.sin(2 * a)), 4],
  identifyAccDec: () => [[[2000, 3], [4000, 5], [6000, 4], [1000, 10]].map(([feed, radius]) => ({ feed, radius, radiusLoss: mt.radiusReduction({ feed, radius, tA: 0.05, T: 0.02 }) }))],
  identifyAxis: () => [axisX, { dt: 1e-3, command: Array.from(ramp), position: Array.from(mt.simulateAxis(axisX, { dt: 1e-3, position: ramp }).position) }],
  identifyPitchError: () => [twoTurns, twoTurns.map((a) => 1e-5 * Math.sin(4 * a)), { maxOrder: 8 }],
  inverseKinematics: () => ['table-on-table-bc', { position: [10, 0, 5], orientation: [0, 0, 1] }, 0],
  machinePreset: () => ['nmv5000', 'inertiaAtLoad'],
  machines: () => [],
  ncMainFile: () => [['O100\nG1 X1 F100\nM99\n', 'G1 X1 F100\nM98 P100\nM30\n']],
  parseBallbarTrace: () => [ballbarText, { nominalRadius: 100 }],
  parseNc: () => [arcs, { files: [{ name: 'sub.nc', text: 'O100\nG1 X1 F100\nM99\n' }] }],
  radiusReduction: () => [{ feed: 2000, radius: 10, tA: 0.04, T: 0.015 }],
  readB5r: () => [b5rText],
  reverseCompensate: () => [arcs, { ...TP, iterations: 1 }, () => true],
  sShapeTestPiece: () => [{ machine: 'pocketnc-v2-10', scale: 0.1 }],
  simulateAxis: () => [axisC, { dt: 1e-3, position: ramp }],
  simulateToolPath: () => [arcs, TP, () => true],
  simulateToolPathColumns: () => [arcs, TP, () => true],
  start: () => [],
  syntheticBallbarTrace: () => [{ offsetX: 0.003, harmonics: [{ order: 3, amplitude: 0.001 }] }],
  toolpathExample: () => ['lines'],
  torqueSaturation: () => ['nmv5000', { j1: [1.7], torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200 }],
  traceColumns: () => [servoTrace],
  traceLayout: () => [servoTrace, { ratedTorque: 10 }, 'feedVector'],
  travelRangeSweep: () => [{ offset: { z: 0.01, x: -0.02 }, ranges: [90, 180], samples: 200, harmonics: [{ order: 2, amplitude: 0.005, phase: 0.1 }] }],
  version: () => [],
};

/** A fresh good argument list whose objects are copies (functions kept). */
const goodArgs = (name) => GOOD[name]().map((a) => (typeof a === 'function' ? a : structuredClone(a)));

const exported = exportedFunctions(mt, arcs);
testClassesListed(mt, exported);


test('every export has a good argument list here, and it works', () => {
  assert.deepEqual(exported.filter(({ name }) => !(name in GOOD)).map(({ name }) => name), []);
  for (const { name, f } of exported) {
    assert.equal(GOOD[name]().length, f.length, name);
    f(...GOOD[name]());
  }
});

// ---- items 1 and 2: calls that used to kill the instance ----------------------------

const goodBits = () => JSON.stringify([
  mt.simulateToolPath(arcs, TP).maxErrorUm,
  mt.parseNc(arcs).summary,
  mt.radiusReduction({ feed: 2000, radius: 10, tA: 0.04, T: 0.015 }),
]);

test('item 1: expressions nested 2,000 deep, a 500k-term sum and a 100k-sign run: located errors or values, and the instance lives on', () => {
  const out = runIsolated(`
    const nest = (open, close, d = 2000) => open.repeat(d) + '1' + close.repeat(d);
    const say = (f) => { try { f(); return 'returned'; } catch (e) { return (e instanceof WebAssembly.RuntimeError ? 'TRAP ' : '') + e.message; } };
    const deep = '#1=' + nest('[', ']') + '\\nG1 X1 F100';
    const m = {
      parseNc: say(() => mt.parseNc(deep)),
      again: say(() => mt.parseNc(deep)),
      checkNc: mt.checkNc(deep).errors.map((e) => 'line ' + e.line + ', column ' + e.column + ': ' + e.message).join('; '),
      simulateToolPath: say(() => mt.simulateToolPath(deep, {})),
      reverseCompensate: say(() => mt.reverseCompensate(deep, {})),
      compensateNc5: say(() => mt.compensateNc5(deep, { machine: 'pocketnc-v2-10', errors: {} })),
      fanucIf: say(() => mt.parseNc('IF[' + nest('[', ']') + 'GT0]GOTO10\\nN10 G1 X1 F100')),
      oword: say(() => mt.parseNc('o100 if [' + nest('[', ']') + ']\\no100 endif')),
      sin: say(() => mt.parseNc('#1=' + nest('SIN[', ']'))),
      hash: say(() => mt.parseNc('#1=' + nest('#[', ']'))),
    };
    const sum = mt.parseNc('#1=' + new Array(500000).fill('1').join('+') + '\\nG1 X[#1/100000] F100').segments[0].end.x;
    const signs = mt.parseNc('#1=' + '-'.repeat(100000) + '2\\nG1 X#1 F100').segments[0].end.x;
    const bits = JSON.stringify([
      mt.simulateToolPath(mt.toolpathExample('arcs'), { tA: 0.04, T: 0.015, dt: 0.001 }).maxErrorUm,
      mt.parseNc(mt.toolpathExample('arcs')).summary,
      mt.radiusReduction({ feed: 2000, radius: 10, tA: 0.04, T: 0.015 }),
    ]);
    return { m, sum, signs, bits };`);
  for (const [k, m] of Object.entries(out.m)) {
    assert.match(m, /line 1, column \d+: expression nested deeper than 64 levels/, `${k}: ${m.slice(0, 200)}`);
    assert.doesNotMatch(m, /TRAP|Maximum call stack/, k);
  }
  assert.equal(out.sum, 5);
  assert.equal(out.signs, 2);
  assert.equal(out.bits, goodBits());
});

test('item 2: 6,000 calls with a revoked Proxy leak nothing: named Errors, then the same bits', () => {
  const out = runIsolated(`
    const { proxy, revoke } = Proxy.revocable({}, {});
    revoke();
    const seen = new Set();
    for (let i = 0; i < 6000; i++) {
      for (const f of [() => mt.radiusReduction(proxy), () => mt.parseNc(proxy), () => mt.simulateAxis(proxy, proxy), () => mt.fitCircle(proxy, [1])]) {
        try { f(); seen.add('returned'); } catch (e) { seen.add((e instanceof WebAssembly.RuntimeError ? 'TRAP ' : e.constructor.name + ': ') + e.message); }
      }
    }
    const bits = JSON.stringify([
      mt.simulateToolPath(mt.toolpathExample('arcs'), { tA: 0.04, T: 0.015, dt: 0.001 }).maxErrorUm,
      mt.parseNc(mt.toolpathExample('arcs')).summary,
      mt.radiusReduction({ feed: 2000, radius: 10, tA: 0.04, T: 0.015 }),
    ]);
    return { seen: [...seen], bits };`);
  assert.deepEqual(out.seen.sort(), [
    'Error: axis: is a revoked Proxy; pass plain data (numbers, strings, arrays, objects)',
    'Error: radiusReduction: is a revoked Proxy; pass plain data (numbers, strings, arrays, objects)',
    'Error: text: expected a string, got a revoked Proxy',
    'Error: x: is a revoked Proxy; pass plain data (numbers, strings, arrays, objects)',
  ]);
  assert.equal(out.bits, goodBits());
});

// ---- item 7: misspelt keys, arrays read as configs --------------------------------

test('item 7: a misspelt key is refused at any depth, naming it and the keys allowed', () => {
  const unknown = (f, key) => assert.match(message(f), new RegExp(`unknown key '${key}'; expected one of `), key);
  // the case: 0 % reduction instead of 77.6 %
  unknown(() => mt.compensateNc5(sshape.nc, { machine: 'pocketnc-v2-10', errors: { Location: pocket.exampleErrors.location } }), 'Location');
  assert.match(message(() => mt.compensateNc5(sshape.nc, { machine: 'pocketnc-v2-10', errors: { Location: {} } })), /^options\.errors: unknown key 'Location'; expected one of component, location, tool$/);
  unknown(() => mt.travelRangeSweep({ ranges: [90], harmonic: [] }), 'harmonic');
  unknown(() => mt.angleSweep({ sections: [{ y: 0, offset: { z: 0, x: 0 } }, { y: 1, offset: { z: 0, x: 0, q: 1 } }], ranges: [90] }), 'q');
  unknown(() => mt.estimateAlignment({ sections: sections(), radios: 5 }), 'radios');
  unknown(() => mt.estimateAlignment({ sections: [{ ...sections()[0], dev: 1 }] }), 'dev');
  unknown(() => mt.estimateAlignmentBand({ sections: sections(), order: 3 }), 'order');
  unknown(() => mt.circularTest({ ...trace(), nominalRadios: 3 }), 'nominalRadios');
  unknown(() => mt.circularDeviation({ ...trace(), runs: trace().runs.map((r) => ({ ...r, dir: 1 })) }), 'dir');
  unknown(() => mt.syntheticBallbarTrace({ harmonics: [{ order: 2, amplitude: 0.005, phse: 1 }] }), 'phse');
  unknown(() => mt.identifyAccDec([{ feed: 1000, radius: 10, radiusLoss: 0.01, bogus: 1 }]), 'bogus');
  unknown(() => mt.simulateAxis(axisC, { dt: 1e-3, position: ramp, positon: ramp }), 'positon');
  unknown(() => mt.parseBallbarTrace(ballbarText, { nominalRadious: 100 }), 'nominalRadious');
  unknown(() => mt.feedVectorTest({ ...mt.machinePreset('nmv5000'), bogus: 1 }, COND), 'bogus');
  // the travel range keeps its own message
  assert.match(message(() => mt.estimateAlignmentBand({ sections: sections(), travelRangeDeg: 180 })), /^input\.travelRangeDeg: not an input/);
  // arrays are not read as configs
  for (const f of [
    () => mt.syntheticBallbarTrace({ harmonics: [[2, 0.005, 0.1]] }),
    () => mt.travelRangeSweep({ ranges: [90], harmonics: [[2, 0.005, 0.1]] }),
    () => mt.angleSweep({ sections: [[0, [0, 0]], [1, [0, 0]]], ranges: [90] }),
  ]) assert.match(message(f), /expected an object \{ … \}, got an array/);
  // the right keys still give the paper's numbers
  const r = mt.compensateNc5(sshape.nc, { machine: 'pocketnc-v2-10', errors: pocket.exampleErrors });
  assert.ok(r.totalReductionPercent > 50, `${r.totalReductionPercent} %`);
});

test('item 7 property: every config object of every export, and every object nested in it, refuses an unknown key', () => {
  // objects whose keys are data, not fields: error symbols, axis letters, D numbers
  const MAPS = /\.(location|component|axes|limits|toolRadii|backlash|kffp|q)$/;
  const problems = [];
  let checked = 0;
  const objectPaths = (v, path, out) => {
    if (v && typeof v === 'object' && !ArrayBuffer.isView(v)) {
      if (!Array.isArray(v) && !MAPS.test(path)) out.push(path);
      for (const [k, u] of Object.entries(v)) objectPaths(u, Array.isArray(v) ? `${path}[${k}]` : `${path}.${k}`, out);
    }
    return out;
  };
  for (const { name, f } of exported) {
    const good = GOOD[name]();
    good.forEach((arg, i) => {
      for (const path of objectPaths(arg, '', [])) {
        const args = goodArgs(name);
        // the object at `path` inside a fresh copy of argument i
        let o = args[i];
        for (const step of path.match(/[^.[\]]+/g) ?? []) o = o[step];
        o.zzUnknownKey = 1;
        checked += 1;
        const m = message(() => f(...args));
        if (!/unknown key 'zzUnknownKey'; expected one of /.test(m)) problems.push(`${name} #${i}${path}: ${m.slice(0, 160)}`);
      }
    });
  }
  assert.ok(checked >= 50, `only ${checked} config objects checked`);
  assert.deepEqual(problems, []);
});

// ---- item 6: a huge arc radius -----------------------------------------------------

test('item 6: an arc flatter than its centre can resolve is its chord, with a warning', () => {
  const p = mt.parseNc('G0 X0 Y0\nG2 X1 Y0 R999999999 F100');
  assert.equal(p.segments[1].motion.type, 'linear');
  assert.ok(p.warnings.some((w) => w.line === 2 && /^flat arc/.test(w.message)), JSON.stringify(p.warnings));
  const arc = mt.simulateToolPath('G0 X0 Y0\nG2 X1 Y0 R999999999 F100', TP);
  const line = mt.simulateToolPath('G0 X0 Y0\nG1 X1 Y0 F100', TP);
  assert.equal(arc.maxErrorUm, line.maxErrorUm);
  assert.ok(arc.maxErrorUm < 1e-6, `${arc.maxErrorUm} µm (was 1,095,477)`);
  // a real arc is kept
  assert.equal(mt.parseNc('G0 X0 Y0\nG3 X100 Y0 R1000 F100').segments[1].motion.type, 'arc');
});

// ---- item 5: Infinity and NaN ---------------------------------------------------------

test('item 5: a diverging loop is refused in words; NaN in a machine is refused naming the field', () => {
  const m = mt.machinePreset('trunnion-ac');
  m.axes.x.kvi = 1e9;
  const e = message(() => mt.coneFrustumTest({ machine: m, halfApexDeg: 15, inclinationDeg: 10, feed: 1000, points: 200 }));
  assert.match(e, /X.*the axis loop is unstable/);
  assert.ok(!/Infinity/.test(e), e);
  const n = mt.machinePreset('nmv5000');
  n.axes.c.j = NaN;
  assert.equal(message(() => mt.axisInertia(n, 'c')), 'machine.axes.c.j: expected a finite number, got NaN');
  assert.match(message(() => mt.frequencyResponse({ ...axisC, kvp: Infinity }, f64(1))), /^axis\.kvp: expected a finite number, got Infinity$/);
});

// ---- item 8: positional numbers -------------------------------------------------------

test('item 8 property: no position documented as a number accepts a string, a boolean, a one-element array or a BigInt', () => {
  const dts = readFileSync(new URL('../../pkg/mtmotion.d.ts', import.meta.url), 'utf8');
  const problems = [];
  let checked = 0;
  for (const [, name, params] of dts.matchAll(/^export function (\w+)\(([^)]*)\)/gm)) {
    if (name === 'initSync' || !params) continue;
    params.split(/,(?![^{]*})/).forEach((p, i) => {
      if (!/^\s*\w+\??:\s*number\b/.test(p)) return;
      for (const bad of ['5', true, [5], 5n, { valueOf: () => 5 }]) {
        const args = goodArgs(name);
        args[i] = bad;
        checked += 1;
        const m = message(() => mt[name](...args));
        if (!/^[\w.[\]]+: expected (a|a finite) number, got /.test(m)) problems.push(`${name} #${i} ${typeof bad}: ${m.slice(0, 120)}`);
      }
    });
  }
  assert.ok(checked >= 25, `only ${checked} number positions found`);
  assert.deepEqual(problems, []);
});

test('item 8 property: no number inside a config, at any depth, accepts a string, a boolean or a one-element array', () => {
  // every number of every good call's object arguments (plain arrays
  // included; typed arrays cannot hold anything else), replaced in turn
  const paths = (v, path, out) => {
    if (typeof v === 'number') out.push(path);
    else if (v && typeof v === 'object' && !ArrayBuffer.isView(v)) for (const [k, u] of Object.entries(v)) paths(u, [...path, k], out);
    return out;
  };
  const problems = [];
  let checked = 0;
  for (const { name, f } of exported) {
    GOOD[name]().forEach((arg, i) => {
      if (!arg || typeof arg !== 'object' || ArrayBuffer.isView(arg)) return;
      for (const path of paths(arg, [], [])) {
        for (const bad of ['5', true, [5]]) {
          const args = goodArgs(name);
          let o = args[i];
          for (const k of path.slice(0, -1)) o = o[k];
          o[path[path.length - 1]] = bad;
          checked += 1;
          const m = message(() => f(...args));
          const key = path[path.length - 1];
          const named = /^\d+$/.test(key) ? m.includes(`[${key}]`) : m.includes(key);
          // refused, naming the key and what was expected (a number, a
          // time constant or [Tx, Ty, Tz], an array of 3, …)
          if (m === 'returned' || !named || !/expected/.test(m)) problems.push(`${name} #${i}.${path.join('.')} = ${JSON.stringify(bad)}: ${m.slice(0, 140)}`);
        }
      }
    });
  }
  assert.ok(checked >= 300, `only ${checked} config numbers checked`);
  assert.deepEqual(problems.slice(0, 20), []);
});

test('item 8: checkFileSize says a huge size as given, not as 2^64 - 1', () => {
  assert.match(message(() => mt.checkFileSize('a', 1e308)), /^a: file size: 1e308 bytes, more than the limit of 67108864/);
  assert.match(message(() => mt.checkFileSize('a', 5n)), /^bytes: expected a number, got bigint$/);
  assert.match(message(() => mt.harmonics(angles, angles, '2')), /^maxOrder: expected a number, got string$/);
});

// ---- item 4 and 9: long strings, echoed input ----------------------------------------------

test('item 4: long names are refused before they reach wasm memory; messages stay short', () => {
  const before = wasm.memory.buffer.byteLength;
  const huge = 'x'.repeat(1e8);
  for (const f of [
    () => mt.feedVectorTest(huge, COND),
    () => mt.machinePreset(huge),
    () => mt.axisInertia('nmv5000', huge),
    () => mt.coneFrustumTest({ machine: huge, halfApexDeg: 15, inclinationDeg: 10, feed: 1000 }),
    () => mt.parseNc('G1 X1 F100', { dwellP: huge }),
    () => mt.torqueSaturation('nmv5000', { j1: [1.7], accelTime: 0.064, feedAtCuttingPoint: 200, reading: huge }),
    () => mt.analyzeFeedVectorTrace(servoTrace, COND, { x: huge }),
    () => mt.radiusReduction({ [huge.slice(0, 1e6)]: 1 }),
  ]) {
    const t = performance.now();
    const m = message(f);
    assert.ok(m.length < 300, `${m.length} characters: ${m.slice(0, 100)}`);
    assert.ok(performance.now() - t < 3000, `${(performance.now() - t).toFixed(0)} ms: ${m.slice(0, 80)}`);
  }
  assert.ok(wasm.memory.buffer.byteLength - before < 64 << 20, `wasm memory grew by ${(wasm.memory.buffer.byteLength - before) >> 20} MiB`);
  // a name just under the limit is still read, and clipped in the message
  assert.ok(message(() => mt.machinePreset('y'.repeat(999))).length < 300);
});

// ---- item 10: slow refusals -----------------------------------------------------------

test('item 10: oversized inputs are refused before they are copied', () => {
  const time = (f) => {
    const t = performance.now();
    const m = message(f);
    return [performance.now() - t, m];
  };
  const big = new Float64Array(2e7); // 160 MB: over the 8 M-value argument budget
  let [ms, m] = time(() => mt.fitCircle(big, big));
  assert.match(m, /^x: 20000000 values; at most 8000000/);
  assert.ok(ms < 100, `${ms} ms`);
  [ms, m] = time(() => mt.simulateAxis(axisC, { dt: 1e-3, position: big }));
  assert.match(m, /more than 8000000 values/);
  assert.ok(ms < 100, `${ms} ms`);
  // an object of many keys is refused as its keys are listed (1e6 unknown
  // keys took 4.9-18.6 s); the listing itself is the cost left
  const keys = {};
  for (let i = 0; i < 200_000; i++) keys[`k${i}`] = 1;
  [ms, m] = time(() => mt.simulateToolPath('G1 X1 F100', keys));
  assert.match(m, /^options: an object of 200000 keys, more than the limit of 10000$/);
  assert.ok(ms < 2000, `${ms} ms`);
  // 100,000 pitch harmonics: refused by the list's length, not after reading each
  [ms, m] = time(() => mt.simulateAxis({ ...axisC, pitchError: Array.from({ length: 100_000 }, () => ({ n: 1, w: 1e-5, phi: 0 })) }, { dt: 1e-3, position: ramp }));
  assert.match(m, /^axis\.pitchError: 100000 harmonics, more than the limit of 64/);
  assert.ok(ms < 2000, `${ms} ms`);
});

test('item 10: a bounded list of 1e6 items is refused by its length, naming its budget, before any item is read', () => {
  // Each list's first item is a getter: the copy into plain data reads
  // items through it, so a refusal that comes after the copy has started
  // touches it (and then refuses the getter instead, naming another thing).
  let touched = 0;
  const N = 1_000_000;
  const list = (item) => {
    const a = new Array(N).fill(item);
    Object.defineProperty(a, 0, { get: () => (touched++, item), enumerable: true, configurable: true });
    return a;
  };
  const sec = { y: 0, angleDeg: f64(0, 1, 2, 3), deviation: f64(0, 0, 0, 0) };
  const run = { direction: 'ccw', angleRad: f64(0, 1, 2), deviation: f64(0, 0, 0) };
  const radii = {};
  for (let i = 0; i < N; i++) radii[`D${i}`] = 1;
  const cases = [
    [() => mt.identifyAccDec(list({ feed: 1000, radius: 1, radiusLoss: 0.001 })), /^data: 1000000 circles, more than the limit of 10000; /],
    [() => mt.ncMainFile(list('G1 X1')), /^texts: 1000000 texts, more than the limit of 1000; /],
    [() => mt.torqueSaturation('nmv5000', { j1: list(1), torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200 }), /^query\.j1: 1000000 load inertias, more than the limit of 1000; /],
    [() => mt.torqueSaturation('nmv5000', { j1: new Float64Array(N).fill(1), torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200 }), /^query\.j1: 1000000 load inertias, more than the limit of 1000; /],
    [() => mt.estimateAlignmentBand({ sections: list(sec) }), /^input\.sections: 1000000 sections, more than the limit of 1000; /],
    [() => mt.estimateAlignment({ sections: list(sec) }), /^input\.sections: 1000000 sections, more than the limit of 1000; /],
    [() => mt.angleSweep({ sections: list({ y: 0, offset: { z: 0, x: 0 } }), ranges: [90] }), /^config\.sections: 1000000 sections, more than the limit of 1000; /],
    [() => mt.simulateAxis({ ...axisC, pitchError: list({ n: 1, w: 1e-5, phi: 0 }) }, { dt: 1e-3, position: ramp }), /^axis\.pitchError: 1000000 harmonics, more than the limit of 64; /],
    [() => mt.syntheticBallbarTrace({ harmonics: list({ order: 2, amplitude: 1e-3 }) }), /^config\.harmonics: 1000000 harmonics, more than the limit of 256; /],
    [() => mt.travelRangeSweep({ ranges: [90], harmonics: list({ order: 2, amplitude: 1e-3 }) }), /^config\.harmonics: 1000000 harmonics, more than the limit of 256; /],
    [() => mt.parseNc('G1 X1 F100', { files: list({ name: 'f.nc', text: 'G1' }) }), /^options\.files: 1000000 texts, more than the limit of 1000; /],
    [() => mt.circularTest({ nominalRadius: 100, feed: null, runs: list(run) }), /^trace\.runs: 1000000 runs, more than the limit of 64; /],
    [() => mt.simulateToolPath('G1 X1 F100', { toolRadii: radii }), /^options\.toolRadii: 1000000 tool radii, more than the limit of 1000; /],
  ];
  for (const [f, want] of cases) assert.match(message(f), want);
  assert.equal(touched, 0, 'an item of a refused list was read');
  // an object's keys are counted before they are listed in full: 1e6 tool
  // radii are refused in less time than one Reflect.ownKeys listing of
  // them takes (about 0.45 s against 0.95 s; the listing first took 1.2-5 s)
  let t = performance.now();
  message(() => mt.simulateToolPath('G1 X1 F100', { toolRadii: radii }));
  const refusal = performance.now() - t;
  t = performance.now();
  Reflect.ownKeys(radii);
  const listing = performance.now() - t;
  assert.ok(refusal < 0.75 * listing, `refused in ${refusal.toFixed(0)} ms, one listing ${listing.toFixed(0)} ms`);
  // at the limit the lists are still read (and the core's own checks apply)
  assert.match(message(() => mt.simulateAxis({ ...axisC, pitchError: Array.from({ length: 65 }, () => ({ n: 1, w: 1e-5, phi: 0 })) }, { dt: 1e-3, position: ramp })), /65 harmonics, more than the limit of 64/);
  assert.equal(mt.travelRangeSweep({ ranges: [90], samples: 100, harmonics: Array.from({ length: 256 }, (_, i) => ({ order: i + 1, amplitude: 1e-6 })) }).length, 1);
  assert.equal(mt.ncMainFile(new Array(1000).fill('G1 X1\nM30')), 0);
});

// ---- item 3: budgets over the whole call ------------------------------------------------

/** A preset with 64 pitch-error harmonics on each of `axes` (declared `kind`, when given). */
const pitched = (name, axes, kind) => {
  const m = mt.machinePreset(name);
  for (const k of axes) {
    m.axes[k].pitchError = Array.from({ length: 64 }, (_, i) => ({ n: i + 1, w: 1e-6, phi: 0 }));
    if (kind) m.axes[k].kind = kind;
  }
  return m;
};
/** A G81 program of `holes` holes: the first G0, the G81 block's own hole at X0 Y0 (3 moves), the
 * first listed hole at the same place (3) and 4 moves (XY, R, bottom, retract) for each other one. */
const g81 = (holes) => 'G90 G21 G0 X0 Y0 Z10\nG81 Z-1 R1 F100\n' + Array.from({ length: holes }, (_, i) => `X${i % 100} Y${Math.floor(i / 100)}`).join('\n') + '\nG80';

test('item 3: each of the issue\'s calls is refused before the work, naming its budget', () => {
  const cases = [
    [() => mt.coneFrustumTest({ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, feed: 1, points: 200 }), /servo simulation: \d+ steps .*limit of 5000000/],
    [() => mt.syntheticBallbarTrace({ samples: 1e7, harmonics: Array.from({ length: 64 }, (_, i) => ({ order: i + 1, amplitude: 1e-3 })) }), /1300000000 terms .*limit of 100000000/],
    [() => mt.travelRangeSweep({ ranges: [180], samples: 1e7, harmonics: Array.from({ length: 256 }, (_, i) => ({ order: i + 1, amplitude: 1e-3 })) }), /2570000000 points .*limit of 10000000/],
    [() => mt.parseNc('G1 X1 F100', { files: Array.from({ length: 20 }, (_, k) => ({ name: `f${k}.nc`, text: 'G1\n'.repeat(210_000) })) }), /program and its files: 4200001 lines, more than the limit of 4000000/],
    [() => mt.torqueSaturation('nmv5000', { j1: new Array(5000).fill(1), torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200 }), /query\.j1: 5000 load inertias, more than the limit of 1000/],
    // the study counts loads × steps, not loads: 1000 loads at dt = 1 µs (3.5e8 steps)
    [() => mt.torqueSaturation('nmv5000', { j1: new Array(1000).fill(1), torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200, dt: 1e-6 }), /^torque-saturation study: \d+ servo steps .*more than the limit of 50000000; give fewer loads or raise dt$/],
    // an axis simulation counts samples × (1 + pitch harmonics) (8 M × 64 took 22 s)
    [() => mt.simulateAxis({ ...axisC, pitchError: Array.from({ length: 64 }, (_, i) => ({ n: i + 1, w: 1e-6, phi: 0 })) }, { dt: 1e-3, position: new Float64Array(2_000_000) }), /axis simulation: 130000000 terms .*limit of 100000000/],
    // a circular test's cyclic search counts pitches (∝ R₀) × points (R₀ = 10 m, 2 × 1e5 points took 17.6 s)
    [() => mt.circularTest({ nominalRadius: 1e4, feed: 1000, runs: ['ccw', 'cw'].map((direction) => ({ direction, angleRad: Float64Array.from({ length: 1e5 }, (_, i) => (i * 2 * Math.PI) / 1e5), deviation: new Float64Array(1e5) })) }), /^circular test, cyclic-error search: \d+ units of work .*limit of 200000000/],
    // every alignment trace's lines together, not each text's: 20 texts of 60,000 lines
    [() => mt.estimateAlignmentBand({ sections: Array.from({ length: 20 }, (_, k) => ({ y: k, text: 'angle,dev\n' + '0,0\n'.repeat(60_000) })) }), /alignment traces: 1200020 lines, more than the limit of 100000/],
    [() => mt.ncMainFile(new Array(5000).fill('G1 X1')), /texts: 5000 texts, more than the limit of 1000/],
    [() => mt.identifyAccDec(Array.from({ length: 20_000 }, () => ({ feed: 1000, radius: 1, radiusLoss: 0.001 }))), /data: 20000 circles, more than the limit of 10000/],
    [() => mt.simulateToolPath('G1 X1 F100', { toolRadii: Object.fromEntries(Array.from({ length: 2000 }, (_, i) => [`D${i}`, 1])) }), /options\.toolRadii: 2000 tool radii, more than the limit of 1000/],
    // pitch-error harmonics count: 64 on A and C at feed 40 (5.2-7.9 s before)
    [() => mt.coneFrustumTest({ machine: pitched('trunnion-ac', ['a', 'c']), halfApexDeg: 15, inclinationDeg: 10, feed: 40, points: 200 }), /^cone-frustum test: servo simulation: \d+ terms \(1 ms steps × \(1 \+ pitch-error harmonics\), over the axes\), more than the limit of 100000000/],
    [() => mt.feedVectorTest(pitched('nmv5000', ['x', 'y', 'c'], 'rotary'), { ...COND, duration: 999 }), /^feed-vector test: 194805195 terms .*limit of 100000000/],
    // (identifyAxis's budget on the fit's simulations is tested in
    // tests/servo_identify.rs: from JS a trace within the 8 M-value argument
    // budget meets it only after seconds of fitting)
    // compensateNc5: lines before reading, moves (cycles expanded) before solving
    [() => mt.compensateNc5('G1 X1 F100' + '\n'.repeat(100_001), { machine: 'pocketnc-v2-10', errors: {} }), /^compensateNc5: program: 100001 lines, more than the limit of 100000/],
    [() => mt.compensateNc5(g81(99_990), { machine: 'pocketnc-v2-10', errors: {} }), /^compensateNc5: program: 399963 moves \(canned cycles and subprogram calls expanded\), more than the limit of 50000/],
  ];
  for (const [f, want] of cases) {
    const t = performance.now();
    const m = message(f);
    assert.match(m, want);
    assert.ok(performance.now() - t < 3000, `${(performance.now() - t).toFixed(0)} ms: ${m}`);
  }
  // the budgets leave the paper's cases alone
  assert.ok(mt.coneFrustumTest({ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, feed: 1000, points: 200 }).angle.length > 0);
  assert.equal(mt.travelRangeSweep({ ranges: [90, 180], samples: 1000, harmonics: [{ order: 2, amplitude: 0.005 }] }).length, 2);
});

// ---- item 9: numbers and echoed input in messages ------------------------------------------------

test('item 9: messages print at most 6 significant digits and clip echoed input', () => {
  for (const f of [
    () => mt.syntheticBallbarTrace({ rangeDeg: 1e308 }),
    () => mt.travelRangeSweep({ ranges: [1e308] }),
    () => mt.angleSweep({ sections: [{ y: 0, offset: { z: 0, x: 0 } }, { y: 1, offset: { z: 0, x: 0 } }], ranges: [-1e300] }),
    () => mt.machinePreset('q'.repeat(900)),
    () => mt.parseBallbarTrace('angle,deviation\n0,' + '9'.repeat(100_000) + 'x\n'),
    () => mt.compensateNc5('G1 X1 F100', { machine: 'pocketnc-v2-10', errors: { location: { ['E'.repeat(500)]: 1 } } }),
  ]) {
    const m = message(f);
    assert.ok(m.length < 300, `${m.length} characters: ${m.slice(0, 120)}`);
    assert.ok(!/\d{20}/.test(m), m.slice(0, 200));
  }
});

test('item 9: trace, ball-bar and alignment messages clip an 8 MB cell, a 1 MB header and a long name', () => {
  const cell = 'q'.repeat(8_000_000);
  const header = 'h'.repeat(1_000_000);
  const long = 'n'.repeat(999); // names over 1,000 characters are refused before they are read
  const tr = (h, c) => `${h},X [mm],Y [mm],C [deg]\n0,1,0,0\n1,${c},0,0\n2,1,0,0\n`;
  const bb = (h, c) => `${h},deviation [um]\n0,1\n10,${c}\n20,1\n`;
  const map = { time: 'time', timeScale: 1e-3 };
  const kffp = { ...COND, kffp: { x: 60, y: 60, c: 60 } };
  const withName = { ...mt.machinePreset('nmv5000'), name: 'm'.repeat(1_000_000) };
  const cases = [
    // an 8 MB cell
    () => mt.traceColumns(tr('time [ms]', cell)),
    () => mt.traceLayout(tr('time [ms]', cell)),
    () => mt.analyzeFeedVectorTrace(tr('time [ms]', cell), COND, map),
    () => mt.bestKffpFromTrace('nmv5000', kffp, tr('time [ms]', cell), map),
    () => mt.parseBallbarTrace(bb('angle [deg]', cell)),
    () => mt.estimateAlignmentBand({ sections: [{ y: 0, text: bb('angle [deg]', cell) }, { y: 1, text: bb('angle [deg]', '1') }] }),
    () => mt.traceColumns(`t,x\n0,1,5\n1,${cell},2\n`),
    () => mt.traceColumns(`t;x\n0;1,5\n1;2.${cell}\n`),
    // a 1 MB header
    () => mt.analyzeFeedVectorTrace(tr(header, '1'), COND, map),
    () => mt.analyzeFeedVectorTrace(tr(header, '1'), COND, { time: 'zz', timeScale: 1e-3 }),
    () => mt.parseBallbarTrace(bb(header, '1')),
    () => mt.parseBallbarTrace(`angle [deg],${header}\n0,1\n10,2\n20,1\n`),
    () => mt.parseBallbarTrace(`${header},${header}\n0,1\n`),
    () => mt.estimateAlignmentBand({ sections: [{ y: 0, text: bb(header, '1') }] }),
    () => mt.estimateAlignmentBand({ sections: [{ y: 0, text: `x,${header}\n1,2\n` }] }),
    // a long name in each position that echoes it
    () => mt.analyzeFeedVectorTrace(tr('time [ms]', '1'), COND, { time: long, timeScale: 1e-3 }),
    () => mt.machinePreset('nmv5000', long),
    () => mt.ballbarExample(long),
    () => mt.feedVectorTest(long, COND),
    () => mt.axisInertia('nmv5000', long),
    () => mt.forwardKinematics(withName, { x: 0, y: 0, z: 0, a: 0, b: 0 }),
    () => mt.toolpathExample(long),
    () => mt.errorSymbols(long),
    // numbers the caller gave: at most 6 significant digits
    () => mt.traceLayout(servoTrace, { samplePeriod: 1.234567890123e-300 }),
    () => mt.traceLayout(servoTrace, { ratedTorque: 1.234567890123e300 }),
    () => mt.traceLayout('x\n0\n1\n', { samplePeriod: 1.234567890123e-4, ratedTorque: 1e-300 }),
  ];
  const problems = [];
  for (const [i, f] of cases.entries()) {
    const m = message(f);
    if (m === 'returned' && i < cases.length - 1) problems.push(`#${i} returned`);
    if (m.length > 400) problems.push(`#${i}: ${m.length} characters: ${m.slice(0, 100)}`);
    else if (/([a-z])\1{60}/.test(m) || /\d{8}/.test(m.replace(/\b(8388608|100000)\b/g, ''))) problems.push(`#${i}: ${m}`);
  }
  assert.deepEqual(problems, []);
  // the layout's notes print the generated time step with 6 digits too
  const notes = JSON.stringify(mt.traceLayout('x\n0\n1\n', { samplePeriod: 1.234567890123e-4 }));
  assert.ok(notes.includes('0.000123457') || notes.includes('1.23457e-4'), notes.slice(0, 300));
});

// ---- item 11: misleading messages ---------------------------------------------------------

test('item 11: messages say what is wrong with what the caller gave', () => {
  assert.match(message(() => mt.parseNc('#100=1E3\nG1 X#100 F100')), /NC numbers take no exponent/);
  assert.doesNotMatch(message(() => mt.parseNc('#100=1E3\nG1 X#100 F100')), /3D-printer/);
  // identifyAxis from j = 1e-9: the fit's doing, the range it left, no rounded value inside it
  const ramp2 = Float64Array.from({ length: 2000 }, (_, i) => 0.05 * Math.sin(i / 50));
  const fit = message(() => mt.identifyAxis({ ...axisX, j: 1e-9 }, { dt: 1e-3, command: ramp2, position: mt.simulateAxis(axisX, { dt: 1e-3, position: ramp2 }).position }));
  assert.match(fit, /^the fit left the physical range from this initial guess \(j = 1e-9, .*\): a trial step took `kpp` out of its range \(must be between 1e-3 and 1e4 1\/s\); start from values nearer the axis$/);
  // compensateNc5 on a 99,992-line G81 program: its moves against its budget, not 'line 1, column 1'
  const t = performance.now();
  const nc5 = message(() => mt.compensateNc5(g81(99_990), { machine: 'pocketnc-v2-10', errors: pocket.exampleErrors }));
  assert.match(nc5, /^compensateNc5: program: 399963 moves .*compensate the program in parts$/);
  assert.ok(performance.now() - t < 3000, `${(performance.now() - t).toFixed(0)} ms`);
  for (const f of [
    () => mt.coneFrustumTest({ machine: 5, halfApexDeg: 15, inclinationDeg: 10, feed: 1000 }),
    () => mt.simulateToolPath('G1 X1 F100', { T: 'a' }),
    () => mt.forwardKinematics('pocketnc-v2-10', 'x'),
    () => mt.compensateNc5('G1 X1 F100', { machine: 'pocketnc-v2-10', errors: { component: { EXX: 'a' } } }),
  ]) {
    const m = message(f);
    assert.doesNotMatch(m, /untagged|expected any value|Error: /, m);
    assert.match(m, /^[\w.[\]]+: /, m);
  }
});

// ---- item 12: a progress callback calling back into the module ------------------------------

test('item 12: a progress callback that calls into the module is refused, and the run goes on', () => {
  const out = runIsolated(`
    let depth = 0, refused = '';
    // 600 s of motion at 1 ms: the callback is called every 262,144 samples
    const cb = () => { depth += 1; try { mt.simulateToolPath('G1 X1000 F100', { dt: 0.001 }, cb); } catch (e) { refused = e.message; } };
    const r = mt.simulateToolPath('G1 X1000 F100', { dt: 0.001 }, cb);
    let cone = '';
    mt.coneFrustumTest({ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, feed: 1000, points: 200 }, () => { try { mt.version(); mt.machinePreset('nmv5000'); } catch (e) { cone = e.message; } });
    return { depth, refused, cone, maxErrorUm: r.maxErrorUm, memory: wasm.memory.buffer.byteLength };`);
  assert.match(out.refused, /^mtmotion is busy: a progress callback may not call into the module/);
  assert.match(out.cone, /^mtmotion is busy/);
  assert.ok(out.depth >= 1 && out.memory < 1 << 30, JSON.stringify(out));
  // the same bits as a run without the callback here
  assert.equal(out.maxErrorUm, mt.simulateToolPath('G1 X1000 F100', { dt: 0.001 }).maxErrorUm);
});
