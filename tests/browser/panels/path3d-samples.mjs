// The 3D view reads each simulated sample's segment from the core
// (sampleSegment), on a program of rapids, lines and arcs whose rapids
// leave the path by more than any cutting move: hovering a known sample
// (the largest error on cutting moves, and one on a rapid) shows its own
// line, time, error and feed, as the core in Node gives them for the same
// program (the sample index is the same: the same deterministic run); the
// simulated path's samples on rapids are drawn dimmed, off the colour
// scale (its maximum is the cutting moves' maximum, below the rapids'), and
// the rapids toggle hides them and breaks the path there.
import { readFileSync } from 'node:fs';
import * as mt from '../../../pkg/mtmotion.js';

mt.initSync({ module: readFileSync(new URL('../../../pkg/mtmotion_bg.wasm', import.meta.url)) });

const PROGRAM = [
  'G21 G90 G17',
  'G0 X10 Y10 Z5',
  'G1 X20 Y0 Z0 F500',
  'G1 X40 F2000',
  'G2 X60 Y-20 I0 J-20',
  'G1 Y-40',
  'G3 X40 Y-60 I-20 J0',
  'G1 X0 Y-60 F3000',
  'G0 Z5',
  'G0 X80 Y-10',
  'G1 Z0 F500',
  'G1 X100 Y-30 F2500',
  'G0 X0 Y0 Z10',
  'M30',
].join('\n');
/** The panel's default model: tA 40 ms, T 15 ms per axis, dt 1 ms, override 100 %. */
const CONFIG = { tA: 0.04, T: [0.015, 0.015, 0.015], dt: 0.001, feedOverride: 1 };
const SIM_RAPID = 0xa8b8db; // path3d.js SIM_RAPID_RGB [0.66, 0.72, 0.86]

const view = (page, fn, arg) => page.evaluate(([f, a]) => {
  const v = /** @type {any} */ (document.querySelector('#toolpath-path3d')).pathView;
  return new Function('v', 'a', `return (${f})(v, a);`)(v, a);
}, [fn.toString(), arg]);

