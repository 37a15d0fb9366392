// The trace import through the JS API (issue 26, items 2–3): traceLayout
// says which layout it read and, given a purpose, what the import reads
// each column as (the page's default column menus); a .mat capture is read
// from a Uint8Array by traceLayout and analyzeFeedVectorTrace; text passed
// as bytes reads as the string does; parseBallbarTrace maps
// EncoderX_Pos/EncoderY_Pos through options.columns; analyzeFeedVectorTrace
// reads the 'Time [ms],X [mm],Y [mm],C [deg]' trace with its
// columns auto-detected and their units applied by the core (at most 2
// periods in 3 s, not 1,499).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as mt from '../../pkg/mtmotion.js';

mt.initSync({ module: readFileSync(new URL('../../pkg/mtmotion_bg.wasm', import.meta.url)) });

const cond = { rc: 5, rw: 8, omega: Math.PI, accelTime: 0.064, j1: 1.7, duration: 3 };
const sim = mt.feedVectorTest('nmv5000', cond);
const n = sim.series.t.length;
const deg = (r) => (r * 180) / Math.PI;

/** A MAT-file Level 5 (uncompressed, little-endian) of real row vectors. */
function mat(vars) {
  const parts = [];
  const header = new Uint8Array(128).fill(32);
  header.set(new TextEncoder().encode('MATLAB 5.0 MAT-file, Platform: node test'));
  header.fill(0, 116, 124);
  header.set([0x00, 0x01, 0x49, 0x4d], 124); // version 0x0100, 'IM'
  parts.push(header);
  const el = (type, bytes) => {
    const pad = (8 - (bytes.length % 8)) % 8;
    const out = new Uint8Array(8 + bytes.length + pad);
    const v = new DataView(out.buffer);
    v.setUint32(0, type, true);
    v.setUint32(4, bytes.length, true);
    out.set(bytes, 8);
    return out;
  };
  const cat = (...a) => {
    const out = new Uint8Array(a.reduce((s, x) => s + x.length, 0));
    let o = 0;
    for (const x of a) { out.set(x, o); o += x.length; }
    return out;
  };
  for (const [name, values] of Object.entries(vars)) {
    const flags = new Uint8Array(8);
    new DataView(flags.buffer).setUint32(0, 6, true); // mxDOUBLE_CLASS
    const dims = new Uint8Array(8);
    new DataView(dims.buffer).setInt32(0, 1, true);
    new DataView(dims.buffer).setInt32(4, values.length, true);
    const data = new Uint8Array(new Float64Array(values).buffer);
    parts.push(el(14, cat(el(6, flags), el(5, dims), el(1, new TextEncoder().encode(name)), el(9, data))));
  }
  return cat(...parts);
}

test('a .mat capture is read from its bytes and gives the simulation\'s summary', () => {
  const s = sim.series;
  const bytes = mat({ t: s.t, x: s.x, y: s.y, c: Array.from(s.c, deg) });
  const layout = mt.traceLayout(bytes, undefined, 'feedVector');
  assert.equal(layout.format, 'matV5');
  assert.deepEqual(layout.columns.map((c) => [c.name, c.role]), [['t', 'time'], ['x', 'x'], ['y', 'y'], ['c', 'c']]);
  const got = mt.analyzeFeedVectorTrace(bytes, cond, { steadyFrom: sim.summary.steadyFrom });
  assert.equal(got.series.t.length, n);
  assert.ok(Math.abs(got.summary.meanAngleDiff - sim.summary.meanAngleDiff) < 1e-9, `${got.summary.meanAngleDiff}`);
  // the same file as text (a browser's file.text()) says what to do
  assert.throws(() => mt.traceLayout(new TextDecoder().decode(bytes)), /a MATLAB \.mat file, which is read from its bytes \(a Uint8Array\)/);
  assert.throws(() => mt.traceLayout(bytes.slice(0, 300)), /^Error: byte \d+: MATLAB \.mat: /);
});

test('text given as bytes reads as the string; TwinCAT columns get their roles from the core', () => {
  const s = sim.series;
  let text = 'Name\tScope\nFile\tC:\\s.svdx\n\nName\tT\tName\tX\tName\tY\tName\tC\nSampleTime[ms]\t1\tSampleTime[ms]\t1\tSampleTime[ms]\t1\tSampleTime[ms]\t1\nUnit\t(None)\tUnit\tmm\tUnit\tmm\tUnit\tdeg\n\n';
  for (let i = 0; i < n; i++) {
    const t = String(s.t[i] * 1e3).replace('.', ',');
    text += [s.t[i], s.x[i], s.y[i], deg(s.c[i])].map((v) => `${t}\t${String(v).replace('.', ',')}`).join('\t') + '\n';
  }
  const layout = mt.traceLayout(text, undefined, 'feedVector');
  assert.equal(layout.format, 'twincatScope');
  assert.deepEqual(layout.columns.map((c) => c.role), ['time', null, 'x', 'y', 'c']);
  assert.deepEqual(mt.traceLayout(new TextEncoder().encode(text)), mt.traceLayout(text));
  assert.equal(mt.traceLayout(text).columns[0].role, null, 'no purpose: no roles');
  assert.throws(() => mt.traceLayout(text, {}, 'servo'), /purpose: 'servo' is not one of 'feedVector', 'ballbar'/);
  assert.throws(() => mt.traceLayout(42), /text: expected a string or a Uint8Array/);
});

test('parseBallbarTrace reads EncoderX_Pos/EncoderY_Pos through options.columns', () => {
  let text = 'Sample;EncoderX_Pos;EncoderY_Pos\n';
  for (let i = 0; i < 72; i++) {
    const a = (i * 5 * Math.PI) / 180;
    text += `${i};${String(100 * Math.cos(a)).replace('.', ',')};${String(100 * Math.sin(a)).replace('.', ',')}\n`;
  }
  assert.throws(() => mt.parseBallbarTrace(text), /no ball-bar columns found.*EncoderX_Pos/);
  const layout = mt.traceLayout(text, undefined, 'ballbar');
  assert.deepEqual(layout.columns.map((c) => c.role), [null, null, null]);
  const t = mt.parseBallbarTrace(text, { columns: { x: 'EncoderX_Pos', y: 'EncoderY_Pos' } });
  assert.ok(Math.abs(t.nominalRadius - 100) < 1e-9, `${t.nominalRadius}`);
  assert.throws(() => mt.parseBallbarTrace(text, { columns: { x: 'EncoderX' } }), /columns\.x: no column named 'EncoderX' in the file/);
  assert.throws(() => mt.parseBallbarTrace(text, { columns: { z: 'a' } }), /options\.columns: unknown key 'z'|unknown field `z`|'z'/);
});

test('analyzeFeedVectorTrace reads Time [ms] as milliseconds with the columns auto-detected', () => {
  const s = sim.series;
  let text = 'Time [ms],X [mm],Y [mm],C [deg]\n';
  for (let i = 0; i < n; i++) text += `${s.t[i] * 1e3},${s.x[i]},${s.y[i]},${deg(s.c[i])}\n`;
  const got = mt.analyzeFeedVectorTrace(text, cond);
  assert.ok(Math.abs(got.series.t[n - 1] - 3) < 1e-9, `the trace ends at ${got.series.t[n - 1]} s`);
  assert.ok(got.summary.periods <= 2, `${got.summary.periods} periods`);
  assert.equal(got.summary.periods, sim.summary.periods);
  // the old reading (header units ignored: ms taken for s) is refused, not summarised
  assert.throws(() => mt.analyzeFeedVectorTrace(text, cond, { headerUnits: false }), /^Error: C turns at .*the time unit/);
});
