// Controls' layouts in the page (issue 26, item 3): the column menus start
// at the columns the core's layout preview marks (no column guessing in
// the page's JS): a MATLAB .mat capture dropped on the servo panel goes to
// the core as bytes, its menus are t/x/y/c, and its analysis equals the
// core's in Node; a halsampler file (numbers only) is refused until the
// sample period is given, then read with a generated time; a ball-bar file
// with EncoderX_Pos/EncoderY_Pos columns is refused by name, and read once
// the page's mapping menus name those columns; a ball-bar .mat capture is
// read as bytes by the core, and a Renishaw .b5r report's features stand
// beside ours as the core pairs them (the numbers equal b5rBeside's in
// Node).
import { readFileSync } from 'node:fs';
import * as mt from '../../../pkg/mtmotion.js';

mt.initSync({ module: readFileSync(new URL('../../../pkg/mtmotion_bg.wasm', import.meta.url)) });

const cond = { rc: 5, rw: 8, omega: Math.PI, accelTime: 0.064, j1: 1.7, dt: 0.001 };
const sim = mt.feedVectorTest(mt.machinePreset('nmv5000'), cond).series;
const deg = (r) => (r * 180) / Math.PI;

/** A MAT-file Level 5 (uncompressed, little-endian) of real row vectors. */
function mat(vars) {
  const el = (type, bytes) => {
    const out = Buffer.alloc(8 + bytes.length + ((8 - (bytes.length % 8)) % 8));
    out.writeUInt32LE(type, 0);
    out.writeUInt32LE(bytes.length, 4);
    Buffer.from(bytes).copy(out, 8);
    return out;
  };
  const header = Buffer.alloc(128, 32);
  header.write('MATLAB 5.0 MAT-file, Platform: browser test');
  header.fill(0, 116, 124);
  header.writeUInt16LE(0x0100, 124);
  header.write('IM', 126);
  const parts = [header];
  for (const [name, values] of Object.entries(vars)) {
    const flags = Buffer.alloc(8);
    flags.writeUInt32LE(6, 0); // mxDOUBLE_CLASS
    const dims = Buffer.alloc(8);
    dims.writeInt32LE(1, 0);
    dims.writeInt32LE(values.length, 4);
    const data = Buffer.from(new Float64Array(values).buffer);
    parts.push(el(14, Buffer.concat([el(6, flags), el(5, dims), el(1, Buffer.from(name)), el(9, data)])));
  }
  return Buffer.concat(parts);
}

