// A 50 MB file dropped on the page: the page keeps answering (a round trip
// through the event loop stays under 200 ms while the file is read and
// refused), the core's budget error is shown in words in place of the
// results, and the page then works as before. Both a ball-bar trace and an
// NC program are tried; no console error may appear (run.mjs fails on any).
import { writeFileSync, mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

const MB50 = 50 * 1024 * 1024;

/** A file of at least `bytes` bytes made of `line` repeated (playwright
 * takes buffers only up to 50 MB, so the file goes through a path). */
function bigFile(name, header, line, bytes) {
  const path = join(mkdtempSync(join(tmpdir(), 'mtmotion-huge-')), name);
  writeFileSync(path, header + line.repeat(Math.ceil(bytes / line.length)));
  return path;
}

/** Largest event-loop delay seen while `work` runs, in ms (a 20 ms probe). */
async function worstDelay(page, work) {
  await page.evaluate(() => {
    const w = /** @type {any} */ (window);
    w.__worst = 0;
    w.__last = performance.now();
    w.__probe = setInterval(() => {
      const now = performance.now();
      w.__worst = Math.max(w.__worst, now - w.__last - 20);
      w.__last = now;
    }, 20);
  });
  await work();
  return page.evaluate(() => {
    const w = /** @type {any} */ (window);
    clearInterval(w.__probe);
    return w.__worst;
  });
}

export default async function (page, check) {
  // ---- ball bar
  await page.click('[data-tab="ballbar"]');
  const trace = bigFile('huge-trace.csv', 'angle_deg,deviation_um\n', '123.456789,0.123456789\n', MB50);
  const bbInput = await page.$('#panel-ballbar .drop input[type=file]:not([multiple])');
  const bbDelay = await worstDelay(page, async () => {
    await bbInput.setInputFiles(trace);
    await page.waitForSelector('#ballbar-results .error-box', { timeout: 60_000 });
  });
  const bbMsg = await page.textContent('#ballbar-results .error-box');
  check(bbDelay < 200, `the page should answer within 200 ms while a 50 MB trace is refused; worst delay ${bbDelay.toFixed(0)} ms`);
  check(/more than the limit|too large|at most/i.test(bbMsg) && bbMsg.length < 400, `the 50 MB trace should get the core's budget error in words: "${bbMsg.slice(0, 300)}"`);
  // The page still works: the synthetic trace analyses.
  await page.selectOption('#ballbar-source', 'synthetic');
  await page.click('#ballbar-run');
  await page.waitForSelector('#ballbar-centre-x', { timeout: 60_000 });
  check(true, 'the ball-bar panel analyses again after the huge file');

  // ---- tool path
  await page.click('[data-tab="toolpath"]');
  const nc = bigFile('huge-program.nc', 'G21 G90\n', 'G01 X12.3456 Y65.4321 F1000\n', MB50);
  const tpInput = await page.$('#panel-toolpath .drop input[type=file]');
  const tpDelay = await worstDelay(page, async () => {
    await tpInput.setInputFiles(nc);
    await page.waitForSelector('#panel-toolpath .error-box', { timeout: 60_000 });
  });
  const tpMsg = await page.textContent('#panel-toolpath .error-box');
  check(tpDelay < 200, `the page should answer within 200 ms while a 50 MB program is refused; worst delay ${tpDelay.toFixed(0)} ms`);
  check(/more than the limit|too large|at most/i.test(tpMsg) && tpMsg.length < 400, `the 50 MB program should get the core's budget error in words: "${tpMsg.slice(0, 300)}"`);
}