export default async function (page, check) {
  const s = mt.simulateToolPath(PROGRAM, CONFIG);
  const segs = mt.parseNc(PROGRAM).segments;
  const rapid = (i) => segs[s.sampleSegment[i]].motion.type === 'rapid';
  let cut = -1;
  let fast = -1;
  for (let i = 0; i < s.errorUm.length; i++) {
    if (!rapid(i) && (cut < 0 || s.errorUm[i] > s.errorUm[cut])) cut = i;
    if (rapid(i) && (fast < 0 || s.errorUm[i] > s.errorUm[fast])) fast = i;
  }
  check(s.errorUm[cut] === s.maxErrorUm && segs[s.sampleSegment[cut]].line === s.maxErrorLine, `Node: the largest cutting-move error is sample ${cut} on line ${segs[s.sampleSegment[cut]].line} (${s.errorUm[cut]} µm); the core's maximum is line ${s.maxErrorLine} (${s.maxErrorUm} µm)`);
  check(s.errorUm[fast] > s.maxErrorUm, `the program's rapids should leave the path by more than its cutting moves: ${s.errorUm[fast]} vs ${s.maxErrorUm} µm`);

  await page.click('[data-tab="toolpath"]');
  await page.fill('#toolpath-nc', PROGRAM);
  await page.click('#toolpath-run');
  await page.waitForSelector('#toolpath-path3d .path3d-mark[data-rank="1"]', { timeout: 60_000 });
  await page.waitForFunction(() => document.querySelector('#toolpath-path3d').pathView.state().frames > 0);
  const headline = parseFloat(await page.textContent('#toolpath-max-error'));
  check(Math.abs(headline - s.maxErrorUm) < 1e-3, `the page ran the same simulation: ${headline} vs ${s.maxErrorUm} µm`);
  const legend = await page.textContent('#toolpath-path3d .path3d-legend');
  check(legend.includes(`${s.maxErrorUm.toFixed(2)} µm (scale: the largest error on cutting moves)`), `the colour scale is the cutting moves' maximum ${s.maxErrorUm.toFixed(2)} µm: "${legend}"`);
  const canvas = await page.$('#toolpath-path3d canvas');
  await canvas.scrollIntoViewIfNeeded();

  // Hover a known sample: its own line, time, error and feed.
  const hover = async (i, what) => {
    const at = await view(page, (v, j) => v.screenOfSample(j), i);
    check(at !== null, `${what}: sample ${i} should be a drawn vertex`);
    if (!at) return '';
    await page.mouse.move(at[0], at[1]);
    await page.waitForFunction((t) => {
      const tip = document.querySelector('.path3d-tip');
      return !tip.hidden && tip.textContent.includes(t);
    }, `t ${s.t[i].toFixed(3)} s`, { timeout: 3_000 }).catch(() => {});
    return page.textContent('.path3d-tip');
  };
  const g = segs[s.sampleSegment[cut]];
  let tip = await hover(cut, 'largest cutting error');
  let want = [`line ${g.line} (F ${g.feed.toFixed(0)} mm/min)`, `t ${s.t[cut].toFixed(3)} s`, `error ${s.errorUm[cut].toFixed(2)} µm`];
  check(want.every((w) => tip.includes(w)), `hovering sample ${cut} should read ${want.join(' · ')}: "${tip}"`);
  const r = segs[s.sampleSegment[fast]];
  tip = await hover(fast, 'largest rapid error');
  want = [`line ${r.line} (rapid)`, `t ${s.t[fast].toFixed(3)} s`, `error ${s.errorUm[fast].toFixed(2)} µm (rapid)`];
  check(want.every((w) => tip.includes(w)), `hovering sample ${fast} should read ${want.join(' · ')}: "${tip}"`);
  await page.mouse.move(0, 0);

  // Rapids of the simulated path: dimmed, and hidden with the toggle.
  const shown = await view(page, (v) => v.state());
  const dim = await view(page, (v, c) => v.countPixels(c), SIM_RAPID);
  const onRapids = s.sampleSegment.reduce((n, _, i) => n + (rapid(i) ? 1 : 0), 0);
  check(shown.drawnSimulatedRapids > 0 && shown.drawnSimulatedRapids <= onRapids && dim > 20, `samples on rapids should be drawn, dimmed: ${shown.drawnSimulatedRapids} of ${onRapids} drawn, ${dim} pixels of their colour`);
  check(shown.drawnSimulatedPieces === shown.drawnSimulated - 1, `with the rapids shown the simulated path is one unbroken line: ${shown.drawnSimulatedPieces} pieces between ${shown.drawnSimulated} vertices`);
  await page.click('#toolpath-show-rapids');
  await page.waitForFunction((n) => document.querySelector('#toolpath-path3d').pathView.state().drawnSimulatedRapids === 0 && document.querySelector('#toolpath-path3d').pathView.state().drawnSimulated < n, shown.drawnSimulated, { timeout: 5_000 }).catch(() => {});
  const hidden = await view(page, (v) => v.state());
  const dimHidden = await view(page, (v, c) => v.countPixels(c), SIM_RAPID);
  check(hidden.drawnSimulatedRapids === 0 && hidden.drawnSimulated < shown.drawnSimulated && dimHidden < 5, `the rapids toggle should hide the simulated path's rapids: ${hidden.drawnSimulatedRapids} rapid samples drawn (${shown.drawnSimulated} → ${hidden.drawnSimulated} samples), ${dimHidden} pixels of their colour`);
  // Broken where rapids were left out, not joined across them: one line
  // per run of consecutive cutting-move samples (counted here from the
  // core's mapping).
  const runs = s.sampleSegment.reduce((n, _, i) => n + (!rapid(i) && (i === 0 || rapid(i - 1)) ? 1 : 0), 0);
  check(runs >= 2 && hidden.drawnSimulatedPieces === hidden.drawnSimulated - runs, `without the rapids the simulated path breaks at them: ${hidden.drawnSimulatedPieces} pieces between ${hidden.drawnSimulated} vertices in ${runs} runs of cutting samples`);
  check((await view(page, (v, j) => v.screenOfSample(j), fast)) === null, 'a hidden rapid\'s sample is not drawn');
  await page.click('#toolpath-show-rapids');
}
