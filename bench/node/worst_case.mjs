// Worst case per export: each export called once on an input at (or near)
// its work budget (src/budget.rs), each in a fresh Node process, with the
// wasm build in pkg/. Prints wall time and the wasm memory after the call
// (wasm memory only grows, so that is its peak). docs/performance.md
// ("Worst case per export") lists the figures.
//
//   node bench/node/worst_case.mjs            # every export
//   node bench/node/worst_case.mjs coneFrustumTest syntheticBallbarTrace
//   node bench/node/worst_case.mjs --refusals  # calls over a budget: time to refuse
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';

const PKG = new URL('../../pkg/', import.meta.url).href;

// name → JS source of the call (with `mt` loaded); setup outside the timing is in `prep`
const CASES = {
  analyzeFeedVectorTrace: { prep: `const t = 'time [ms],X [mm],Y [mm],C [deg]\\n' + Array.from({ length: 99_999 }, (_, i) => \`\${i},\${8 * Math.cos(3e-3 * i)},\${8 * Math.sin(3e-3 * i)},\${(3e-3 * i * 180) / Math.PI}\`).join('\\n');`, call: `mt.analyzeFeedVectorTrace(t, { rc: 5, rw: 8, omega: 3, accelTime: 0.064, j1: 1.7 }, { time: 'time', timeScale: 1e-3, steadyFrom: 0 })`, note: '100,000-line trace' },
  angleSweep: { call: `mt.angleSweep({ sections: [{ y: 0, offset: { z: 0, x: 0.01 } }, { y: 100, offset: { z: 0.01, x: 0 } }], ranges: Array.from({ length: 6 }, (_, i) => 60 * (i + 1)), harmonics: Array.from({ length: 4 }, (_, i) => ({ order: i + 2, amplitude: 0.001 })), samples: 500_000 })`, note: '(6 ranges + 4 harmonics) × 2 sections × 500k samples = 10 M' },
  axisInertia: { call: `mt.axisInertia('nmv5000', 'c')`, note: 'trivial' },
  ballbarExample: { call: `mt.ballbarExample('fig12', 100)`, note: 'largest example' },
  'bestKffp, 64 pitch harmonics on C': { prep: `const m = mt.machinePreset('nmv5000'); m.axes.c.pitchError = Array.from({ length: 64 }, (_, i) => ({ n: i + 1, w: 1e-6, phi: 0 }));`, call: `mt.bestKffp(m, { rc: 5, rw: 8, omega: 3, accelTime: 0.064, j1: 1.7, duration: 999 }, { method: 'simulated' })`, note: 'simulated method, 1 M samples, 64 harmonics on C (C simulated once)' },
  bestKffp: { call: `mt.bestKffp('nmv5000', { rc: 5, rw: 8, omega: 3, accelTime: 0.064, j1: 1.7, duration: 999 }, { method: 'simulated' })`, note: 'simulated method, 1 M samples per simulation' },
  checkFileSize: { call: `mt.checkFileSize('a', 8 << 20)`, note: 'trivial' },
  checkNc: { prep: `const p = Array.from({ length: 99_999 }, (_, i) => \`G1 X\${i % 100} Y\${(i * 7) % 50} F1000\`).join('\\n');`, call: `mt.checkNc(p)`, note: '100,000 lines' },
  circularDeviation: { prep: `const a = Float64Array.from({ length: 1_000_000 }, (_, i) => i * 2 * Math.PI / 1e6); const d = a.map(Math.sin).map((x) => x * 1e-3); const tr = { nominalRadius: 100, feed: 1000, runs: [{ direction: 'ccw', angleRad: a, deviation: d }, { direction: 'cw', angleRad: a, deviation: d }] };`, call: `mt.circularDeviation(tr)`, note: '2 M points' },
  circularTest: { prep: `const a = Float64Array.from({ length: 1_000_000 }, (_, i) => i * 2 * Math.PI / 1e6); const d = a.map(Math.sin).map((x) => x * 1e-3); const tr = { nominalRadius: 100, feed: 1000, runs: [{ direction: 'ccw', angleRad: a, deviation: d }, { direction: 'cw', angleRad: a, deviation: d }] };`, call: `mt.circularTest(tr)`, note: '2 M points' },
  'circularTest, R₀ 1.76 m': { prep: `const a = Float64Array.from({ length: 1_000_000 }, (_, i) => i * 2 * Math.PI / 1e6); const d = a.map(Math.sin).map((x) => x * 1e-3); const tr = { nominalRadius: 1760, feed: 1000, runs: [{ direction: 'ccw', angleRad: a, deviation: d }, { direction: 'cw', angleRad: a, deviation: d }] };`, call: `mt.circularTest(tr)`, note: '2 M points, cyclic search 11,056 pitches × 18,000 bins (budget 2e8)' },
  compensateNc5: { prep: `const p = Array.from({ length: 50_000 }, (_, i) => \`G1 X\${i % 50} Y\${(i * 7) % 40} Z\${i % 20} A\${i % 30} B\${i % 45} F1000\`).join('\\n');`, call: `mt.compensateNc5(p, { machine: 'pocketnc-v2-10', errors: mt.machinePreset('pocketnc-v2-10').exampleErrors })`, note: '50,000 5-axis moves (the budget)' },
  coneFrustumTest: { call: `mt.coneFrustumTest({ machine: 'trunnion-ac', halfApexDeg: 15, inclinationDeg: 10, feed: 40, points: 200 })`, note: 'feed 40 mm/min: just under 5 M servo steps' },
  'coneFrustumTest, 48 pitch harmonics on A and C': { prep: `const m = mt.machinePreset('trunnion-ac'); for (const k of ['a', 'c']) m.axes[k].pitchError = Array.from({ length: 48 }, (_, i) => ({ n: i + 1, w: 1e-6, phi: 0 }));`, call: `mt.coneFrustumTest({ machine: m, halfApexDeg: 15, inclinationDeg: 10, feed: 40, points: 200 })`, note: 'feed 40 mm/min (just under 5 M servo steps), 48 harmonics on A and C: 99.8 M terms (budget 1e8; 64 are refused)' },
  errorSymbols: { call: `mt.errorSymbols('trunnion-ac')`, note: 'trivial' },
  estimateAlignment: { prep: `const n = 1_999_000; const s = [0, 100].map((y) => ({ y, angleDeg: Float64Array.from({ length: n }, (_, i) => -60 + 120 * i / n), deviation: new Float64Array(n).fill(0.001) }));`, call: `mt.estimateAlignment({ sections: s })`, note: '2 sections × 2 M samples (8 M values)' },
  estimateAlignmentBand: { prep: `const n = 1_100_000; const s = [0, 100].map((y) => ({ y, angleDeg: Float64Array.from({ length: n }, (_, i) => -60 + 120 * i / n), deviation: Float64Array.from({ length: n }, (_, i) => 0.001 * Math.sin(i / 1e4) + 1e-4 * Math.sin(i)) }));`, call: `mt.estimateAlignmentBand({ sections: s })`, note: '2.2 M samples at order 10' },
  feedVectorTest: { call: `mt.feedVectorTest('nmv5000', { rc: 5, rw: 8, omega: 3, accelTime: 0.064, j1: 1.7, duration: 999, dt: 0.001 })`, note: '1 M samples' },
  'feedVectorTest, 64 pitch harmonics on C': { prep: `const m = mt.machinePreset('nmv5000'); m.axes.c.pitchError = Array.from({ length: 64 }, (_, i) => ({ n: i + 1, w: 1e-6, phi: 0 }));`, call: `mt.feedVectorTest(m, { rc: 5, rw: 8, omega: 3, accelTime: 0.064, j1: 1.7, duration: 999, dt: 0.001 })`, note: '1 M samples, 64 harmonics on C' },
  fitCircle: { prep: `const n = 8_000_000; const x = Float64Array.from({ length: n }, (_, i) => 50 * Math.cos(i / n * 6.28)); const y = Float64Array.from({ length: n }, (_, i) => 50 * Math.sin(i / n * 6.28));`, call: `mt.fitCircle(x, y)`, note: '8 M points' },
  forwardKinematics: { call: `mt.forwardKinematics('pocketnc-v2-10', { x: 1, y: 2, z: 3, a: 10, b: 20 })`, note: 'one pose' },
  forwardKinematicsBulk: { prep: `const q = new Float64Array(7_999_998).fill(1);`, call: `mt.forwardKinematicsBulk('pocketnc-v2-10', q)`, note: '1.33 M poses (8 M values)' },
  frequencyResponse: { prep: `const w = Float64Array.from({ length: 8_000_000 }, (_, i) => 1 + i * 1e-3);`, call: `mt.frequencyResponse(mt.machinePreset('nmv5000').axes.c, w)`, note: '8 M frequencies' },
  harmonics: { prep: `const n = 198_000; const a = Float64Array.from({ length: n }, (_, i) => i * 6.28 / n); const d = a.map(Math.sin);`, call: `mt.harmonics(a, d, 50)`, note: '198,000 samples × 101 coefficients (2e7)' },
  identifyAccDec: { prep: `const rows = Array.from({ length: 10_000 }, (_, i) => { const feed = 1000 + i, radius = 5 + (i % 10); return { feed, radius, radiusLoss: mt.radiusReduction({ feed, radius, tA: 0.05, T: 0.02 }) }; });`, call: `mt.identifyAccDec(rows)`, note: '10,000 circles (the limit)' },
  'identifyAxis, 4 M samples': { prep: `const ax = mt.machinePreset('nmv5000').axes.x; const c = Float64Array.from({ length: 3_999_000 }, (_, i) => 0.05 * Math.sin(i / 500)); const pos = mt.simulateAxis({ ...ax, kpp: ax.kpp * 1.1 }, { dt: 1e-3, position: c }).position;`, call: `mt.identifyAxis(ax, { dt: 1e-3, command: c, position: pos })`, note: '4 M samples (command and position: the 8 M-value argument budget), Kpp 10 % off: refused when the fit\'s simulations reach 30 M samples' },
  'identifyAxis, 2.67 M samples with torque': { prep: `const ax = mt.machinePreset('nmv5000').axes.x; const c = Float64Array.from({ length: 2_666_000 }, (_, i) => 0.05 * Math.sin(i / 500)); const rr = mt.simulateAxis({ ...ax, kpp: ax.kpp * 1.1, j: ax.j * 1.2 }, { dt: 1e-3, position: c });`, call: `mt.identifyAxis(ax, { dt: 1e-3, command: c, position: rr.position, torque: rr.torque })`, note: '2.67 M samples with torque (8 M values), J and Kpp off' },
  'identifyAxis, 1 M samples': { prep: `const ax = mt.machinePreset('nmv5000').axes.x; const c = Float64Array.from({ length: 1_000_000 }, (_, i) => 0.05 * Math.sin(i / 500)); const pos = mt.simulateAxis({ ...ax, kpp: ax.kpp * 1.1 }, { dt: 1e-3, position: c }).position;`, call: `mt.identifyAxis(ax, { dt: 1e-3, command: c, position: pos })`, note: '1 M samples, Kpp 10 % off: fitted' },
  identifyAxis: { prep: `const ax = mt.machinePreset('nmv5000').axes.x; const c = Float64Array.from({ length: 100_000 }, (_, i) => 0.05 * Math.sin(i / 500)); const pos = mt.simulateAxis(ax, { dt: 1e-3, position: c }).position;`, call: `mt.identifyAxis(ax, { dt: 1e-3, command: Array.from(c), position: Array.from(pos) })`, note: '100,000 samples' },
  identifyPitchError: { prep: `const n = 1_000_000; const a = Float64Array.from({ length: n }, (_, i) => i * 6.28 * 10 / n); const e = a.map((x) => 1e-5 * Math.sin(4 * x));`, call: `mt.identifyPitchError(a, e, { maxOrder: 8 })`, note: '1 M samples over 10 turns' },
  inverseKinematics: { call: `mt.inverseKinematics('table-on-table-bc', { position: [10, 0, 5], orientation: [0, 0, 1] })`, note: 'one pose' },
  machinePreset: { call: `mt.machinePreset('nmv5000')`, note: 'trivial' },
  machines: { call: `mt.machines()`, note: 'trivial' },
  ncMainFile: { prep: `const t = Array.from({ length: 1000 }, (_, k) => Array.from({ length: 99 }, (_, i) => \`G1 X\${i} F100\`).join('\\n') + (k === 999 ? '\\nM30' : ''));`, call: `mt.ncMainFile(t)`, note: '1000 texts, 99,000 lines' },
  parseBallbarTrace: { prep: `const t = 'angle [deg],deviation [um]\\n' + Array.from({ length: 99_999 }, (_, i) => \`\${i * 360 / 1e5},\${Math.sin(i)}\`).join('\\n');`, call: `mt.parseBallbarTrace(t)`, note: '100,000 lines' },
  parseNc: { prep: `const p = Array.from({ length: 99_999 }, (_, i) => \`G1 X\${i % 100} Y\${(i * 7) % 50} F1000\`).join('\\n');`, call: `mt.parseNc(p)`, note: '100,000 lines' },
  radiusReduction: { call: `mt.radiusReduction({ feed: 2000, radius: 10, tA: 0.04, T: 0.015 })`, note: 'trivial' },
  reverseCompensate: { call: `mt.reverseCompensate('G1 X100 F100\\nG3 X100 Y0 I-50 J0\\nG1 X0 Y0', { dt: 0.001 })`, note: '250 s of motion at 1 ms (8 M simulated samples at most)' },
  sShapeTestPiece: { call: `mt.sShapeTestPiece({ machine: 'pocketnc-v2-10', scale: 0.15 })`, note: "the paper's scale" },
  simulateAxis: { prep: `const p = Float64Array.from({ length: 7_999_000 }, (_, i) => Math.sin(i / 1e4));`, call: `mt.simulateAxis(mt.machinePreset('nmv5000').axes.c, { dt: 1e-3, position: p })`, note: '8 M samples' },
  'simulateAxis, 64 pitch harmonics': { prep: `const p = Float64Array.from({ length: 1_530_000 }, (_, i) => Math.sin(i / 1e4)); const ax = { ...mt.machinePreset('nmv5000').axes.c, pitchError: Array.from({ length: 64 }, (_, i) => ({ n: i + 1, w: 1e-6, phi: 0 })) };`, call: `mt.simulateAxis(ax, { dt: 1e-3, position: p })`, note: '1.53 M samples × (1 + 64 harmonics) = 99.5 M terms (budget 1e8)' },
  simulateToolPath: { call: `mt.simulateToolPath('G1 X330000 F1000', { dt: 0.001 })`, note: '20 M samples' },
  start: { call: `mt.start()`, note: 'trivial' },
  syntheticBallbarTrace: { call: `mt.syntheticBallbarTrace({ samples: 10_000_000, bothDirections: true, harmonics: Array.from({ length: 4 }, (_, i) => ({ order: i + 2, amplitude: 1e-3 })) })`, note: '10 M samples × 2 directions × (1 + 4 harmonics) = 1e8 terms' },
  toolpathExample: { call: `mt.toolpathExample('arcs')`, note: 'trivial' },
  torqueSaturation: { call: `mt.torqueSaturation('nmv5000', { j1: Array.from({ length: 1000 }, (_, i) => i / 100), torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200, dt: 9e-6 })`, note: '1000 loads at dt = 9 µs: 48.8 M servo steps (budget 50 M)' },
  traceColumns: { prep: `const t = 'time [ms],X [mm],Y [mm],C [deg]\\n' + Array.from({ length: 99_999 }, (_, i) => \`\${i},\${Math.cos(i)},\${Math.sin(i)},\${i}\`).join('\\n');`, call: `mt.traceColumns(t)`, note: '100,000 lines' },
  travelRangeSweep: { call: `mt.travelRangeSweep({ ranges: [90, 180, 270, 360], harmonics: Array.from({ length: 6 }, (_, i) => ({ order: i + 2, amplitude: 1e-3 })), samples: 1_000_000 })`, note: '(4 ranges + 6 harmonics) × 1 M samples = 10 M' },
  version: { call: `mt.version()`, note: 'trivial' },
};

