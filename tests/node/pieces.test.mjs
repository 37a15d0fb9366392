// The page's drawing-ready calls (www/lib/derived.js), served next to the
// core: programPieces draws each parseNc arc on its circle, in its plane,
// the way the core signs its sweep (G17 about +Z, G18 about +Y from Z to X,
// G19 about +X from Y to Z), helices rising linearly, ending exactly on the
// segment's end point; simulateToolPathPacked + unpackSimulation give the
// page the very SegmentStats the core returns.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as mt from '../../pkg/mtmotion.js';
import { derived, unpackSimulation } from '../../www/lib/derived.js';

mt.initSync({ module: readFileSync(new URL('../../pkg/mtmotion_bg.wasm', import.meta.url)) });

const program = [
  'G21 G90 G17 G0 X10 Y0 Z0',
  'G3 X0 Y10 I-10 J0 F600', // CCW quarter in XY: through (7.07, 7.07)
  'G2 X10 Y0 I0 J-10', // back, clockwise, the short way
  'G18 G3 X0 Z-10 I-10 K0', // ZX: from X10 Z0 about +Y to Z-10: through X7.07 Z-7.07
  'G0 X0 Y10 Z0',
  'G19 G3 Y0 Z10 J-10 K0', // YZ: from Y10 Z0 about +X to Z10: through Y7.07 Z7.07
  'G17 G0 X10 Y0 Z0',
  'G3 X10 Y0 Z5 I-10 J0', // a full helical turn, Z 0 → 5
  'M30',
].join('\n');

const r = Math.SQRT1_2 * 10;

test('programPieces: arcs on their circle, in their plane and direction, ending on the end point', () => {
  const parsed = mt.parseNc(program);
  const p = derived.programPieces(mt, program);
  const midOf = (line) => {
    const g = parsed.segments.findIndex((s) => s.line === line);
    const a = p.first[g], b = p.first[g + 1];
    const m = (a + b) >> 1; // the piece starting at half the sweep
    return { start: Array.from(p.pos.subarray(m * 6, m * 6 + 3)), end: Array.from(p.pos.subarray((b - 1) * 6 + 3, (b - 1) * 6 + 6)), g, n: b - a };
  };
  const near = (a, b, what) => a.forEach((v, i) => assert.ok(Math.abs(v - b[i]) < 1e-9, `${what}: ${a} vs ${b}`));
  near(midOf(2).start, [r, r, 0], 'G17 G3 half-way');
  near(midOf(3).start, [r, r, 0], 'G17 G2 half-way');
  near(midOf(4).start, [r, 0, -r], 'G18 G3 half-way');
  near(midOf(6).start, [0, r, r], 'G19 G3 half-way');
  near(midOf(8).start, [-10, 0, 2.5], 'helix half-way');
  for (const [g, s] of parsed.segments.entries()) {
    assert.equal(p.line[g], s.line);
    assert.equal(p.rapid[g], s.motion.type === 'rapid' ? 1 : 0);
    const last = p.first[g + 1] - 1;
    near(Array.from(p.pos.subarray(last * 6 + 3, last * 6 + 6)), [s.end.x, s.end.y, s.end.z], `line ${s.line} ends on its end point`);
    if (s.motion.type !== 'arc') continue;
    const m = s.motion;
    assert.ok(p.first[g + 1] - p.first[g] >= Math.ceil(Math.abs(m.sweep) / (Math.PI / 36)), `line ${s.line}: chords of at most 5°`);
    const [u, v] = { XY: [0, 1], ZX: [2, 0], YZ: [1, 2] }[m.plane];
    for (let i = p.first[g]; i < p.first[g + 1]; i++) {
      const q = p.pos.subarray(i * 6, i * 6 + 3);
      assert.ok(Math.abs(Math.hypot(q[u] - m.center[u], q[v] - m.center[v]) - m.radius) < 1e-9, `line ${s.line}: on its circle`);
    }
  }
});

test('simulateToolPathPacked + unpackSimulation give the core\'s segment statistics', () => {
  const cfg = { tA: 0.04, T: 0.015, dt: 0.001 };
  const direct = mt.simulateToolPath(program, cfg);
  const packed = derived.simulateToolPathPacked(mt, program, cfg);
  assert.ok(Object.values(packed.segmentColumns).every((c) => ArrayBuffer.isView(c)), 'the statistics cross as typed arrays');
  const s = unpackSimulation(packed);
  assert.deepEqual(s.segments, direct.segments);
  assert.equal(s.maxErrorUm, direct.maxErrorUm);
  assert.deepEqual(Array.from(s.errorUm), Array.from(direct.errorUm));
});

test('sampleSegment: one parseNc segment index per kept sample, the segment its statistics count it on', () => {
  const cfg = { tA: 0.04, T: 0.015, dt: 0.001 };
  const s = unpackSimulation(derived.simulateToolPathPacked(mt, program, cfg));
  const parsed = mt.parseNc(program);
  assert.ok(s.sampleSegment instanceof Uint32Array);
  assert.equal(s.seriesStride, 1);
  assert.equal(s.sampleSegment.length, s.t.length);
  const count = new Map();
  for (const g of s.sampleSegment) {
    assert.ok(g < parsed.segments.length, `index ${g}`);
    count.set(g, (count.get(g) ?? 0) + 1);
  }
  for (const st of s.segments) {
    assert.equal(parsed.segments[st.segment].line, st.line);
    assert.equal(count.get(st.segment) ?? 0, st.samples, `line ${st.line}`);
  }
  // The largest error on cutting moves is on a sample mapped to its line.
  const cutMax = s.errorUm.reduce((m, e, i) => (parsed.segments[s.sampleSegment[i]].motion.type !== 'rapid' && e > s.errorUm[m] ? i : m), 0);
  assert.equal(s.errorUm[cutMax], s.maxErrorUm);
  assert.equal(parsed.segments[s.sampleSegment[cutMax]].line, s.maxErrorLine);
});
