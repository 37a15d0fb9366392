// Trace import: a SERVO GUIDE-style trace whose header states its units
// ("Time [ms]", "X [mm]", "C [deg]") is read with those units — the core's
// layout preview shows each column's factor, the unit menus are set from it and the result equals the same samples
// written in seconds (analysed by the core in Node, a second path); a PNG
// is refused by both imports with "this is not a text trace (it looks like
// a PNG image)" and fills no column menu; a trace shorter than the steady
// window is refused until the steady window is set in the page; an empty ball-bar file's hint
// names the ball-bar columns, not the servo ones.
import { readFileSync } from 'node:fs';
import * as mt from '../../../pkg/mtmotion.js';

mt.initSync({ module: readFileSync(new URL('../../../pkg/mtmotion_bg.wasm', import.meta.url)) });

// The page's default condition (servo panel fields).
const cond = { rc: 5, rw: 8, omega: Math.PI, accelTime: 0.064, j1: 1.7, dt: 0.001 };
const sim = mt.feedVectorTest(mt.machinePreset('nmv5000'), cond).series;
const rows = (tScale) => Array.from(sim.t, (t, i) => `${t * tScale},${sim.x[i]},${sim.y[i]},${(sim.c[i] * 180) / Math.PI}`);
const inSeconds = ['time,x,y,c', ...rows(1)].join('\n') + '\n';
const inMs = ['Time [ms],X [mm],Y [mm],C [deg]', ...rows(1000)].join('\n') + '\n';
const want = mt.analyzeFeedVectorTrace(inSeconds, cond, {}).summary.meanAngleDiff * 1e3; // mrad
// The first bytes of a PNG file (signature + IHDR chunk).
const png = Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 13, 0x49, 0x48, 0x44, 0x52, 0, 0, 1, 0, 0, 0, 1, 0, 8, 6, 0, 0, 0, 0x5c, 0x72, 0xa8, 0x66, 0, 0, 0, 0]);
const PNG_MSG = 'this is not a text trace (it looks like a PNG image)';

export default async function (page, check) {
  await page.click('[data-tab="servo"]');
  const servoInput = await page.$('#panel-servo .drop input[type=file]');
  await servoInput.setInputFiles({ name: 'trace-ms.csv', mimeType: 'text/csv', buffer: Buffer.from(inMs) });
  await page.waitForSelector('#servo-map-time');
  check((await page.inputValue('#servo-map-time')) === 'Time [ms]', `the time column should be 'Time [ms]', is '${await page.inputValue('#servo-map-time')}'`);
  check((await page.inputValue('#servo-map-tunit')) === '0.001', 'the header unit [ms] should set the time unit menu to ms');
  // the core's layout preview: what each column was read as
  const layoutText = (await page.textContent('#servo-trace-layout')) ?? '';
  check(layoutText.includes('× 0.001 → s') && layoutText.includes('→ rad'), `the layout preview should show the core's factors (ms → s, deg → rad), shows "${layoutText}"`);
  await page.click('#servo-trace-run');
  await page.waitForSelector('#servo-trace-angle-diff, #servo-trace-results .error-box');
  const err = await page.$('#servo-trace-results .error-box');
  check(!err, `the Time [ms] trace should be analysed, shows: ${err && (await err.textContent())}`);
  if (!err) {
    const got = Number(await page.textContent('#servo-trace-angle-diff'));
    check(Math.abs(got - want) <= 1e-4 + 1e-3 * Math.abs(want), `mean α − β of the ms trace ${got} mrad should equal the seconds trace's ${want} mrad`);
  }

  // A trace that ends before the steady window (the first 0.3 s): refused
  // with what to set; with the steady window from 0.1 s it is analysed as
  // the core analyses it with that mapping.
  const short = ['time,x,y,c', ...rows(1).slice(0, 301)].join('\n') + '\n';
  const shortWant = mt.analyzeFeedVectorTrace(short, cond, { steadyFrom: 0.1 }).summary.meanAngleDiff * 1e3;
  await servoInput.setInputFiles({ name: 'short.csv', mimeType: 'text/csv', buffer: Buffer.from(short) });
  await page.waitForFunction(() => /short\.csv/.test(document.querySelector('#servo-trace-file').textContent));
  await page.click('#servo-trace-run');
  await page.waitForSelector('#servo-trace-results .error-box');
  const shortMsg = await page.textContent('#servo-trace-results .error-box');
  check(/steady window starts 0\.464 s after the motion start.*mapping\.steadyFrom/.test(shortMsg), `a 0.3 s trace should be refused for its empty steady window, says "${shortMsg}"`);
  await page.fill('#servo-map-steady', '0.1');
  await page.click('#servo-trace-run');
  await page.waitForSelector('#servo-trace-angle-diff');
  const shortGot = Number(await page.textContent('#servo-trace-angle-diff'));
  check(Math.abs(shortGot - shortWant) <= 1e-4 + 1e-3 * Math.abs(shortWant), `the 0.3 s trace from 0.1 s: ${shortGot} mrad, the core gives ${shortWant} mrad`);

  // A PNG: refused in words, and no column menus full of junk.
  await servoInput.setInputFiles({ name: 'photo.png', mimeType: 'image/png', buffer: png });
  await page.waitForSelector('#servo-trace-results .error-box');
  const msg = await page.textContent('#servo-trace-results .error-box');
  check(msg.includes(PNG_MSG), `the servo import should refuse a PNG with "${PNG_MSG}", says "${msg}"`);
  check(!(await page.$('#servo-map-time')), 'no column menus after a PNG');
  check(!(await page.$('#servo-trace-angle-diff')), 'the previous trace result must be gone after the PNG');

  await page.click('[data-tab="ballbar"]');
  const bbInput = await page.$('#panel-ballbar .drop input[type=file]:not([multiple])');
  await bbInput.setInputFiles({ name: 'photo.png', mimeType: 'image/png', buffer: png });
  await page.waitForSelector('#ballbar-results .error-box');
  const bbMsg = await page.textContent('#ballbar-results .error-box');
  check(bbMsg.includes(PNG_MSG), `the ball-bar import should refuse a PNG with "${PNG_MSG}", says "${bbMsg}"`);
  await bbInput.setInputFiles({ name: 'empty.csv', mimeType: 'text/csv', buffer: Buffer.from('') });
  await page.waitForFunction(() => /empty\.csv/.test(document.querySelector('#ballbar-file-info').textContent));
  const empty = await page.textContent('#ballbar-results .error-box');
  check(/angle_deg,deviation_um/.test(empty) && !/time,x,y,c/.test(empty), `the empty ball-bar file's hint should name the ball-bar columns: "${empty}"`);
}