export default async function (page, check) {
  await page.click('[data-tab="servo"]');
  const servoInput = await page.$('#panel-servo .drop input[type=file]');
  const bytes = mat({ t: sim.t, x: sim.x, y: sim.y, c: Array.from(sim.c, deg) });
  const want = mt.analyzeFeedVectorTrace(new Uint8Array(bytes), cond, {}).summary.meanAngleDiff * 1e3;
  await servoInput.setInputFiles({ name: 'capture.mat', mimeType: 'application/octet-stream', buffer: bytes });
  await page.waitForSelector('#servo-map-time');
  const picked = await Promise.all(['time', 'x', 'y', 'c'].map((k) => page.inputValue(`#servo-map-${k}`)));
  check(picked.join() === 't,x,y,c', `the .mat's menus should be t, x, y, c (the core's roles), are ${picked.join()}`);
  const info = await page.textContent('#servo-trace-file');
  check(info.includes('layout read: matV5'), `the page should say the .mat layout was read: "${info}"`);
  await page.click('#servo-trace-run');
  await page.waitForSelector('#servo-trace-angle-diff, #servo-trace-results .error-box');
  const err = await page.$('#servo-trace-results .error-box');
  check(!err, `the .mat capture should be analysed, shows: ${err && (await err.textContent())}`);
  if (!err) {
    const got = Number(await page.textContent('#servo-trace-angle-diff'));
    check(Math.abs(got - want) <= 1e-4 + 1e-3 * Math.abs(want), `mean α − β of the .mat ${got} mrad should equal the core's ${want} mrad`);
  }

  // halsampler: numbers only, refused until the sample period is given
  const hal = Array.from(sim.t, (_, i) => `${sim.x[i]} ${sim.y[i]} ${deg(sim.c[i])} `).join('\n') + '\n';
  await servoInput.setInputFiles({ name: 'hal.txt', mimeType: 'text/plain', buffer: Buffer.from(hal) });
  await page.waitForSelector('#servo-trace-results .error-box');
  const halMsg = await page.textContent('#servo-trace-results .error-box');
  check(/line 1: option samplePeriod: this file is numbers only/.test(halMsg), `a halsampler file without a period should ask for it, says "${halMsg}"`);
  await page.fill('#servo-trace-period', '0.001');
  await page.dispatchEvent('#servo-trace-period', 'change');
  await page.waitForSelector('#servo-map-time');
  check((await page.inputValue('#servo-map-time')) === 'time', 'the generated time column should be the time menu\'s choice');
  check((await page.textContent('#servo-trace-file')).includes('layout read: halsampler'), 'the page should say halsampler was read');

  // ball-bar: EncoderX_Pos/EncoderY_Pos read through the page's mapping
  await page.click('[data-tab="ballbar"]');
  const bbInput = await page.$('#panel-ballbar .drop input[type=file]:not([multiple])');
  const rows = ['Sample;EncoderX_Pos;EncoderY_Pos'];
  for (let i = 0; i <= 72; i++) rows.push(`${i};${String(100 * Math.cos((i * 5 * Math.PI) / 180)).replace('.', ',')};${String(100 * Math.sin((i * 5 * Math.PI) / 180)).replace('.', ',')}`);
  for (let i = 71; i >= 0; i--) rows.push(`${144 - i};${String(100 * Math.cos((i * 5 * Math.PI) / 180)).replace('.', ',')};${String(100 * Math.sin((i * 5 * Math.PI) / 180)).replace('.', ',')}`);
  await bbInput.setInputFiles({ name: 'encoder.csv', mimeType: 'text/csv', buffer: Buffer.from(rows.join('\n') + '\n') });
  await page.waitForSelector('#ballbar-map-read');
  const bbErr = await page.textContent('#ballbar-results .error-box');
  check(/no ball-bar columns found.*EncoderX_Pos/.test(bbErr), `without a mapping the file is refused naming its columns: "${bbErr}"`);
  check((await page.inputValue('#ballbar-map-mode')) === 'xy', 'no angle/deviation roles: the mapping reads X/Y');
  await page.selectOption('#ballbar-map-x', 'EncoderX_Pos');
  await page.selectOption('#ballbar-map-y', 'EncoderY_Pos');
  await page.click('#ballbar-map-read');
  await page.waitForFunction(() => /encoder\.csv: 2 run/.test(document.querySelector('#ballbar-file-info').textContent));

  // ball-bar: a .mat capture (vectors t, x, y) goes to the core as bytes
  const t = [];
  const bx = [];
  const by = [];
  const at = (i, a) => {
    const r = 100 + 0.005 * Math.sin(2 * a);
    t.push(i * 0.01);
    bx.push(r * Math.cos(a));
    by.push(r * Math.sin(a));
  };
  for (let i = 0; i <= 72; i++) at(i, (i * 5 * Math.PI) / 180);
  for (let i = 71; i >= 0; i--) at(144 - i, (i * 5 * Math.PI) / 180);
  const bbMat = mat({ t, x: bx, y: by });
  await bbInput.setInputFiles({ name: 'ballbar.mat', mimeType: 'application/octet-stream', buffer: bbMat });
  await page.waitForFunction(() => /ballbar\.mat: 2 run/.test(document.querySelector('#ballbar-file-info').textContent));
  const matRead = await page.waitForFunction(() => /Layout read: matV5/.test(document.querySelector('#ballbar-trace-format')?.textContent || ''), null, { timeout: 10000 }).then(() => true, () => false);
  check(matRead, 'the page should say the .mat layout was read (the core\'s layout preview of the bytes)');

  // a Renishaw .b5r report beside ours
  const b5r = readFileSync(new URL('../../b5r/xy_100mm_1000.b5r', import.meta.url), 'utf8');
  const pairs = mt.b5rBeside(b5r, mt.parseBallbarTrace(new Uint8Array(bbMat), { nominalRadius: 100 }));
  await page.setInputFiles('#ballbar-b5r-input', { name: 'report.b5r', mimeType: 'application/xml', buffer: Buffer.from(b5r) });
  await page.waitForSelector('#ballbar-b5r-beside');
  const b5rInfo = await page.textContent('#ballbar-b5r-info');
  check(/report\.b5r: 100mm XY 1000; bar 100 mm; F 1000 mm\/min; plane XY; runs CCW, CW; 12 feature\(s\)/.test(b5rInfo), `the report's settings should be shown: "${b5rInfo}"`);
  check(b5rInfo.includes('the raw samples are not read'), 'the page should say the samples are not read');
  const cells = await page.$$eval('#ballbar-b5r-beside tbody tr', (trs) => trs.map((tr) => Array.from(tr.children, (td) => td.textContent)));
  check(cells.length === pairs.length, `${cells.length} rows beside ours, the core pairs ${pairs.length}`);
  const sq = cells.find((c) => c[1] === 'AF_SQUARENESS');
  const wantSq = pairs.find((r) => r.feature === 'AF_SQUARENESS');
  check(sq && sq[3].endsWith('µrad') && Math.abs(parseFloat(sq[4]) - wantSq.ours) <= 1e-3 * Math.max(1, Math.abs(wantSq.ours)), `squareness beside ours should be the core's ${wantSq.ours} µrad: ${sq}`);
  const st = cells.find((c) => c[1] === 'AF_STRAIGHTNESS_A');
  check(st && st[4].includes('not computed here'), `a feature we do not compute should say so: ${st}`);
}
