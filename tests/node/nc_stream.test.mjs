// NcStream (the program given chunk by chunk as Uint8Arrays) gives what
// the whole-text calls give for the text the bytes decode to: checkNc's
// result and simulateToolPathColumns' numbers, for small chunks that cut
// lines, CRLFs and multi-byte characters; a budget refusal is thrown by
// the push that passes it and names its line.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as mt from '../../pkg/mtmotion.js';

mt.initSync({ module: readFileSync(new URL('../../pkg/mtmotion_bg.wasm', import.meta.url)) });

/** `bytes` cut into chunks of `size`. */
function* chunks(bytes, size) {
  for (let i = 0; i < bytes.length; i += size) yield bytes.subarray(i, i + size);
}

/** A stream that has read `bytes` in chunks of `size`. */
function streamed(bytes, size) {
  const s = new mt.NcStream();
  for (const c of chunks(bytes, size)) s.push(c);
  return s;
}

// The arcs example with CRLF line ends, an unknown word (a warning), a
// UTF-8 comment and a Windows-1252 byte (0xD8, read as U+FFFD) in another.
const text = `%\r\n(Ø 10 mm)\r\n${mt.toolpathExample('arcs').replace(/\n/g, '\r\n').replace('M30', 'G1 X0 Q5 (#)\r\nM30')}`;
const bytes = new TextEncoder().encode(text);
bytes[bytes.indexOf(0x23)] = 0xd8; // the # of the last comment
const decoded = new TextDecoder().decode(bytes);

test('checkNc of a stream in small chunks is checkNc of the whole text', () => {
  const whole = mt.checkNc(decoded);
  assert.equal(whole.errors.length, 0, JSON.stringify(whole.errors[0]));
  assert.ok(whole.warnings.length > 0 && whole.summary.arcs === 43, 'the text reaches a warning and the arcs');
  assert.ok(decoded.includes('\ufffd'), 'the Windows-1252 byte is read as U+FFFD');
  for (const size of [1, 2, 7, 4096]) assert.deepEqual(streamed(bytes, size).checkNc(), whole, `chunks of ${size}`);
  // options are read as checkNc reads them
  assert.deepEqual(streamed(bytes, 7).checkNc({ units: 'inch' }), mt.checkNc(decoded, { units: 'inch' }));
  assert.throws(() => streamed(bytes, 7).checkNc({ unit: 'inch' }), /unknown key 'unit'/);
});

test('simulateToolPathColumns of a stream gives the whole text\'s numbers', () => {
  const config = { dt: 0.001, tA: 0.05, T: 0.03 };
  const whole = mt.simulateToolPathColumns(decoded, config);
  const s = streamed(bytes, 5).simulateToolPathColumns(config);
  assert.ok(whole.maxErrorUm > 1, `${whole.maxErrorUm}`);
  for (const k of ['samples', 'maxErrorUm', 'maxErrorLine', 'maxErrorTime', 'motionTime']) assert.equal(s[k], whole[k], k);
  assert.deepEqual(s.errorUm, whole.errorUm);
  assert.deepEqual(s.segmentColumns, whole.segmentColumns);
  assert.deepEqual(s.warnings, whole.warnings);
});

test('a budget refusal is thrown by the push that passes it, naming the line', () => {
  const s = new mt.NcStream();
  const ends = new Uint8Array(1 << 20).fill(0x0a);
  for (let n = 0; n < 4_000_000; n += ends.length) s.push(ends.subarray(0, Math.min(ends.length, 4_000_000 - n)));
  const refusal = /line 4000001, column 1: program: 4000001 lines, more than the limit of 4000000/;
  assert.throws(() => s.push(new TextEncoder().encode('G0 X0')), refusal);
  // the stream stays refused, and checkNc reports it as not read
  assert.throws(() => s.push(new TextEncoder().encode('G0 X0')), refusal);
  const c = s.checkNc();
  assert.equal(c.notRead, true);
  assert.equal(c.errors[0].line, 4000001);
});

test('a binary file, a bad chunk, files and a spent stream are refused with what to do', () => {
  const png = new Uint8Array([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 0x0d]);
  assert.deepEqual(streamed(png, 3).checkNc(), mt.checkNc(new TextDecoder().decode(png)));
  assert.equal(streamed(png, 3).checkNc().notRead, true);
  // checkNc of a string tells a refusal as a whole from a line's error at
  // line 1, column 1 (the core says which; the text is not read twice)
  assert.equal(mt.checkNc(new TextDecoder().decode(png)).notRead, true);
  const lineError = mt.checkNc('X\nG0 X1\n');
  assert.deepEqual([lineError.notRead, lineError.errors[0].line, lineError.errors[0].column], [false, 1, 1]);
  const s = new mt.NcStream();
  assert.throws(() => s.push('G0 X0'), /chunk: expected a Uint8Array, got string/);
  assert.throws(() => s.checkNc({ files: [] }), /options\.files: an NcStream reads the main program alone/);
  s.push(new TextEncoder().encode('G0 X1\nM30\n'));
  assert.equal(s.checkNc().summary.rapids, 1);
  assert.throws(() => s.checkNc(), /has been checked or simulated already/);
  assert.throws(() => s.push(new Uint8Array(1)), /has been checked or simulated already/);
  assert.throws(() => new mt.NcStream(-1), /totalBytes: expected/);
  assert.throws(() => new mt.NcStream(100 << 20), /program: 104857600 bytes, more than the limit/);
});
