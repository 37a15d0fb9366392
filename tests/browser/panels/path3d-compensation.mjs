// The reverse compensation's before and after in 3D (lib/path3d.js, a view
// of its own in the compensation card), on the built-in arc example: the
// view opens on "after", on one colour scale for both (the larger cutting
// maximum, the original's); its worst spot is the after maximum; the
// switch flips to "before" with the camera kept (an orbit made first
// stays) and its worst spot is the before maximum. Hovering the after
// run's largest cutting-move sample reads its line in the ORIGINAL
// program (both runs are measured against it: sampleSegment indexes the
// original's segments), its time and error, as the core in Node gives
// them for the same program and config.
import { readFileSync } from 'node:fs';
import * as mt from '../../../pkg/mtmotion.js';

mt.initSync({ module: readFileSync(new URL('../../../pkg/mtmotion_bg.wasm', import.meta.url)) });

/** The panel's defaults: tA 40 ms, T 15 ms per axis, dt 1 ms, override 100 %, time budget 5 %. */
const CONFIG = { tA: 0.04, T: [0.015, 0.015, 0.015], dt: 0.001, feedOverride: 1, timeBudget: 0.05 };

const view = (page, fn, arg) => page.evaluate(([f, a]) => {
  const v = /** @type {any} */ (document.querySelector('#toolpath-comp-path3d')).pathView;
  return new Function('v', 'a', `return (${f})(v, a);`)(v, a);
}, [fn.toString(), arg]);

export default async function (page, check) {
  const text = mt.toolpathExample('arcs');
  const c = mt.reverseCompensate(text, CONFIG);
  const segs = mt.parseNc(text).segments;
  const a = c.afterSim;
  let worst = -1;
  a.errorUm.forEach((e, i) => {
    if (segs[a.sampleSegment[i]].motion.type !== 'rapid' && (worst < 0 || e > a.errorUm[worst])) worst = i;
  });
  check(a.errorUm[worst] === a.maxErrorUm, `Node: the after run's largest cutting sample ${worst} (${a.errorUm[worst]} µm) is its maximum ${a.maxErrorUm} µm`);
  const scale = Math.max(c.beforeSim.maxErrorUm, c.afterSim.maxErrorUm);

  await page.click('[data-tab="toolpath"]');
  await page.selectOption('#toolpath-example', 'arcs');
  await page.click('#toolpath-compensate');
  await page.waitForSelector('#toolpath-comp-path3d .path3d-mark[data-rank="1"]', { timeout: 60_000 });
  await page.waitForFunction(() => document.querySelector('#toolpath-comp-path3d').pathView.state().frames > 0);
  const shownAfter = parseFloat(await page.textContent('#toolpath-after-error'));
  check(Math.abs(shownAfter - c.after.maxErrorUm) < 1e-3 * c.after.maxErrorUm, `the page ran the same compensation: after ${shownAfter} vs ${c.after.maxErrorUm} µm`);
  const state = () => page.evaluate(() => {
    const e = /** @type {any} */ (document.querySelector('#toolpath-comp-path3d'));
    const m = e.querySelector('.path3d-mark[data-rank="1"]');
    return { showing: e.dataset.showing, legend: e.querySelector('.path3d-legend').textContent, mark: m?.title ?? '', camera: [...e.pathView.camera.position.toArray(), e.pathView.camera.zoom] };
  });
  let s = await state();
  const errorOf = (title) => parseFloat(/, ([\d.]+) µm$/.exec(title)?.[1] ?? 'NaN');
  check(s.showing === 'after' && s.legend.includes(`${scale.toFixed(2)} µm (scale`), `the view opens on the after run, scale ${scale.toFixed(2)} µm: showing ${s.showing}, "${s.legend}"`);
  check(Math.abs(errorOf(s.mark) - c.after.maxErrorUm) < 0.01, `after: worst spot #1 is the after maximum ${c.after.maxErrorUm} µm: "${s.mark}"`);

  // Hover the after run's largest sample: its line in the original program.
  const canvas = await page.$('#toolpath-comp-path3d canvas');
  await canvas.scrollIntoViewIfNeeded();
  const at = await view(page, (v, i) => v.screenOfSample(i), worst);
  check(at !== null, `sample ${worst} should be drawn`);
  if (at) {
    await page.mouse.move(at[0], at[1]);
    const tip = '#toolpath-comp-path3d .path3d-tip';
    await page.waitForSelector(`${tip}:not([hidden])`, { timeout: 3_000 }).catch(() => {});
    const read = (await page.textContent(tip)) ?? '';
    const g = segs[a.sampleSegment[worst]];
    const want = [`line ${g.line} (F ${g.feed.toFixed(0)} mm/min)`, `t ${a.t[worst].toFixed(3)} s`, `error ${a.errorUm[worst].toFixed(2)} µm`];
    check(want.every((w) => read.includes(w)), `hovering the after maximum should read ${want.join(' · ')}: "${read}"`);
    await page.mouse.move(0, 0);
  }

  // Orbit, then flip to before: the camera stays, the marks are the before run's.
  const b = await canvas.boundingBox();
  await page.mouse.move(b.x + b.width / 2, b.y + b.height / 2);
  await page.mouse.down();
  await page.mouse.move(b.x + b.width / 2 + 90, b.y + b.height / 2 - 50, { steps: 5 });
  await page.mouse.up();
  await page.waitForTimeout(200);
  const orbited = (await state()).camera;
  await page.check('#toolpath-comp-before');
  await page.waitForFunction(() => document.querySelector('#toolpath-comp-path3d').dataset.showing === 'before');
  s = await state();
  check(s.camera.every((x, i) => Math.abs(x - orbited[i]) < 1e-9), `flipping to before keeps the camera: ${orbited} → ${s.camera}`);
  check(Math.abs(errorOf(s.mark) - c.before.maxErrorUm) < 0.01 && s.legend.includes(`${scale.toFixed(2)} µm (scale`), `before: worst spot #1 is the before maximum ${c.before.maxErrorUm} µm on the same scale: "${s.mark}", "${s.legend}"`);
}
