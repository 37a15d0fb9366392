// The built pkg/ loads in Node through initSync({ module: bytes }) — the
// README's example — and the binding pattern holds: plain objects out,
// thrown Errors with the core's message for bad input.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as mt from '../../pkg/mtmotion.js';

mt.initSync({ module: readFileSync(new URL('../../pkg/mtmotion_bg.wasm', import.meta.url)) });

test('machinePreset returns Table 1 of suzuki-best-kffp', () => {
  const m = mt.machinePreset('nmv5000');
  assert.equal(m.axes.c.torqueMax, 725);
  assert.equal(m.axes.x.kind, 'linear');
  assert.equal(m.axes.x.lead, 0.016);
  assert.match(m.source, /Table 1/);
  assert.ok(mt.machines().includes('nmv5000'));
});

test('an unknown preset throws an Error listing the known names', () => {
  assert.throws(() => mt.machinePreset('dmu50'), (e) => e instanceof Error && /dmu50/.test(e.message) && /nmv5000/.test(e.message));
});

test('errorSymbols lists the location errors a cone-frustum test sees', () => {
  const s = mt.errorSymbols('trunnion-ac');
  // C (about Z) and A (about X): two radial offsets and three angles each, plus squareness.
  for (const sym of ['EX0C', 'EY0C', 'EA0C', 'EB0C', 'EC0C', 'EY0A', 'EZ0A', 'EA0A', 'EB0A', 'EC0A', 'EC0Y', 'EB0Z', 'EA0Z']) assert.ok(s.includes(sym), sym);
  assert.ok(!s.includes('EZ0C') && !s.includes('EX0A'), 'no translation along an axis of its own');
  assert.equal(s.length, 13);
});