// Refusals: a call over a budget, refused before the work. The lists of
// 1e6 items are refused by their length before any item is copied into
// plain data (src/wasm/convert.rs); `--refusals` times them (the list is
// built before the clock starts).
const list = (item) => `const list = new Array(1_000_000).fill(${item});`;
const REFUSALS = {
  'identifyAccDec 1e6 circles': { prep: list('{ feed: 1000, radius: 1, radiusLoss: 0.001 }'), call: 'mt.identifyAccDec(list)' },
  'ncMainFile 1e6 texts': { prep: list("'G1 X1'"), call: 'mt.ncMainFile(list)' },
  'torqueSaturation 1e6 loads': { prep: list('1'), call: "mt.torqueSaturation('nmv5000', { j1: list, torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200 })" },
  'torqueSaturation 1000 loads at dt 1 µs': { prep: list('1').replace('1_000_000', '1000'), call: "mt.torqueSaturation('nmv5000', { j1: list, torqueMax: 725, accelTime: 0.064, feedAtCuttingPoint: 200, dt: 1e-6 })" },
  'estimateAlignmentBand 1e6 sections': { prep: list('{ y: 0, angleDeg: [0, 1, 2, 3], deviation: [0, 0, 0, 0] }'), call: 'mt.estimateAlignmentBand({ sections: list })' },
  'simulateAxis 1e6 pitch harmonics': { prep: list('{ n: 1, w: 1e-5, phi: 0 }'), call: "mt.simulateAxis({ ...mt.machinePreset('nmv5000').axes.c, pitchError: list }, { dt: 1e-3, position: [0, 1] })" },
  'syntheticBallbarTrace 1e6 harmonics': { prep: list('{ order: 2, amplitude: 1e-3 }'), call: 'mt.syntheticBallbarTrace({ harmonics: list })' },
  'parseNc 1e6 files': { prep: list("{ name: 'f.nc', text: 'G1' }"), call: "mt.parseNc('G1 X1 F100', { files: list })" },
  'circularTest 1e6 runs': { prep: list("{ direction: 'ccw', angleRad: [0, 1, 2], deviation: [0, 0, 0] }"), call: 'mt.circularTest({ nominalRadius: 100, feed: null, runs: list })' },
  'compensateNc5 99,992-line G81 program': { prep: "const p = 'G90 G21 G0 X0 Y0 Z10\\nG81 Z-1 R1 F100\\n' + Array.from({ length: 99_990 }, (_, i) => `X${i % 100} Y${Math.floor(i / 100)}`).join('\\n') + '\\nG80';", call: "mt.compensateNc5(p, { machine: 'pocketnc-v2-10', errors: {} })" },
  'coneFrustumTest 64 pitch harmonics on A and C': { prep: "const m = mt.machinePreset('trunnion-ac'); for (const k of ['a', 'c']) m.axes[k].pitchError = Array.from({ length: 64 }, (_, i) => ({ n: i + 1, w: 1e-6, phi: 0 }));", call: "mt.coneFrustumTest({ machine: m, halfApexDeg: 15, inclinationDeg: 10, feed: 40, points: 200 })" },
  'simulateToolPath 1e6 tool radii': { prep: 'const list = {}; for (let i = 0; i < 1e6; i++) list[`D${i}`] = 1;', call: "mt.simulateToolPath('G1 X1 F100', { toolRadii: list })" },
};

