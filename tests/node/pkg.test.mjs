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

test('estimateAlignmentBand reads X/Y trace texts about the common centre, and refuses them without one', () => {
  // Two X/Y arcs (240° from −30°) about (150, 20) + an offset of 6 µm and
  // 14 µm along X at heights 80 and 330 mm.
  const xy = (dx) => ['X,Y', ...Array.from({ length: 241 }, (_, i) => {
    const t = ((i - 30) * Math.PI) / 180;
    return `${(150 + dx + 100 * Math.cos(t)).toFixed(8)},${(20 + 100 * Math.sin(t)).toFixed(8)}`;
  })].join('\n');
  const sections = [{ y: 80, text: xy(0.006) }, { y: 330, text: xy(0.014) }];
  const r = mt.estimateAlignmentBand({ sections, centre: { x: 150, y: 20 } });
  assert.ok(Math.abs(r.estimate.sections[0].z - 0.006) < 1e-6 && Math.abs(r.estimate.sections[1].z - 0.014) < 1e-6, JSON.stringify(r.estimate));
  assert.ok(Math.abs(r.estimate.deltaBz - 0.008 / 250) < 1e-9, `${r.estimate.deltaBz}`);
  assert.ok(Math.abs(r.sections[0].rangeDeg - 240) < 1e-6 && r.bandBz.determined && r.coverage === 3);
  assert.throws(() => mt.estimateAlignmentBand({ sections }), /sections\[0\]: an X\/Y trace needs the common centre/);
  assert.throws(() => mt.estimateAlignmentBand({ sections, centre: { x: 150, y: 20 }, travelRangeDeg: 90 }), /travelRangeDeg: not an input/);
});
