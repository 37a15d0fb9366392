// Outdated results (issue: an input edited after a run left the old results
// on screen, unmarked).

/** After a good run, an edit of an input the results came from marks them
 * outdated at once (a note, downloads off), on every tab; a display-only
 * control (the error magnification) does not; the next run clears it. */
export default async function (page, check) {
  const note = (sel) => page.$(`${sel} > .outdated-note`);
  // ---- tool path: tA edited after a simulation.
  await page.click('[data-tab="toolpath"]');
  await page.click('#toolpath-run');
  await page.waitForSelector('#toolpath-out:not(.stale) #toolpath-max-error');
  await page.fill('#toolpath-mag', '500');
  await page.dispatchEvent('#toolpath-mag', 'input');
  check(!(await note('#toolpath-out')), 'tool path: the error magnification is display-only and must not mark the results outdated');
  await page.fill('#toolpath-ta', '60');
  check(Boolean(await note('#toolpath-out')), 'tool path: editing tA after a run must mark the results outdated at once');
  check(await page.isDisabled('#toolpath-csv'), 'tool path: the CSV of outdated results must not be offered');
  await page.click('#toolpath-run');
  await page.waitForSelector('#toolpath-out:not(.stale) #toolpath-max-error');
  check(!(await note('#toolpath-out')), 'tool path: a new run must clear the outdated mark');

  // ---- servo: R_W edited after a simulation; the sweep area has no result and stays unmarked.
  await page.click('[data-tab="servo"]');
  await page.click('#servo-run');
  await page.waitForSelector('#servo-results:not(.stale) #servo-mean-angle-diff');
  await page.fill('#servo-rw', '9');
  check(Boolean(await note('#servo-results')), 'servo: editing R_W after a run must mark the results outdated');
  check(!(await note('#servo-sweep-results')), 'servo: an empty result area gets no outdated note');
  await page.fill('#servo-p-c-kpp', '31');
  check((await page.$$('#servo-results > .outdated-note')).length === 1, 'servo: a second edit must not add a second note');

  // ---- ball bar: the feed edited after an analysis.
  await page.click('[data-tab="ballbar"]');
  await page.selectOption('#ballbar-source', 'synthetic');
  await page.click('#ballbar-run');
  await page.waitForSelector('#ballbar-results:not(.stale) #ballbar-iso');
  await page.fill('#ballbar-feed', '1500');
  check(Boolean(await note('#ballbar-results')), 'ball bar: editing the feed after an analysis must mark the results outdated');
  check(!(await note('#align-results')), 'ball bar: the alignment area (empty, other inputs) must not be marked');
}
