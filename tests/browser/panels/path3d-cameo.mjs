// The real 35k-line CAMotics cameo raster program (shared corpus, never
// copied into the repository) is dropped on the tool-path panel, simulated
// and drawn in the 3D view with no main-thread task over 200 ms (the
// browser's long-task entries, from the drop until the view and the
// velocity chart are drawn; the longest is printed). Then the worst spot's
// mark scrolls the editor, 35k lines long, to the line the core names.
import { join } from 'node:path';
import { corpusDir, corpusMissing } from '../../support/corpus.mjs';

const LIMIT_MS = 200;

export default async function (page, check) {
  if (!corpusDir) {
    console.log(`  cameo: skipped, ${corpusMissing}`);
    return;
  }
  await page.click('[data-tab="toolpath"]');
  await page.evaluate(() => {
    const w = /** @type {any} */ (window);
    w.__longTasks = [];
    new PerformanceObserver((list) => {
      for (const e of list.getEntries()) w.__longTasks.push(e.duration);
    }).observe({ type: 'longtask' });
  });
  const t0 = Date.now();
  await page.setInputFiles('#toolpath-file', join(corpusDir, 'camotics_cameo.nc'));
  await page.waitForFunction(() => document.querySelector('#toolpath-nc').value.split('\n').length > 35_000, null, { timeout: 60_000 });
  await page.waitForSelector('#toolpath-check-time', { timeout: 60_000 });
  const loaded = Date.now() - t0;
  await page.click('#toolpath-run');
  await page.waitForSelector('#toolpath-path3d .path3d-mark[data-rank="1"]', { timeout: 120_000 });
  await page.waitForSelector('#toolpath-velocity .uplot', { timeout: 60_000 });
  await page.waitForFunction(() => document.querySelector('#toolpath-path3d').pathView.state().frames > 0);
  await page.waitForTimeout(500);
  const tasks = await page.evaluate(() => /** @type {any} */ (window).__longTasks);
  const longest = Math.max(0, ...tasks);
  const state = await page.evaluate(() => document.querySelector('#toolpath-path3d').pathView.state());
  console.log(`  cameo: loaded in ${loaded} ms, simulated and drawn in ${Date.now() - t0} ms in all; longest main-thread task ${longest.toFixed(0)} ms (${tasks.length} over 50 ms: ${tasks.map((d) => d.toFixed(0)).join(', ')}); drawn ${state.drawnProgram} program pieces, ${state.drawnSimulated} simulated vertices`);
  check(longest <= LIMIT_MS, `cameo: no main-thread task over ${LIMIT_MS} ms from the drop to the drawn view; the longest took ${longest.toFixed(0)} ms`);
  check(state.drawnProgram > 1000 && state.drawnSimulated > 1000, `cameo: the view draws the program and the simulation (${state.drawnProgram}, ${state.drawnSimulated})`);

  // The worst spot is the core's maximum: its mark selects that line, in view in the editor.
  const atLine = await page.$eval('#toolpath-out', (o) => Number(/at line \/ time\s*(\d+)/.exec(o.textContent)?.[1]));
  await page.click('.path3d-mark[data-rank="1"]');
  await page.waitForFunction((n) => {
    const t = /** @type {HTMLTextAreaElement} */ (document.querySelector('#toolpath-nc'));
    const line = t.value.slice(0, t.selectionStart).split('\n').length;
    const a = document.querySelector('.nc-editor .cm-activeLine')?.getBoundingClientRect();
    const box = document.querySelector('.nc-editor .cm-scroller').getBoundingClientRect();
    return line === n && a && a.top >= box.top - 1 && a.bottom <= box.bottom + 1;
  }, atLine, { timeout: 5_000 }).then(() => check(true, ''), () => check(false, `cameo: mark #1 should select line ${atLine} (the core's maximum) in view in the editor`));
}