function run(name) {
  const { prep = '', call } = CASES[name] ?? REFUSALS[name];
  const src = `import * as mt from '${PKG}mtmotion.js';
import { readFileSync } from 'node:fs';
const wasm = mt.initSync({ module: readFileSync(new URL('mtmotion_bg.wasm', '${PKG}')) });
${prep}
const m0 = wasm.memory.buffer.byteLength;
const t0 = performance.now();
let outcome = 'ok';
try { ${call}; } catch (e) { outcome = 'Error: ' + String(e.message).slice(0, 120); }
const ms = performance.now() - t0;
console.log(JSON.stringify({ ms, mib: wasm.memory.buffer.byteLength / 2 ** 20, before: m0 / 2 ** 20, outcome }));`;
  const r = spawnSync(process.execPath, ['--max-old-space-size=4096', '--input-type=module', '-e', src], { encoding: 'utf8', timeout: 120_000 });
  if (r.status !== 0) return { outcome: `process failed: ${(r.stderr || r.error || '').toString().slice(0, 200)}` };
  return JSON.parse(r.stdout.trim().split('\n').pop());
}

if (process.argv[1] === fileURLToPath(import.meta.url) && process.argv[2] === '--refusals') {
  console.log('| refused call | time | outcome |\n|---|---:|---|');
  for (const name of Object.keys(REFUSALS)) {
    const r = run(name);
    const t = r.ms === undefined ? '–' : `${r.ms.toFixed(1)} ms`;
    console.log(`| ${name} | ${t} | ${r.outcome} |`);
  }
} else if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const names = process.argv.slice(2).length ? process.argv.slice(2) : Object.keys(CASES);
  console.log('| export | input | time | wasm memory | outcome |\n|---|---|---:|---:|---|');
  for (const name of names) {
    const r = run(name);
    const t = r.ms === undefined ? '–' : r.ms >= 1000 ? `${(r.ms / 1000).toFixed(1)} s` : `${r.ms.toFixed(0)} ms`;
    const m = r.mib === undefined ? '–' : `${r.mib.toFixed(0)} MiB`;
    console.log(`| \`${name}\` | ${CASES[name].note} | ${t} | ${m} | ${r.outcome} |`);
  }
}

export { CASES, REFUSALS };
