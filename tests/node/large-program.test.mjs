// A real 40,306-line CAM pocket (5.2 M samples at dt = 1 ms, over the
// 1 M-sample series budget) simulates through the built package: every
// number from every sample, the series thinned to the largest error of
// each group, progress reported, and cancel honoured.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as mt from '../../pkg/mtmotion.js';
import { corpusMissing, readCorpus } from '../support/corpus.mjs';

mt.initSync({ module: readFileSync(new URL('../../pkg/mtmotion_bg.wasm', import.meta.url)) });
// The pocket is in the shared corpus (tests/support/corpus.mjs); without
// it both tests are skipped, saying why.
const pocket = readCorpus('cncjs_tball-pocket.gcode');
const skip = corpusMissing || false;
const SERIES = 1_000_000; // budget::MAX_TOOLPATH_SERIES
const EVERY = 262_144; // toolpath::PROGRESS_EVERY

test('a 5.2 M-sample program simulates with thinned series, progress and the time of its length over feed', { skip }, () => {
  const fractions = [];
  const s = mt.simulateToolPath(pocket, { tA: 0, T: 0, dt: 0.001 }, (f, stage) => {
    assert.equal(stage, 'simulating');
    fractions.push(f);
  });
  assert.ok(s.samples > 5e6, `${s.samples}`);
  const stride = Math.ceil(s.samples / SERIES);
  assert.equal(s.seriesStride, stride);
  const kept = Math.ceil(s.samples / stride);
  for (const key of ['t', 'cmdX', 'simY', 'nearZ', 'velCmdX', 'velSimZ', 'errorUm', 'sampleSegment']) assert.equal(s[key].length, kept, key);
  for (let i = 1; i < kept; i++) assert.ok(s.t[i] > s.t[i - 1], `t at ${i}`);
  // The sample of the maximum (cutting moves) is the largest of its group
  // unless a rapid beats it there, so the series' peak is never below it.
  assert.ok(s.errorUm.reduce((a, b) => Math.max(a, b), 0) >= s.maxErrorUm - 1e-9);
  // With acc/dec and lag off the tool is where the command is: the motion
  // time is the nominal time within one sample.
  assert.ok(Math.abs(s.motionTime - s.nominalTime) <= 0.002, `${s.motionTime} vs ${s.nominalTime}`);
  assert.ok(s.nominalTime > 5000, `${s.nominalTime}`);
  assert.equal(fractions.length, Math.floor((s.samples - 1) / EVERY));
  for (let i = 0; i < fractions.length; i++) {
    assert.ok(fractions[i] > 0 && fractions[i] < 1 && (i === 0 || fractions[i] > fractions[i - 1]), `${fractions[i]}`);
  }
});

test('a progress callback that returns false cancels the simulation, and the instance still works', { skip }, () => {
  let calls = 0;
  assert.throws(
    () => mt.simulateToolPath(pocket, {}, () => { calls++; return false; }),
    (e) => e instanceof Error && e.message === 'cancelled',
  );
  assert.equal(calls, 1);
  const small = mt.simulateToolPath(mt.toolpathExample('arcs'), {});
  assert.equal(small.seriesStride, 1);
  assert.equal(small.t.length, small.samples);
});
