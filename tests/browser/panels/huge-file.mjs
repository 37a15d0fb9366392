// A 70 MB file (over the 64 MiB text budget) dropped on the page: the
// page keeps answering (a round trip through the event loop stays under
// 200 ms while the file is refused), the core's budget error is shown in words in place of the results (the core's
// checkFileSize refuses it from its size, so it is never read into the
// page), and the page then works as before. Both a ball-bar trace and an NC
// program are tried; no console error may appear (run.mjs fails on any).
import { writeFileSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { worstDelay } from '../event-loop.mjs';

const MB70 = 70 * 1024 * 1024;
/** The temporary folders made, removed at the end (each run made 140 MB). */
const made = [];

/** A file of at least `bytes` bytes made of `line` repeated (playwright
 * takes buffers only up to 50 MB, so the file goes through a path). */
function bigFile(name, header, line, bytes) {
  const dir = mkdtempSync(join(tmpdir(), 'mtmotion-huge-'));
  made.push(dir);
  const path = join(dir, name);
  writeFileSync(path, header + line.repeat(Math.ceil(bytes / line.length)));
  return path;
}

/** Drops `file` on the tab's drop zone and checks the page answered and
 * showed the core's budget error in `errorSelector`. */
async function dropHuge(page, check, { tab, input, file, errorSelector, what }) {
  await page.click(`[data-tab="${tab}"]`);
  const handle = await page.$(input);
  const delay = await worstDelay(page, async () => {
    await handle.setInputFiles(file);
    await page.waitForSelector(errorSelector, { timeout: 60_000 });
  });
  const msg = await page.textContent(errorSelector);
  console.log(`  ${what}: worst event-loop delay ${delay.toFixed(0)} ms while the 70 MB file was refused`);
  check(delay < 200, `the page should answer within 200 ms while a 70 MB ${what} is refused; worst delay ${delay.toFixed(0)} ms`);
  check(/more than the limit|too large|at most/i.test(msg) && msg.length < 400, `the 70 MB ${what} should get the core's budget error in words: "${msg.slice(0, 300)}"`);
}

export default async function (page, check) {
  try {
    await run(page, check);
  } finally {
    for (const dir of made.splice(0)) rmSync(dir, { recursive: true, force: true });
  }
}

async function run(page, check) {
  await dropHuge(page, check, {
    tab: 'ballbar',
    input: '#panel-ballbar .drop input[type=file]:not([multiple])',
    file: bigFile('huge-trace.csv', 'angle_deg,deviation_um\n', '123.456789,0.123456789\n', MB70),
    errorSelector: '#ballbar-results .error-box',
    what: 'trace',
  });
  // The page still works: the synthetic trace analyses.
  await page.selectOption('#ballbar-source', 'synthetic');
  await page.click('#ballbar-run');
  await page.waitForSelector('#ballbar-centre-x', { timeout: 60_000 });

  await dropHuge(page, check, {
    tab: 'toolpath',
    input: '#panel-toolpath .drop input[type=file]',
    file: bigFile('huge-program.nc', 'G21 G90\n', 'G01 X12.3456 Y65.4321 F1000\n', MB70),
    errorSelector: '#panel-toolpath .error-box',
    what: 'program',
  });
}
