// Tool-path panel: simulate three full circles (R10, F2000, tA 40 ms,
// T 15 ms) and check the shown maximum contour error against Eq. 3 computed
// here independently; then reverse-compensate the built-in arc example and
// check the shown before/after figures (≥ 60 % less error, ≤ 5 % more time)
// and that the corrected program is offered for download, with the
// per-region notes; then start the compensation of a real program
// (LinuxCNC cds.ngc, seconds), cancel it, and check that the page says so
// and the engine still simulates.
import { readFileSync } from 'node:fs';

export default async function (page, check) {
  await page.click('[data-tab="toolpath"]');
  await page.waitForSelector('#toolpath-nc');
  const nc = 'G90 G17 G21\nG0 X10 Y0\nG3 X10 Y0 I-10 J0 F2000\nG3 X10 Y0 I-10 J0\nG3 X10 Y0 I-10 J0';
  await page.fill('#toolpath-nc', nc);
  await page.click('#toolpath-run');
  await page.waitForSelector('#toolpath-max-error', { timeout: 60_000 });
  const shown = parseFloat(await page.textContent('#toolpath-max-error'));
  const w = 2000 / 60 / 10;
  const x = (0.04 * w) / 2;
  const eq3 = (1 - Math.sin(x) / x / Math.sqrt(0.015 ** 2 * w * w + 1)) * 10 * 1000;
  check(Math.abs(shown - eq3) / eq3 < 0.005, `max error ${shown} µm vs Eq. 3 ${eq3.toFixed(3)} µm`);

  await page.selectOption('#toolpath-example', 'arcs');
  await page.click('#toolpath-compensate');
  await page.waitForSelector('#toolpath-after-error', { timeout: 60_000 });
  const before = parseFloat(await page.textContent('#toolpath-before-error'));
  const after = parseFloat(await page.textContent('#toolpath-after-error'));
  check(before > 30 && before < 100, `before ${before} µm`);
  check(after <= 0.4 * before, `after ${after} µm vs before ${before} µm`);
  const nctext = await page.textContent('#toolpath-comp-nc');
  check(nctext.includes('N40 G3') && nctext.includes('(C)'), 'compensated program keeps N numbers and comments');
  check(await page.isVisible('#toolpath-download'), 'download button shown');
  const regions = await page.textContent('#toolpath-regions');
  check(/region\(s\) changed/.test(regions), `region notes shown: ${regions.slice(0, 80)}`);
  check(!(await page.isVisible('#toolpath-cancel')), 'cancel hidden when done');

  const cds = readFileSync(new URL('../../nc_corpus/linuxcnc_cds.ngc', import.meta.url), 'utf8');
  await page.fill('#toolpath-nc', cds);
  await page.click('#toolpath-compensate');
  await page.waitForSelector('#toolpath-cancel', { state: 'visible', timeout: 10_000 });
  await page.waitForTimeout(300);
  await page.click('#toolpath-cancel');
  await page.waitForFunction(() => /cancelled/.test(document.querySelector('#toolpath-comp-out')?.textContent ?? ''), null, { timeout: 20_000 });
  check(true, 'compensation cancelled');
  await page.fill('#toolpath-nc', nc);
  await page.click('#toolpath-run');
  await page.waitForFunction(() => document.querySelector('#toolpath-max-error')?.textContent, null, { timeout: 60_000 });
  check(parseFloat(await page.textContent('#toolpath-max-error')) > 0, 'engine works after the cancel');
}
