// Tool-path panel: simulate three full circles (R10, F2000, tA 40 ms,
// T 15 ms) and check the shown maximum contour error against Eq. 3 computed
// here independently; then reverse-compensate the built-in arc example and
// check the shown before/after figures (≥ 60 % less error, ≤ 5 % more time)
// and that the corrected program is offered for download, with the
// per-region notes; a program with nothing to rewrite is refused a download,
// with the reason; a line range keeps the lines outside it and a reversed
// one is refused by name; then start the compensation of a real program
// (LinuxCNC cds.ngc, seconds), cancel it, and check that the page says so
// and the engine still simulates. Last, a real 40,306-line CAM pocket
// (5.2 M samples): its simulation shows progress and can be cancelled,
// and run to the end shows the core's maximum error (the built package in
// Node gives the same number) with a note that the plots are thinned.
import { readFileSync } from 'node:fs';
import { worstDelay } from '../event-loop.mjs';
import { corpusMissing, readCorpus } from '../../support/corpus.mjs';

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
  check(!(await page.$('#toolpath-unchanged')) && !(await page.isDisabled('#toolpath-download')), 'a compensated program is offered for download');

  // A line range (fromLine 6, toLine 27: the arcs from B to C): the lines
  // outside are the example's byte for byte, some inside changed, and the
  // region notes say which moves were outside; a reversed range is refused
  // naming the field.
  const src = (await page.inputValue('#toolpath-nc')).split('\n');
  await page.fill('#toolpath-from', '6');
  await page.fill('#toolpath-to', '27');
  await page.click('#toolpath-compensate');
  await page.waitForFunction(() => /outside the lines to compensate \(6–27\)/.test(document.querySelector('#toolpath-regions')?.textContent ?? ''), null, { timeout: 60_000 });
  const ranged = ((await page.textContent('#toolpath-comp-nc')) ?? '').split('\n');
  const tail = src.length - 27;
  check(ranged.slice(0, 5).join('\n') === src.slice(0, 5).join('\n') && ranged.slice(ranged.length - tail).join('\n') === src.slice(27).join('\n'), 'a line range keeps every line outside it');
  check(ranged.slice(5, ranged.length - tail).join('\n') !== src.slice(5, 27).join('\n'), 'a line range changes lines inside it');
  check(!(await page.isDisabled('#toolpath-download')), 'a compensated range is offered for download');
  await page.fill('#toolpath-from', '30');
  await page.fill('#toolpath-to', '29');
  await page.click('#toolpath-compensate');
  await page.waitForFunction(() => /fromLine/.test(document.querySelector('#toolpath-comp-out')?.textContent ?? ''), null, { timeout: 60_000 });
  const refused = (await page.textContent('#toolpath-comp-out')) ?? '';
  check(/fromLine: line 30 comes after toLine 29/.test(refused), `a reversed range is refused by name: ${refused.slice(0, 160)}`);
  await page.fill('#toolpath-from', '');
  await page.fill('#toolpath-to', '');

  // A program whose every word is a macro expression cannot be rewritten
  // in place: the core writes it flat and compensates that, and the page
  // says so and offers the flat program.
  const macro = '#1=20\n#2=0\nG0 X0 Y0 Z1\nG1 Z#2 F600\nG1 X#1 F2000\nG1 Y#1\nG1 X#2\nG1 Y[#1-20]\nG0 Z5\nM30\n';
  await page.fill('#toolpath-nc', macro);
  await page.click('#toolpath-compensate');
  await page.waitForSelector('#toolpath-expand-note, #toolpath-comp-out .error-box', { timeout: 60_000 });
  const flat = (await page.textContent('#toolpath-comp-out')) ?? '';
  check(/Written flat: the largest error sat on moves the program computes/.test(flat) && !/No compensated program/.test(flat), `a macro program is compensated written flat: ${flat.slice(0, 200)}`);
  check(!(await page.isDisabled('#toolpath-download')) && /written flat/.test((await page.textContent('#toolpath-download')) ?? ''), 'the flat program is offered for download, saying so');
  check(((await page.textContent('#toolpath-comp-nc')) ?? '').startsWith('G21 G90 G94 G17'), 'the flat program starts with its modes');
  // With a spindle speed computed by macro code it cannot be written flat
  // either: the core returns it byte for byte and says why; no download.
  await page.fill('#toolpath-nc', `#3=8000\nS#3 M3\n${macro}`);
  await page.click('#toolpath-compensate');
  await page.waitForSelector('#toolpath-unchanged, #toolpath-comp-out .error-box', { timeout: 60_000 });
  const unchanged = (await page.textContent('#toolpath-comp-out')) ?? '';
  check(/No compensated program: nothing in the program changed/.test(unchanged) && /macro/.test(unchanged), `an unchanged program says why: ${unchanged.slice(0, 200)}`);
  check(/Not written flat: line 2, column 1: its S word is computed by macro code/.test(unchanged), `and why it is not written flat: ${unchanged.slice(0, 400)}`);
  check(await page.isDisabled('#toolpath-download'), 'no download is offered for an unchanged program');

  // The real programs are in the shared corpus (tests/support/corpus.mjs).
  if (corpusMissing) {
    console.log(`  skipped the real programs (cds.ngc, the pocket): ${corpusMissing}`);
    return;
  }
  const cds = readCorpus('linuxcnc_cds.ngc');
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

  const pocket = readCorpus('cncjs_tball-pocket.gcode');
  // page.fill types into the editor too slowly for 1.2 MB; set it as a
  // paste would.
  await page.$eval('#toolpath-nc', (el, text) => {
    el.value = text;
    el.dispatchEvent(new Event('input', { bubbles: true }));
  }, pocket);
  await page.click('#toolpath-run');
  await page.waitForSelector('#toolpath-sim-cancel', { state: 'visible', timeout: 20_000 });
  await page.click('#toolpath-sim-cancel');
  await page.waitForFunction(() => /Simulation cancelled/.test(document.querySelector('#toolpath-out')?.textContent ?? ''), null, { timeout: 20_000 });
  check(true, 'simulation of the pocket cancelled');
  // The cancel ends the run: its message is not shown greyed, and no chart
  // of the run before stays on screen.
  check(!(await page.$('#toolpath-out.stale, #toolpath-out.dimmed')), 'the cancel message is not left greyed as a stale result');
  check((await page.$$('#toolpath-path canvas, #toolpath-velocity .uplot')).length === 0, 'no chart of the previous run stays after a cancel');
  const delay = await worstDelay(page, async () => {
    // A run marks the old results stale at once, but greys them and shows
    // its progress bar only once it has lasted SHOW_AFTER_MS (200 ms, lib/ui.js):
    // quick runs redraw without a flash and without the fade's frames.
    const early = await page.evaluate(async () => {
      const out = document.querySelector('#toolpath-out');
      const bar = out.previousElementSibling;
      const seen = () => ({ stale: out.classList.contains('stale'), opacity: getComputedStyle(out).opacity, bar: !bar.hidden });
      document.querySelector('#toolpath-run').click();
      const atClick = seen();
      await new Promise((r) => setTimeout(r, 100)); // due before the 200 ms timers
      return { atClick, after100: seen() };
    });
    const plain = (v) => v.stale && v.opacity === '1' && !v.bar;
    check(plain(early.atClick) && plain(early.after100), `for its first 200 ms a run is stale but not greyed, with no progress bar: ${JSON.stringify(early)}`);
    await page.waitForFunction(() => getComputedStyle(document.querySelector('#toolpath-out')).opacity !== '1', null, { timeout: 20_000 });
    await page.waitForFunction(() => !document.querySelector('#toolpath-out').previousElementSibling.hidden, null, { timeout: 20_000 });
    check(true, 'a long run greys the old results and shows its progress bar');
    await page.waitForSelector('#toolpath-series-note', { timeout: 90_000 });
  });
  check(!(await page.$('#toolpath-out.dimmed, #toolpath-out.stale')), 'the finished run is neither stale nor greyed');
  console.log(`  pocket: worst event-loop delay ${delay.toFixed(0)} ms while 5.2 M samples were simulated and drawn`);
  check(delay < 500, `the page should stay responsive while the pocket simulates and draws; worst delay ${delay.toFixed(0)} ms`);
  const mt = await import('../../../pkg/mtmotion.js');
  mt.initSync({ module: readFileSync(new URL('../../../pkg/mtmotion_bg.wasm', import.meta.url)) });
  const core = mt.simulateToolPath(pocket, { tA: 0.04, T: [0.015, 0.015, 0.015], dt: 0.001, feedOverride: 1 });
  const pocketShown = parseFloat(await page.textContent('#toolpath-max-error'));
  check(Math.abs(pocketShown - core.maxErrorUm) < 1e-3 * core.maxErrorUm, `pocket max error ${pocketShown} µm vs core ${core.maxErrorUm.toFixed(3)} µm`);
  const note = await page.textContent('#toolpath-series-note');
  check(note.includes(`each ${core.seriesStride} `) && note.includes(core.samples.toLocaleString('en')), `thinning note: ${note}`);
  check(!(await page.isVisible('#toolpath-sim-cancel')), 'simulation cancel hidden when done');
}
