// The study pool (www/lib/pool.js) gives identical results whatever the
// worker count: 1 and 3 workers, and the unsplit single call where one
// exists (travel-range and angle sweeps). Also: progress counts every call,
// and cancel rejects with an AbortError.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import * as mt from '../../pkg/mtmotion.js';
import { createPool, kffpSweep, travelRangeSweep, angleSweep, monteCarloNc5, chunks } from '../../www/lib/pool.js';
import { nodeSpawn } from './pool-spawn.mjs';

mt.initSync({ module: readFileSync(new URL('../../pkg/mtmotion_bg.wasm', import.meta.url)) });

const m = mt.machinePreset('nmv5000');
const conditions = [1.7, 5.9].flatMap((j1) => [2, 3.2].map((k) => ({ rc: 5, rw: 8, omega: k * Math.PI, accelTime: 0.064, j1 })));
const harmonics = [{ order: 2, amplitude: 0.005, phase: 0.3 }, { order: 3, amplitude: 0.002, phase: 1 }];
const sweepCfg = { offset: { z: 0.01, x: -0.02 }, harmonics, ranges: Array.from({ length: 37 }, (_, i) => 10 + 350 * (i / 36)), radius: 100, samples: 1000 };
const angleCfg = { sections: [{ y: 0, offset: { z: 0.01, x: 0 } }, { y: 350, offset: { z: 0.02, x: -0.01 } }], ranges: Array.from({ length: 19 }, (_, i) => 20 + 340 * (i / 18)), harmonics, radius: 100, samples: 720 };

async function studies(size) {
  const pool = createPool({ size, spawn: nodeSpawn });
  try {
    const s = mt.sShapeTestPiece({ machine: 'pocketnc-v2-10' });
    let calls = 0;
    const kffp = await kffpSweep(pool, m, conditions, { onProgress: () => calls++ });
    assert.equal(calls, conditions.length, 'progress after every call');
    return {
      kffp,
      travel: await travelRangeSweep(pool, sweepCfg),
      angle: await angleSweep(pool, angleCfg),
      mc: (await monteCarloNc5(pool, s.nc, { machine: 'pocketnc-v2-10', monteCarlo: { sigmaMm: 0.01, sigmaRad: 1e-4 } }, [1, 2, 3, 4])).map((r) => ({ nc: r.nc, after: r.after, machineErrors: r.machineErrors })),
    };
  } finally {
    pool.close();
  }
}

test('chunks covers the list in order with near-equal parts', () => {
  assert.deepEqual(chunks([1, 2, 3, 4, 5], 2), [[1, 2], [3, 4, 5]]);
  assert.deepEqual(chunks([1, 2], 8), [[1], [2]]);
  assert.deepEqual(chunks([1, 2, 3, 4, 5, 6, 7], 3).flat(), [1, 2, 3, 4, 5, 6, 7]);
});

test('1 and 3 workers give identical results, equal to the unsplit calls', async () => {
  const one = await studies(1);
  const three = await studies(3);
  assert.deepEqual(three, one);
  assert.deepEqual(one.travel, mt.travelRangeSweep(sweepCfg));
  assert.deepEqual(one.angle, mt.angleSweep(angleCfg));
  assert.deepEqual(one.kffp[0], mt.bestKffp(m, conditions[0]));
  // Different seeds draw different machines (the seeds really reach the core).
  assert.notDeepEqual(one.mc[0].machineErrors, one.mc[1].machineErrors);
});

test('cancel terminates the workers and rejects with AbortError; the pool still works after', async () => {
  const pool = createPool({ size: 2, spawn: nodeSpawn });
  const ctl = new AbortController();
  const p = kffpSweep(pool, m, [...conditions, ...conditions], { signal: ctl.signal, onProgress: (d) => d === 1 && ctl.abort() });
  await assert.rejects(p, (e) => e.name === 'AbortError');
  const again = await kffpSweep(pool, m, conditions.slice(0, 1));
  assert.deepEqual(again[0], mt.bestKffp(m, conditions[0]));
  pool.close();
});

test('a core error reaches the caller with its message', async () => {
  const pool = createPool({ size: 1, spawn: nodeSpawn });
  await assert.rejects(travelRangeSweep(pool, { ...sweepCfg, ranges: [400] }), /400/);
  pool.close();
});

test('the cone-frustum panel\'s four runs side by side equal the runs in sequence', async () => {
  // The kinematics panel's runCone: 15°/45° × perpendicular/parallel, 1440 points, servo models.
  const args = [[15, 'perpendicular'], [15, 'parallel'], [45, 'perpendicular'], [45, 'parallel']].map(([halfApexDeg, method]) => [{
    machine: 'trunnion-ac', halfApexDeg, inclinationDeg: 10, method, barLength: 100, feed: 1000, centre: [60, 40, 20],
    errors: { location: { EX0C: 0.01 } }, drives: { backlash: { c: 1e-4 } }, idealServo: false, points: 1440,
  }]);
  const sequential = args.map(([cfg]) => mt.coneFrustumTest(cfg));
  const pool = createPool({ size: 2, spawn: nodeSpawn });
  try {
    assert.deepEqual(await pool.map('coneFrustumTest', args), sequential);
  } finally {
    pool.close();
  }
});
